#include "seaplan/risk/horizon_risk.h"

#include <array>
#include <vector>

#include "gtest/gtest.h"

namespace seaplan::risk {
namespace {

TEST(HorizonRiskTest, TwoIntervalsByHand) {
  // P1 = 0.1; P2 = 0.2 * (1 - 0.1) = 0.18; P = 0.28; risk = 100 * 0.28.
  const std::array<double, 2> p = {0.1, 0.2};
  const std::array<double, 1> cost = {100.0};
  std::array<double, 2> per = {};
  auto r = AccumulateOverHorizon(p, cost, per);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_DOUBLE_EQ(per[0], 0.1);
  EXPECT_DOUBLE_EQ(per[1], 0.18);
  EXPECT_DOUBLE_EQ(r->probability, 0.28);
  EXPECT_DOUBLE_EQ(r->expected_cost, 28.0);
  // Per-interval costs: 0.1 * 100 + 0.18 * 1000 = 190.
  const std::array<double, 2> costs = {100.0, 1000.0};
  auto r2 = AccumulateOverHorizon(p, costs);
  ASSERT_TRUE(r2.ok());
  EXPECT_DOUBLE_EQ(r2->expected_cost, 190.0);
  const HorizonRisk fast = AccumulateOverHorizonUnchecked(p, 100.0);
  EXPECT_DOUBLE_EQ(fast.probability, 0.28);
  EXPECT_DOUBLE_EQ(fast.expected_cost, 28.0);
}

TEST(HorizonRiskTest, SumFormOnThreeIntervals) {
  // P3 = 0.5 * (1 - (0.5 + 0.25)) = 0.125 (sum form, as the public code).
  const std::array<double, 3> p = {0.5, 0.5, 0.5};
  const std::array<double, 1> cost = {1.0};
  auto r = AccumulateOverHorizon(p, cost);
  ASSERT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r->probability, 0.875);
}

TEST(HorizonRiskTest, CertainGroundingStopsAccumulation) {
  const std::array<double, 3> p = {1.0, 0.7, 0.9};
  const std::array<double, 1> cost = {5.0};
  auto r = AccumulateOverHorizon(p, cost);
  ASSERT_TRUE(r.ok());
  EXPECT_DOUBLE_EQ(r->probability, 1.0);
  EXPECT_DOUBLE_EQ(r->expected_cost, 5.0);
}

TEST(HorizonRiskTest, RejectsBadInput) {
  const std::array<double, 2> p = {0.1, 1.5};
  const std::array<double, 1> cost = {1.0};
  EXPECT_EQ(AccumulateOverHorizon(p, cost).status().code(), absl::StatusCode::kInvalidArgument);
  const std::array<double, 2> ok = {0.1, 0.2};
  const std::array<double, 3> three = {1, 2, 3};
  EXPECT_FALSE(AccumulateOverHorizon(ok, three).ok());
  std::array<double, 1> short_out = {};
  EXPECT_FALSE(AccumulateOverHorizon(ok, cost, short_out).ok());
}

TEST(HorizonRiskTest, GroundingCostTotal) {
  GroundingCost c;
  EXPECT_DOUBLE_EQ(c.Total(), 8.5e6);
  EXPECT_TRUE(c.Validate().ok());
  c.environment_eur = -1;
  EXPECT_FALSE(c.Validate().ok());
}

}  // namespace
}  // namespace seaplan::risk
