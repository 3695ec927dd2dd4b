#include "seaplan/colav/autopilot.h"

#include <algorithm>

#include "absl/strings/str_format.h"
#include "seaplan/colav/geometry.h"

namespace seaplan::colav {

Status AutopilotOptions::Validate() const {
  if (!(heading_kp > 0) || !(heading_kd_s >= 0) || !(max_rudder_rad > 0) || !(speed_kp >= 0) ||
      !(speed_ki >= 0) || !(max_throttle > 0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "autopilot: heading_kp (%g), max_rudder_rad (%g) and max_throttle (%g) must be > 0, "
        "heading_kd_s (%g), speed_kp (%g) and speed_ki (%g) >= 0",
        heading_kp, max_rudder_rad, max_throttle, heading_kd_s, speed_kp, speed_ki));
  }
  return absl::OkStatus();
}

ActuatorCommand Autopilot::Update(double course_setpoint_rad, double speed_setpoint_mps,
                                  double heading_rad, double yaw_rate_radps, double surge_mps,
                                  double dt_s) {
  ActuatorCommand c;
  const double e = WrapAngle(course_setpoint_rad - heading_rad);
  const double rate =
      options_.derivative_on_error ? -(e - previous_error_rad_) / dt_s : yaw_rate_radps;
  previous_error_rad_ = e;
  c.rudder_rad = std::clamp(-(options_.heading_kp * e - options_.heading_kd_s * rate),
                            -options_.max_rudder_rad, options_.max_rudder_rad);
  const double ev = speed_setpoint_mps - surge_mps;
  const double unsaturated = options_.speed_kp * ev + options_.speed_ki * speed_integral_m_;
  const bool high = unsaturated >= options_.max_throttle && ev > 0;
  const bool low = unsaturated <= 0 && ev < 0;
  if (!high && !low) {
    speed_integral_m_ += ev * dt_s;
    // The integral alone never asks for more than the saturation.
    if (options_.speed_ki > 0) {
      speed_integral_m_ =
          std::clamp(speed_integral_m_, 0.0, options_.max_throttle / options_.speed_ki);
    }
  }
  c.throttle = std::clamp(options_.speed_kp * ev + options_.speed_ki * speed_integral_m_, 0.0,
                          options_.max_throttle);
  return c;
}

void Autopilot::HoldThrottle(double throttle) {
  speed_integral_m_ = options_.speed_ki > 0
                          ? std::clamp(throttle, 0.0, options_.max_throttle) / options_.speed_ki
                          : 0.0;
}

}  // namespace seaplan::colav
