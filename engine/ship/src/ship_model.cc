#include "seaplan/ship/ship_model.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "absl/strings/str_cat.h"

namespace seaplan::ship {
namespace {

Status CheckStep(double throttle, double rudder, double dt_s) {
  if (!std::isfinite(throttle) || !std::isfinite(rudder) || !(dt_s > 0.0) || !std::isfinite(dt_s)) {
    return absl::InvalidArgumentError(absl::StrCat("ship step: throttle ", throttle, ", rudder ",
                                                   rudder, ", dt ", dt_s,
                                                   " must be finite and dt > 0"));
  }
  return absl::OkStatus();
}

Status CheckInitial(const ShipState& s) {
  if (!s.eta.allFinite() || !s.nu.allFinite()) {
    return absl::InvalidArgumentError("ship model: initial state must be finite");
  }
  return absl::OkStatus();
}

}  // namespace

StatusOr<ShipModel> ShipModel::Create(const ShipParams& ship, const MachineryParams& machinery,
                                      const Environment& env, const ShipState& initial,
                                      MsoMode mode, double initial_thrust_n) {
  SEAPLAN_RETURN_IF_ERROR(ship.Validate());
  SEAPLAN_RETURN_IF_ERROR(machinery.Validate());
  SEAPLAN_RETURN_IF_ERROR(env.Validate());
  SEAPLAN_RETURN_IF_ERROR(CheckInitial(initial));
  if (!std::isfinite(initial_thrust_n)) {
    return absl::InvalidArgumentError("ShipModel: initial thrust must be finite");
  }
  return ShipModel(ship, machinery, env, initial, mode, initial_thrust_n);
}

StepReport ShipModel::Step(double throttle, double rudder_angle_rad, double dt_s) {
  // Inputs are the caller's controller outputs; a non-finite value is a bug
  // in the caller, not bad user input.
  if (!CheckStep(throttle, rudder_angle_rad, dt_s).ok()) std::abort();
  const double max_delta = dynamics_.params().max_rudder_angle_rad;
  const double delta = std::clamp(rudder_angle_rad, -max_delta, max_delta);

  StepReport report;
  report.thrust_n = propulsion_.thrust_n();
  report.load = DistributeLoad(machinery_, mode_, throttle);
  report.fuel_rate = FuelRateAt(machinery_, mode_, throttle);
  fuel_me_kg_ += report.fuel_rate.main_engine_kgps * dt_s;
  fuel_el_kg_ += report.fuel_rate.electrical_kgps * dt_s;
  fuel_kg_ += report.fuel_rate.total_kgps() * dt_s;

  const double thrust_dot = propulsion_.ThrustDerivative(mode_, throttle);
  Eigen::Vector3d tau = dynamics_.RudderForce(state_, env_, delta);
  tau[0] = propulsion_.thrust_n();
  dynamics_.EulerStep(state_, env_, tau, dt_s);
  propulsion_.Integrate(thrust_dot, dt_s);
  time_s_ += dt_s;
  return report;
}

StatusOr<ShaftShipModel> ShaftShipModel::Create(const ShipParams& ship,
                                                const MachineryParams& machinery,
                                                const ShaftParams& shaft, const Environment& env,
                                                const ShipState& initial, MsoMode mode) {
  SEAPLAN_RETURN_IF_ERROR(ship.Validate());
  SEAPLAN_RETURN_IF_ERROR(machinery.Validate());
  SEAPLAN_RETURN_IF_ERROR(shaft.Validate());
  SEAPLAN_RETURN_IF_ERROR(env.Validate());
  SEAPLAN_RETURN_IF_ERROR(CheckInitial(initial));
  return ShaftShipModel(ship, machinery, shaft, env, initial, mode);
}

StepReport ShaftShipModel::Step(double throttle, double rudder_angle_rad, double dt_s) {
  if (!CheckStep(throttle, rudder_angle_rad, dt_s).ok()) std::abort();
  const double max_delta = dynamics_.params().max_rudder_angle_rad;
  const double delta = std::clamp(rudder_angle_rad, -max_delta, max_delta);

  StepReport report;
  report.thrust_n = shaft_.ThrustN();
  report.load = DistributeLoad(machinery_, mode_, throttle);
  report.fuel_rate = FuelRateAt(machinery_, mode_, throttle);
  fuel_kg_ += report.fuel_rate.total_kgps() * dt_s;

  const double omega_dot = shaft_.OmegaDerivative(mode_, throttle);
  Eigen::Vector3d tau = dynamics_.RudderForce(state_, env_, delta);
  tau[0] = shaft_.ThrustN();
  dynamics_.EulerStep(state_, env_, tau, dt_s);
  shaft_.Integrate(omega_dot, dt_s);
  time_s_ += dt_s;
  return report;
}

}  // namespace seaplan::ship
