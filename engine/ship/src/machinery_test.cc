#include "seaplan/ship/machinery.h"

#include "gtest/gtest.h"

namespace seaplan::ship {
namespace {

TEST(MachineryTest, AvailablePowerPerMode) {
  const MachineryParams p;
  EXPECT_DOUBLE_EQ(AvailablePower(p, MsoMode::kPto).total_w, 1960e3);
  EXPECT_DOUBLE_EQ(AvailablePower(p, MsoMode::kMec).total_w, 2160e3);
  EXPECT_DOUBLE_EQ(AvailablePower(p, MsoMode::kPti).total_w, 820e3);
  EXPECT_DOUBLE_EQ(AvailablePower(p, MsoMode::kPti).main_engine_w, 0.0);
  EXPECT_DOUBLE_EQ(AvailablePower(p, MsoMode::kPti).electrical_w, 820e3);
}

TEST(MachineryTest, DistributeLoadFollowsSitsRules) {
  const MachineryParams p;
  const LoadOnPowerSources pto = DistributeLoad(p, MsoMode::kPto, 0.8);
  EXPECT_DOUBLE_EQ(pto.main_engine_w, 0.8 * 1960e3 + 200e3);
  EXPECT_DOUBLE_EQ(pto.electrical_w, 0.0);
  EXPECT_DOUBLE_EQ(pto.electrical_fraction, 0.0);
  const LoadOnPowerSources mec = DistributeLoad(p, MsoMode::kMec, 0.8);
  EXPECT_DOUBLE_EQ(mec.main_engine_w, 0.8 * 2160e3);
  EXPECT_DOUBLE_EQ(mec.electrical_w, 200e3);
  EXPECT_DOUBLE_EQ(mec.electrical_fraction, 200.0 / 510.0);
  const LoadOnPowerSources pti = DistributeLoad(p, MsoMode::kPti, 0.8);
  EXPECT_DOUBLE_EQ(pti.main_engine_w, 0.0);
  EXPECT_DOUBLE_EQ(pti.electrical_w, 0.8 * 820e3 + 200e3);
  EXPECT_DOUBLE_EQ(pti.electrical_fraction, (0.8 * 820e3 + 200e3) / 1020e3);
}

TEST(MachineryTest, SfcQuadraticByHand) {
  // 128.9 x^2 - 168.9 x + 246.8 at x = 0.5: 32.225 - 84.45 + 246.8
  EXPECT_NEAR(kSfcWartsila6L26(0.5), 194.575, 1e-9);
  EXPECT_NEAR(kSfcBaudouin6M26_3(1.0), 108.7 - 289.9 + 324.9, 1e-9);
}

TEST(MachineryTest, FuelRateIsPowerTimesSfc) {
  const MachineryParams p;
  const FuelRate mec = FuelRateAt(p, MsoMode::kMec, 0.5);
  EXPECT_NEAR(mec.main_engine_kgps, 1080e3 * kSfcWartsila6L26(0.5) / 3.6e9, 1e-12);
  EXPECT_NEAR(mec.electrical_kgps, 200e3 * kSfcBaudouin6M26_3(200.0 / 510.0) / 3.6e9, 1e-12);
}

TEST(MachineryTest, SimplifiedThrustSettlesAtPowerOverK) {
  const MachineryParams p;
  SimplifiedPropulsion prop(p);
  for (int i = 0; i < 2000; ++i) prop.Integrate(prop.ThrustDerivative(MsoMode::kMec, 1.0), 0.5);
  EXPECT_NEAR(prop.thrust_n(), 790e3, 1.0);  // 2160 kW gives 790 kN
}

TEST(MachineryTest, ShaftModelSpinsUpAndMakesThrust) {
  const MachineryParams p;
  ShaftPropulsion shaft(p, ShaftParams{});
  const double w0 = shaft.omega_radps();
  EXPECT_NEAR(w0, 400 * std::numbers::pi / 30, 1e-12);
  for (int i = 0; i < 4000; ++i) shaft.Integrate(shaft.OmegaDerivative(MsoMode::kMec, 1.0), 0.5);
  // Steady: torque balance, positive thrust, below the max shaft speed.
  EXPECT_GT(shaft.ThrustN(), 0.0);
  EXPECT_NEAR(shaft.OmegaDerivative(MsoMode::kMec, 1.0), 0.0, 1e-6);
  ShaftPropulsion half(p, ShaftParams{});
  for (int i = 0; i < 4000; ++i) half.Integrate(half.OmegaDerivative(MsoMode::kMec, 0.5), 0.5);
  EXPECT_LT(half.ThrustN(), shaft.ThrustN());
}

TEST(MachineryTest, ValidateRejectsHotelLoadAboveEngine) {
  MachineryParams p;
  p.hotel_load_w = 3e6;
  EXPECT_EQ(p.Validate().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_TRUE(MachineryParams{}.Validate().ok());
}

}  // namespace
}  // namespace seaplan::ship
