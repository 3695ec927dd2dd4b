// A closed-loop encounter simulation: the own ship (engine/ship model, this
// library's autopilot and path follower) sails a path among traffic that
// keeps a constant velocity (after lying still, for a vessel that gets
// under way), with the collision avoidance in the loop. It
// measures what COLREG and the safety distance are judged on: the closest
// approach to each vessel and the side it was passed on, the course offsets
// and speed factors commanded, the deviation from the path, the land
// clearance and the time to the path's end. For the unit tests and the
// encounter benchmark (bench/colav); no I/O.
#pragma once

#include <string>
#include <vector>

#include "seaplan/colav/colav.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::colav {

struct EncounterVessel {
  int id = 0;
  std::string name;
  EastNorth position;  // at t = 0
  EastNorth velocity;  // constant once under way
  // The vessel lies still at `position` until this time, then moves at
  // `velocity` at once (as the simulation client's scripted tracks do).
  double still_until_s = 0.0;
  Kinematics At(double time_s) const;
};

struct EncounterSetup {
  std::vector<EastNorth>
      path;  // >= 2 points; the ship starts at the first on the first leg's course
  double cruise_speed_mps = 9.0;
  // The ship starts under way at the cruise speed (false), or at rest as a
  // ship leaving its berth does in the simulation client (true).
  bool start_at_rest = false;
  std::vector<EncounterVessel> traffic;
  std::vector<std::vector<EastNorth>> land;  // outer rings
  ship::Environment environment;
  double dt_s = 0.5;
  double max_time_s = 3000.0;
  CollisionAvoidanceOptions avoidance;
  AutopilotOptions autopilot;
  // The simulation client's path following for this hull.
  PathFollowerOptions follower = ShipPathFollowerOptions();
};

struct VesselOutcome {
  int id = 0;
  double min_distance_m = 1e18;
  double time_s = 0.0;
  // Relative bearing of the vessel from the own ship's heading at the
  // closest approach, starboard positive: < 0 = passed on our port side.
  double bearing_rad = 0.0;
  Role role = Role::kNone;  // the role the avoidance fixed for it (first one)
  // First time a manoeuvre was commanded mainly for this vessel, and the
  // straight-line TCPA to it then (-1: none).
  double first_manoeuvre_s = -1.0;
  double tcpa_at_first_manoeuvre_s = -1.0;
};

struct EncounterOutcome {
  bool arrived = false;
  double arrival_time_s = 0.0;  // or the time simulated
  std::vector<VesselOutcome> vessels;
  double max_path_deviation_m = 0.0;   // distance to the path polyline
  double min_land_clearance_m = 1e18;  // signed (< 0 aground), sampled every 2 s
  double aground_s = 0.0;
  // Commanded course minus the path follower's course while manoeuvring,
  // starboard positive: the extremes over the run.
  double max_starboard_offset_rad = 0.0;
  double max_port_offset_rad = 0.0;
  double min_speed_factor = 1.0;  // commanded speed / desired speed
  int manoeuvres = 0;             // manoeuvre-start events
  // Per manoeuvre (a stretch of commands flagged manoeuvring): the largest
  // course offset and the smallest speed factor commanded in it, what rule 8
  // (readily apparent) is judged on. A manoeuvre onto a track parallel to
  // the path turns away by a large offset and then steers a small one.
  struct Manoeuvre {
    double start_s = 0.0;
    double max_offset_rad = 0.0;  // magnitude
    double min_speed_factor = 1.0;
  };
  std::vector<Manoeuvre> manoeuvre_extents;
  std::vector<EastNorth> track;  // the ship's position every 2 s, and at the end
  std::vector<std::string> log;  // "t: event" lines
};

// A ship under way at `speed_mps` (PTO, calm-water operating point: its
// thrust, and the autopilot's integral holding its throttle) at `position`
// on `heading_rad`.
struct UnderWay {
  ship::ShipModel model;
  Autopilot autopilot;
};
StatusOr<UnderWay> ShipUnderWay(EastNorth position, double heading_rad, double speed_mps,
                                const ship::Environment& environment = {},
                                const AutopilotOptions& autopilot = {});

// Runs the encounter until the ship reaches the path's end or max_time_s.
StatusOr<EncounterOutcome> SimulateEncounter(const EncounterSetup& setup);

}  // namespace seaplan::colav
