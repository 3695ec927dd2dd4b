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

EastNorth Along(double course_rad, double distance_m) {
  return {distance_m * std::sin(course_rad), distance_m * std::cos(course_rad)};
}

// The turn from course a to course b, either way, in [0, pi].
double TurnBetween(double a_rad, double b_rad) {
  return std::abs(std::remainder(b_rad - a_rad, 2.0 * M_PI));
}

// The course of the route's first leg (from its first waypoint to the first
// one at least 1 m away); nullopt for a route that does not move.
std::optional<double> FirstCourse(const Route& r) {
  if (r.waypoints.empty()) return std::nullopt;
  const EastNorth a = r.waypoints.front().position;
  for (const RouteWaypoint& w : r.waypoints) {
    const EastNorth d = w.position - a;
    if (d.Norm() >= 1.0) return std::atan2(d.east_m, d.north_m);
  }
  return std::nullopt;
}

}  // namespace

Status LeadInOptions::Validate() const {
  if (!(reaction_time_s >= 0) || !(turn_radius_m > 0) ||
      !(max_join_turn_rad > 0 && max_join_turn_rad <= M_PI)) {
    return absl::InvalidArgumentError(
        "lead-in: reaction_time_s must be >= 0, turn_radius_m > 0 and max_join_turn_rad in (0, "
        "pi]");
  }
  return absl::OkStatus();
}

std::vector<LeadIn> LeadInCandidates(EastNorth from, const ShipMotion& motion,
                                     double join_course_rad, const LeadInOptions& options) {
  const double psi = motion.course_rad;
  const double reaction_m = std::max(0.0, motion.speed_mps) * options.reaction_time_s;
  const double radius_m = options.turn_radius_m;
  std::vector<LeadIn> out;
  for (double k : {0.0, 1.0, 2.0, 4.0}) {
    const double d = reaction_m + k * radius_m;
    if (d < 1.0) continue;
    out.push_back({{from, from + Along(psi, d)}, psi, d});
  }
  constexpr double kArcStepRad = 10.0 * M_PI / 180.0;
  for (double side : {1.0, -1.0}) {  // starboard (clockwise), port
    const double turn = std::fmod(side * (join_course_rad - psi) + 4.0 * M_PI, 2.0 * M_PI);
    if (turn < 1e-6) continue;
    LeadIn c;
    c.points.push_back(from);
    const EastNorth start = from + Along(psi, reaction_m);
    if (reaction_m >= 1.0) c.points.push_back(start);
    const EastNorth centre = start + Along(psi + side * M_PI / 2, radius_m);
    const int steps = static_cast<int>(std::ceil(turn / kArcStepRad));
    for (int j = 1; j <= steps; ++j) {
      const double heading = psi + side * turn * j / steps;
      c.points.push_back(centre - Along(heading + side * M_PI / 2, radius_m));
    }
    c.end_course_rad = join_course_rad;
    c.length_m = reaction_m + radius_m * turn;
    out.push_back(std::move(c));
  }
  return out;
}

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
                           route::Environment environment, LeadInOptions lead_in)
    : frame_(frame), planner_(std::move(planner)), environment_(environment), lead_in_(lead_in) {}

StatusOr<Route> ChartRouting::Plan(const RouteRequest& req, const StopToken& stop) {
  if (req.start_motion && req.start_motion->speed_mps > 0) return PlanUnderWay(req, stop);
  return PlanFromRest(req, stop);
}

bool ChartRouting::TrackClear(const std::vector<EastNorth>& track, double floor_m) const {
  constexpr double kSampleM = 10.0;
  constexpr double kSlackM = 1.0;
  const route::ObstacleField& field = planner_->field();
  for (size_t i = 0; i + 1 < track.size(); ++i) {
    const EastNorth d = track[i + 1] - track[i];
    const int n = std::max(1, static_cast<int>(std::ceil(d.Norm() / kSampleM)));
    for (int j = 1; j <= n; ++j) {
      if (field.SignedDistance(track[i] + d * (static_cast<double>(j) / n)) < floor_m - kSlackM)
        return false;
    }
  }
  return true;
}

StatusOr<Route> ChartRouting::PlanUnderWay(const RouteRequest& req, const StopToken& stop) {
  const ShipMotion motion = *req.start_motion;
  RouteRequest from_rest = req;
  from_rest.start_motion.reset();
  StatusOr<Route> direct = PlanFromRest(from_rest, stop);
  if (!direct.ok() && !absl::IsFailedPrecondition(direct.status())) return direct;
  const EastNorth from = req.from_position;
  const EastNorth to_goal = req.to_position - from;
  double join_course = std::atan2(to_goal.east_m, to_goal.north_m);
  if (direct.ok()) {
    const std::optional<double> first = FirstCourse(*direct);
    if (!first || TurnBetween(motion.course_rad, *first) <= lead_in_.max_join_turn_rad) {
      return direct;
    }
    join_course = *first;
  }
  // Never deeper into the safety buffer than the ship already is.
  const double floor_m = std::min(0.0, planner_->field().SignedDistance(from));
  std::optional<Route> best;
  for (const LeadIn& c : LeadInCandidates(from, motion, join_course, lead_in_)) {
    const EastNorth end = c.points.back();
    if (planner_->field().Inside(end) || !TrackClear(c.points, floor_m)) continue;
    RouteRequest rest = from_rest;
    rest.from_position = end;
    StatusOr<Route> r = PlanFromRest(rest, stop);
    if (!r.ok()) {
      if (stop.StopRequested()) return StoppedStatus(stop);
      continue;
    }
    const std::optional<double> first = FirstCourse(*r);
    if (first && TurnBetween(c.end_course_rad, *first) > lead_in_.max_join_turn_rad) continue;
    if (best && best->length_m <= c.length_m + r->length_m) continue;
    for (size_t i = c.points.size() - 1; i-- > 0;) PrependWayOut(c.points[i], &*r);
    best = std::move(*r);
  }
  if (!best) {
    log::Warn(
        "route from ({:.0f}, {:.0f}) under way on {:.0f} deg: no lead-in keeps clear of the "
        "obstacles; the route turns {:.0f} deg at its start",
        from.east_m, from.north_m, motion.course_rad * 180 / M_PI,
        TurnBetween(motion.course_rad, join_course) * 180 / M_PI);
    return direct;
  }
  log::Info("route from ({:.0f}, {:.0f}) under way on {:.0f} deg starts with a {:.0f} m lead-in",
            from.east_m, from.north_m, motion.course_rad * 180 / M_PI,
            best->waypoints.empty() ? 0.0 : best->length_m);
  return std::move(*best);
}

StatusOr<Route> ChartRouting::PlanFromRest(const RouteRequest& req, const StopToken& stop) {
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
          "start ", chart::FormatLatLon(frame_.ToLatLon(from)),
          " lies inside a grounding obstacle with no free water within ", kMaxWayOutM, " m"));
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

void ChartRoutingCache::Forget(const std::string& chart_id) {
  const std::string prefix = absl::StrCat(chart_id, "|");
  std::lock_guard lock(mu_);
  std::erase_if(routings_, [&](const auto& entry) { return entry.first.starts_with(prefix); });
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
  if (Status st = settings.lead_in.Validate(); !st.ok()) return st;
  auto planner = route::RoutePlanner::Create(*map, settings.ship, settings.options);
  if (!planner.ok()) {
    return absl::Status(planner.status().code(), absl::StrCat("routing over chart '", chart_id,
                                                              "': ", planner.status().message()));
  }
  auto routing = std::make_shared<ChartRouting>(
      (*map)->frame(), std::make_shared<const route::RoutePlanner>(std::move(*planner)),
      settings.environment, settings.lead_in);
  std::lock_guard lock(mu_);
  if (routings_.size() >= kMaxCachedRoutings) routings_.erase(routings_.begin());
  return routings_.emplace(key, std::move(routing)).first->second;
}

}  // namespace seaplan::mission
