// Heading and speed autopilot for the SITS hull (engine/ship): rudder and
// throttle from a course and a speed setpoint. The simulation client steers
// with it, and the collision avoidance predicts each scenario with a copy of
// it, so what is predicted is what the ship does.
//
// Heading: rudder = -(kp * e - kd * r), e the wrapped course error, r the
// yaw rate (a PD on the measured rate, not on the error's difference: a
// setpoint step does not kick the rudder, and the law does not depend on the
// step size, so a prediction with a coarser step follows the same law).
// Speed: PI on the surge speed with conditional integration (no windup while
// the throttle is saturated in the error's direction).
//
// A small value type; copies are independent. Not thread-safe.
#pragma once

#include "seaplan/common/status.h"

namespace seaplan::colav {

struct AutopilotOptions {
  // Tuned on the hull's step response at 9 m/s (a sweep of kp 1-6, kd
  // 50-300): a 60 deg course change is half done in 46 s (the rudder is
  // saturated until then) and within 2 deg from 88 s on, overshooting by
  // 0.3 deg; the former gains (kp 2, kd 200) took 344 s to settle, and a
  // smaller kd overshoots (kp 4, kd 50: 12 deg).
  double heading_kp = 4.0;         // rudder rad per rad of course error
  double heading_kd_s = 100.0;     // rudder rad per rad/s of yaw rate
  double max_rudder_rad = 0.5236;  // 30 deg
  // The simulation client's former form (SITS' PID): the derivative on the
  // error's change per step instead of the yaw rate, so every setpoint
  // change kicks the rudder. Kept to compare against (seaplan-sim
  // --former-autopilot: kp 2, kd 200 in this form).
  bool derivative_on_error = false;
  double speed_kp = 0.2;    // throttle per m/s
  double speed_ki = 0.004;  // throttle per m of integrated speed error
  double max_throttle = 1.1;
  Status Validate() const;
};

struct ActuatorCommand {
  double throttle = 0.0;
  double rudder_rad = 0.0;
};

class Autopilot {
 public:
  explicit Autopilot(const AutopilotOptions& options = {}) : options_(options) {}
  ActuatorCommand Update(double course_setpoint_rad, double speed_setpoint_mps, double heading_rad,
                         double yaw_rate_radps, double surge_mps, double dt_s);
  const AutopilotOptions& options() const { return options_; }
  // Sets the speed integral so that it alone asks for `throttle` (a ship
  // already under way at the speed that throttle holds).
  void HoldThrottle(double throttle);

 private:
  AutopilotOptions options_;
  double speed_integral_m_ = 0.0;
  double previous_error_rad_ = 0.0;  // derivative_on_error only
};

}  // namespace seaplan::colav
