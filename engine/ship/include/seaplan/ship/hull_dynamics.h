// 3-DOF rigid-body + hydrodynamics of SITS (spec SHIP_MODEL.md §3) and the
// drift model used by the time-to-grounding simulation.
//
//   eta_dot = R(psi) nu
//   M nu_dot = -C_RB(nu) nu - C_A(u_r, v_r)(nu - nu_c)
//              - (D_L + D_NL(nu))(nu - nu_c) + tau_wind + tau_ctrl
//
// with nu_c = R(psi)^T [Vc_N, Vc_E, 0]. Integration is forward Euler
// (x += x_dot dt), as SITS. HullDynamics precomputes M^-1 and D_L once; a
// step is a handful of fixed-size 3x3 products and never touches the heap.
//
// Thread-safety: HullDynamics is immutable after construction and may be
// shared between threads; ShipModelWithoutPropulsion owns mutable state.
#pragma once

#include <cmath>

#include "Eigen/Core"
#include "seaplan/common/status.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::ship {

// Time derivative of the 6 kinematic states.
struct StateDerivative {
  Eigen::Vector3d eta_dot;
  Eigen::Vector3d nu_dot;
};

// Environment with trigonometry done once, for hot loops (the TTG drift):
// the wind-from vector and the current in NED components.
struct PreparedEnvironment {
  double wind_from_north_mps = 0.0;  // V cos(beta)
  double wind_from_east_mps = 0.0;   // V sin(beta)
  double current_north_mps = 0.0;
  double current_east_mps = 0.0;
  static PreparedEnvironment From(const Environment& env) {
    return {env.wind_speed_mps * std::cos(env.wind_direction_from_rad),
            env.wind_speed_mps * std::sin(env.wind_direction_from_rad), env.current_north_mps,
            env.current_east_mps};
  }
};

class HullDynamics {
 public:
  // `params` must be valid (Create checks it; the constructor CHECKs nothing
  // and is for callers that validated already).
  explicit HullDynamics(const ShipParams& params);
  static StatusOr<HullDynamics> Create(const ShipParams& params);

  const ShipParams& params() const { return params_; }
  double mass_kg() const { return mass_; }
  double yaw_inertia_kgm2() const { return i_z_; }
  const Eigen::Matrix3d& mass_matrix() const { return m_; }
  const Eigen::Matrix3d& linear_damping() const { return d_l_; }

  // Wind force [X, Y, N] in the body frame (SITS get_wind_force). Uses
  // cos/sin of gamma = -atan2(v_rw, u_rw) computed algebraically from the
  // relative wind (same value, no trig call).
  Eigen::Vector3d WindForce(const ShipState& s, const Environment& env) const;

  // Rudder force [0, Y, N] for rudder angle `delta_rad` (not saturated here).
  Eigen::Vector3d RudderForce(const ShipState& s, const Environment& env, double delta_rad) const;

  // Full derivative with an extra body-frame control force `tau_ctrl`
  // (thrust in [0], rudder in [1..2]). Wind is added inside.
  StateDerivative Derivative(const ShipState& s, const Environment& env,
                             const Eigen::Vector3d& tau_ctrl) const;

  // One forward-Euler step of length dt_s with the derivative evaluated at s.
  void EulerStep(ShipState& s, const Environment& env, const Eigen::Vector3d& tau_ctrl,
                 double dt_s) const;

  // Hot-loop forms: cos/sin of s.eta[2] supplied by the caller (who usually
  // needs them anyway, e.g. for the hull outline), environment prepared once.
  // Relative wind in the body frame is R(psi)^T [Vw_N, Vw_E], which equals
  // SITS' V [cos(beta - psi), sin(beta - psi)].
  StateDerivative Derivative(const ShipState& s, double cos_psi, double sin_psi,
                             const PreparedEnvironment& env, const Eigen::Vector3d& tau_ctrl) const;
  void EulerStep(ShipState& s, double cos_psi, double sin_psi, const PreparedEnvironment& env,
                 const Eigen::Vector3d& tau_ctrl, double dt_s) const;

 private:
  Eigen::Vector3d WindForceBody(double u_rw, double v_rw) const;
  ShipParams params_;
  double mass_;
  double i_z_;
  double x_du_, y_dv_, n_dr_;
  double area_front_m2_, area_side_m2_;
  Eigen::Matrix3d m_;
  Eigen::Matrix3d m_inv_;
  Eigen::Matrix3d d_l_;
};

// SITS ShipModelWithoutPropulsion: the ship drifting freely under wind and
// current, no thrust, no rudder.
class ShipModelWithoutPropulsion {
 public:
  ShipModelWithoutPropulsion(const HullDynamics& dynamics, const Environment& env,
                             const ShipState& initial)
      : dynamics_(&dynamics), env_(env), state_(initial) {}

  // One Euler step; advances time by dt_s.
  void Step(double dt_s) {
    dynamics_->EulerStep(state_, env_, Eigen::Vector3d::Zero(), dt_s);
    time_s_ += dt_s;
  }
  // SITS loop convention: `while t <= T: step; t += dt`, so the last step
  // ends at the first multiple of dt above T (T + dt when dt divides T).
  void RunUntil(double horizon_s, double dt_s) {
    while (time_s_ <= horizon_s) Step(dt_s);
  }

  const ShipState& state() const { return state_; }
  double time_s() const { return time_s_; }

 private:
  const HullDynamics* dynamics_;  // not owned; must outlive this object
  Environment env_;
  ShipState state_;
  double time_s_ = 0.0;
};

}  // namespace seaplan::ship
