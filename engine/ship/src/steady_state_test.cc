// Case D of SHIP_MODEL.md §6: simplified propulsion, throttle 0.8, 3000 s.
#include "seaplan/ship/steady_state.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "gtest/gtest.h"
#include "seaplan/ship/ship_model.h"

namespace seaplan::ship {
namespace {

struct CaseD {
  MsoMode mode;
  double speed_mps, thrust_kn, p_me_kw, p_el_kw, fuel_kgps;
};

void ExpectWithin1Percent(double actual, double expected, const char* what) {
  std::printf("  %-10s actual %.6g reference %.6g error %+.4f %%\n", what, actual, expected,
              100.0 * (actual - expected) / expected);
  EXPECT_NEAR(actual, expected, 0.01 * std::abs(expected))
      << what << ": error " << 100.0 * (actual - expected) / expected << " %";
}

class CaseDTest : public ::testing::TestWithParam<CaseD> {};

// Runs the SITS loop (while t <= 3000: step) at constant throttle 0.8, no
// rudder, calm water, from rest.
TEST_P(CaseDTest, SimulatedSteadyStateMatchesReference) {
  const CaseD& ref = GetParam();
  auto model =
      ShipModel::Create(ShipParams{}, MachineryParams{}, Environment{}, ShipState{}, ref.mode);
  ASSERT_TRUE(model.ok()) << model.status();
  StepReport last;
  while (model->time_s() <= 3000.0) last = model->Step(0.8, 0.0, 0.5);
  ExpectWithin1Percent(model->state().nu[0], ref.speed_mps, "u");
  ExpectWithin1Percent(model->thrust_n() / 1e3, ref.thrust_kn, "F");
  if (ref.p_me_kw > 0) {
    ExpectWithin1Percent(last.load.main_engine_w / 1e3, ref.p_me_kw, "P_ME");
  } else {
    EXPECT_EQ(last.load.main_engine_w, 0.0);
  }
  if (ref.p_el_kw > 0) ExpectWithin1Percent(last.load.electrical_w / 1e3, ref.p_el_kw, "P_EL");
  ExpectWithin1Percent(last.fuel_rate.total_kgps(), ref.fuel_kgps, "fuel rate");
  // Accumulated fuel is the integral of the rate (constant throttle).
  EXPECT_NEAR(model->fuel_consumed_kg(), last.fuel_rate.total_kgps() * model->time_s(), 1e-6);
}

TEST_P(CaseDTest, ClosedFormMatchesReferenceAndSimulation) {
  const CaseD& ref = GetParam();
  const OperatingPoint op = CalmWaterOperatingPoint(ShipParams{}, MachineryParams{}, ref.mode, 0.8);
  ExpectWithin1Percent(op.speed_mps, ref.speed_mps, "u");
  ExpectWithin1Percent(op.thrust_n / 1e3, ref.thrust_kn, "F");
  ExpectWithin1Percent(op.fuel_rate.total_kgps(), ref.fuel_kgps, "fuel rate");
  auto sim = SimulateSteadyState(ShipParams{}, MachineryParams{}, ref.mode, 0.8);
  ASSERT_TRUE(sim.ok()) << sim.status();
  EXPECT_NEAR(sim->speed_mps, op.speed_mps, 1e-4);
}

INSTANTIATE_TEST_SUITE_P(Modes, CaseDTest,
                         ::testing::Values(CaseD{MsoMode::kPto, 9.153, 573.5, 1768, 0, 0.09572},
                                           CaseD{MsoMode::kMec, 9.835, 632.0, 1728, 200, 0.10587},
                                           CaseD{MsoMode::kPti, 4.619, 239.9, 0, 856, 0.03761}),
                         [](const auto& param_info) {
                           return std::string(MsoModeName(param_info.param.mode));
                         });

TEST(SteadyStateTest, ThrottleForSpeedInvertsSteadySpeed) {
  const ShipParams ship;
  const MachineryParams mach;
  for (MsoMode m : kAllMsoModes) {
    const double u = CalmWaterSteadySpeed(ship, mach, m, 0.6);
    auto t = ThrottleForSpeed(ship, mach, m, u);
    ASSERT_TRUE(t.ok());
    EXPECT_NEAR(*t, 0.6, 1e-9);
  }
  // PTI tops out near 5 m/s: 8 m/s is out of range with a clear error.
  auto too_fast = ThrottleForSpeed(ship, mach, MsoMode::kPti, 8.0);
  EXPECT_EQ(too_fast.status().code(), absl::StatusCode::kOutOfRange);
  EXPECT_LT(TopSpeed(ship, mach, MsoMode::kPti), TopSpeed(ship, mach, MsoMode::kPto));
  EXPECT_LT(TopSpeed(ship, mach, MsoMode::kPto), TopSpeed(ship, mach, MsoMode::kMec));
}

TEST(SteadyStateTest, SailingCostAlongPolyline) {
  const ShipParams ship;
  const MachineryParams mach;
  // 3-4-5 triangle legs: 3000 m + 4000 m = 7000 m.
  const std::vector<Eigen::Vector2d> route = {{0, 0}, {3000, 0}, {3000, 4000}};
  auto c = SailingCostAtSpeed(ship, mach, route, MsoMode::kMec, 7.0);
  ASSERT_TRUE(c.ok()) << c.status();
  EXPECT_DOUBLE_EQ(c->length_m, 7000.0);
  EXPECT_DOUBLE_EQ(c->time_s, 1000.0);
  EXPECT_NEAR(c->fuel_kg, FuelRateAt(mach, MsoMode::kMec, c->throttle).total_kgps() * 1000.0, 1e-9);
  auto ct = SailingCostAtThrottle(ship, mach, route, MsoMode::kPto, 0.8);
  ASSERT_TRUE(ct.ok());
  EXPECT_NEAR(ct->time_s, 7000.0 / CalmWaterSteadySpeed(ship, mach, MsoMode::kPto, 0.8), 1e-9);
  const std::vector<Eigen::Vector2d> one = {{0, 0}};
  EXPECT_EQ(SailingCostAtSpeed(ship, mach, one, MsoMode::kPto, 5).status().code(),
            absl::StatusCode::kInvalidArgument);
}

TEST(SteadyStateTest, HeadWindSlowsTheShip) {
  Environment env;
  env.wind_speed_mps = 15;
  env.wind_direction_from_rad = 0.0;  // from ahead (ship holds heading 0)
  auto calm = SimulateSteadyState(ShipParams{}, MachineryParams{}, MsoMode::kMec, 0.8);
  auto windy = SimulateSteadyState(ShipParams{}, MachineryParams{}, MsoMode::kMec, 0.8, env);
  ASSERT_TRUE(calm.ok() && windy.ok());
  EXPECT_LT(windy->speed_mps, calm->speed_mps - 0.05);
}

}  // namespace
}  // namespace seaplan::ship
