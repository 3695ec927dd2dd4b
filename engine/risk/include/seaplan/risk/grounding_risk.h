// One-call drifting-grounding risk at a point of a route: the TTG drift
// simulation followed by P(grounding | mode) for all three MSO modes. This is
// what the Level-2 optimiser calls per particle and waypoint.
//
// Cost: one TTG simulation (<= 21 Euler steps + hull tests with the
// defaults) and three table lookups; no heap allocation.
// Thread-safety: immutable after Create; Evaluate is const and reentrant
// provided the GroundingTest is.
#pragma once

#include <span>

#include "seaplan/common/status.h"
#include "seaplan/risk/drifting_grounding.h"
#include "seaplan/risk/grounding_test.h"
#include "seaplan/risk/horizon_risk.h"
#include "seaplan/risk/time_to_grounding.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::risk {

// What P(G) is when the drift does not ground within the horizon.
enum class UngroundedPolicy {
  // AMM: use the stopping time (horizon + dt) as the recovery time. The
  // probabilities are then small but not zero. Default (reproduces AMM).
  kUseStopTime,
  // No grounding within the horizon means no grounding risk in this interval.
  kZero,
};

struct GroundingRiskOptions {
  TtgOptions ttg;
  DriftingGroundingParams probability;
  UngroundedPolicy ungrounded = UngroundedPolicy::kUseStopTime;
  Status Validate() const;
};

struct PointRisk {
  TtgResult ttg;
  ModeProbabilities probability;  // P(G in the risk interval | mode)
};

class GroundingRiskEvaluator {
 public:
  static StatusOr<GroundingRiskEvaluator> Create(const ship::ShipParams& ship,
                                                 const GroundingRiskOptions& options = {});

  PointRisk Evaluate(const ship::ShipState& start, const ship::Environment& env,
                     const GroundingTest& obstacles) const;

  // Grounding risk accumulated along a route over a horizon: `samples[i]` is
  // the ship's state at the start of risk interval i and `modes[i]` the MSO
  // mode sailed in it (same sizes). Each sample gets one TTG drift and
  // P(G_i | mode_i); the P_i are accumulated as in horizon_risk.h with the
  // constant cost `cost`. The sample spacing in time should equal
  // DriftingGroundingParams::risk_interval_s (the paper: 30 s; AMM: 600 s).
  // If `interval_p` is non-empty (same size) it receives P_i. No allocation.
  StatusOr<HorizonRisk> RouteRisk(std::span<const ship::ShipState> samples,
                                  std::span<const MsoMode> modes, const ship::Environment& env,
                                  const GroundingTest& obstacles, double cost,
                                  std::span<double> interval_p = {}) const;

  const TimeToGroundingSimulator& ttg() const { return ttg_; }
  const DriftingGroundingModel& model() const { return model_; }

 private:
  GroundingRiskEvaluator(TimeToGroundingSimulator t, DriftingGroundingModel m, UngroundedPolicy p)
      : ttg_(std::move(t)), model_(std::move(m)), policy_(p) {}
  TimeToGroundingSimulator ttg_;
  DriftingGroundingModel model_;
  UngroundedPolicy policy_;
};

}  // namespace seaplan::risk
