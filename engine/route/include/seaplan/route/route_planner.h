// Route planner facade: chart + start/goal + ship + weather -> risk-aware
// route alternatives with MSO modes, sailing time, fuel and expected cost.
//
// PlanRoute = Level-1 alternatives (chart::PlanAlternatives, Algorithm A1)
//           + Level-2 optimisation of each (level2_optimizer.h), repaired
//             where a segment would cut an obstacle, so an optimised route
//             exists whenever Level 1 finds one
//           + an exact clearance check of every optimised route against the
//             chart's unbuffered obstacles (GEOS): it must keep the chart's
//             safety buffer
//           + choice of the safe alternative with the lowest expected cost
//             (fuel + grounding risk + mode switches).
// The mission loop calls it for every move of a plan to learn its sailing
// time. A RoutePlanner keeps the obstacle field (the expensive part that
// depends only on chart and ship) for repeated calls.
//
// Sign conventions (Environment): wind_from_deg is where the wind comes FROM,
// current_toward_deg where the water flows TOWARD (nautical "set"), both
// degrees clockwise from north. The public code of paper 002 feeds one angle
// (-110 deg) to both: wind from -110 deg and water moving toward -110 deg.
//
// Thread-safety: RoutePlanner is immutable after Create; Plan/EstimateRisk
// may run concurrently (each call uses its own threads and scratch).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "seaplan/chart/alternatives.h"
#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/route/grounding_risk.h"
#include "seaplan/route/level2_optimizer.h"
#include "seaplan/route/obstacle_field.h"
#include "seaplan/ship/machinery.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::route {

struct Environment {
  double wind_speed_mps = 0.0;
  double wind_from_deg = 0.0;
  double current_speed_mps = 0.0;
  double current_toward_deg = 0.0;
  absl::Status Validate() const;
};

struct ShipParticulars {
  ship::ShipParams hull;            // drift dynamics; length/beam = grounding footprint
  ship::MachineryParams machinery;  // fuel and speed per mode
  // Sailing speed and fuel per mode come from engine/ship's calm-water
  // steady state at this throttle (0.8: SITS example, PTO 9.15 m/s,
  // MEC 9.84 m/s, PTI 4.62 m/s).
  double service_throttle = 0.8;
  // Planning speed through the water, m/s; 0 = the speeds at
  // service_throttle. When set, each mode sails at the throttle that holds
  // this speed in calm water, or at its top speed where it cannot (fuel per
  // mode follows), so route times match the ship's ordered speed.
  double service_speed_mps = 0.0;
  absl::Status Validate() const;
};

struct RouteOptions {
  Level2Options level2;
  chart::AlternativesOptions alternatives;
  // Level-1 alternatives optimised (shortest first; paper: 2).
  int max_alternatives = 2;
  risk::DriftingGroundingParams risk;  // engine/risk event trees (Tables 2-4)
  // Minimum depth the route needs, metres; 0 = accept the chart's. The
  // obstacles are fixed when the chart is loaded (ChartOptions::min_depth_m),
  // so a chart loaded for a shallower depth is FailedPrecondition.
  double min_depth_m = 0.0;
  // Obstacle-field grid cell, metres (grown automatically on large charts).
  double field_cell_m = 50.0;
  absl::Status Validate() const;
};

struct RouteWaypoint {
  chart::LatLon latlon;
  EastNorth local;
  // For the segment from this waypoint to the next (the goal repeats the last).
  MsoMode mode = MsoMode::kPto;
  double ttg_s = 0.0;
  double grounding_probability = 0.0;    // P(G) in `mode`
  double expected_grounding_cost = 0.0;  // C_G * P(G) (cost units of CostWeights)
  double segment_length_m = 0.0;
  double segment_time_s = 0.0;
  double segment_fuel_kg = 0.0;
};

struct RouteAlternative {
  std::vector<EastNorth> level1;         // the A1 polyline it started from
  std::vector<RouteWaypoint> waypoints;  // start .. goal (segments + 1)
  double length_m = 0.0;
  double sailing_time_s = 0.0;
  double fuel_kg = 0.0;
  double expected_cost = 0.0;            // objective used for the choice
  double expected_grounding_cost = 0.0;  // sum of C_G P(G)
  int mode_switches = 0;
  // No waypoint or segment touches an obstacle, and the route keeps the
  // chart's safety buffer from the unbuffered obstacles (exact GEOS check).
  bool safe = true;
  // Distance from the unbuffered obstacles, metres (+infinity: none; NaN:
  // unknown, the chart was stored without them and only the buffered
  // obstacles were checked).
  double clearance_m = 0.0;
  // Level-2 safety repair (level2_optimizer.h): waypoints put back on the
  // Level-1 path, Level-1 vertices inserted.
  int snapped_waypoints = 0;
  int inserted_waypoints = 0;
  // Corners replaced by fillets round the ship's turning circle
  // (Level2Options::fillet_turns), and one warning per corner the hull
  // cannot sail that could not be (where, how sharp, why), and one when
  // the track the hull sails on the route comes within the safety margin
  // (Level2Options::sail_check; where).
  int filleted_turns = 0;
  int tightened_turns = 0;  // of those, on a circle smaller than the fillet radius
  std::vector<std::string> warnings;
};

struct RouteResult {
  std::vector<RouteAlternative> alternatives;
  int chosen = -1;
  bool used_level1_fallback = false;
  bool stopped = false;  // the StopToken fired; results are partial
  int64_t evaluations = 0;
  double level2_wall_s = 0.0;
  // The speed step 6 sailed the routes at (0: no sail check): the PTO
  // planning speed when the ship has a service speed (the speed the route
  // is ordered for, PTO the mode most segments sail in), else
  // level2.sail_speed_mps.
  double sail_speed_mps = 0.0;
};

struct TrackPoint {
  chart::LatLon latlon;
  std::optional<double> heading_deg;  // default: toward the next point
  std::optional<double> speed_mps;    // default: level2.drift_initial_speed_mps
  std::optional<MsoMode> mode;        // default: PTO
};

struct PointRisk {
  MsoMode mode = MsoMode::kPto;
  double ttg_s = 0.0;
  double grounding_probability = 0.0;
  double expected_cost = 0.0;  // C_G * P(G)
};

class RoutePlanner {
 public:
  // Errors: InvalidArgument (bad options/ship), FailedPrecondition (chart
  // loaded for a shallower minimum depth than options.min_depth_m).
  static StatusOr<RoutePlanner> Create(std::shared_ptr<const chart::ObstacleMap> map,
                                       const ShipParticulars& ship, const RouteOptions& options);

  // Errors: InvalidArgument when start or goal is outside the chart coverage
  // or inside an obstacle (the message says which, in latitude/longitude,
  // with the nearest navigable point and its distance); FailedPrecondition
  // when no safe route exists.
  StatusOr<RouteResult> Plan(EastNorth start, EastNorth goal, const Environment& env,
                             const StopToken& stop = StopToken()) const;
  StatusOr<RouteResult> Plan(chart::LatLon start, chart::LatLon goal, const Environment& env,
                             const StopToken& stop = StopToken()) const;
  // Grounding risk along a track (e.g. a planned or sailed route).
  StatusOr<std::vector<PointRisk>> EstimateRisk(const std::vector<TrackPoint>& track,
                                                const Environment& env) const;

  const ObstacleField& field() const { return *field_; }
  const RouteOptions& options() const { return options_; }

 private:
  RoutePlanner() = default;
  // GEOS query objects (one per concurrent Plan) for the final clearance
  // check, kept between calls: building one copies the chart's geometry.
  class QueryPool;
  std::shared_ptr<const chart::ObstacleMap> map_;
  std::shared_ptr<QueryPool> queries_;
  std::shared_ptr<const ObstacleField> field_;
  ShipParticulars ship_;
  RouteOptions options_;
  std::shared_ptr<const risk::DriftingGroundingModel> risk_model_;
  ModeArray speed_mps_{};
  ModeArray fuel_kgps_{};
};

// One-shot helpers (build the field each call; prefer RoutePlanner in loops).
StatusOr<RouteResult> PlanRoute(const chart::ObstacleMap& map, chart::LatLon start,
                                chart::LatLon goal, const ShipParticulars& ship,
                                const Environment& env, const RouteOptions& options,
                                const StopToken& stop = StopToken());
StatusOr<std::vector<PointRisk>> EstimateRisk(const chart::ObstacleMap& map,
                                              const std::vector<TrackPoint>& track,
                                              const ShipParticulars& ship, const Environment& env,
                                              const RouteOptions& options);

// The ship::Environment the drift model uses (angles converted, current split).
ship::Environment ToShipEnvironment(const Environment& env);

}  // namespace seaplan::route
