#include "seaplan/route/grounding_risk.h"

#include <gtest/gtest.h>

#include <cmath>

namespace seaplan::route {
namespace {

TEST(GroundingRiskTest, RecoveryEventCdfReading) {
  RecoveryEvent e{0.4, 50.0, 1.4, 20.0};
  EXPECT_EQ(e.Probability(20.0), 0.0);             // not before the minimum time
  EXPECT_NEAR(e.Probability(70.0), 0.2, 1e-12);    // median = shift + scale
  EXPECT_NEAR(e.Probability(1e9), 0.4, 1e-6);      // nominal probability at the end
}

TEST(GroundingRiskTest, ProbabilitiesFallWithTimeAndMecIsMoreRobustThanPto) {
  EventTreeGroundingModel model;
  ModeArray prev = model.Probabilities(30.0);
  const double lopp_me = 1 - std::exp(-3e-9 * 600.0);
  // No time to recover: P(G) = P(LOPP).
  EXPECT_NEAR(model.Probabilities(1.0)[0], lopp_me, 1e-15);
  EXPECT_NEAR(model.Probabilities(1.0)[1], lopp_me, 1e-15);
  for (double t = 60.0; t <= 630.0; t += 30.0) {
    const ModeArray p = model.Probabilities(t);
    for (int m = 0; m < kModeCount; ++m) EXPECT_LE(p[m], prev[m]) << t;
    // Restarting the HSG (12 s) beats starting a DG and the HSG (35 s + 12 s).
    EXPECT_LT(p[1], p[0]) << t;
    prev = p;
  }
  EXPECT_LT(model.Probabilities(630.0)[0], 1e-3 * lopp_me);
}

}  // namespace
}  // namespace seaplan::route
