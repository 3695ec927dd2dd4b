#include "server/core/route_handlers.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>

#include "absl/strings/str_cat.h"
#include "seaplan/chart/geojson.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/convert/mission_convert.h"
#include "seaplan/mission/chart_routing.h"
#include "seaplan/route/route_planner.h"
#include "server/core/convert.h"
#include "server/core/route_convert.h"

namespace seaplan::server {
namespace {

v1::MsoMode ModeToProto(route::MsoMode m) {
  switch (m) {
    case route::MsoMode::kPto:
      return v1::MSO_MODE_PTO;
    case route::MsoMode::kMec:
      return v1::MSO_MODE_MEC;
    case route::MsoMode::kPti:
      return v1::MSO_MODE_PTI;
  }
  return v1::MSO_MODE_UNSPECIFIED;
}

std::optional<route::MsoMode> ModeFromProto(v1::MsoMode m) {
  switch (m) {
    case v1::MSO_MODE_PTO:
      return route::MsoMode::kPto;
    case v1::MSO_MODE_MEC:
      return route::MsoMode::kMec;
    case v1::MSO_MODE_PTI:
      return route::MsoMode::kPti;
    default:
      return std::nullopt;
  }
}

v1::LatLon LatLonToProto(const chart::LatLon& p) {
  v1::LatLon out;
  out.set_latitude_deg(p.lat_deg);
  out.set_longitude_deg(p.lon_deg);
  return out;
}

}  // namespace

route::ShipParticulars ShipToEngine(const v1::ShipParticulars& p) {
  route::ShipParticulars ship;
  if (p.length_m() > 0) ship.hull.length_m = p.length_m();
  if (p.beam_m() > 0) ship.hull.beam_m = p.beam_m();
  if (p.displacement_t() > 0) ship.hull.mass_override_kg = p.displacement_t() * 1000.0;
  if (p.service_speed_mps() > 0) ship.service_speed_mps = p.service_speed_mps();
  return ship;
}

route::Environment EnvironmentToEngine(const v1::Environment& e) {
  route::Environment env;
  env.wind_speed_mps = e.wind_speed_mps();
  env.wind_from_deg = e.wind_from_deg();
  env.current_speed_mps = e.current_speed_mps();
  env.current_toward_deg = std::fmod(e.current_from_deg() + 180.0, 360.0);
  return env;
}

route::RouteOptions OptionsToEngine(const v1::OptimizerOptions& o) {
  route::RouteOptions r;
  auto& l2 = r.level2;
  if (o.segments() > 0) l2.segments = o.segments();
  if (o.particles() > 0) l2.pso.particles = o.particles();
  if (o.iterations() > 0) l2.pso.iterations = o.iterations();
  if (o.inertia() != 0) l2.pso.inertia = o.inertia();
  if (o.cognitive() != 0) l2.pso.cognitive = o.cognitive();
  if (o.social() != 0) l2.pso.social = o.social();
  if (o.velocity_limit() != 0) l2.pso.velocity_limit = o.velocity_limit();
  l2.pso.seed = o.random_seed() != 0 ? o.random_seed() : 1;
  if (o.ttg_horizon_s() > 0) l2.ttg_horizon_s = o.ttg_horizon_s();
  if (o.safety_distance_m() > 0) r.alternatives.margin_m = o.safety_distance_m();
  const v1::CostWeights& w = o.weights();
  if (w.path_deviation() != 0) l2.weights.mu1_per_m2 = w.path_deviation();
  if (w.segment_balance() != 0) l2.weights.mu2_per_m6 = w.segment_balance();
  if (w.obstacle_proximity() != 0) l2.weights.mu3 = w.obstacle_proximity();
  if (w.grounding_risk() != 0) l2.weights.mu4 = w.grounding_risk();
  if (w.fuel() != 0) l2.weights.mu5_per_m = w.fuel();
  if (w.proximity_decay_per_m() != 0) l2.weights.zeta1_per_m = w.proximity_decay_per_m();
  if (w.grounding_cost() != 0) l2.weights.grounding_cost = w.grounding_cost();
  if (w.mode_switch_cost() != 0) l2.weights.mode_switch_cost = w.mode_switch_cost();
  return r;
}

namespace {

v1::RouteAlternative AlternativeToProto(const route::RouteAlternative& a, int index,
                                        double horizon_s) {
  v1::RouteAlternative out;
  out.set_index(index);
  double distance = 0, eta = 0, max_p = 0;
  for (const auto& wp : a.waypoints) {
    v1::RouteWaypoint* w = out.add_waypoints();
    *w->mutable_position() = LatLonToProto(wp.latlon);
    w->set_mode(ModeToProto(wp.mode));
    w->set_time_to_grounding_s(wp.ttg_s);
    w->set_grounds_within_horizon(wp.ttg_s < horizon_s);
    w->set_grounding_probability(wp.grounding_probability);
    w->set_expected_grounding_cost(wp.expected_grounding_cost);
    w->set_fuel_kg(wp.segment_fuel_kg);
    w->set_distance_from_start_m(distance);
    w->set_eta_s(eta);
    distance += wp.segment_length_m;
    eta += wp.segment_time_s;
    max_p = std::max(max_p, wp.grounding_probability);
  }
  out.set_length_m(a.length_m);
  out.set_sailing_time_s(a.sailing_time_s);
  out.set_fuel_kg(a.fuel_kg);
  out.set_expected_grounding_cost(a.expected_grounding_cost);
  out.set_total_cost(a.expected_cost);
  out.set_max_grounding_probability(max_p);
  for (const std::string& warning : a.warnings) out.add_warnings(warning);
  return out;
}

}  // namespace

absl::StatusOr<std::shared_ptr<const chart::ObstacleMap>> LoadMap(storage::ChartRepository& charts,
                                                                  const std::string& id) {
  SEAPLAN_ASSIGN_OR_RETURN(storage::ChartRecord record, charts.Get(id, /*with_blobs=*/true));
  auto map = chart::DeserializeObstacleMap(record.obstacles);
  if (!map.ok()) {
    return absl::DataLossError(absl::StrCat("stored obstacles of chart '", id,
                                            "' are unreadable: ", map.status().message()));
  }
  return std::make_shared<const chart::ObstacleMap>(std::move(*map));
}

namespace {

absl::Status CheckLatLon(const v1::LatLon& p, const char* field) {
  if (!std::isfinite(p.latitude_deg()) || !std::isfinite(p.longitude_deg()) ||
      std::abs(p.latitude_deg()) > 90 || std::abs(p.longitude_deg()) > 180) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": not a WGS84 position (",
                                                   p.latitude_deg(), ", ", p.longitude_deg(), ")"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<v1::PlanRouteResponse> RouteHandlers::PlanRoute(const v1::PlanRouteRequest& request,
                                                               const CallContext& ctx) {
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  SEAPLAN_RETURN_IF_ERROR(CheckLatLon(request.start(), "start"));
  SEAPLAN_RETURN_IF_ERROR(CheckLatLon(request.goal(), "goal"));
  route::RouteOptions options = OptionsToEngine(request.options());
  route::ShipParticulars ship = ShipToEngine(request.ship());
  route::Environment env = EnvironmentToEngine(request.environment());
  if (absl::Status st = options.Validate(); !st.ok())
    return absl::InvalidArgumentError(absl::StrCat("options: ", st.message()));
  if (absl::Status st = ship.Validate(); !st.ok())
    return absl::InvalidArgumentError(absl::StrCat("ship: ", st.message()));
  if (absl::Status st = env.Validate(); !st.ok())
    return absl::InvalidArgumentError(absl::StrCat("environment: ", st.message()));
  double time_limit_s = 30.0;  // documented default of OptimizerOptions.time_limit
  if (request.options().has_time_limit()) {
    SEAPLAN_ASSIGN_OR_RETURN(double s,
                             DurationSeconds(request.options().time_limit(), "options.time_limit"));
    if (s > 0) time_limit_s = s;
  }
  if (time_limit_s > budgets_.max_route_time_s) {
    return absl::InvalidArgumentError(absl::StrCat("options.time_limit: ", time_limit_s,
                                                   " s is more than this server allows (",
                                                   budgets_.max_route_time_s, " s)"));
  }
  const long long evaluations = static_cast<long long>(options.level2.pso.particles) *
                                static_cast<long long>(options.level2.pso.iterations);
  if (evaluations > budgets_.max_route_evaluations) {
    return absl::InvalidArgumentError(
        absl::StrCat("options: particles x iterations = ", evaluations,
                     " is more than this server allows (", budgets_.max_route_evaluations, ")"));
  }
  SEAPLAN_ASSIGN_OR_RETURN(auto map, LoadMap(charts_, request.chart_id()));
  // The optimiser's own budget is a child of the call's token: the client's
  // deadline or cancellation still wins.
  const StopToken budget = ctx.stop.Child(StopToken::Clock::now() +
                                          std::chrono::duration_cast<StopToken::Clock::duration>(
                                              std::chrono::duration<double>(time_limit_s)));
  const chart::LatLon start{request.start().latitude_deg(), request.start().longitude_deg()};
  const chart::LatLon goal{request.goal().latitude_deg(), request.goal().longitude_deg()};
  absl::StatusOr<route::RouteResult> result = absl::UnknownError("route planner did not run");
  const auto started = std::chrono::steady_clock::now();
  SEAPLAN_RETURN_IF_ERROR(
      pool_.Run([&] { result = route::PlanRoute(*map, start, goal, ship, env, options, budget); },
                ctx.stop, [&] { ctx.ForwardCancellation(); }));
  if (ctx.stop.StopRequested())
    return StopStatus(ctx.stop, root_.StopRequested(), "route planning");
  if (!result.ok()) return result.status();
  v1::PlanRouteResponse response;
  const double horizon = options.level2.ttg_horizon_s;
  for (std::size_t i = 0; i < result->alternatives.size(); ++i) {
    *response.add_alternatives() =
        AlternativeToProto(result->alternatives[i], static_cast<int>(i), horizon);
  }
  response.set_chosen_alternative(result->chosen);
  if (result->chosen >= 0 && result->chosen < response.alternatives_size()) {
    *response.mutable_chosen_route() = response.alternatives(result->chosen);
    convert::AddModeSchedule(
        mission::RouteFromAlternative(
            result->alternatives[static_cast<std::size_t>(result->chosen)], result->chosen),
        response.mutable_mode_schedule());
  }
  if (request.options().include_obstacles_geojson()) {
    // The map for the operator: obstacles plus every alternative, the chosen one named so.
    std::vector<chart::NamedRoute> routes;
    for (std::size_t i = 0; i < result->alternatives.size(); ++i) {
      chart::NamedRoute named;
      named.name =
          absl::StrCat("alternative ", i, static_cast<int>(i) == result->chosen ? " (chosen)" : "");
      for (const auto& waypoint : result->alternatives[i].waypoints)
        named.waypoints.push_back(waypoint.local);
      routes.push_back(std::move(named));
    }
    response.set_obstacles_geojson(chart::ToGeoJson(*map, routes));
  }
  response.set_computation_time_s(
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
  return response;
}

absl::StatusOr<v1::EstimateRiskResponse> RouteHandlers::EstimateRisk(
    const v1::EstimateRiskRequest& request, const CallContext& ctx) {
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  if (request.track_size() == 0) return absl::InvalidArgumentError("track: no track point");
  for (int i = 0; i < request.track_size(); ++i) {
    SEAPLAN_RETURN_IF_ERROR(CheckLatLon(request.track(i).position(), "track[].position"));
  }
  if (request.ttg_horizon_s() < 0)
    return absl::InvalidArgumentError("ttg_horizon_s must not be negative");
  SEAPLAN_ASSIGN_OR_RETURN(auto map, LoadMap(charts_, request.chart_id()));
  route::RouteOptions options;
  if (request.ttg_horizon_s() > 0) options.level2.ttg_horizon_s = request.ttg_horizon_s();
  route::ShipParticulars ship = ShipToEngine(request.ship());
  route::Environment env = EnvironmentToEngine(request.environment());
  std::vector<route::TrackPoint> track;
  for (const auto& p : request.track()) {
    route::TrackPoint t;
    t.latlon = {p.position().latitude_deg(), p.position().longitude_deg()};
    if (p.has_heading_deg()) t.heading_deg = p.heading_deg();
    if (p.has_speed_mps()) t.speed_mps = p.speed_mps();
    t.mode = ModeFromProto(p.mode());
    track.push_back(t);
  }
  absl::StatusOr<std::vector<route::PointRisk>> risks =
      absl::UnknownError("risk estimation did not run");
  SEAPLAN_RETURN_IF_ERROR(
      pool_.Run([&] { risks = route::EstimateRisk(*map, track, ship, env, options); }, ctx.stop,
                [&] { ctx.ForwardCancellation(); }));
  if (ctx.stop.StopRequested())
    return StopStatus(ctx.stop, root_.StopRequested(), "risk estimation");
  if (!risks.ok()) return risks.status();
  v1::EstimateRiskResponse response;
  double total = 0, max_p = 0;
  for (std::size_t i = 0; i < risks->size(); ++i) {
    const route::PointRisk& r = (*risks)[i];
    v1::RiskPoint* out = response.add_points();
    *out->mutable_position() = request.track(static_cast<int>(i)).position();
    out->set_time_to_grounding_s(r.ttg_s);
    out->set_grounds_within_horizon(r.ttg_s < options.level2.ttg_horizon_s);
    out->set_grounding_probability(r.grounding_probability);
    out->set_expected_cost(r.expected_cost);
    v1::ModeRisk* mode = out->add_per_mode();
    mode->set_mode(ModeToProto(r.mode));
    mode->set_grounding_probability(r.grounding_probability);
    mode->set_expected_cost(r.expected_cost);
    total += r.expected_cost;
    max_p = std::max(max_p, r.grounding_probability);
  }
  response.set_total_expected_cost(total);
  response.set_max_grounding_probability(max_p);
  return response;
}

}  // namespace seaplan::server
