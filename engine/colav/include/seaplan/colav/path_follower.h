// Line-of-sight path following over a route polyline that survives leaving
// the path (collision avoidance manoeuvres, drift, a slow-turning hull
// overshooting a corner).
//
// Why not seaplan::ship::LosGuidance alone: it switches legs only when the
// ship enters a waypoint's acceptance circle. After an avoidance manoeuvre
// the ship is often past a waypoint it never came near, so it keeps steering
// for the old leg (or circles trying to reach the waypoint) and drifts
// hundreds of metres off the route. Here the leg is chosen by along-track
// progress: the nearest of the next legs (never going back), advancing once
// the projection passes a leg's end, and the cross-track error is always
// measured to that leg. There is no integral term (nothing to wind up while
// the ship is away from the path) and the look-ahead is fixed, so the
// approach angle back to the path is bounded (atan(e / lookahead)). Past
// the end of the last leg the line is followed on (the caller decides
// arrival with on_last_leg() / leg_remaining_m(): steering for the end
// point itself makes a hull with a large turning circle orbit it).
//
// Frame: local metric, x east, y north; courses clockwise from north.
#pragma once

#include <vector>

#include "seaplan/colav/geometry.h"
#include "seaplan/common/status.h"

namespace seaplan::colav {

struct PathFollowerOptions {
  double lookahead_m = 400.0;       // Delta: psi_d = alpha - atan(e / Delta)
  double switch_distance_m = 60.0;  // advance to the next leg this far before a leg's end
  // Legs starting within this path distance past the current leg's end are
  // candidates when re-choosing the leg (bounds the search on long routes
  // and keeps a route that doubles back from being short-cut).
  double search_distance_m = 1500.0;
  // Wheel-over: a hull that needs a turning circle of this radius starts
  // turning onto the next leg R * tan(course change / 2) before the corner,
  // so its arc meets both legs instead of overshooting the corner outwards
  // by about R (0: only switch_distance_m).
  double turn_radius_m = 0.0;
  // Leads bends: > 0, the course is the direction of the path's chord
  // from the ship's abeam point to the point c = chord_s x the ship's
  // speed further along the path (round the corners), less
  // atan(e / lookahead_m) for the ship's distance e from the nearest leg
  // (the wheel-over's switch to the next leg then only decides leg() and
  // cross_track_m()); 0, the current leg's course less
  // atan(cross_track_m() / lookahead_m). The same on a straight leg, but
  // on an arc of radius R the chord leads the tangent by c / (2 R), most of
  // the course error the yaw-damped autopilot needs to hold the arc's turn
  // rate (kd V / (kp R): 225 m / R at 9 m/s, in proportion to the speed,
  // so c = 2 kd V / kp would be all of it), which the leg's course left to
  // ~200 m of cross-track error; and the turn onto a corner starts c
  // before it. A longer chord cuts the inside of sharp corners (the same
  // 200 Ålesund routes sailed at 9 m/s: 500 m put 9 tracks aground, 400 m
  // 1; bench/route README).
  double chord_s = 0.0;
  Status Validate() const;
};

// The path following this hull sails under the autopilot, read by the
// simulation client, the collision avoidance's predictions and the route's
// sail check alike. The hull's circle at full rudder is ~240 m, but the
// autopilot needs ~46 s (~400 m at 9 m/s) to half complete a 60 deg course
// change, so the closed-loop turn is wider: with a 300 m wheel-over the ship
// overshot 76-88 deg corners by ~340 m and crossed back onto the shallows
// (SharpCornerOvershootIsBoundedByTheWheelOver), hence 450 m. The chord of
// 44 s (400 m at 9 m/s) leads bends: a fillet's polygon is held ~100 m
// closer than by following its legs one by one. Legs advance by along-track
// progress only (search distance 0): a nearer later leg across a headland
// is not a shortcut the ship may take.
inline PathFollowerOptions ShipPathFollowerOptions() {
  PathFollowerOptions o;
  o.lookahead_m = 400.0;
  o.switch_distance_m = 60.0;
  o.search_distance_m = 0.0;
  o.turn_radius_m = 450.0;
  o.chord_s = 44.0;
  return o;
}

class PathFollower {
 public:
  // `path` has >= 2 points, consecutive points distinct.
  static StatusOr<PathFollower> Create(std::vector<EastNorth> path,
                                       const PathFollowerOptions& options = {});

  // Chooses the leg for `here` (forward only) and returns the desired
  // course [rad, clockwise from north]; `speed_mps` sets the chord (0: none).
  double Update(EastNorth here, double speed_mps = 0.0);

  int leg() const { return leg_; }  // index of the leg's first point
  bool on_last_leg() const { return leg_ + 2 == static_cast<int>(path_.size()); }
  // Along-track distance still to go to the current leg's end (< 0: past it).
  double leg_remaining_m() const { return leg_remaining_m_; }
  double cross_track_m() const { return cross_track_m_; }  // > 0: ship to starboard of the leg
  const std::vector<EastNorth>& path() const { return path_; }

 private:
  PathFollower(std::vector<EastNorth> path, const PathFollowerOptions& o);
  double Along(int leg, EastNorth p) const;       // projection on the leg's line, from its start
  double DistanceTo(int leg, EastNorth p) const;  // to the segment
  EastNorth PointAt(double s) const;  // at path distance s (past the end: on the last leg's line)

  std::vector<EastNorth> path_;
  std::vector<double> start_distance_;  // path distance at each point
  PathFollowerOptions options_;
  int leg_ = 0;
  double cross_track_m_ = 0.0;
  double leg_remaining_m_ = 0.0;
  std::vector<double> wheel_over_m_;  // per leg: switch this far before its end
  double max_wheel_over_m_ = 0.0;
};

}  // namespace seaplan::colav
