#include "seaplan/ship/control.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>

#include "absl/strings/str_cat.h"

namespace seaplan::ship {

double WrapToPi(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);  // in [-pi, pi]
  if (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

double PiController::Update(double setpoint, double measurement) {
  const double error = setpoint - measurement;
  integral_ = std::clamp(integral_ + error * dt_s_, lo_, hi_);
  return error * kp_ + integral_ * ki_;
}

double PiController::UpdateSaturated(double setpoint, double measurement, double out_lo,
                                     double out_hi) {
  const double error = setpoint - measurement;
  const double unsaturated = error * kp_ + integral_ * ki_;
  const bool pushing_out =
      (unsaturated >= out_hi && error > 0.0) || (unsaturated <= out_lo && error < 0.0);
  if (!pushing_out) integral_ = std::clamp(integral_ + error * dt_s_, lo_, hi_);
  return std::clamp(error * kp_ + integral_ * ki_, out_lo, out_hi);
}

double PidController::UpdateFromError(double error) {
  const double d_error = (error - prev_error_) / dt_s_;
  integral_ = std::clamp(integral_ + error * dt_s_, lo_, hi_);
  prev_error_ = error;
  return error * kp_ + d_error * kd_ + integral_ * ki_;
}

Status SpeedControllerOptions::Validate() const {
  if (!(kp >= 0.0) || !(ki >= 0.0) || !(max_throttle > 0.0) || !std::isfinite(kp) ||
      !std::isfinite(ki) || !std::isfinite(max_throttle)) {
    return absl::InvalidArgumentError(absl::StrCat("SpeedControllerOptions: kp ", kp, ", ki ", ki,
                                                   ", max_throttle ", max_throttle,
                                                   " must be finite, gains >= 0, max > 0"));
  }
  return absl::OkStatus();
}

SpeedController::SpeedController(const SpeedControllerOptions& o, double dt_s)
    : options_(o), pi_(o.kp, o.ki, dt_s) {
  if (o.ki > 0.0) pi_.set_integral_limits(0.0, o.max_throttle / o.ki);
}

double SpeedController::Throttle(double setpoint, double measured) {
  return pi_.UpdateSaturated(setpoint, measured, 0.0, options_.max_throttle);
}

ShaftSpeedController::ShaftSpeedController(const ShaftSpeedControllerOptions& o, double dt_s)
    : options_(o),
      ship_(o.kp_ship_speed, o.ki_ship_speed, dt_s),
      shaft_(o.kp_shaft_speed, o.ki_shaft_speed, dt_s, o.initial_shaft_integral) {}

double ShaftSpeedController::Throttle(double setpoint, double measured, double shaft_speed) {
  const double desired_shaft =
      std::clamp(ship_.Update(setpoint, measured), 0.0, options_.max_shaft_speed_radps);
  return std::clamp(shaft_.Update(desired_shaft, shaft_speed), 0.0, 1.1);
}

Status HeadingControllerOptions::Validate() const {
  if (!std::isfinite(kp) || !std::isfinite(kd) || !std::isfinite(ki) ||
      !(max_rudder_angle_rad > 0.0)) {
    return absl::InvalidArgumentError(
        "HeadingControllerOptions: gains must be finite and max_rudder_angle_rad > 0");
  }
  return absl::OkStatus();
}

HeadingController::HeadingController(const HeadingControllerOptions& o, double dt_s)
    : options_(o), pid_(o.kp, o.kd, o.ki, dt_s) {}

double HeadingController::RudderAngle(double setpoint, double measured) {
  double error = setpoint - measured;
  if (options_.wrap_heading_error) error = WrapToPi(error);
  const double delta = -pid_.UpdateFromError(error);
  return std::clamp(delta, -options_.max_rudder_angle_rad, options_.max_rudder_angle_rad);
}

Status LosOptions::Validate() const {
  if (!(acceptance_radius_m > 0.0) || !(lookahead_m > 0.0) || !std::isfinite(k_i) ||
      !(max_integral >= 0.0) || !std::isfinite(acceptance_radius_m) ||
      !std::isfinite(lookahead_m)) {
    return absl::InvalidArgumentError(
        absl::StrCat("LosOptions: acceptance_radius_m ", acceptance_radius_m, ", lookahead_m ",
                     lookahead_m, " must be > 0; k_i finite; max_integral >= 0"));
  }
  return absl::OkStatus();
}

StatusOr<LosGuidance> LosGuidance::Create(std::vector<Eigen::Vector2d> waypoints,
                                          const LosOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (waypoints.size() < 2) {
    return absl::InvalidArgumentError(
        absl::StrCat("LosGuidance needs at least 2 waypoints, got ", waypoints.size()));
  }
  for (size_t i = 0; i < waypoints.size(); ++i) {
    if (!waypoints[i].allFinite()) {
      return absl::InvalidArgumentError(
          absl::StrCat("LosGuidance: waypoint ", i, " is not finite"));
    }
    if (i > 0 && waypoints[i] == waypoints[i - 1]) {
      return absl::InvalidArgumentError(
          absl::StrCat("LosGuidance: waypoints ", i - 1, " and ", i, " coincide"));
    }
  }
  return LosGuidance(std::move(waypoints), options);
}

double LosGuidance::Update(double north, double east) {
  const int n = static_cast<int>(waypoints_.size());
  const Eigen::Vector2d& tgt = waypoints_[target_];
  const double dn = tgt[0] - north, de = tgt[1] - east;
  if (dn * dn + de * de <= options_.acceptance_radius_m * options_.acceptance_radius_m) {
    if (target_ + 1 < n) {
      ++target_;
    } else {
      finished_ = true;  // hold the last leg
    }
  }
  const Eigen::Vector2d& prev = waypoints_[target_ - 1];
  const Eigen::Vector2d& next = waypoints_[target_];
  const double alpha = std::atan2(next[1] - prev[1], next[0] - prev[0]);
  double e = -(north - prev[0]) * std::sin(alpha) + (east - prev[1]) * std::cos(alpha);
  const double r = options_.lookahead_m;
  if (e * e >= r * r) e = std::copysign(0.99 * r, e);
  last_e_ = e;
  const double delta = std::sqrt(r * r - e * e);
  if (std::abs(integral_ + e / delta) <= options_.max_integral) integral_ += e / delta;
  return alpha + std::atan(-e / delta - options_.k_i * integral_);
}

}  // namespace seaplan::ship
