// The encounter suite: standard COLREG situations (1 to 3 vessels; head-on,
// crossing from either side, overtaking and being overtaken, a vessel lying
// still; in open water and in a narrow channel between two banks), each with
// the behaviour COLREG expects of the own ship, run in the closed-loop
// encounter simulation (engine/colav/encounter_sim.h) and checked.
//
// Own ship: the SITS hull at 9 m/s sailing north along a 9 km path (or the
// channel's axis, 80 m east of it: rule 9, the starboard side of the
// fairway), safety distance 150 m. Traffic keeps course and speed: it is
// never the give-way vessel in fact, so a stand-on own ship must act under
// rule 17 in the end.
#pragma once

#include <string>
#include <vector>

#include "seaplan/colav/encounter_sim.h"

namespace seaplan::colav::suite {

enum class Side { kEither, kPort, kStarboard };  // the side the vessel is passed on

struct Expectation {
  Role role = Role::kNone;  // the role the own ship should take (kNone: keep clear, either side)
  Side side = Side::kEither;
  bool no_port_turn =
      false;                 // rules 14, 15 (give-way) and 17 c (stand-on, vessel on the port side)
  bool stand_on = false;     // keep course and speed until rule 17 applies
  bool role_checked = true;  // false: any role (or none) will do
};

struct Situation {
  std::string name;
  std::string description;
  EncounterSetup setup;
  std::vector<Expectation> expected;   // per setup.traffic entry
  double max_time_lost = -1.0;         // fraction of the leg without traffic; < 0: not checked
  double min_land_clearance_m = -1.0;  // the ship's closest approach to land; < 0: not checked
};

// Every situation of the suite with `options` as the avoidance's.
std::vector<Situation> Situations(const CollisionAvoidanceOptions& options = {});

struct Result {
  EncounterOutcome outcome;
  double time_lost = 0.0;             // (arrival - arrival without traffic) / the latter
  std::vector<std::string> failures;  // every check that failed, in words
};

// Runs a situation (and the same leg without traffic, for the time lost)
// and checks it: every closest approach at or above the safety distance, no
// grounding, arrival, the expected side and role, no port turn where ruled
// out, a stand-on ship's first manoeuvre not before rule 17's time, course
// offsets of at least 25 deg or speed reductions of at least 40 % (rule 8,
// readily apparent), the time lost and the land clearance where bounded.
StatusOr<Result> Run(const Situation& s);

std::string_view SideName(Side s);  // "port", "starboard", "either"

}  // namespace seaplan::colav::suite
