#include "seaplan/risk/grounding_risk.h"

#include "gtest/gtest.h"

namespace seaplan::risk {
namespace {

using ship::Environment;
using ship::MsoMode;
using ship::ShipState;

TEST(GroundingRiskTest, CloserShoreMeansHigherRisk) {
  auto eval = GroundingRiskEvaluator::Create(ship::ShipParams{});
  ASSERT_TRUE(eval.ok()) << eval.status();
  Environment env;
  env.current_east_mps = 1.0;
  auto shore_at = [](double e) {
    return *PolygonObstacles::Create({{{-1e4, e}, {1e4, e}, {1e4, e + 1e3}, {-1e4, e + 1e3}}});
  };
  const PointRisk near = eval->Evaluate(ShipState::At(0, 0, 0), env, shore_at(100));
  const PointRisk far = eval->Evaluate(ShipState::At(0, 0, 0), env, shore_at(400));
  ASSERT_TRUE(near.ttg.grounded && far.ttg.grounded);
  EXPECT_LT(near.ttg.ttg_s, far.ttg.ttg_s);
  for (MsoMode m : ship::kAllMsoModes) {
    EXPECT_GT(near.probability[m], far.probability[m]) << ship::MsoModeName(m);
    EXPECT_EQ(near.probability[m], eval->model().GroundingProbability(m, near.ttg.ttg_s));
  }
}

TEST(GroundingRiskTest, UngroundedPolicy) {
  auto none = *PolygonObstacles::Create({});
  GroundingRiskOptions amm;
  auto a = GroundingRiskEvaluator::Create(ship::ShipParams{}, amm);
  GroundingRiskOptions zero;
  zero.ungrounded = UngroundedPolicy::kZero;
  auto z = GroundingRiskEvaluator::Create(ship::ShipParams{}, zero);
  ASSERT_TRUE(a.ok() && z.ok());
  const PointRisk ra = a->Evaluate(ShipState::At(0, 0, 0, 2), Environment{}, none);
  const PointRisk rz = z->Evaluate(ShipState::At(0, 0, 0, 2), Environment{}, none);
  EXPECT_FALSE(ra.ttg.grounded);
  EXPECT_DOUBLE_EQ(ra.ttg.ttg_s, 630.0);
  EXPECT_GT(ra.probability[MsoMode::kPti], 0.0);  // AMM: tiny but not zero
  EXPECT_EQ(rz.probability[MsoMode::kPti], 0.0);
  EXPECT_EQ(rz.probability[MsoMode::kPto], 0.0);
}

}  // namespace
}  // namespace seaplan::risk
