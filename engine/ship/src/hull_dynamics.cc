#include "seaplan/ship/hull_dynamics.h"

#include <cmath>

#include "Eigen/LU"

namespace seaplan::ship {

HullDynamics::HullDynamics(const ShipParams& params)
    : params_(params), mass_(params.Mass()), i_z_(params.YawInertia()) {
  x_du_ = mass_ * params.added_mass_coefficient_surge;
  y_dv_ = mass_ * params.added_mass_coefficient_sway;
  n_dr_ = i_z_ * params.added_mass_coefficient_yaw;
  area_front_m2_ = params.beam_m * params.front_height_m;
  area_side_m2_ = params.length_m * params.side_height_m;
  const double mxg = mass_ * params.x_g_m;
  m_ << mass_ + x_du_, 0.0, 0.0,  //
      0.0, mass_ + y_dv_, mxg,    //
      0.0, mxg, i_z_ + n_dr_;
  m_inv_ = m_.inverse();
  d_l_.setZero();
  d_l_(0, 0) = mass_ / params.damping_time_constant_surge_s;
  d_l_(1, 1) = mass_ / params.damping_time_constant_sway_s;
  d_l_(2, 2) = i_z_ / params.damping_time_constant_yaw_s;
}

StatusOr<HullDynamics> HullDynamics::Create(const ShipParams& params) {
  SEAPLAN_RETURN_IF_ERROR(params.Validate());
  return HullDynamics(params);
}

Eigen::Vector3d HullDynamics::WindForceBody(double u_rw, double v_rw) const {
  const double v2 = u_rw * u_rw + v_rw * v_rw;
  if (v2 == 0.0) return Eigen::Vector3d::Zero();
  // gamma = -atan2(v_rw, u_rw): cos(gamma) = u_rw/|V|, sin(gamma) = -v_rw/|V|.
  const double inv_v = 1.0 / std::sqrt(v2);
  const double cos_g = u_rw * inv_v;
  const double sin_g = -v_rw * inv_v;
  const double sin_2g = 2.0 * sin_g * cos_g;
  const double q = 0.5 * params_.air_density_kgpm3 * v2;
  return {q * (-params_.wind_coefficient_x * cos_g) * area_front_m2_,
          q * (params_.wind_coefficient_y * sin_g) * area_side_m2_,
          q * (params_.wind_coefficient_n * sin_2g) * area_side_m2_ * params_.length_m};
}

Eigen::Vector3d HullDynamics::WindForce(const ShipState& s, const Environment& env) const {
  const double rel_dir = env.wind_direction_from_rad - s.eta[2];
  return WindForceBody(env.wind_speed_mps * std::cos(rel_dir) - s.nu[0],
                       env.wind_speed_mps * std::sin(rel_dir) - s.nu[1]);
}

Eigen::Vector3d HullDynamics::RudderForce(const ShipState& s, const Environment& env,
                                          double delta_rad) const {
  const double c = std::cos(s.eta[2]);
  const double sn = std::sin(s.eta[2]);
  const double u_c = c * env.current_north_mps + sn * env.current_east_mps;
  const double u_r = s.nu[0] - u_c;
  return {0.0, -params_.rudder_sway_coefficient * delta_rad * u_r,
          -params_.rudder_yaw_coefficient * delta_rad * u_r};
}

StateDerivative HullDynamics::Derivative(const ShipState& s, const Environment& env,
                                         const Eigen::Vector3d& tau_ctrl) const {
  return Derivative(s, std::cos(s.eta[2]), std::sin(s.eta[2]), PreparedEnvironment::From(env),
                    tau_ctrl);
}

StateDerivative HullDynamics::Derivative(const ShipState& s, double c, double sn,
                                         const PreparedEnvironment& env,
                                         const Eigen::Vector3d& tau_ctrl) const {
  const double u = s.nu[0], v = s.nu[1], r = s.nu[2];

  StateDerivative d;
  d.eta_dot = {c * u - sn * v, sn * u + c * v, r};

  // Current in the body frame: R(psi)^T [Vc_N, Vc_E, 0].
  const double u_c = c * env.current_north_mps + sn * env.current_east_mps;
  const double v_c = -sn * env.current_north_mps + c * env.current_east_mps;
  const double u_r = u - u_c;
  const double v_r = v - v_c;

  // Relative wind: R(psi)^T (wind-from vector) minus the ship's velocity.
  const double u_rw = c * env.wind_from_north_mps + sn * env.wind_from_east_mps - u;
  const double v_rw = -sn * env.wind_from_north_mps + c * env.wind_from_east_mps - v;

  const double m = mass_;
  const double xg = params_.x_g_m;
  // C_RB(nu) nu.
  const Eigen::Vector3d crb(-m * (xg * r + v) * r, m * u * r, m * (xg * r + v) * u - m * u * v);
  // C_A(u_r, v_r) (nu - nu_c); nu - nu_c = [u_r, v_r, r].
  const Eigen::Vector3d ca(y_dv_ * v_r * r, -x_du_ * u_r * r,
                           -y_dv_ * v_r * u_r + x_du_ * u_r * v_r);
  // (D_L + D_NL(nu)) (nu - nu_c); D_NL uses the signed absolute velocities as SITS.
  const Eigen::Vector3d damp((d_l_(0, 0) + params_.nonlinear_damping_surge * u) * u_r,
                             (d_l_(1, 1) + params_.nonlinear_damping_sway * v) * v_r,
                             (d_l_(2, 2) + params_.nonlinear_damping_yaw * r) * r);
  d.nu_dot = m_inv_ * (-crb - ca - damp + WindForceBody(u_rw, v_rw) + tau_ctrl);
  return d;
}

void HullDynamics::EulerStep(ShipState& s, const Environment& env, const Eigen::Vector3d& tau_ctrl,
                             double dt_s) const {
  const StateDerivative d = Derivative(s, env, tau_ctrl);
  s.eta += d.eta_dot * dt_s;
  s.nu += d.nu_dot * dt_s;
}

void HullDynamics::EulerStep(ShipState& s, double c, double sn, const PreparedEnvironment& env,
                             const Eigen::Vector3d& tau_ctrl, double dt_s) const {
  const StateDerivative d = Derivative(s, c, sn, env, tau_ctrl);
  s.eta += d.eta_dot * dt_s;
  s.nu += d.nu_dot * dt_s;
}

}  // namespace seaplan::ship
