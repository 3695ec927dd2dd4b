// Routing a mission's moves over a chart (paper 000 fig. 7 with the router
// of engine/route): a route::RoutePlanner per (chart, ship, route options,
// environment), built once and shared by every mission that uses it, and
// the routes it planned between two positions (a replan asks again for most
// legs of the previous version).
//
// A replan may start where the ship is, and a ship pushed off its route
// (avoidance, drift, a GNSS jump) can be inside the buffered obstacles (land
// plus safety buffer) while still afloat. The route planner refuses such a
// start; a real ship leaves the buffer the shortest way out, so the route
// gets one more leg in front: from the ship to the nearest free point.
//
// Thread-safety: ChartRouting and ChartRoutingCache may be used from any
// thread; the route planner is immutable and the caches are locked.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/mission/refine.h"
#include "seaplan/mission/types.h"
#include "seaplan/route/route_planner.h"

namespace seaplan::mission {

// The obstacles of a stored chart by id; NotFound for an unknown id.
using ChartLoader =
    std::function<StatusOr<std::shared_ptr<const chart::ObstacleMap>>(const std::string& chart_id)>;

// How a route starts for a ship under way (RouteRequest::start_motion).
// The ship sails on while the new route reaches it (reaction_time_s) and
// turns no tighter than turn_radius_m (this hull turns on a circle of
// about 240 m radius at full rudder at 9 m/s; the radius hardly depends on
// the speed). A route whose first leg turns more than max_join_turn_rad from
// the ship's course gets a lead-in: straight on, or a turn on the side whose
// circle is clear, before the route proper.
struct LeadInOptions {
  double reaction_time_s = 20.0;
  double turn_radius_m = 400.0;
  double max_join_turn_rad = M_PI / 3;  // 60 deg: the path follower's wheel-over copes
  Status Validate() const;
};

// What routes over a chart depend on besides the chart.
struct ChartRouteSettings {
  route::ShipParticulars ship;
  route::RouteOptions options;
  route::Environment environment;
  LeadInOptions lead_in;
};

// The lead-ins tried for a ship at `from` under way (motion.course_rad,
// motion.speed_mps), when the route it would get turns back on it: straight
// on for the reaction distance and then 0, R, 2R or 4R further; or the
// reaction distance and a turn of radius R to port or to starboard onto
// `join_course_rad`. Each is a polyline from `from` (arcs every 10 deg); the
// last point is where the route proper starts, the ship then on
// `end_course_rad`.
struct LeadIn {
  std::vector<EastNorth> points;
  double end_course_rad = 0.0;
  double length_m = 0.0;
};
std::vector<LeadIn> LeadInCandidates(EastNorth from, const ShipMotion& motion,
                                     double join_course_rad, const LeadInOptions& options);

// Farthest a start inside the buffered obstacles is moved to free water.
inline constexpr double kMaxWayOutM = 500.0;

// The nearest free point within kMaxWayOutM of `p` (rings every 5 m, 64
// bearings), 10 m further out when that is free too (clear of the buffer's
// edge); nullopt when there is none.
std::optional<EastNorth> ShortestWayOut(const route::ObstacleField& field, EastNorth p);

// Puts `from` in front of `route` (which starts at the way out): one more
// leg, sailed at the route's mean speed in the mode of its first leg, with
// the fuel of the first leg scaled by length. No-op on an empty route.
void PrependWayOut(EastNorth from, Route* route);

// The mission's view of a route alternative: waypoints with their ETA and
// distance from the start, modes, risk and fuel per segment.
Route RouteFromAlternative(const route::RouteAlternative& alternative, int index);

// Routing over one chart with one set of settings.
class ChartRouting {
 public:
  ChartRouting(chart::LocalFrame frame, std::shared_ptr<const route::RoutePlanner> planner,
               route::Environment environment, LeadInOptions lead_in = {});
  ChartRouting(const ChartRouting&) = delete;
  ChartRouting& operator=(const ChartRouting&) = delete;

  const chart::LocalFrame& frame() const { return frame_; }

  // The chosen safe route from req.from_position to req.to_position
  // (cached per position pair). A start inside the buffered obstacles
  // leaves them the shortest way first. Errors: FailedPrecondition when the
  // leg cannot be sailed (an end off the chart or inside an obstacle, no
  // free water near the start, no obstacle-free alternative);
  // DeadlineExceeded / Cancelled when `stop` stopped it.
  // With req.start_motion at speed, the route starts the way the ship is
  // going: when the direct route's first leg turns more than
  // max_join_turn_rad from its course, the shortest lead-in
  // (LeadInCandidates) whose track keeps clear of the obstacles (never
  // deeper into the safety buffer than the ship already is) and from whose
  // end the route turns no more than that; the direct route when none does.
  StatusOr<Route> Plan(const RouteRequest& req, const StopToken& stop);

 private:
  StatusOr<Route> PlanFromRest(const RouteRequest& req, const StopToken& stop);
  StatusOr<Route> PlanUnderWay(const RouteRequest& req, const StopToken& stop);
  // The track stays out of the buffered obstacles, or no deeper in than
  // `floor_m` (the ship's own signed distance when it is inside).
  bool TrackClear(const std::vector<EastNorth>& track, double floor_m) const;

  chart::LocalFrame frame_;
  std::shared_ptr<const route::RoutePlanner> planner_;
  route::Environment environment_;
  LeadInOptions lead_in_;
  std::mutex mu_;
  std::map<std::array<double, 4>, Route> routes_;  // (from x, y, to x, y) -> route
};

// A mission::RoutePlanner callback over `routing` that stops with `stop`.
RoutePlanner ChartRouter(std::shared_ptr<ChartRouting> routing, StopToken stop);

// One ChartRouting per (chart id, settings), built on first use; a bounded
// number of them (one is dropped when full, as is a full route cache).
class ChartRoutingCache {
 public:
  explicit ChartRoutingCache(ChartLoader loader) : loader_(std::move(loader)) {}

  // `settings_key` identifies `settings` (equal keys must mean equal
  // settings). Errors: FailedPrecondition naming the chart when it is
  // unknown; the route planner's errors with the chart id.
  StatusOr<std::shared_ptr<ChartRouting>> Get(const std::string& chart_id,
                                              const std::string& settings_key,
                                              const ChartRouteSettings& settings);
  // Drops every routing built on the chart (it was deleted): a later Get
  // loads it again, and fails when it is gone.
  void Forget(const std::string& chart_id);

 private:
  ChartLoader loader_;
  std::mutex mu_;
  std::map<std::string, std::shared_ptr<ChartRouting>> routings_;
};

}  // namespace seaplan::mission
