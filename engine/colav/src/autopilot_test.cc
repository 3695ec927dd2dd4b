#include "seaplan/colav/autopilot.h"

#include <gtest/gtest.h>

#include <cmath>

#include "seaplan/colav/encounter_sim.h"
#include "seaplan/colav/geometry.h"

namespace seaplan::colav {
namespace {

struct StepResponse {
  double overshoot_rad = 0.0;
  double settle_s = -1.0;  // within 2 deg of the setpoint from then on
  double time_to_half_s = -1.0;
};

// A course change of `change_rad` at 9 m/s on the SITS hull.
StepResponse CourseStep(const AutopilotOptions& o, double change_rad) {
  const double dt = 0.5;
  auto ship = ShipUnderWay({0, 0}, 0.0, 9.0, {}, o);
  EXPECT_TRUE(ship.ok()) << ship.status();
  ship::ShipModel& model = ship->model;
  Autopilot& ap = ship->autopilot;
  StepResponse r;
  for (double t = 0; t < 600; t += dt) {
    const ship::ShipState& s = model.state();
    const double e = WrapAngle(s.heading_rad() - change_rad);
    r.overshoot_rad = std::max(r.overshoot_rad, e);
    if (r.time_to_half_s < 0 && s.heading_rad() >= change_rad / 2) r.time_to_half_s = t;
    if (std::abs(e) > 2 * M_PI / 180)
      r.settle_s = -1;
    else if (r.settle_s < 0)
      r.settle_s = t;
    const ActuatorCommand c =
        ap.Update(change_rad, 9.0, s.heading_rad(), s.yaw_rate_radps(), s.surge_mps(), dt);
    model.Step(c.throttle, c.rudder_rad, dt);
  }
  return r;
}

TEST(AutopilotTest, CourseChangeSettlesWithoutLargeOvershoot) {
  const StepResponse r = CourseStep({}, 60 * M_PI / 180);
  EXPECT_GE(r.settle_s, 0) << "never settled within 2 deg";
  EXPECT_LT(r.settle_s, 120);  // the former gains (kp 2, kd 200): 344 s
  EXPECT_LT(r.overshoot_rad, 2 * M_PI / 180);
  EXPECT_GT(r.time_to_half_s, 0);
}

TEST(AutopilotTest, SpeedIsHeldAndRejectsBadOptions) {
  AutopilotOptions bad;
  bad.heading_kp = 0;
  EXPECT_FALSE(bad.Validate().ok());
  EXPECT_TRUE(AutopilotOptions{}.Validate().ok());
  Autopilot ap;
  // Below the setpoint: more throttle than at it; never beyond the saturation.
  const double low = ap.Update(0, 9, 0, 0, 5, 0.5).throttle;
  Autopilot at;
  const double same = at.Update(0, 9, 0, 0, 9, 0.5).throttle;
  EXPECT_GT(low, same);
  EXPECT_LE(low, AutopilotOptions{}.max_throttle);
  // The rudder turns the ship towards a course to starboard (negative rudder, SITS).
  EXPECT_LT(ap.Update(0.5, 9, 0, 0, 9, 0.5).rudder_rad, 0);
}

}  // namespace
}  // namespace seaplan::colav
