#include "seaplan/ship/steady_state.h"

#include <cmath>
#include <string>

#include "absl/strings/str_cat.h"
#include "seaplan/ship/control.h"
#include "seaplan/ship/ship_model.h"

namespace seaplan::ship {
namespace {

// Surge resistance F(u) = lin u + quad u^2 in calm water (see header).
struct SurgeBalance {
  double lin;
  double quad;
};
SurgeBalance CalmSurge(const ShipParams& ship) {
  const double area_front = ship.beam_m * ship.front_height_m;
  return {ship.Mass() / ship.damping_time_constant_surge_s,
          ship.nonlinear_damping_surge -
              0.5 * ship.air_density_kgpm3 * ship.wind_coefficient_x * area_front};
}

double PolylineLength(std::span<const Eigen::Vector2d> p) {
  double len = 0.0;
  for (size_t i = 1; i < p.size(); ++i) len += (p[i] - p[i - 1]).norm();
  return len;
}

Status CheckPolyline(std::span<const Eigen::Vector2d> p) {
  if (p.size() < 2) {
    return absl::InvalidArgumentError(
        absl::StrCat("sailing cost: polyline needs >= 2 points, got ", p.size()));
  }
  for (size_t i = 0; i < p.size(); ++i) {
    if (!p[i].allFinite()) {
      return absl::InvalidArgumentError(absl::StrCat("sailing cost: point ", i, " not finite"));
    }
  }
  return absl::OkStatus();
}

// Cost of sailing a checked polyline at a steady speed reached with `throttle`.
SailingCost CostAt(const MachineryParams& machinery, std::span<const Eigen::Vector2d> polyline,
                   MsoMode mode, double speed_mps, double throttle) {
  SailingCost c;
  c.length_m = PolylineLength(polyline);
  c.time_s = c.length_m / speed_mps;
  c.throttle = throttle;
  c.fuel_kg = FuelRateAt(machinery, mode, throttle).total_kgps() * c.time_s;
  return c;
}

}  // namespace

double CalmWaterSteadySpeed(const ShipParams& ship, const MachineryParams& machinery, MsoMode mode,
                            double throttle) {
  const double f = SteadyThrust(machinery, mode, throttle);
  const SurgeBalance b = CalmSurge(ship);
  if (f <= 0.0) return 0.0;
  if (std::abs(b.quad) < 1e-12) return f / b.lin;
  // Positive root of quad u^2 + lin u - f = 0, in the cancellation-free form.
  return 2.0 * f / (b.lin + std::sqrt(b.lin * b.lin + 4.0 * b.quad * f));
}

OperatingPoint CalmWaterOperatingPoint(const ShipParams& ship, const MachineryParams& machinery,
                                       MsoMode mode, double throttle) {
  OperatingPoint op;
  op.mode = mode;
  op.throttle = throttle;
  op.speed_mps = CalmWaterSteadySpeed(ship, machinery, mode, throttle);
  op.thrust_n = SteadyThrust(machinery, mode, throttle);
  op.load = DistributeLoad(machinery, mode, throttle);
  op.fuel_rate = FuelRateAt(machinery, mode, throttle);
  return op;
}

StatusOr<double> ThrottleForSpeed(const ShipParams& ship, const MachineryParams& machinery,
                                  MsoMode mode, double speed_mps, double max_throttle) {
  if (!std::isfinite(speed_mps) || speed_mps < 0.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("ThrottleForSpeed: speed ", speed_mps, " m/s must be finite and >= 0"));
  }
  const SurgeBalance b = CalmSurge(ship);
  const double f = b.lin * speed_mps + b.quad * speed_mps * speed_mps;
  const double p_per_throttle = PropulsionPower(machinery, mode, 1.0);
  const double throttle = f * machinery.power_to_thrust_ratio_mps / p_per_throttle;
  if (throttle > max_throttle) {
    return absl::OutOfRangeError(
        absl::StrCat("ThrottleForSpeed: ", speed_mps, " m/s needs throttle ", throttle, " in ",
                     std::string(MsoModeName(mode)), " (max ", max_throttle, ", top speed ",
                     TopSpeed(ship, machinery, mode, max_throttle), " m/s)"));
  }
  return throttle;
}

double TopSpeed(const ShipParams& ship, const MachineryParams& machinery, MsoMode mode,
                double max_throttle) {
  return CalmWaterSteadySpeed(ship, machinery, mode, max_throttle);
}

Status SteadyStateOptions::Validate() const {
  if (!(dt_s > 0.0) || !(max_time_s > 0.0) || !(surge_acceleration_tolerance_mps2 > 0.0) ||
      !(settle_time_s >= 0.0) || !std::isfinite(initial_speed_mps) || !std::isfinite(heading_rad) ||
      !std::isfinite(max_time_s)) {
    return absl::InvalidArgumentError(
        "SteadyStateOptions: dt_s, max_time_s, tolerance must be > 0, settle_time_s >= 0");
  }
  return absl::OkStatus();
}

StatusOr<OperatingPoint> SimulateSteadyState(const ShipParams& ship,
                                             const MachineryParams& machinery, MsoMode mode,
                                             double throttle, const Environment& env,
                                             const SteadyStateOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (!std::isfinite(throttle) || throttle < 0.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("SimulateSteadyState: throttle ", throttle, " must be finite and >= 0"));
  }
  SEAPLAN_ASSIGN_OR_RETURN(
      ShipModel model,
      ShipModel::Create(ship, machinery, env,
                        ShipState::At(0, 0, options.heading_rad, options.initial_speed_mps), mode));
  HeadingControllerOptions hopt;
  hopt.max_rudder_angle_rad = ship.max_rudder_angle_rad;
  HeadingController autopilot(hopt, options.dt_s);
  double settled_s = 0.0;
  while (model.time_s() < options.max_time_s) {
    const double u_before = model.state().nu[0];
    const double rudder = autopilot.RudderAngle(options.heading_rad, model.state().eta[2]);
    model.Step(throttle, rudder, options.dt_s);
    const double u_dot = (model.state().nu[0] - u_before) / options.dt_s;
    settled_s = std::abs(u_dot) < options.surge_acceleration_tolerance_mps2
                    ? settled_s + options.dt_s
                    : 0.0;
    if (settled_s >= options.settle_time_s && settled_s > 0.0) break;
  }
  OperatingPoint op;
  op.mode = mode;
  op.throttle = throttle;
  op.speed_mps = model.state().nu[0];
  op.thrust_n = model.thrust_n();
  op.load = DistributeLoad(machinery, mode, throttle);
  op.fuel_rate = FuelRateAt(machinery, mode, throttle);
  op.simulated_time_s = model.time_s();
  return op;
}

StatusOr<SailingCost> SailingCostAtSpeed(const ShipParams& ship, const MachineryParams& machinery,
                                         std::span<const Eigen::Vector2d> polyline, MsoMode mode,
                                         double speed_mps) {
  SEAPLAN_RETURN_IF_ERROR(CheckPolyline(polyline));
  if (!(speed_mps > 0.0)) {
    return absl::InvalidArgumentError(
        absl::StrCat("SailingCostAtSpeed: speed ", speed_mps, " m/s must be > 0"));
  }
  SEAPLAN_ASSIGN_OR_RETURN(double throttle, ThrottleForSpeed(ship, machinery, mode, speed_mps));
  return CostAt(machinery, polyline, mode, speed_mps, throttle);
}

StatusOr<SailingCost> SailingCostAtThrottle(const ShipParams& ship,
                                            const MachineryParams& machinery,
                                            std::span<const Eigen::Vector2d> polyline, MsoMode mode,
                                            double throttle) {
  SEAPLAN_RETURN_IF_ERROR(CheckPolyline(polyline));
  if (!(throttle > 0.0) || !std::isfinite(throttle)) {
    return absl::InvalidArgumentError(
        absl::StrCat("SailingCostAtThrottle: throttle ", throttle, " must be > 0"));
  }
  const double speed = CalmWaterSteadySpeed(ship, machinery, mode, throttle);
  return CostAt(machinery, polyline, mode, speed, throttle);
}

}  // namespace seaplan::ship
