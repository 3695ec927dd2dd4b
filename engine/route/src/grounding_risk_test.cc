#include "seaplan/route/grounding_risk.h"

#include <gtest/gtest.h>

#include <cmath>

namespace seaplan::route {
namespace {

TEST(GroundingRiskTest, AdapterFallsWithTimeAndMecIsMoreRobustThanPto) {
  auto model = risk::DriftingGroundingModel::Create();
  ASSERT_TRUE(model.ok()) << model.status();
  DriftingGroundingAdapter adapter(*model);
  const double lopp_me = 1 - std::exp(-3e-9 * 600.0);
  // No time to recover: P(G) = P(LOPP).
  EXPECT_NEAR(adapter.Probabilities(1.0)[0], lopp_me, 1e-15);
  EXPECT_NEAR(adapter.Probabilities(1.0)[1], lopp_me, 1e-15);
  ModeArray prev = adapter.Probabilities(30.0);
  for (double t = 60.0; t <= 630.0; t += 30.0) {
    const ModeArray p = adapter.Probabilities(t);
    for (int m = 0; m < kModeCount; ++m) {
      EXPECT_LE(p[m], prev[m]) << t;
      EXPECT_EQ(p[m], model->GroundingProbabilityExact(static_cast<MsoMode>(m), t));
    }
    // Restarting the HSG (12 s) beats starting a DG and the HSG (35 s + 12 s).
    EXPECT_LT(p[1], p[0]) << t;
    prev = p;
  }
  EXPECT_LT(adapter.Probabilities(630.0)[0], 1e-3 * lopp_me);
}

}  // namespace
}  // namespace seaplan::route
