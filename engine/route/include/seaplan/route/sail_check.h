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
#include "seaplan/common/stop_token.h"
#include "seaplan/route/obstacle_field.h"
#include "seaplan/route/turn_fillet.h"

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

  // The track arrives and never enters the obstacles.
  bool Clear() const { return arrived && !touches && clearance_m > 0.0; }
};

// Sails `route` (start .. goal; points closer than 1 m to the previous are
// dropped) from rest at `speed_mps` and checks the track against `field`
// (null: not checked), with the simulation client's path follower or
// `follower` (to compare followers). Errors: InvalidArgument for fewer than
// 2 distinct points, non-finite points, speed <= 0 or bad follower options.
StatusOr<SailedTrack> SailRoute(const std::vector<EastNorth>& route, double speed_mps,
                                const ObstacleField* field,
                                const colav::PathFollowerOptions* follower = nullptr);

// Repair of a route whose sailed track enters the obstacles (Level-2 step 6,
// level2_optimizer.h): where the track comes closest to an obstacle, the
// route is bent away from it and sailed again.
//
// Why: the hull leaves its route where the closed loop lags it (S-bends of
// opposite fillets, corners of vertices tens of metres apart, hairpins the
// hull's circle is too wide for, runs of small corners both ways), by
// amounts no geometric rule of the corner predicts. The track itself says
// where and by how much: its point closest to (or deepest in) an obstacle.
// The route near the point of it nearest that point is moved away from the
// obstacle (along the gradient of the signed distance there) by the depth
// plus `target_clearance_m`, tapered (cosine bump) to nothing `window_m`
// along the route either side, so that the hull, which follows a smooth
// bend of the route, is carried out by about as much. A bent route whose
// segments touch an obstacle is tried with half the shift; one that keeps
// clear is sailed, and kept when its track keeps more clearance. Rounds
// repeat from the new track's closest point, wider windows and larger
// shifts when a bend does not help. When none does (the water beside the
// route too narrow, e.g. a hairpin round a shoal's tip whose legs lie
// closer than the hull's turning circle), the route's vertex nearest the
// point is pushed outwards along its corner's bisector by 1/4, 1/2 and 1
// window, the turn made where there may be room. It stops
// when the track keeps clear, nothing improves it or `max_sails` sailings
// are spent (the time bound).
struct SailRepairOptions {
  int max_sails = 12;
  double target_clearance_m = 40.0;
  double window_m = 600.0;  // a little over the follower's 450 m wheel-over radius

  absl::Status Validate() const;
};

struct SailRepair {
  // The best route found, start .. goal (source: the input point it is,
  // -1 a new or moved point); the input as it was when no bend improved.
  std::vector<FilletPoint> points;
  SailedTrack track;  // its sailed track (the input's when nothing improved)
  int sails = 0;      // sailings spent
  int bends = 0;      // repairs kept (bends or corner pushes)
};

// `route` and `sailed`: the route and its track as SailRoute gave it (sailed
// over `field`). A stop request ends the repair before its next sailing,
// with the best route so far. Errors: those of SailRoute, InvalidArgument
// for bad options.
StatusOr<SailRepair> RepairSailedRoute(const ObstacleField& field,
                                       const std::vector<EastNorth>& route,
                                       const SailedTrack& sailed, double speed_mps,
                                       const SailRepairOptions& options,
                                       const StopToken* stop = nullptr);

}  // namespace seaplan::route
