// Ship encounters for the simulation client: closest point of approach,
// COLREG role classification (rules 13-17) and collision avoidance with
// velocity obstacles under COLREG constraints (Kuwata et al., "Safe maritime
// autonomous navigation with COLREGS, using velocity obstacles", IEEE JOE
// 2014).
//
// Frame: local metric, x east, y north. Courses/headings are radians
// clockwise from north (navigation convention), so a course c has the
// velocity (sin c, cos c) * speed.
//
// Why velocity obstacles and not the paper's fuzzy logic: a VO gives a
// guarantee the fuzzy rule base does not (a velocity outside every
// safety-inflated obstacle keeps the CPA above the safety distance for as
// long as the others hold their velocities), and COLREG roles map onto it as
// simple half-plane constraints. All functions are pure.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "seaplan/common/east_north.h"

namespace seaplan::sim {

// Velocity of `speed_mps` along course `course_rad` (clockwise from north).
EastNorth VelocityOf(double course_rad, double speed_mps);
double CourseOf(EastNorth velocity);  // in [0, 2 pi)

struct Kinematics {
  EastNorth position;
  EastNorth velocity;
};

struct Cpa {
  double tcpa_s = 0.0;  // time to the closest point; 0 when diverging or equal velocities
  double dcpa_m = 0.0;  // distance at that time
};
// CPA of straight-line motion from now on (times before now are not
// considered: a diverging pair has tcpa 0 and dcpa = current distance).
Cpa ComputeCpa(const Kinematics& own, const Kinematics& other);

enum class Role {
  kNone,             // no COLREG situation (far, diverging, or safe CPA)
  kHeadOn,           // rule 14: both alter to starboard
  kCrossingGiveWay,  // rule 15: the other is on our starboard side; we keep out of its way
  kCrossingStandOn,  // rule 15/17: the other is on our port side; we keep course and speed
  kOvertaking,       // rule 13: we overtake; we keep out of its way
  kOvertaken,        // rule 13/17: we are overtaken; we keep course and speed
};
std::string_view RoleName(Role role);  // "head-on", "crossing give-way", ...
bool IsGiveWay(Role role);             // head-on, crossing give-way, overtaking

struct ColregOptions {
  double head_on_sector_rad = 0.2618;     // +-15 deg about the bow, both ways
  double overtaking_sector_rad = 1.9635;  // abaft 112.5 deg from the bow (rule 13)
};
// The role of `own` towards `other` from geometry alone (the caller decides
// whether the encounter is dangerous, e.g. by CPA).
Role ClassifyEncounter(const Kinematics& own, const Kinematics& other,
                       const ColregOptions& options = {});

struct AvoidanceOptions {
  double safety_distance_m = 150.0;  // keep every CPA above this
  double horizon_s = 600.0;          // look this far ahead
  // Stand-on vessels act only when the give-way vessel evidently does not
  // (rule 17 a ii): CPA under safety and TCPA under this.
  double stand_on_action_tcpa_s = 300.0;
  double max_course_change_rad = 1.5708;  // candidate courses within +-90 deg of desired
  double course_step_rad = 0.0436;        // 2.5 deg
  std::vector<double> speed_factors = {1.0, 0.8, 0.6, 0.4, 0.2};
  // The own ship's top speed, m/s; 0 = unknown. When above the desired
  // speed, faster candidates (x1.25, x1.5, capped here) are tried too: a
  // slow ship overtaken by a vessel that does not keep clear, or caught
  // ahead of a crossing one, gets out of the way by speeding up, which
  // slowing down and turning alone cannot do (seen in the fjord cases
  // at 3.6 m/s).
  double max_speed_mps = 0.0;
  ColregOptions colreg;
  // The own ship's manoeuvrability. A velocity obstacle assumes a new
  // velocity is taken at once; a slow-turning hull keeps its present
  // velocity for lag + |course change| / turn_rate (+ |speed change| /
  // acceleration) first, which is what let a CPA fall below the safety
  // distance. Candidates (and the desired velocity) are checked with that
  // delay: the ship goes on at its present velocity, then at the candidate.
  // turn_rate_rad_s <= 0: velocities change at once (the plain VO).
  double turn_rate_rad_s = 0.0;
  double manoeuvre_lag_s = 0.0;
  double acceleration_mps2 = 0.05;
  // Land (outer rings, local frame; not owned, may be null). A candidate
  // whose straight track over land_lookahead_s comes closer than
  // land_clearance_m to it is taken only when every candidate does: the
  // velocity obstacles alone once sent the ship round the wrong side of an
  // island and onto the shore (fjord case C).
  const class LandIndex* land = nullptr;
  double land_clearance_m = 60.0;
  double land_lookahead_s = 45.0;  // ~400 m at the routes' 9 m/s
};

// The closest approach to `other` (straight-line motion) of a ship that
// sails the polyline `path` from `position`, first towards path[next] and
// then along the following points, at `speed_mps`, sampled every `step_s`
// within `horizon_s`. A straight-line CPA cannot see a conflict that lies
// past a turn of the route: at 9 m/s a crossing vessel found only once the
// turn is under way is too close for a slow-turning hull (fjord case C).
struct PathApproach {
  double distance_m = 0.0;
  double time_s = 0.0;
};
// With start_speed_mps >= 0 and acceleration_mps2 > 0 the speed ramps from
// start_speed_mps to speed_mps at that rate (a ship leaving its berth).
PathApproach PathAheadClosestApproach(const std::vector<EastNorth>& path, size_t next,
                                      EastNorth position, double speed_mps, const Kinematics& other,
                                      double horizon_s, double step_s = 5.0,
                                      double start_speed_mps = -1.0,
                                      double acceleration_mps2 = 0.0);

// Distance from p to the segment a-b.
double PointSegmentDistance(EastNorth p, EastNorth a, EastNorth b);

// Smallest distance from the segment a-b to the rings' edges, 0 when it
// crosses one or starts inside a ring. Scans every edge (tests, small maps).
double LandClearance(const std::vector<std::vector<EastNorth>>& rings, EastNorth a, EastNorth b);

// The land's edges in a uniform grid, for the avoidance's per-candidate
// checks: a real chart has ~55k land vertices (Trondheim), and scanning them
// all for every candidate velocity of every step took minutes per mission.
// Immutable after construction; thread-compatible.
class LandIndex {
 public:
  LandIndex() = default;
  explicit LandIndex(const std::vector<std::vector<EastNorth>>& rings, double cell_m = 250.0);
  bool empty() const { return edges_.empty(); }
  // min(limit_m, distance from the segment a-b to the land's edges); 0 when
  // it crosses an edge. Only edges within limit_m of the segment's bounding
  // box are looked at. (A segment wholly inside land and far from its
  // edges reads as clear: the ship is aground already, not the avoidance's
  // concern.)
  double Clearance(EastNorth a, EastNorth b, double limit_m) const;
  // Inside the land (even-odd over every ring): a ray east from p through
  // the grid row of p.
  bool Inside(EastNorth p) const;
  // Distance from p to the land's edges, at most limit_m; negative inside
  // (how far aground). For the report's closest approach to land.
  double SignedClearance(EastNorth p, double limit_m) const;

 private:
  int64_t Key(int64_t i, int64_t j) const { return i * 1'000'003 + j; }
  std::vector<std::pair<EastNorth, EastNorth>> edges_;
  std::unordered_map<int64_t, std::vector<int32_t>> cells_;
  double cell_m_ = 250.0;
  int64_t max_i_ = 0;                  // easternmost cell column with an edge
  mutable std::vector<int32_t> seen_;  // scratch: last query that looked at each edge
  mutable int32_t query_ = 0;
};

struct Obstacle {
  Kinematics kinematics;
  int id = 0;
};

struct AvoidanceDecision {
  EastNorth velocity;        // the velocity to steer for
  bool manoeuvring = false;  // differs from the desired velocity because of another vessel
  int vessel_id = -1;        // the most constraining vessel when manoeuvring
  Role role = Role::kNone;
  bool feasible = true;  // false: no candidate clears every vessel (best effort returned)
};

// Chooses the velocity closest to `desired` that is outside every dangerous
// vessel's velocity obstacle (inflated by the safety distance, within the
// horizon) and respects COLREG: against a head-on or crossing-from-starboard
// vessel only passes that leave it on our port side (we go to starboard /
// astern of it) are allowed; as stand-on the desired velocity is kept unless
// rule 17 applies. Only vessels with a dangerous CPA are considered.
AvoidanceDecision ChooseVelocity(const Kinematics& own, EastNorth desired,
                                 const std::vector<Obstacle>& others,
                                 const AvoidanceOptions& options = {});

}  // namespace seaplan::sim
