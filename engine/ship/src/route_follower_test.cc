#include "seaplan/ship/route_follower.h"

#include "gtest/gtest.h"
#include "seaplan/ship/steady_state.h"

namespace seaplan::ship {
namespace {

PlannedRoute LRoute(MsoMode first, MsoMode second, double speed) {
  return PlannedRoute{{{0, 0}, {4000, 0}, {4000, 4000}}, {first, second}, {speed, speed}};
}

TEST(RouteFollowerTest, SailsRouteSwitchingModesAndTracksFuel) {
  auto f = RouteFollower::Create(ShipParams{}, MachineryParams{}, Environment{},
                                 LRoute(MsoMode::kMec, MsoMode::kPto, 7.0));
  ASSERT_TRUE(f.ok()) << f.status();
  bool saw_leg1_pto = false;
  while (!f->finished() && f->time_s() < 3000) {
    f->Step();
    if (f->current_leg() == 1) saw_leg1_pto |= f->ship().mode() == MsoMode::kPto;
    if (f->current_leg() == 0) {
      EXPECT_EQ(f->ship().mode(), MsoMode::kMec);
    }
  }
  EXPECT_TRUE(f->finished());
  EXPECT_TRUE(saw_leg1_pto);
  // 8 km at about 7 m/s, minus the 600 m acceptance radius at the end.
  EXPECT_GT(f->time_s(), (8000.0 - 600.0 - 600.0) / 7.5);
  EXPECT_LT(f->time_s(), 8000.0 / 6.0);
  // Fuel close to the calm-water steady rate times time (within 15 %:
  // turning and the speed transient cost a little).
  const double rate =
      FuelRateAt(MachineryParams{}, MsoMode::kMec,
                 *ThrottleForSpeed(ShipParams{}, MachineryParams{}, MsoMode::kMec, 7.0))
          .total_kgps();
  EXPECT_NEAR(f->ship().fuel_consumed_kg(), rate * f->time_s(), 0.15 * rate * f->time_s());
}

TEST(RouteFollowerTest, HoldsTrackInCrossCurrent) {
  Environment env;
  env.current_east_mps = 0.5;  // pushes the northbound first leg sideways
  auto f = RouteFollower::Create(ShipParams{}, MachineryParams{}, env,
                                 PlannedRoute{{{0, 0}, {6000, 0}}, {MsoMode::kMec}, {6.0}});
  ASSERT_TRUE(f.ok());
  double worst = 0.0;
  while (!f->finished() && f->time_s() < 3000) {
    f->Step();
    if (f->time_s() > 300) worst = std::max(worst, std::abs(f->cross_track_error_m()));
  }
  EXPECT_TRUE(f->finished());
  EXPECT_LT(worst, 100.0);
}

TEST(RouteFollowerTest, RejectsInconsistentPlans) {
  PlannedRoute bad{{{0, 0}, {1000, 0}, {1000, 1000}}, {MsoMode::kPto}, {5.0, 5.0}};
  EXPECT_EQ(
      RouteFollower::Create(ShipParams{}, MachineryParams{}, Environment{}, bad).status().code(),
      absl::StatusCode::kInvalidArgument);
  PlannedRoute neg{{{0, 0}, {1000, 0}}, {MsoMode::kPto}, {-1.0}};
  EXPECT_FALSE(RouteFollower::Create(ShipParams{}, MachineryParams{}, Environment{}, neg).ok());
}

}  // namespace
}  // namespace seaplan::ship
