// Controllers and guidance of SITS (spec SHIP_MODEL.md §5).
//
//  * PiController / PidController: SITS PiController / PidController
//    (rectangular integration of the error, optional integral clamp).
//  * SpeedController: PI from speed error to throttle in [0, 1.1] for the
//    simplified propulsion model.
//  * ShaftSpeedController: the cascaded PI of the shaft model (ship speed ->
//    shaft-speed setpoint in [0, w_max] -> throttle in [0, 1.1]).
//  * HeadingController: delta = -PID(psi_d, psi), saturated to +-delta_max.
//    SITS does not wrap the heading error; here wrapping to (-pi, pi] is an
//    option, ON by default, because a route leg through south (atan2 jumps at
//    +-pi) otherwise makes the ship turn a full circle. No reference figure
//    depends on it.
//  * LosGuidance: SITS NavigationSystem.los_guidance with waypoint switching
//    inside the radius of acceptance.
//
// All of these are small value types with mutable controller state; one
// instance per simulated ship. No heap use after construction. Not
// thread-safe: an instance belongs to the one thread stepping its ship.
#pragma once

#include <cmath>
#include <numbers>
#include <vector>

#include "Eigen/Core"
#include "seaplan/common/status.h"

namespace seaplan::ship {

// Wraps an angle to (-pi, pi].
double WrapToPi(double angle_rad);

class PiController {
 public:
  PiController(double kp, double ki, double dt_s, double initial_integral = 0.0)
      : kp_(kp), ki_(ki), dt_s_(dt_s), integral_(initial_integral) {}
  // Integral clamp [lo, hi]; default: unclamped.
  void set_integral_limits(double lo, double hi) { lo_ = lo, hi_ = hi; }
  double Update(double setpoint, double measurement);
  // Update with the output saturated to [out_lo, out_hi] and conditional
  // integration (anti-windup): the error is not integrated while the output
  // is saturated and the error would push it further out. Without it, a
  // long acceleration at full throttle fills the integral and a lower
  // setpoint is overshot for minutes.
  double UpdateSaturated(double setpoint, double measurement, double out_lo, double out_hi);
  double integral() const { return integral_; }

 private:
  double kp_, ki_, dt_s_, integral_;
  double lo_ = -HUGE_VAL, hi_ = HUGE_VAL;
};

class PidController {
 public:
  PidController(double kp, double kd, double ki, double dt_s)
      : kp_(kp), kd_(kd), ki_(ki), dt_s_(dt_s) {}
  void set_integral_limits(double lo, double hi) { lo_ = lo, hi_ = hi; }
  // `error` is setpoint - measurement (callers wrap it when they need to).
  double UpdateFromError(double error);

 private:
  double kp_, kd_, ki_, dt_s_;
  double integral_ = 0.0;
  double prev_error_ = 0.0;
  double lo_ = -HUGE_VAL, hi_ = HUGE_VAL;
};

struct SpeedControllerOptions {
  // Throttle per m/s of error and per m of integrated error. Chosen for the
  // SITS ship with simplified propulsion (not given in the spec): settles in
  // about 3 minutes without overshooting the 1.1 saturation for long.
  double kp = 0.2;
  double ki = 0.004;
  double max_throttle = 1.1;
  Status Validate() const;
};

class SpeedController {
 public:
  SpeedController(const SpeedControllerOptions& o, double dt_s);
  // Returns the throttle in [0, max_throttle]. Anti-windup: the integral is
  // clamped so that ki * integral stays within [0, max_throttle] and is not
  // integrated while the throttle is saturated in the error's direction.
  double Throttle(double speed_setpoint_mps, double measured_speed_mps);

 private:
  SpeedControllerOptions options_;
  PiController pi_;
};

struct ShaftSpeedControllerOptions {
  double kp_ship_speed = 7.0;
  double ki_ship_speed = 0.13;
  double kp_shaft_speed = 0.05;
  double ki_shaft_speed = 0.005;
  double initial_shaft_integral = 114.0;
  double max_shaft_speed_radps = 1.1 * 1000.0 * std::numbers::pi / 30.0 * 0.6;
};

class ShaftSpeedController {
 public:
  ShaftSpeedController(const ShaftSpeedControllerOptions& o, double dt_s);
  double Throttle(double speed_setpoint_mps, double measured_speed_mps, double shaft_speed_radps);

 private:
  ShaftSpeedControllerOptions options_;
  PiController ship_;
  PiController shaft_;
};

struct HeadingControllerOptions {
  double kp = 4.0;
  double kd = 90.0;
  double ki = 0.01;
  double max_rudder_angle_rad = 30.0 * std::numbers::pi / 180.0;
  bool wrap_heading_error = true;  // SITS: false (see header comment)
  Status Validate() const;
};

class HeadingController {
 public:
  HeadingController(const HeadingControllerOptions& o, double dt_s);
  // Rudder angle [rad], saturated.
  double RudderAngle(double heading_setpoint_rad, double measured_heading_rad);

 private:
  HeadingControllerOptions options_;
  PidController pid_;
};

struct LosOptions {
  double acceptance_radius_m = 600.0;  // R_a: switch when inside
  double lookahead_m = 450.0;          // R
  double k_i = 0.01;
  double max_integral = 0.5;  // I_max
  Status Validate() const;
};

// Waypoints are (N, E) in metres. The list is copied once at construction;
// Update() does no allocation.
class LosGuidance {
 public:
  static StatusOr<LosGuidance> Create(std::vector<Eigen::Vector2d> waypoints_ne,
                                      const LosOptions& options);

  // Advances the waypoint index if (N, E) is inside the acceptance radius of
  // the current target, then returns the desired heading psi_d [rad]:
  //   alpha = atan2(dE, dN) of leg k-1 -> k
  //   e = -(N - N_{k-1}) sin(alpha) + (E - E_{k-1}) cos(alpha)
  //   if e^2 >= R^2: e = 0.99 R sign(e)   (SITS drops the sign; we keep it)
  //   Delta = sqrt(R^2 - e^2); if |I + e/Delta| <= I_max: I += e/Delta
  //   psi_d = alpha + atan(-e/Delta - k_i I)
  double Update(double north_m, double east_m);

  // Index of the waypoint currently steered towards (>= 1).
  int target_index() const { return target_; }
  // True once the target is the last waypoint and the ship is inside its
  // acceptance radius.
  bool finished() const { return finished_; }
  double cross_track_error_m() const { return last_e_; }
  const std::vector<Eigen::Vector2d>& waypoints() const { return waypoints_; }

 private:
  LosGuidance(std::vector<Eigen::Vector2d> w, const LosOptions& o)
      : waypoints_(std::move(w)), options_(o) {}
  std::vector<Eigen::Vector2d> waypoints_;
  LosOptions options_;
  int target_ = 1;
  double integral_ = 0.0;
  double last_e_ = 0.0;
  bool finished_ = false;
};

}  // namespace seaplan::ship
