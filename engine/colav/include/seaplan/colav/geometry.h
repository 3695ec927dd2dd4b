// Encounter geometry: closest point of approach, COLREG role
// classification (rules 13-17), the land's edges in a grid index and the
// closest approach along a path ahead.
//
// Frame: local metric, x east, y north. Courses/headings are radians
// clockwise from north (navigation convention), so a course c has the
// velocity (sin c, cos c) * speed.
// All functions are pure; LandIndex is immutable after construction.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "seaplan/common/east_north.h"

namespace seaplan::colav {

// Velocity of `speed_mps` along course `course_rad` (clockwise from north).
EastNorth VelocityOf(double course_rad, double speed_mps);
double CourseOf(EastNorth velocity);  // in [0, 2 pi)
double WrapAngle(double angle_rad);   // to (-pi, pi]

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

// The closest approach to `other` (straight-line motion) of a ship that
// sails the polyline `path` from `position`, first towards path[next] and
// then along the following points, at `speed_mps`, sampled every `step_s`
// within `horizon_s`. A straight-line CPA cannot see a conflict that lies
// past a turn of the route: at 9 m/s a crossing vessel found only once the
// turn is under way is too close for a slow-turning hull (the fjord's case C).
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

}  // namespace seaplan::colav
