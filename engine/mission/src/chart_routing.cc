#include "seaplan/mission/chart_routing.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"

namespace seaplan::mission {
namespace {

inline constexpr size_t kMaxCachedRoutings = 16;
inline constexpr size_t kMaxCachedRoutes = 4096;

MsoMode ModeFromRoute(route::MsoMode m) {
  switch (m) {
    case route::MsoMode::kPto:
      return MsoMode::kPto;
    case route::MsoMode::kMec:
      return MsoMode::kMec;
    case route::MsoMode::kPti:
      return MsoMode::kPti;
  }
  return MsoMode::kUnspecified;
}

Status StoppedStatus(const StopToken& stop) {
  return stop.Reason() == StopReason::kDeadline
             ? absl::DeadlineExceededError("routing stopped: deadline")
             : absl::CancelledError("routing stopped");
}

}  // namespace

std::optional<EastNorth> ShortestWayOut(const route::ObstacleField& field, EastNorth p) {
  constexpr int kBearings = 64;
  for (double r = 5.0; r <= kMaxWayOutM; r += 5.0) {
    for (int k = 0; k < kBearings; ++k) {
      const double a = 2.0 * M_PI * k / kBearings;
      const EastNorth q{p.east_m + r * std::sin(a), p.north_m + r * std::cos(a)};
      if (field.Inside(q)) continue;
      const EastNorth clear{p.east_m + (r + 10.0) * std::sin(a),
                            p.north_m + (r + 10.0) * std::cos(a)};
      return field.Inside(clear) ? q : clear;
    }
  }
  return std::nullopt;
}

void PrependWayOut(EastNorth from, Route* r) {
  if (r->waypoints.empty()) return;
  const EastNorth first = r->waypoints.front().position;
  const double leg_m = std::hypot(first.east_m - from.east_m, first.north_m - from.north_m);
  const double speed =
      r->sailing_time_s > 0 && r->length_m > 0 ? r->length_m / r->sailing_time_s : 1.0;
  const double leg_s = leg_m / speed;
  for (RouteWaypoint& w : r->waypoints) {
    w.eta_s += leg_s;
    w.distance_from_start_m += leg_m;
  }
  RouteWaypoint out = r->waypoints.front();
  out.position = {from.east_m, from.north_m};
  out.eta_s = 0.0;
  out.distance_from_start_m = 0.0;
  out.fuel_kg = r->waypoints.front().fuel_kg * (r->length_m > 0 ? leg_m / r->length_m : 0.0);
  r->waypoints.insert(r->waypoints.begin(), out);
  r->length_m += leg_m;
  r->sailing_time_s += leg_s;
}

Route RouteFromAlternative(const route::RouteAlternative& a, int index) {
  Route r;
  r.alternative_index = index;
  r.length_m = a.length_m;
  r.sailing_time_s = a.sailing_time_s;
  r.fuel_kg = a.fuel_kg;
  r.expected_grounding_cost = a.expected_grounding_cost;
  double eta = 0, distance = 0;
  for (const auto& w : a.waypoints) {
    RouteWaypoint m;
    m.position = {w.local.east_m, w.local.north_m};
    m.mode = ModeFromRoute(w.mode);
    m.eta_s = eta;
    m.distance_from_start_m = distance;
    m.time_to_grounding_s = w.ttg_s;
    m.grounding_probability = w.grounding_probability;
    m.expected_grounding_cost = w.expected_grounding_cost;
    m.fuel_kg = w.segment_fuel_kg;
    r.max_grounding_probability = std::max(r.max_grounding_probability, w.grounding_probability);
    eta += w.segment_time_s;
    distance += w.segment_length_m;
    r.waypoints.push_back(m);
  }
  return r;
}

ChartRouting::ChartRouting(chart::LocalFrame frame,
                           std::shared_ptr<const route::RoutePlanner> planner,
                           route::Environment environment)
    : frame_(std::move(frame)), planner_(std::move(planner)), environment_(environment) {}

StatusOr<Route> ChartRouting::Plan(const RouteRequest& req, const StopToken& stop) {
  const std::array<double, 4> key = {req.from_position.east_m, req.from_position.north_m,
                                     req.to_position.east_m, req.to_position.north_m};
  {
    std::lock_guard lock(mu_);
    if (auto it = routes_.find(key); it != routes_.end()) return it->second;
  }
  if (stop.StopRequested()) return StoppedStatus(stop);
  const EastNorth from{req.from_position.east_m, req.from_position.north_m};
  EastNorth start = from;
  bool way_out = false;
  if (planner_->field().Inside({from.east_m, from.north_m})) {
    std::optional<EastNorth> out = ShortestWayOut(planner_->field(), from);
    if (!out) {
      return absl::FailedPreconditionError(absl::StrCat(
          "start (", from.east_m, ", ", from.north_m,
          ") lies inside a grounding obstacle with no free water within ", kMaxWayOutM, " m"));
    }
    start = *out;
    way_out = true;
  }
  auto result = planner_->Plan(start, EastNorth{req.to_position.east_m, req.to_position.north_m},
                               environment_, stop);
  if (!result.ok()) {
    // A location outside the chart or inside an obstacle: the mission
    // cannot sail this leg as specified.
    if (absl::IsInvalidArgument(result.status()))
      return absl::FailedPreconditionError(result.status().message());
    return result.status();
  }
  if (result->stopped) return StoppedStatus(stop);
  if (result->chosen < 0 || result->chosen >= static_cast<int>(result->alternatives.size()) ||
      !result->alternatives[static_cast<size_t>(result->chosen)].safe) {
    return absl::FailedPreconditionError("no obstacle-free route alternative");
  }
  Route r = RouteFromAlternative(result->alternatives[static_cast<size_t>(result->chosen)],
                                 result->chosen);
  if (way_out) {
    PrependWayOut(from, &r);
    log::Info(
        "route from ({:.0f}, {:.0f}) inside the buffered obstacles leaves them at ({:.0f}, "
        "{:.0f})",
        from.east_m, from.north_m, start.east_m, start.north_m);
  }
  std::lock_guard lock(mu_);
  if (routes_.size() >= kMaxCachedRoutes) routes_.clear();
  routes_.emplace(key, r);
  return r;
}

RoutePlanner ChartRouter(std::shared_ptr<ChartRouting> routing, StopToken stop) {
  return [routing = std::move(routing), stop = std::move(stop)](const RouteRequest& req) {
    return routing->Plan(req, stop);
  };
}

StatusOr<std::shared_ptr<ChartRouting>> ChartRoutingCache::Get(const std::string& chart_id,
                                                               const std::string& settings_key,
                                                               const ChartRouteSettings& settings) {
  const std::string key = absl::StrCat(chart_id, "|", settings_key);
  {
    std::lock_guard lock(mu_);
    if (auto it = routings_.find(key); it != routings_.end()) return it->second;
  }
  // Built outside the lock: loading a chart and its field takes a while and
  // must not hold up missions on other charts. Two first calls may both
  // build; the first stored wins.
  auto map = loader_(chart_id);
  if (!map.ok()) {
    if (absl::IsNotFound(map.status())) {
      return absl::FailedPreconditionError(absl::StrCat("spec.chart_id: ", map.status().message()));
    }
    return map.status();
  }
  auto planner = route::RoutePlanner::Create(*map, settings.ship, settings.options);
  if (!planner.ok()) {
    return absl::Status(planner.status().code(), absl::StrCat("routing over chart '", chart_id,
                                                              "': ", planner.status().message()));
  }
  auto routing = std::make_shared<ChartRouting>(
      (*map)->frame(), std::make_shared<const route::RoutePlanner>(std::move(*planner)),
      settings.environment);
  std::lock_guard lock(mu_);
  if (routings_.size() >= kMaxCachedRoutings) routings_.erase(routings_.begin());
  return routings_.emplace(key, std::move(routing)).first->second;
}

}  // namespace seaplan::mission
