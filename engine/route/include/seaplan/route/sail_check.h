// The track a ship sails along a route, and its clearance from the
// obstacles: the band the hull actually sweeps, not the polyline.
//
// Why: the route's polyline and its fillets keep the safety margin, but the
// hull under its autopilot and path follower does not sail the polyline: it
// turns on a wider circle than drawn (the yaw-damped autopilot lags a run of
// small corners), overshoots corners between short legs and rejoins the
// route at the follower's approach angle, 100 m and more off it at times.
// Sailing the route in the same closed loop as the simulation client
// (engine/colav `SimulateEncounter`: the SITS hull, the autopilot, the LOS
// path follower with its default options, from rest, no wind, no traffic)
// gives the band to check.
//
// Frame: local metric frame (EastNorth). Thread-safety: a pure function.
#pragma once

#include <vector>

#include "seaplan/colav/path_follower.h"
#include "seaplan/common/east_north.h"
#include "seaplan/common/status.h"
#include "seaplan/route/obstacle_field.h"

namespace seaplan::route {

struct SailedTrack {
  bool arrived = false;
  std::vector<EastNorth> track;  // the ship's position every 2 s, and at the end
  // Smallest signed distance of the track's points from the field's
  // obstacles (negative inside), and where; +inf without a field.
  double clearance_m = 0.0;
  EastNorth closest;
  // A segment between two track points touches an obstacle.
  bool touches = false;
};

// Sails `route` (start .. goal; points closer than 1 m to the previous are
// dropped) from rest at `speed_mps` and checks the track against `field`
// (null: not checked), with the simulation client's path follower or
// `follower` (to compare followers). Errors: InvalidArgument for fewer than
// 2 distinct points, non-finite points, speed <= 0 or bad follower options.
StatusOr<SailedTrack> SailRoute(const std::vector<EastNorth>& route, double speed_mps,
                                const ObstacleField* field,
                                const colav::PathFollowerOptions* follower = nullptr);

}  // namespace seaplan::route
