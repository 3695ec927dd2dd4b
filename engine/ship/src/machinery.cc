#include "seaplan/ship/machinery.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "absl/strings/str_cat.h"

namespace seaplan::ship {

std::string_view MsoModeName(MsoMode mode) {
  switch (mode) {
    case MsoMode::kPto:
      return "PTO";
    case MsoMode::kMec:
      return "MEC";
    case MsoMode::kPti:
      return "PTI";
  }
  return "?";
}

Status MachineryParams::Validate() const {
  auto bad = [](const char* name, double v) {
    return absl::InvalidArgumentError(
        absl::StrCat("MachineryParams.", name, " must be finite and > 0, got ", v));
  };
  if (!(main_engine_capacity_w > 0.0) || !std::isfinite(main_engine_capacity_w))
    return bad("main_engine_capacity_w", main_engine_capacity_w);
  if (!(diesel_generator_capacity_w > 0.0) || !std::isfinite(diesel_generator_capacity_w))
    return bad("diesel_generator_capacity_w", diesel_generator_capacity_w);
  if (!(hotel_load_w >= 0.0) || !std::isfinite(hotel_load_w)) {
    return absl::InvalidArgumentError(
        absl::StrCat("MachineryParams.hotel_load_w must be finite and >= 0, got ", hotel_load_w));
  }
  if (hotel_load_w >= main_engine_capacity_w || hotel_load_w >= 2 * diesel_generator_capacity_w ||
      hotel_load_w > diesel_generator_capacity_w) {
    return absl::InvalidArgumentError(
        absl::StrCat("MachineryParams.hotel_load_w ", hotel_load_w,
                     " must be below the ME capacity and within one DG's capacity"));
  }
  if (!(power_to_thrust_ratio_mps > 0.0) || !std::isfinite(power_to_thrust_ratio_mps))
    return bad("power_to_thrust_ratio_mps", power_to_thrust_ratio_mps);
  if (!(thrust_time_constant_s > 0.0) || !std::isfinite(thrust_time_constant_s))
    return bad("thrust_time_constant_s", thrust_time_constant_s);
  for (const SfcQuadratic& q : {sfc_main_engine, sfc_diesel_generator}) {
    if (!std::isfinite(q.a) || !std::isfinite(q.b) || !std::isfinite(q.c)) {
      return absl::InvalidArgumentError("MachineryParams: SFC coefficients must be finite");
    }
  }
  return absl::OkStatus();
}

Status ShaftParams::Validate() const {
  for (double v : {propeller_inertia_kgm2, propeller_diameter_m, propeller_thrust_coefficient,
                   main_engine_gear_ratio, hsg_gear_ratio, rated_main_engine_speed_rpm}) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      return absl::InvalidArgumentError(
          absl::StrCat("ShaftParams: inertia, diameter, k_T, gear ratios and rated speed must "
                       "be finite and > 0, got ",
                       v));
    }
  }
  return absl::OkStatus();
}

ModeCapacity CapacityOf(const MachineryParams& p, MsoMode mode) {
  switch (mode) {
    case MsoMode::kPto:
      return {p.main_engine_capacity_w, 0.0, HsgState::kGenerator};
    case MsoMode::kMec:
      return {p.main_engine_capacity_w, p.diesel_generator_capacity_w, HsgState::kOff};
    case MsoMode::kPti:
      return {0.0, 2.0 * p.diesel_generator_capacity_w, HsgState::kMotor};
  }
  return {};
}

AvailablePropulsionPower AvailablePower(const MachineryParams& p, MsoMode mode) {
  const ModeCapacity cap = CapacityOf(p, mode);
  const double hotel = p.hotel_load_w;
  switch (cap.hsg) {
    case HsgState::kMotor:
      return {cap.main_engine_w + cap.electrical_w - hotel, cap.main_engine_w,
              cap.electrical_w - hotel};
    case HsgState::kGenerator:
      return {cap.main_engine_w - hotel, cap.main_engine_w - hotel, 0.0};
    case HsgState::kOff:
      return {cap.main_engine_w, cap.main_engine_w, 0.0};
  }
  return {};
}

LoadOnPowerSources DistributeLoad(const MachineryParams& p, MsoMode mode, double load_fraction) {
  const ModeCapacity cap = CapacityOf(p, mode);
  const double hotel = p.hotel_load_w;
  const double prop = load_fraction * AvailablePower(p, mode).total_w;
  LoadOnPowerSources out;
  switch (cap.hsg) {
    case HsgState::kMotor:
      out.main_engine_w = std::min(prop, cap.main_engine_w);
      out.electrical_w = prop + hotel - out.main_engine_w;
      break;
    case HsgState::kGenerator:
      // The electrical plant carries the hotel load as far as it can.
      out.electrical_w = std::min(hotel, cap.electrical_w);
      out.main_engine_w = prop + hotel - out.electrical_w;
      break;
    case HsgState::kOff:
      out.main_engine_w = prop;
      out.electrical_w = hotel;
      break;
  }
  out.main_engine_fraction = cap.main_engine_w > 0.0 ? out.main_engine_w / cap.main_engine_w : 0.0;
  out.electrical_fraction = cap.electrical_w > 0.0 ? out.electrical_w / cap.electrical_w : 0.0;
  return out;
}

FuelRate FuelRateAt(const MachineryParams& p, MsoMode mode, double load_fraction) {
  const LoadOnPowerSources load = DistributeLoad(p, mode, load_fraction);
  FuelRate rate;
  if (load.main_engine_w != 0.0) {
    rate.main_engine_kgps =
        load.main_engine_w * p.sfc_main_engine(load.main_engine_fraction) / 3.6e9;
  }
  if (load.electrical_fraction != 0.0) {
    rate.electrical_kgps =
        load.electrical_w * p.sfc_diesel_generator(load.electrical_fraction) / 3.6e9;
  }
  return rate;
}

double PropulsionPower(const MachineryParams& p, MsoMode mode, double throttle) {
  const AvailablePropulsionPower avail = AvailablePower(p, mode);
  return throttle * (avail.main_engine_w + avail.electrical_w);
}

double SteadyThrust(const MachineryParams& p, MsoMode mode, double throttle) {
  return PropulsionPower(p, mode, throttle) / p.power_to_thrust_ratio_mps;
}

double ShaftPropulsion::ThrustN() const {
  const double d2 = shaft_.propeller_diameter_m * shaft_.propeller_diameter_m;
  return d2 * d2 * shaft_.propeller_thrust_coefficient * omega_radps_ * std::abs(omega_radps_);
}

double ShaftPropulsion::MainEngineTorque(MsoMode mode, double load) const {
  const double p = AvailablePower(machinery_, mode).main_engine_w;
  return std::min(load * p / (omega_radps_ + 0.1), p / 5.0 * std::numbers::pi / 30.0);
}

double ShaftPropulsion::HsgTorque(MsoMode mode, double load) const {
  const double p = AvailablePower(machinery_, mode).electrical_w;
  return std::min(load * p / (omega_radps_ + 0.1), p / 5.0 * std::numbers::pi / 30.0);
}

double ShaftPropulsion::OmegaDerivative(MsoMode mode, double load) const {
  const double eq_me = (MainEngineTorque(mode, load) - shaft_.main_engine_friction * omega_radps_) /
                       shaft_.main_engine_gear_ratio;
  const double eq_hsg =
      (HsgTorque(mode, load) - shaft_.hsg_friction * omega_radps_) / shaft_.hsg_gear_ratio;
  return (eq_me + eq_hsg - shaft_.propeller_torque_coefficient * omega_radps_ * omega_radps_) /
         shaft_.propeller_inertia_kgm2;
}

}  // namespace seaplan::ship
