// The propelled ship: hull dynamics + machinery in an MSO mode + fuel
// tracking (SITS ShipModelSimplifiedPropulsion and ShipModel).
//
// One Step(throttle, rudder, dt) follows SITS' loop body exactly:
//   1. fuel rate at the commanded throttle (store_simulation_data) is
//      accumulated over dt,
//   2. derivatives are evaluated at the current state with the CURRENT thrust
//      (the thrust state is integrated in the same Euler step),
//   3. all states are integrated with forward Euler.
// The rudder angle is saturated to +-max_rudder_angle_rad here. Step's
// arguments come from controllers, not users: a non-finite throttle/rudder or
// dt <= 0 is a programming error and aborts (callers validate user input). The mode can
// be switched at any step (the paper adds no switching cost or delay; callers
// that want one model it outside).
//
// Thread-safety: one instance per simulated ship; not shared.
#pragma once

#include "seaplan/common/status.h"
#include "seaplan/ship/hull_dynamics.h"
#include "seaplan/ship/machinery.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::ship {

// What one step reports (values at the START of the step, as SITS stores).
struct StepReport {
  double thrust_n = 0.0;
  LoadOnPowerSources load;
  FuelRate fuel_rate;
};

// Ship with the first-order thrust model (spec §3a).
class ShipModel {
 public:
  static StatusOr<ShipModel> Create(const ShipParams& ship, const MachineryParams& machinery,
                                    const Environment& env, const ShipState& initial, MsoMode mode,
                                    double initial_thrust_n = 0.0);

  StepReport Step(double throttle, double rudder_angle_rad, double dt_s);

  const ShipState& state() const { return state_; }
  void set_state(const ShipState& s) { state_ = s; }
  double thrust_n() const { return propulsion_.thrust_n(); }
  MsoMode mode() const { return mode_; }
  void set_mode(MsoMode m) { mode_ = m; }
  const Environment& environment() const { return env_; }
  void set_environment(const Environment& e) { env_ = e; }
  double time_s() const { return time_s_; }
  double fuel_consumed_kg() const { return fuel_kg_; }
  double fuel_consumed_main_engine_kg() const { return fuel_me_kg_; }
  double fuel_consumed_electrical_kg() const { return fuel_el_kg_; }
  const HullDynamics& dynamics() const { return dynamics_; }
  const MachineryParams& machinery() const { return machinery_; }

 private:
  ShipModel(const ShipParams& ship, const MachineryParams& machinery, const Environment& env,
            const ShipState& initial, MsoMode mode, double thrust)
      : dynamics_(ship),
        machinery_(machinery),
        propulsion_(machinery, thrust),
        env_(env),
        state_(initial),
        mode_(mode) {}
  HullDynamics dynamics_;
  MachineryParams machinery_;
  SimplifiedPropulsion propulsion_;
  Environment env_;
  ShipState state_;
  MsoMode mode_;
  double time_s_ = 0.0;
  double fuel_kg_ = 0.0, fuel_me_kg_ = 0.0, fuel_el_kg_ = 0.0;
};

// Ship with the shaft-dynamics propulsion model (spec §3b). Same step order;
// the thrust is D^4 k_T w|w| from the current shaft speed.
class ShaftShipModel {
 public:
  static StatusOr<ShaftShipModel> Create(const ShipParams& ship, const MachineryParams& machinery,
                                         const ShaftParams& shaft, const Environment& env,
                                         const ShipState& initial, MsoMode mode);

  StepReport Step(double throttle, double rudder_angle_rad, double dt_s);

  const ShipState& state() const { return state_; }
  double shaft_speed_radps() const { return shaft_.omega_radps(); }
  double thrust_n() const { return shaft_.ThrustN(); }
  MsoMode mode() const { return mode_; }
  void set_mode(MsoMode m) { mode_ = m; }
  double time_s() const { return time_s_; }
  double fuel_consumed_kg() const { return fuel_kg_; }

 private:
  ShaftShipModel(const ShipParams& ship, const MachineryParams& machinery, const ShaftParams& shaft,
                 const Environment& env, const ShipState& initial, MsoMode mode)
      : dynamics_(ship),
        machinery_(machinery),
        shaft_(machinery, shaft),
        env_(env),
        state_(initial),
        mode_(mode) {}
  HullDynamics dynamics_;
  MachineryParams machinery_;
  ShaftPropulsion shaft_;
  Environment env_;
  ShipState state_;
  MsoMode mode_;
  double time_s_ = 0.0;
  double fuel_kg_ = 0.0;
};

}  // namespace seaplan::ship
