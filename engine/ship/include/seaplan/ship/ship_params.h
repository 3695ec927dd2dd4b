// Ship parameters, environment and state of the 3-DOF ship model.
//
// The model is the public Ship-in-Transit Simulator (SITS,
// BorgeRokseth/ship_in_transit_simulator, MIT) re-implemented on fixed-size
// Eigen types; see ../shared/spec/SHIP_MODEL.md §1–§5. Every default below
// is the SITS example value (AMM thesis/models/setup.py uses the same), and
// every value is configurable.
//
// Conventions (exactly those of SITS, spec §1):
//  * Frame: NED, flat local metric frame. eta = [N, E, psi] (metres, metres,
//    radians), psi measured from north towards east (clockwise seen from
//    above). nu = [u, v, r]: surge (forward), sway (starboard), yaw rate.
//  * Current: `current_north_mps`/`current_east_mps` are the velocity of the
//    WATER in NED (the direction it flows TOWARD). current_east_mps = +1 moves
//    a drifting ship towards +E. (SITS names these fields "..._from_north",
//    but they behave as "toward"; we name them by what they do.)
//  * Wind: `wind_direction_from_rad` is the direction the wind comes FROM,
//    measured like psi (0 = from north, pi/2 = from east). A 25 m/s wind from
//    45 degrees makes a drifting ship move south-west. Internally SITS forms
//    the relative wind u_rw = V cos(beta - psi) - u, v_rw = V sin(beta - psi) - v
//    and the force formula of spec §3 turns that into a push away from beta.
//
// Thread-safety: plain values, freely copyable.
#pragma once

#include <cmath>
#include <numbers>

#include "Eigen/Core"
#include "seaplan/common/status.h"

namespace seaplan::ship {

// Hull, mass, damping, wind and rudder parameters. All SI units.
struct ShipParams {
  // --- mass derivation (SITS BaseShipModel) ---
  double dead_weight_tonnage_kg = 3'850'000.0;
  // DWT / displacement; lightship = DWT/coef - DWT.
  double dwt_to_displacement_coefficient = 0.7;
  double bunkers_kg = 200'000.0;
  double ballast_kg = 200'000.0;
  // payload = payload_fraction * (DWT - bunkers).
  double payload_fraction = 0.9;
  // If > 0, overrides the derived mass (5 335 000 kg with the defaults).
  double mass_override_kg = 0.0;

  // --- geometry ---
  double length_m = 80.0;  // the paper states LOA 81.5 m; the code uses 80
  double beam_m = 16.0;
  double x_g_m = 0.0;  // longitudinal centre of gravity from midship
  // If > 0, overrides I_z = m (L^2 + B^2) / 12.
  double yaw_inertia_override_kgm2 = 0.0;

  // --- added mass, as fractions of m (surge, sway) and I_z (yaw) ---
  double added_mass_coefficient_surge = 0.4;
  double added_mass_coefficient_sway = 0.4;
  double added_mass_coefficient_yaw = 0.4;

  // --- linear damping as time constants: D_L = diag(m/T_surge, m/T_sway, I_z/T_yaw) ---
  double damping_time_constant_surge_s = 130.0;
  double damping_time_constant_sway_s = 18.0;
  double damping_time_constant_yaw_s = 90.0;

  // --- nonlinear damping D_NL = diag(k_u u, k_v v, k_r r) (signed, as SITS) ---
  double nonlinear_damping_surge = 2400.0;
  double nonlinear_damping_sway = 4000.0;
  double nonlinear_damping_yaw = 400.0;

  // --- wind ---
  double air_density_kgpm3 = 1.2;
  double front_height_m = 8.0;  // A_F = B * h_f
  double side_height_m = 8.0;   // A_L = L * h_s
  double wind_coefficient_x = 0.5;
  double wind_coefficient_y = 0.7;
  // SITS uses 0.08; the AMM copy (paper 002) uses 0.016.
  double wind_coefficient_n = 0.08;

  // --- rudder: tau = [0, -c_v delta u_r, -c_r delta u_r] ---
  double rudder_sway_coefficient = 50e3;
  double rudder_yaw_coefficient = 500e3;
  double max_rudder_angle_rad = 30.0 * std::numbers::pi / 180.0;

  // Derived quantities.
  double Mass() const;
  double YawInertia() const;

  // Returns InvalidArgument naming the first non-finite or non-positive field.
  Status Validate() const;
};

// Wind and current. See the header comment for the sign conventions.
struct Environment {
  double wind_speed_mps = 0.0;
  double wind_direction_from_rad = 0.0;  // direction the wind comes FROM
  double current_north_mps = 0.0;        // water velocity toward north
  double current_east_mps = 0.0;         // water velocity toward east

  // Current of `speed_mps` flowing TOWARD `direction_to_rad` (AMM setup.py:
  // N = s cos(dir), E = s sin(dir)).
  static Environment WithCurrentToward(double speed_mps, double direction_to_rad) {
    Environment env;
    env.current_north_mps = speed_mps * std::cos(direction_to_rad);
    env.current_east_mps = speed_mps * std::sin(direction_to_rad);
    return env;
  }
  Status Validate() const;
};

// Kinematic state. Value type; 48 bytes of doubles, no heap.
struct ShipState {
  Eigen::Vector3d eta = Eigen::Vector3d::Zero();  // [N, E, psi]
  Eigen::Vector3d nu = Eigen::Vector3d::Zero();   // [u, v, r]

  double north_m() const { return eta[0]; }
  double east_m() const { return eta[1]; }
  double heading_rad() const { return eta[2]; }
  double surge_mps() const { return nu[0]; }
  double sway_mps() const { return nu[1]; }
  double yaw_rate_radps() const { return nu[2]; }

  static ShipState At(double north_m, double east_m, double heading_rad, double surge_mps = 0.0,
                      double sway_mps = 0.0, double yaw_rate_radps = 0.0) {
    ShipState s;
    s.eta = {north_m, east_m, heading_rad};
    s.nu = {surge_mps, sway_mps, yaw_rate_radps};
    return s;
  }
};

}  // namespace seaplan::ship
