#include "seaplan/risk/grounding_risk.h"

#include <vector>

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

TEST(GroundingRiskTest, RouteRiskAccumulatesPerIntervalModes) {
  GroundingRiskOptions o;
  o.probability.risk_interval_s = 30.0;
  auto eval = GroundingRiskEvaluator::Create(ship::ShipParams{}, o);
  ASSERT_TRUE(eval.ok());
  Environment env;
  env.current_east_mps = 1.0;
  auto shore = *PolygonObstacles::Create({{{-1e4, 300}, {1e4, 300}, {1e4, 1e3}, {-1e4, 1e3}}});
  // Three samples approaching the shore, sailed north.
  const std::vector<ShipState> samples = {ShipState::At(0, 0, 0, 5), ShipState::At(150, 100, 0, 5),
                                          ShipState::At(300, 200, 0, 5)};
  const std::vector<MsoMode> modes = {MsoMode::kPto, MsoMode::kMec, MsoMode::kPti};
  std::vector<double> per(3);
  auto r = eval->RouteRisk(samples, modes, env, shore, 1e6, per);
  ASSERT_TRUE(r.ok()) << r.status();
  // By hand from the single-point evaluations.
  double acc = 0.0;
  for (int i = 0; i < 3; ++i) {
    const double p = eval->Evaluate(samples[i], env, shore).probability[modes[i]];
    EXPECT_DOUBLE_EQ(per[i], p * (1.0 - acc));
    acc += per[i];
  }
  EXPECT_DOUBLE_EQ(r->probability, acc);
  EXPECT_DOUBLE_EQ(r->expected_cost, acc * 1e6);
  // All in PTO is riskier than MEC everywhere.
  const std::vector<MsoMode> pto(3, MsoMode::kPto), mec(3, MsoMode::kMec);
  EXPECT_GT(eval->RouteRisk(samples, pto, env, shore, 1.0)->probability,
            eval->RouteRisk(samples, mec, env, shore, 1.0)->probability);
  EXPECT_FALSE(
      eval->RouteRisk(samples, std::span<const MsoMode>(modes).first(2), env, shore, 1.0).ok());
}

}  // namespace
}  // namespace seaplan::risk
