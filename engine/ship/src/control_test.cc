#include "seaplan/ship/control.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "gtest/gtest.h"
#include "seaplan/ship/ship_model.h"

namespace seaplan::ship {
namespace {

TEST(ControlTest, WrapToPi) {
  EXPECT_NEAR(WrapToPi(3 * std::numbers::pi / 2), -std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(WrapToPi(-3 * std::numbers::pi / 2), std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(WrapToPi(-std::numbers::pi), std::numbers::pi, 1e-12);
  EXPECT_NEAR(WrapToPi(0.3), 0.3, 1e-15);
}

TEST(ControlTest, HeadingControllerSignConvention) {
  // Heading error positive (want to turn to starboard) -> negative rudder,
  // which with tau_N = -c_r delta u gives a positive yaw moment.
  HeadingController hc(HeadingControllerOptions{}, 0.5);
  const double delta = hc.RudderAngle(0.2, 0.0);
  EXPECT_LT(delta, 0.0);
  EXPECT_GE(delta, -30 * std::numbers::pi / 180 - 1e-12);
}

TEST(ControlTest, LosRejectsBadRoutes) {
  EXPECT_FALSE(LosGuidance::Create({{0, 0}}, LosOptions{}).ok());
  EXPECT_FALSE(LosGuidance::Create({{0, 0}, {0, 0}}, LosOptions{}).ok());
  LosOptions bad;
  bad.lookahead_m = 0;
  EXPECT_FALSE(LosGuidance::Create({{0, 0}, {1000, 0}}, bad).ok());
}

TEST(ControlTest, LosOnTrackPointsAlongLeg) {
  auto los = LosGuidance::Create({{0, 0}, {0, 5000}}, LosOptions{});  // leg due east
  ASSERT_TRUE(los.ok());
  EXPECT_NEAR(los->Update(0, 1000), std::numbers::pi / 2, 1e-12);
  // Ship 100 m north (port side of an eastbound leg): e = -100 -> steer south of east.
  auto los2 = LosGuidance::Create({{0, 0}, {0, 5000}}, LosOptions{});
  EXPECT_GT(los2->Update(100, 1000), std::numbers::pi / 2);
}

// Closed loop: the ship follows a dog-leg route with LOS + heading PID +
// speed PI, switches waypoints and ends near the last waypoint.
TEST(ControlTest, ClosedLoopRouteFollowing) {
  const double dt = 0.5;
  auto model = ShipModel::Create(ShipParams{}, MachineryParams{}, Environment{},
                                 ShipState::At(0, 0, 0, 5), MsoMode::kMec);
  ASSERT_TRUE(model.ok());
  LosOptions lo;
  lo.acceptance_radius_m = 300;
  auto los = LosGuidance::Create({{0, 0}, {3000, 0}, {3000, 3000}, {0, 3000}}, lo);
  ASSERT_TRUE(los.ok());
  HeadingController heading(HeadingControllerOptions{}, dt);
  SpeedController speed(SpeedControllerOptions{}, dt);
  double max_cross_track_m = 0.0;
  while (!los->finished() && model->time_s() < 4000) {
    const ShipState& s = model->state();
    const double psi_d = los->Update(s.eta[0], s.eta[1]);
    if (model->time_s() > 600)
      max_cross_track_m = std::max(max_cross_track_m, std::abs(los->cross_track_error_m()));
    model->Step(speed.Throttle(7.0, s.nu[0]), heading.RudderAngle(psi_d, s.eta[2]), dt);
  }
  EXPECT_TRUE(los->finished());
  EXPECT_EQ(los->target_index(), 3);
  EXPECT_NEAR(model->state().nu[0], 7.0, 0.3);
  EXPECT_LT((model->state().eta.head<2>() - Eigen::Vector2d(0, 3000)).norm(), 310.0);
  EXPECT_LT(max_cross_track_m, 450.0);
  EXPECT_GT(model->fuel_consumed_kg(), 0.0);
}

// Full throttle from rest to 9 m/s, then an order for 3.6 m/s (a collision
// avoidance slowing down): the speed comes down promptly instead of rising
// on a wound-up integral.
TEST(ControlTest, SpeedControllerFollowsALowerSetpointAfterALongAcceleration) {
  const double dt = 0.5;
  auto model = ShipModel::Create(ShipParams{}, MachineryParams{}, Environment{},
                                 ShipState::At(0, 0, 0, 0), MsoMode::kPto);
  ASSERT_TRUE(model.ok());
  SpeedController speed(SpeedControllerOptions{}, dt);
  while (model->time_s() < 60) model->Step(speed.Throttle(9.0, model->state().nu[0]), 0.0, dt);
  const double at_order = model->state().nu[0];
  ASSERT_LT(at_order, 9.0) << "still accelerating when the lower order comes";
  double peak = at_order;
  while (model->time_s() < 420) {
    model->Step(speed.Throttle(3.6, model->state().nu[0]), 0.0, dt);
    peak = std::max(peak, model->state().nu[0]);
  }
  EXPECT_LT(peak, at_order + 0.5)
      << "kept accelerating after the order (a wound-up integral: +1.5 m/s)";
  EXPECT_NEAR(model->state().nu[0], 3.6, 0.4);
}

// The shaft-dynamics ship with the cascaded speed controller of §5 (ship-speed
// PI -> shaft-speed setpoint -> throttle PI) and heading hold reaches a speed
// setpoint.
TEST(ControlTest, ShaftModelWithCascadedSpeedController) {
  const double dt = 0.5;
  auto model = ShaftShipModel::Create(ShipParams{}, MachineryParams{}, ShaftParams{}, Environment{},
                                      ShipState::At(0, 0, 0, 7.0), MsoMode::kMec);
  ASSERT_TRUE(model.ok()) << model.status();
  ShaftSpeedControllerOptions so;
  so.max_shaft_speed_radps = ShaftParams{}.MaxShaftSpeedRadps();
  ShaftSpeedController speed(so, dt);
  HeadingController heading(HeadingControllerOptions{}, dt);
  while (model->time_s() < 3000) {
    const ShipState& s = model->state();
    model->Step(speed.Throttle(8.0, s.nu[0], model->shaft_speed_radps()),
                heading.RudderAngle(0.0, s.eta[2]), dt);
  }
  EXPECT_NEAR(model->state().nu[0], 8.0, 0.1);
  EXPECT_NEAR(model->state().eta[2], 0.0, 1e-3);
  EXPECT_GT(model->thrust_n(), 0.0);
  EXPECT_GT(model->fuel_consumed_kg(), 0.0);
}

}  // namespace
}  // namespace seaplan::ship
