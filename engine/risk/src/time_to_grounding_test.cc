#include "seaplan/risk/time_to_grounding.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "gtest/gtest.h"

namespace seaplan::risk {
namespace {

using ship::Environment;
using ship::ShipParams;
using ship::ShipState;

// Land east of E = shore_e (a 20 km wide block).
PolygonObstacles ShoreEastOf(double shore_e) {
  auto obs = PolygonObstacles::Create(
      {{{-10000, shore_e}, {10000, shore_e}, {10000, shore_e + 5000}, {-10000, shore_e + 5000}}});
  EXPECT_TRUE(obs.ok());
  return *std::move(obs);
}

TimeToGroundingSimulator Simulator(TtgOptions o = {}) {
  auto sim = TimeToGroundingSimulator::Create(ShipParams{}, o);
  EXPECT_TRUE(sim.ok()) << sim.status();
  return *std::move(sim);
}

// A ship already moving with a 1 m/s eastward current (no wind) drifts east at
// 1 m/s; heading north, its side is 8 m east of the centre, so it touches a
// shore 300 m away after (300 - 8) / 1 = 292 s: detected at the first step end
// at or after that.
TEST(TimeToGroundingTest, StraightShoreCurrentOnly) {
  const PolygonObstacles shore = ShoreEastOf(300);
  Environment env;
  env.current_east_mps = 1.0;
  const ShipState start = ShipState::At(0, 0, 0, 0, 1.0);  // v = 1 m/s = current
  const TtgResult coarse = Simulator().Run(start, env, shore);
  EXPECT_TRUE(coarse.grounded);
  EXPECT_GE(coarse.ttg_s, 292.0);
  EXPECT_LE(coarse.ttg_s, 292.0 + 30.0);
  TtgOptions fine;
  fine.dt_s = 1.0;
  const TtgResult r = Simulator(fine).Run(start, env, shore);
  EXPECT_TRUE(r.grounded);
  EXPECT_NEAR(r.ttg_s, 292.0, 1.0);
}

TEST(TimeToGroundingTest, StartingFromRestLagsButGrounds) {
  const PolygonObstacles shore = ShoreEastOf(300);
  Environment env;
  env.current_east_mps = 1.0;
  const TtgResult r = Simulator().Run(ShipState::At(0, 0, 0), env, shore);
  EXPECT_TRUE(r.grounded);
  EXPECT_GE(r.ttg_s, 292.0);
  EXPECT_LE(r.ttg_s, 292.0 + 120.0);  // sway time constant of order 30 s
}

TEST(TimeToGroundingTest, NoObstacleRunsWholeHorizon) {
  auto empty = PolygonObstacles::Create({});
  ASSERT_TRUE(empty.ok());
  Environment env = Environment::WithCurrentToward(1.0, -110 * std::numbers::pi / 180);
  env.wind_speed_mps = 10;
  env.wind_direction_from_rad = -110 * std::numbers::pi / 180;
  std::vector<DriftTrackPoint> track;
  const TtgResult r = Simulator().Run(ShipState::At(0, 0, 0.3, 2.0), env, *empty, &track);
  EXPECT_FALSE(r.grounded);
  EXPECT_DOUBLE_EQ(r.ttg_s, 630.0);  // while t <= 600: last step ends at 630
  EXPECT_EQ(r.steps, 21);
  ASSERT_EQ(track.size(), 22u);
  // Same end point as SHIP_MODEL.md §6 case C.
  EXPECT_NEAR(track.back().state.eta[0], 172.676, 1.7);
  EXPECT_NEAR(track.back().state.eta[1], -517.815, 5.2);
}

TEST(TimeToGroundingTest, UpwindShoreIsNotReached) {
  // Wind 20 m/s from the west pushes the ship east: a shore to the west is safe.
  Environment env;
  env.wind_speed_mps = 20;
  env.wind_direction_from_rad = -std::numbers::pi / 2;
  auto west =
      PolygonObstacles::Create({{{-5000, -400}, {5000, -400}, {5000, -3000}, {-5000, -3000}}});
  ASSERT_TRUE(west.ok());
  EXPECT_FALSE(Simulator().Run(ShipState::At(0, 0, 0), env, *west).grounded);
  const TtgResult east = Simulator().Run(ShipState::At(0, 0, 0), env, ShoreEastOf(100));
  EXPECT_TRUE(east.grounded);
  EXPECT_LT(east.ttg_s, 630.0);
}

TEST(TimeToGroundingTest, AlreadyTouchingGivesZero) {
  const TtgResult r = Simulator().Run(ShipState::At(0, 295, 0), Environment{}, ShoreEastOf(300));
  EXPECT_TRUE(r.grounded);
  EXPECT_EQ(r.ttg_s, 0.0);
  EXPECT_EQ(r.steps, 0);
}

TEST(TimeToGroundingTest, HullSizeComesFromOptions) {
  // A ship lying across the current (heading east) reaches 40 m further east.
  const PolygonObstacles shore = ShoreEastOf(300);
  Environment env;
  env.current_east_mps = 1.0;
  TtgOptions fine;
  fine.dt_s = 1.0;
  const TtgResult across =
      Simulator(fine).Run(ShipState::At(0, 0, std::numbers::pi / 2, 1.0), env, shore);
  EXPECT_NEAR(across.ttg_s, 260.0, 1.5);
  fine.hull_length_m = 200;
  const TtgResult longer =
      Simulator(fine).Run(ShipState::At(0, 0, std::numbers::pi / 2, 1.0), env, shore);
  EXPECT_NEAR(longer.ttg_s, 200.0, 1.5);
}

TEST(TimeToGroundingTest, RejectsBadOptionsAndInputs) {
  TtgOptions o;
  o.dt_s = 0;
  EXPECT_FALSE(TimeToGroundingSimulator::Create(ShipParams{}, o).ok());
  o = TtgOptions{};
  o.dt_s = 1e-6;  // 6e8 steps
  EXPECT_FALSE(TimeToGroundingSimulator::Create(ShipParams{}, o).ok());
  EXPECT_FALSE(TimeToGroundingSimulator::CheckInputs(ShipState::At(NAN, 0, 0), Environment{}).ok());
  EXPECT_TRUE(TimeToGroundingSimulator::CheckInputs(ShipState{}, Environment{}).ok());
}

}  // namespace
}  // namespace seaplan::risk
