// Machinery system operating (MSO) modes, load sharing, fuel and propulsion
// (spec SHIP_MODEL.md §3a, §3b, §4; SITS MachineryMode / BaseMachineryModel /
// SimplifiedMachineryModel / ShipMachineryModel).
//
// Modes (defaults: ME 2160 kW, DG 510 kW each, hotel load 200 kW):
//  * PTO: ME drives the propeller and the hybrid shaft generator (HSG) as a
//    generator carries the hotel load. ME cap 2160, EL cap 0,
//    P_prop,avail = ME - hotel = 1960 kW.
//  * MEC: ME drives the propeller, one DG carries the hotel load, HSG off.
//    ME 2160, EL 510, P_prop,avail = 2160 kW.
//  * PTI: ME off; both DGs drive the propeller through the HSG as a motor.
//    ME 0, EL 1020, P_prop,avail = EL - hotel = 820 kW.
// Powers are in watts, fuel rates in kg/s, specific fuel consumption in g/kWh.
//
// All functions are pure; MachineryParams is a value type.
#pragma once

#include <array>
#include <numbers>
#include <string_view>

#include "seaplan/common/status.h"

namespace seaplan::ship {

enum class MsoMode { kPto = 0, kMec = 1, kPti = 2 };
inline constexpr std::array<MsoMode, 3> kAllMsoModes = {MsoMode::kPto, MsoMode::kMec,
                                                        MsoMode::kPti};
std::string_view MsoModeName(MsoMode mode);  // "PTO", "MEC", "PTI"

// What the hybrid shaft generator does in a mode (SITS 'GEN', 'OFF', 'MOTOR').
enum class HsgState { kGenerator, kOff, kMotor };

// sfc(x) = a x^2 + b x + c [g/kWh], x = load fraction of the engine's capacity.
struct SfcQuadratic {
  double a = 0.0, b = 0.0, c = 0.0;
  double operator()(double load_fraction) const {
    return (a * load_fraction + b) * load_fraction + c;
  }
};
// Wärtsilä 6L26 (ME) and Baudouin 6M26.3 (DG), SITS SimplifiedMachineryModel.
inline constexpr SfcQuadratic kSfcWartsila6L26{128.9, -168.9, 246.8};
inline constexpr SfcQuadratic kSfcBaudouin6M26_3{108.7, -289.9, 324.9};

struct MachineryParams {
  double main_engine_capacity_w = 2160e3;
  // Per diesel generator. The paper states 590 kW; the public code uses 510.
  double diesel_generator_capacity_w = 510e3;
  double hotel_load_w = 200e3;
  SfcQuadratic sfc_main_engine = kSfcWartsila6L26;
  SfcQuadratic sfc_diesel_generator = kSfcBaudouin6M26_3;

  // Simplified propulsion (§3a): F_dot = (-k F + P) / T, k = P_max/F_max [W/N].
  double power_to_thrust_ratio_mps = 2160.0 / 790.0;
  double thrust_time_constant_s = 30.0;

  Status Validate() const;
};

// Capacities that are online in a mode.
struct ModeCapacity {
  double main_engine_w = 0.0;
  double electrical_w = 0.0;
  HsgState hsg = HsgState::kOff;
};
ModeCapacity CapacityOf(const MachineryParams& p, MsoMode mode);

// SITS update_available_propulsion_power.
struct AvailablePropulsionPower {
  double total_w = 0.0;
  double main_engine_w = 0.0;
  double electrical_w = 0.0;
};
AvailablePropulsionPower AvailablePower(const MachineryParams& p, MsoMode mode);

// SITS distribute_load: how the power for `load_fraction` x P_prop,avail
// plus the hotel load is shared between ME and the electrical plant.
struct LoadOnPowerSources {
  double main_engine_w = 0.0;
  double electrical_w = 0.0;
  double main_engine_fraction = 0.0;  // of ME capacity (0 if ME offline)
  double electrical_fraction = 0.0;   // of EL capacity (0 if EL offline)
};
LoadOnPowerSources DistributeLoad(const MachineryParams& p, MsoMode mode, double load_fraction);

struct FuelRate {
  double main_engine_kgps = 0.0;
  double electrical_kgps = 0.0;
  double total_kgps() const { return main_engine_kgps + electrical_kgps; }
};
// Fuel rate at a commanded load (SITS fuel_consumption): P[W] * sfc / 3.6e9.
FuelRate FuelRateAt(const MachineryParams& p, MsoMode mode, double load_fraction);

// Propulsion power commanded by the throttle in the simplified model:
// throttle * (P_avail,ME + P_avail,EL).
double PropulsionPower(const MachineryParams& p, MsoMode mode, double throttle);
// Thrust the simplified model settles at: P / k.
double SteadyThrust(const MachineryParams& p, MsoMode mode, double throttle);

// First-order thrust model (§3a). Holds the thrust state F [N].
class SimplifiedPropulsion {
 public:
  explicit SimplifiedPropulsion(const MachineryParams& p, double initial_thrust_n = 0.0)
      : params_(p), thrust_n_(initial_thrust_n) {}
  double thrust_n() const { return thrust_n_; }
  void set_thrust_n(double f) { thrust_n_ = f; }
  double ThrustDerivative(MsoMode mode, double throttle) const {
    return (-params_.power_to_thrust_ratio_mps * thrust_n_ +
            PropulsionPower(params_, mode, throttle)) /
           params_.thrust_time_constant_s;
  }
  void Integrate(double thrust_dot, double dt_s) { thrust_n_ += thrust_dot * dt_s; }

 private:
  MachineryParams params_;
  double thrust_n_;
};

// Shaft-dynamics propulsion (§3b, SITS ShipMachineryModel):
//   J_p w_dot = (tau_ME - d_ME w)/r_ME + (tau_HSG - d_HSG w)/r_HSG - k_p w^2
//   F = D_p^4 k_T w |w|
//   tau_X = min(load P_X,avail / (w + 0.1), P_X,avail / 5 * pi / 30)
struct ShaftParams {
  double propeller_inertia_kgm2 = 6000.0;
  double propeller_torque_coefficient = 7.5;  // k_p
  double propeller_diameter_m = 3.1;
  double propeller_thrust_coefficient = 1.7;  // k_T
  double main_engine_friction = 68.0;         // d_ME
  double hsg_friction = 57.0;                 // d_HSG
  double main_engine_gear_ratio = 0.6;        // r_ME
  double hsg_gear_ratio = 0.6;                // r_HSG
  double rated_main_engine_speed_rpm = 1000.0;
  double initial_shaft_speed_rpm = 400.0;
  // Max shaft speed = 1.1 * rated ME speed [rad/s] * r_ME.
  double MaxShaftSpeedRadps() const {
    return 1.1 * rated_main_engine_speed_rpm * std::numbers::pi / 30.0 * main_engine_gear_ratio;
  }
  Status Validate() const;
};

class ShaftPropulsion {
 public:
  ShaftPropulsion(const MachineryParams& machinery, const ShaftParams& shaft)
      : machinery_(machinery),
        shaft_(shaft),
        omega_radps_(shaft.initial_shaft_speed_rpm * std::numbers::pi / 30.0) {}
  double omega_radps() const { return omega_radps_; }
  void set_omega_radps(double w) { omega_radps_ = w; }
  double ThrustN() const;
  double MainEngineTorque(MsoMode mode, double load) const;
  double HsgTorque(MsoMode mode, double load) const;
  double OmegaDerivative(MsoMode mode, double load) const;
  void Integrate(double omega_dot, double dt_s) { omega_radps_ += omega_dot * dt_s; }
  const ShaftParams& shaft_params() const { return shaft_; }

 private:
  MachineryParams machinery_;
  ShaftParams shaft_;
  double omega_radps_;
};

}  // namespace seaplan::ship
