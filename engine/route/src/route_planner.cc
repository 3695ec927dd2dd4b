#include "seaplan/route/route_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "seaplan/common/log.h"
#include "seaplan/ship/steady_state.h"

namespace seaplan::route {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

EastNorth ToVec(EastNorth p) {
  return {p.east_m, p.north_m};
}
EastNorth ToLocal(EastNorth p) {
  return {p.east_m, p.north_m};
}

std::vector<ObstaclePolygon> ToObstacles(const std::vector<chart::Polygon>& polygons) {
  std::vector<ObstaclePolygon> out;
  out.reserve(polygons.size());
  for (const chart::Polygon& poly : polygons) {
    ObstaclePolygon o;
    auto add = [&](const chart::Ring& ring) {
      if (ring.size() < 3) return;
      std::vector<EastNorth> r;
      r.reserve(ring.size());
      for (const auto& p : ring) r.push_back(ToVec(p));
      o.rings.push_back(std::move(r));
    };
    add(poly.outer);
    for (const auto& h : poly.holes) add(h);
    if (!o.rings.empty()) out.push_back(std::move(o));
  }
  return out;
}

// Where the nearest navigable point is, for an endpoint the route cannot
// start or end at: "; the nearest navigable point is 38.98012,-76.37955,
// 212 m away" (or why there is none).
std::string NearestNavigableHint(const chart::ObstacleMap& map, EastNorth p) {
  chart::ObstacleQuery query(map);
  const std::optional<EastNorth> q = query.NearestNavigable(p);
  if (!q) return "; the chart has no navigable water near it";
  const double distance_m = std::hypot(q->east_m - p.east_m, q->north_m - p.north_m);
  return absl::StrCat("; the nearest navigable point is ",
                      chart::FormatLatLon(map.frame().ToLatLon(*q)), ", ",
                      static_cast<int64_t>(std::lround(distance_m)), " m away");
}

// Positions in the user's latitude/longitude (the local frame is internal).
absl::Status CheckEndpoint(const chart::ObstacleMap& map, const ObstacleField& field, EastNorth p,
                           const char* name) {
  if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) {
    return absl::InvalidArgumentError(absl::StrCat(name, " is not a finite position"));
  }
  const std::string where = chart::FormatLatLon(map.frame().ToLatLon(p));
  if (!map.Covers(p)) {
    const chart::LocalBox box = map.summary().coverage;
    return absl::InvalidArgumentError(absl::StrCat(
        name, " ", where, " is outside the chart coverage (",
        chart::FormatLatLon(map.frame().ToLatLon(box.min)), " to ",
        chart::FormatLatLon(map.frame().ToLatLon(box.max)), ")", NearestNavigableHint(map, p)));
  }
  if (field.Inside(ToVec(p))) {
    const chart::ChartOptions& o = map.summary().options;
    return absl::InvalidArgumentError(absl::StrCat(
        name, " ", where, " lies inside a grounding obstacle (land or water under ", o.min_depth_m,
        " m, with the ", o.safety_buffer_m, " m safety buffer)", NearestNavigableHint(map, p)));
  }
  return absl::OkStatus();
}

}  // namespace

class RoutePlanner::QueryPool {
 public:
  explicit QueryPool(std::shared_ptr<const chart::ObstacleMap> map) : map_(std::move(map)) {}
  std::unique_ptr<chart::ObstacleQuery> Take() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (!free_.empty()) {
        std::unique_ptr<chart::ObstacleQuery> q = std::move(free_.back());
        free_.pop_back();
        return q;
      }
    }
    return std::make_unique<chart::ObstacleQuery>(*map_);
  }
  void Give(std::unique_ptr<chart::ObstacleQuery> q) {
    std::lock_guard<std::mutex> lock(mutex_);
    free_.push_back(std::move(q));
  }

 private:
  std::shared_ptr<const chart::ObstacleMap> map_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<chart::ObstacleQuery>> free_;
};

absl::Status Environment::Validate() const {
  for (double v : {wind_speed_mps, wind_from_deg, current_speed_mps, current_toward_deg}) {
    if (!std::isfinite(v)) return absl::InvalidArgumentError("environment values must be finite");
  }
  if (wind_speed_mps < 0 || wind_speed_mps > 100) {
    return absl::InvalidArgumentError(
        absl::StrCat("wind_speed_mps must be in [0, 100], got ", wind_speed_mps));
  }
  if (current_speed_mps < 0 || current_speed_mps > 20) {
    return absl::InvalidArgumentError(
        absl::StrCat("current_speed_mps must be in [0, 20], got ", current_speed_mps));
  }
  return absl::OkStatus();
}

absl::Status ShipParticulars::Validate() const {
  SEAPLAN_RETURN_IF_ERROR(hull.Validate());
  if (!(service_throttle > 0.0 && service_throttle <= 1.1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("service_throttle must be in (0, 1.1], got ", service_throttle));
  }
  if (!(service_speed_mps >= 0.0 && std::isfinite(service_speed_mps))) {
    return absl::InvalidArgumentError(
        absl::StrCat("service_speed_mps must be >= 0 and finite, got ", service_speed_mps));
  }
  return absl::OkStatus();
}

absl::Status RouteOptions::Validate() const {
  SEAPLAN_RETURN_IF_ERROR(level2.Validate());
  SEAPLAN_RETURN_IF_ERROR(alternatives.Validate());
  SEAPLAN_RETURN_IF_ERROR(risk.Validate());
  if (max_alternatives < 1 || max_alternatives > 64) {
    return absl::InvalidArgumentError(
        absl::StrCat("max_alternatives must be in [1, 64], got ", max_alternatives));
  }
  if (!(min_depth_m >= 0.0 && min_depth_m < 1000.0)) {
    return absl::InvalidArgumentError("min_depth_m must be in [0, 1000)");
  }
  if (!(field_cell_m >= 5.0 && field_cell_m <= 1000.0)) {
    return absl::InvalidArgumentError("field_cell_m must be in [5, 1000]");
  }
  return absl::OkStatus();
}

ship::Environment ToShipEnvironment(const Environment& env) {
  ship::Environment e = ship::Environment::WithCurrentToward(env.current_speed_mps,
                                                             env.current_toward_deg * kDegToRad);
  e.wind_speed_mps = env.wind_speed_mps;
  e.wind_direction_from_rad = env.wind_from_deg * kDegToRad;
  return e;
}

StatusOr<RoutePlanner> RoutePlanner::Create(std::shared_ptr<const chart::ObstacleMap> map,
                                            const ShipParticulars& ship,
                                            const RouteOptions& options) {
  if (map == nullptr) return absl::InvalidArgumentError("RoutePlanner needs a chart");
  SEAPLAN_RETURN_IF_ERROR(ship.Validate());
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  const double chart_depth = map->summary().options.min_depth_m;
  if (options.min_depth_m > chart_depth) {
    return absl::FailedPreconditionError(
        absl::StrCat("the chart's obstacles were built for a minimum depth of ", chart_depth,
                     " m but the route needs ", options.min_depth_m,
                     " m: reload the chart with min_depth_m >= ", options.min_depth_m));
  }
  RoutePlanner p;
  p.map_ = std::move(map);
  p.queries_ = std::make_shared<QueryPool>(p.map_);
  p.ship_ = ship;
  p.options_ = options;
  for (int m = 0; m < kModeCount; ++m) {
    const auto mode = static_cast<ship::MsoMode>(m);
    double throttle = ship.service_throttle;
    if (ship.service_speed_mps > 0.0) {
      // OutOfRange: the mode's top speed is below the ordered speed.
      const StatusOr<double> t =
          ship::ThrottleForSpeed(ship.hull, ship.machinery, mode, ship.service_speed_mps);
      throttle = t.ok() ? *t : 1.0;
    }
    const ship::OperatingPoint op =
        ship::CalmWaterOperatingPoint(ship.hull, ship.machinery, mode, throttle);
    p.speed_mps_[m] = op.speed_mps;
    p.fuel_kgps_[m] = op.fuel_rate.total_kgps();
    if (!(op.speed_mps > 0.1)) {
      return absl::InvalidArgumentError(
          absl::StrCat("mode ", std::string(ship::MsoModeName(static_cast<MsoMode>(m))),
                       " has no service speed at throttle ", throttle));
    }
  }
  const chart::LocalBox cov = p.map_->summary().coverage;
  ObstacleFieldOptions fo;
  // Large charts (a 1:80 000 ENC cell is ~50 x 80 km): coarser cells keep
  // the grid near 250k cells; queries stay exact, candidate lists get longer.
  const double area_m2 = (cov.max.east_m - cov.min.east_m + 2 * fo.margin_m) *
                         (cov.max.north_m - cov.min.north_m + 2 * fo.margin_m);
  fo.cell_m = std::max(options.field_cell_m, std::sqrt(std::max(area_m2, 0.0) / 250e3));
  fo.far_cutoff_m = std::min(3000.0, 30.0 / options.level2.weights.zeta1_per_m);
  fo.hull = {ship.hull.length_m, ship.hull.beam_m};
  SEAPLAN_ASSIGN_OR_RETURN(
      ObstacleField field,
      ObstacleField::Build(ToObstacles(p.map_->polygons()), ToVec(cov.min), ToVec(cov.max), fo));
  p.field_ = std::make_shared<const ObstacleField>(std::move(field));
  SEAPLAN_ASSIGN_OR_RETURN(risk::DriftingGroundingModel risk_model,
                           risk::DriftingGroundingModel::Create(options.risk));
  p.risk_model_ = std::make_shared<const risk::DriftingGroundingModel>(std::move(risk_model));
  return p;
}

StatusOr<RouteResult> RoutePlanner::Plan(chart::LatLon start, chart::LatLon goal,
                                         const Environment& env, const StopToken& stop) const {
  return Plan(map_->frame().ToLocal(start), map_->frame().ToLocal(goal), env, stop);
}

StatusOr<RouteResult> RoutePlanner::Plan(EastNorth start, EastNorth goal, const Environment& env,
                                         const StopToken& stop) const {
  SEAPLAN_RETURN_IF_ERROR(env.Validate());
  SEAPLAN_RETURN_IF_ERROR(CheckEndpoint(*map_, *field_, start, "start"));
  SEAPLAN_RETURN_IF_ERROR(CheckEndpoint(*map_, *field_, goal, "goal"));
  auto level1 = chart::PlanAlternatives(*map_, start, goal, options_.alternatives);
  if (!level1.ok()) {
    if (level1.status().code() == absl::StatusCode::kNotFound) {
      return absl::FailedPreconditionError(
          absl::StrCat("no safe route: ", level1.status().message()));
    }
    return level1.status();
  }
  if (level1->alternatives.empty())
    return absl::FailedPreconditionError("no safe route: Level 1 found none");

  DriftingGroundingAdapter grounding(*risk_model_);
  Level2Problem problem;
  problem.field = field_.get();
  problem.grounding = &grounding;
  problem.drift_ship = ship_.hull;
  problem.environment = ToShipEnvironment(env);
  const size_t count = std::min<size_t>(options_.max_alternatives, level1->alternatives.size());
  for (size_t a = 0; a < count; ++a) {
    std::vector<EastNorth> line;
    for (const auto& p : level1->alternatives[a].waypoints) line.push_back(ToVec(p));
    problem.alternatives.push_back(std::move(line));
  }
  Level2Options level2 = options_.level2;
  if (ship_.service_speed_mps > 0.0) {
    level2.sail_speed_mps = speed_mps_[static_cast<int>(MsoMode::kPto)];
  }
  SEAPLAN_ASSIGN_OR_RETURN(Level2Result l2, OptimizeLevel2(problem, level2, stop));

  RouteResult out;
  out.used_level1_fallback = level1->used_fallback;
  out.stopped = l2.stopped;
  out.evaluations = l2.evaluations;
  out.level2_wall_s = l2.wall_s;
  out.sail_speed_mps = level2.sail_check ? level2.sail_speed_mps : 0.0;
  out.chosen = l2.chosen;
  const CostWeights& w = options_.level2.weights;
  for (size_t a = 0; a < l2.alternatives.size(); ++a) {
    const AlternativeResult& src = l2.alternatives[a];
    RouteAlternative alt;
    alt.level1 = level1->alternatives[a].waypoints;
    alt.expected_cost = src.expected_cost;
    alt.mode_switches = src.mode_switches;
    alt.safe = !src.crosses_obstacle;
    alt.snapped_waypoints = src.snapped_waypoints;
    alt.inserted_waypoints = src.inserted_waypoints;
    alt.filleted_turns = src.filleted_turns;
    alt.tightened_turns = src.tightened_turns;
    const TurnFilletOptions fillet = options_.level2.Fillet();
    const std::string circle =
        fillet.min_radius_m > 0.0 && fillet.min_radius_m < fillet.radius_m
            ? absl::StrCat("a turning circle of ", std::lround(fillet.min_radius_m), " to ",
                           std::lround(fillet.radius_m), " m")
            : absl::StrCat("a ", std::lround(fillet.radius_m), " m turning circle");
    for (const UnsailableTurn& t : src.unsailable_turns) {
      alt.warnings.push_back(
          absl::StrCat("the turn of ", std::lround(std::abs(t.turn_rad) * 180.0 / M_PI), " deg at ",
                       chart::FormatLatLon(map_->frame().ToLatLon(ToLocal(t.corner))),
                       " cannot be sailed on ", circle, ": ",
                       t.legs_too_short ? "the legs either side are too short for it"
                                        : "the water is too narrow for it"));
    }
    if (src.sail_checked && !src.sailed_clear) {
      // The closed loop's track (step 6 of level2_optimizer.h): no candidate
      // route kept it out of the buffered obstacles.
      alt.warnings.push_back(absl::StrFormat(
          "the track this hull sails on the route (from rest at %.1f m/s) %s near %s",
          level2.sail_speed_mps,
          src.sailed_arrived ? absl::StrFormat("comes within the %.0f m safety margin",
                                               map_->summary().options.safety_buffer_m)
                             : std::string("does not reach the goal"),
          chart::FormatLatLon(map_->frame().ToLatLon(ToLocal(src.sailed_closest)))));
    }
    for (size_t k = 0; k < src.waypoints.size(); ++k) {
      const WaypointResult& wr = src.waypoints[k];
      RouteWaypoint rw;
      rw.local = ToLocal(wr.position);
      rw.latlon = map_->frame().ToLatLon(rw.local);
      rw.mode = wr.mode;
      rw.ttg_s = wr.ttg_s;
      const int m = static_cast<int>(wr.mode);
      rw.grounding_probability = wr.grounding_probability[m];
      rw.expected_grounding_cost = w.grounding_cost * rw.grounding_probability;
      if (k + 1 < src.waypoints.size()) {
        const EastNorth a0 = wr.position, a1 = src.waypoints[k + 1].position;
        rw.segment_length_m = std::hypot(a1.east_m - a0.east_m, a1.north_m - a0.north_m);
        rw.segment_time_s = rw.segment_length_m / speed_mps_[m];
        rw.segment_fuel_kg = rw.segment_time_s * fuel_kgps_[m];
        alt.expected_grounding_cost += rw.expected_grounding_cost;
      }
      alt.length_m += rw.segment_length_m;
      alt.sailing_time_s += rw.segment_time_s;
      alt.fuel_kg += rw.segment_fuel_kg;
      alt.waypoints.push_back(rw);
    }
    out.alternatives.push_back(std::move(alt));
  }
  // The exact check: every route against the obstacles as charted.
  const double margin_m = map_->summary().options.safety_buffer_m;
  std::string closest;  // the worst violation, for the error message
  double closest_m = std::numeric_limits<double>::infinity();
  {
    std::unique_ptr<chart::ObstacleQuery> query = queries_->Take();
    for (RouteAlternative& alt : out.alternatives) {
      std::vector<EastNorth> line;
      line.reserve(alt.waypoints.size());
      for (const RouteWaypoint& wp : alt.waypoints) line.push_back(wp.local);
      const std::optional<chart::Clearance> c = query->UnbufferedClearance(line);
      if (!c) {
        alt.clearance_m = std::numeric_limits<double>::quiet_NaN();
        if (query->PolylineHits(line)) alt.safe = false;
        continue;
      }
      alt.clearance_m = c->distance_m;
      // 1 mm of slack for the rounding of GEOS distances.
      if (c->distance_m < margin_m - 1e-3) {
        alt.safe = false;
        if (c->distance_m < closest_m) {
          closest_m = c->distance_m;
          closest = chart::FormatLatLon(map_->frame().ToLatLon(c->route_point));
        }
      }
    }
    queries_->Give(std::move(query));
  }
  if (out.chosen >= 0 && !out.alternatives[out.chosen].safe) {
    out.chosen = -1;
    for (size_t a = 0; a < out.alternatives.size(); ++a) {
      if (out.alternatives[a].safe &&
          (out.chosen < 0 ||
           out.alternatives[a].expected_cost < out.alternatives[out.chosen].expected_cost)) {
        out.chosen = static_cast<int>(a);
      }
    }
  }
  log::Info("route: {} alternatives, chosen {}, {} evaluations, level-2 {:.3f} s",
            out.alternatives.size(), out.chosen, out.evaluations, out.level2_wall_s);
  if (out.chosen < 0 && !out.stopped) {
    if (!closest.empty()) {
      return absl::FailedPreconditionError(absl::StrCat(
          "no safe route: the best route passes ", std::round(closest_m * 10.0) / 10.0,
          " m from a charted obstacle at ", closest, " (safety buffer ", margin_m, " m)"));
    }
    return absl::FailedPreconditionError(
        "no safe route: every optimised alternative touches a grounding obstacle");
  }
  return out;
}

StatusOr<std::vector<PointRisk>> RoutePlanner::EstimateRisk(const std::vector<TrackPoint>& track,
                                                            const Environment& env) const {
  SEAPLAN_RETURN_IF_ERROR(env.Validate());
  const ship::Environment senv = ToShipEnvironment(env);
  DriftingGroundingAdapter grounding(*risk_model_);
  std::vector<EastNorth> local;
  for (size_t i = 0; i < track.size(); ++i) {
    const EastNorth p = map_->frame().ToLocal(track[i].latlon);
    if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) {
      return absl::InvalidArgumentError(
          absl::StrCat("track point ", i, " is not a valid position"));
    }
    local.push_back(ToVec(p));
  }
  std::vector<PointRisk> out;
  for (size_t i = 0; i < track.size(); ++i) {
    const TrackPoint& t = track[i];
    double heading = 0.0;
    if (t.heading_deg) {
      heading = *t.heading_deg * kDegToRad;
    } else if (track.size() > 1) {
      const EastNorth a = local[i + 1 < local.size() ? i : i - 1],
                      b = local[i + 1 < local.size() ? i + 1 : i];
      heading = std::atan2(b.east_m - a.east_m, b.north_m - a.north_m);
    }
    const double speed = t.speed_mps.value_or(options_.level2.drift_initial_speed_mps);
    if (!(speed >= 0 && speed < 50)) {
      return absl::InvalidArgumentError(
          absl::StrCat("track point ", i, " speed must be in [0, 50) m/s"));
    }
    SEAPLAN_ASSIGN_OR_RETURN(
        double ttg,
        SimulateTimeToGrounding(*field_, ship_.hull, senv, local[i], heading, speed,
                                options_.level2.ttg_horizon_s, options_.level2.ttg_step_s));
    PointRisk r;
    r.mode = t.mode.value_or(MsoMode::kPto);
    r.ttg_s = ttg;
    r.grounding_probability = grounding.Probabilities(ttg)[static_cast<int>(r.mode)];
    r.expected_cost = options_.level2.weights.grounding_cost * r.grounding_probability;
    out.push_back(r);
  }
  return out;
}

namespace {
std::shared_ptr<const chart::ObstacleMap> Borrow(const chart::ObstacleMap& map) {
  return std::shared_ptr<const chart::ObstacleMap>(&map, [](const chart::ObstacleMap*) {});
}
}  // namespace

StatusOr<RouteResult> PlanRoute(const chart::ObstacleMap& map, chart::LatLon start,
                                chart::LatLon goal, const ShipParticulars& ship,
                                const Environment& env, const RouteOptions& options,
                                const StopToken& stop) {
  SEAPLAN_ASSIGN_OR_RETURN(RoutePlanner planner, RoutePlanner::Create(Borrow(map), ship, options));
  return planner.Plan(start, goal, env, stop);
}

StatusOr<std::vector<PointRisk>> EstimateRisk(const chart::ObstacleMap& map,
                                              const std::vector<TrackPoint>& track,
                                              const ShipParticulars& ship, const Environment& env,
                                              const RouteOptions& options) {
  SEAPLAN_ASSIGN_OR_RETURN(RoutePlanner planner, RoutePlanner::Create(Borrow(map), ship, options));
  return planner.EstimateRisk(track, env);
}

}  // namespace seaplan::route
