#include "seaplan/risk/grounding_risk.h"

#include <utility>

namespace seaplan::risk {

Status GroundingRiskOptions::Validate() const {
  SEAPLAN_RETURN_IF_ERROR(ttg.Validate());
  return probability.Validate();
}

StatusOr<GroundingRiskEvaluator> GroundingRiskEvaluator::Create(const ship::ShipParams& ship,
                                                                const GroundingRiskOptions& o) {
  SEAPLAN_RETURN_IF_ERROR(o.Validate());
  SEAPLAN_ASSIGN_OR_RETURN(TimeToGroundingSimulator sim, TimeToGroundingSimulator::Create(ship, o.ttg));
  SEAPLAN_ASSIGN_OR_RETURN(DriftingGroundingModel model, DriftingGroundingModel::Create(o.probability));
  return GroundingRiskEvaluator(std::move(sim), std::move(model), o.ungrounded);
}

PointRisk GroundingRiskEvaluator::Evaluate(const ship::ShipState& start,
                                           const ship::Environment& env,
                                           const GroundingTest& obstacles) const {
  PointRisk r;
  r.ttg = ttg_.Run(start, env, obstacles);
  if (!r.ttg.grounded && policy_ == UngroundedPolicy::kZero) return r;
  r.probability = model_.GroundingProbabilities(r.ttg.ttg_s);
  return r;
}

}  // namespace seaplan::risk
