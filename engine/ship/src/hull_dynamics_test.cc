// Reference figures: SHIP_MODEL.md §6 (the public SITS models.py run unchanged).
#include "seaplan/ship/hull_dynamics.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "gtest/gtest.h"

namespace seaplan::ship {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// |actual - expected| <= 1 % of |expected| (or `abs_floor` for values near 0).
void ExpectWithin1Percent(double actual, double expected, const char* what,
                          double abs_floor = 0.0) {
  std::printf("  %-10s actual %.6g reference %.6g error %+.4f %%\n", what, actual, expected,
              100.0 * (actual - expected) / expected);
  const double tol = std::max(0.01 * std::abs(expected), abs_floor);
  EXPECT_NEAR(actual, expected, tol)
      << what << ": error " << 100.0 * (actual - expected) / expected << " %";
}

TEST(ShipParamsTest, DerivedMassAndInertiaMatchSpecTable) {
  const ShipParams p;
  EXPECT_DOUBLE_EQ(p.Mass(), 5'335'000.0);
  EXPECT_NEAR(p.YawInertia(), 2.959147e9, 1e3);
  const HullDynamics d(p);
  EXPECT_NEAR(d.mass_matrix()(0, 0), 7.469e6, 1.0);
  EXPECT_NEAR(d.mass_matrix()(2, 2), 4.142805e9, 1e3);
  EXPECT_NEAR(d.linear_damping()(0, 0), 41038.5, 0.1);
  EXPECT_NEAR(d.linear_damping()(1, 1), 296388.9, 0.1);
  EXPECT_NEAR(d.linear_damping()(2, 2), 3.28794e7, 1e2);
}

TEST(ShipParamsTest, RejectsBadValues) {
  ShipParams p;
  p.length_m = -1;
  EXPECT_EQ(p.Validate().code(), absl::StatusCode::kInvalidArgument);
  p = ShipParams{};
  p.damping_time_constant_sway_s = 0.0;
  EXPECT_FALSE(HullDynamics::Create(p).ok());
  p = ShipParams{};
  p.wind_coefficient_n = NAN;
  EXPECT_FALSE(p.Validate().ok());
  EXPECT_TRUE(ShipParams{}.Validate().ok());
  Environment env;
  env.wind_speed_mps = -3;
  EXPECT_FALSE(env.Validate().ok());
}

TEST(HullDynamicsTest, WindFromNorthPushesSouth) {
  const HullDynamics d{ShipParams{}};
  Environment env;
  env.wind_speed_mps = 10;
  env.wind_direction_from_rad = 0.0;  // from north, ship heading north at rest
  const Eigen::Vector3d f = d.WindForce(ShipState{}, env);
  EXPECT_LT(f[0], 0.0);  // pushed astern = south
  EXPECT_NEAR(f[1], 0.0, 1e-9);
  // 0.5 * 1.2 * 100 * 0.5 * 128
  EXPECT_NEAR(f[0], -3840.0, 1e-9);
}

TEST(HullDynamicsTest, RestInStillWaterStaysAtRest) {
  const HullDynamics d{ShipParams{}};
  ShipModelWithoutPropulsion drift(d, Environment{}, ShipState::At(10, 20, 0.5));
  drift.RunUntil(100, 0.5);
  EXPECT_DOUBLE_EQ(drift.state().eta[0], 10);
  EXPECT_DOUBLE_EQ(drift.state().eta[1], 20);
  EXPECT_DOUBLE_EQ(drift.state().nu.norm(), 0.0);
}

TEST(HullDynamicsTest, LoopConventionEndsOneStepAfterHorizon) {
  const HullDynamics d{ShipParams{}};
  ShipModelWithoutPropulsion drift(d, Environment{}, ShipState{});
  drift.RunUntil(600, 30);
  EXPECT_DOUBLE_EQ(drift.time_s(), 630.0);
}

// Case A: drift, wind 25 m/s from 45 deg, no current, u0 = 0, dt 0.5, T 2000.
TEST(DriftReferenceTest, CaseA_WindOnly) {
  const HullDynamics d{ShipParams{}};
  Environment env;
  env.wind_speed_mps = 25;
  env.wind_direction_from_rad = 45 * kDeg;
  ShipModelWithoutPropulsion drift(d, env, ShipState{});
  drift.RunUntil(2000, 0.5);
  EXPECT_DOUBLE_EQ(drift.time_s(), 2000.5);
  const ShipState& s = drift.state();
  ExpectWithin1Percent(s.eta[0], -817.397, "N");
  ExpectWithin1Percent(s.eta[1], -835.746, "E");
  ExpectWithin1Percent(s.eta[2], -0.785697, "psi");
  ExpectWithin1Percent(s.nu[0], 0.000099, "u", 1e-5);
  ExpectWithin1Percent(s.nu[1], -0.599163, "v");
}

// Case B: current 1 m/s toward east, u0 = 2, psi0 = 0, dt 0.5, T 600.
TEST(DriftReferenceTest, CaseB_CurrentOnly) {
  const HullDynamics d{ShipParams{}};
  Environment env;
  env.current_east_mps = 1.0;
  ShipModelWithoutPropulsion drift(d, env, ShipState::At(0, 0, 0, 2.0));
  drift.RunUntil(600, 0.5);
  const ShipState& s = drift.state();
  ExpectWithin1Percent(s.eta[0], 334.277, "N");
  ExpectWithin1Percent(s.eta[1], 572.760, "E");
  ExpectWithin1Percent(s.eta[2], -0.039022, "psi");
  ExpectWithin1Percent(s.nu[1], 1.000162, "v");
}

// Case C: AMM TTG settings: dt 30, T 600, wind 10 m/s from -110 deg and
// current 1 m/s toward -110 deg, u0 = 2, psi0 = 0.3.
TEST(DriftReferenceTest, CaseC_AmmTtgSettings) {
  const HullDynamics d{ShipParams{}};
  Environment env = Environment::WithCurrentToward(1.0, -110 * kDeg);
  env.wind_speed_mps = 10;
  env.wind_direction_from_rad = -110 * kDeg;
  ShipModelWithoutPropulsion drift(d, env, ShipState::At(0, 0, 0.3, 2.0));
  drift.RunUntil(600, 30);
  const ShipState& s = drift.state();
  ExpectWithin1Percent(s.eta[0], 172.676, "N");
  ExpectWithin1Percent(s.eta[1], -517.815, "E");
}

}  // namespace
}  // namespace seaplan::ship
