#include "seaplan/risk/grounding_risk.h"

#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"

namespace seaplan::risk {

Status GroundingRiskOptions::Validate() const {
  SEAPLAN_RETURN_IF_ERROR(ttg.Validate());
  return probability.Validate();
}

StatusOr<GroundingRiskEvaluator> GroundingRiskEvaluator::Create(const ship::ShipParams& ship,
                                                                const GroundingRiskOptions& o) {
  SEAPLAN_RETURN_IF_ERROR(o.Validate());
  SEAPLAN_ASSIGN_OR_RETURN(TimeToGroundingSimulator sim,
                           TimeToGroundingSimulator::Create(ship, o.ttg));
  SEAPLAN_ASSIGN_OR_RETURN(DriftingGroundingModel model,
                           DriftingGroundingModel::Create(o.probability));
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

StatusOr<HorizonRisk> GroundingRiskEvaluator::RouteRisk(std::span<const ship::ShipState> samples,
                                                        std::span<const MsoMode> modes,
                                                        const ship::Environment& env,
                                                        const GroundingTest& obstacles, double cost,
                                                        std::span<double> interval_p) const {
  if (samples.size() != modes.size() ||
      (!interval_p.empty() && interval_p.size() != samples.size())) {
    return absl::InvalidArgumentError(absl::StrCat("RouteRisk: ", samples.size(), " samples, ",
                                                   modes.size(), " modes, ", interval_p.size(),
                                                   " outputs (need equal sizes)"));
  }
  if (!std::isfinite(cost)) return absl::InvalidArgumentError("RouteRisk: cost must be finite");
  SEAPLAN_RETURN_IF_ERROR(env.Validate());
  HorizonRisk r;
  for (size_t i = 0; i < samples.size(); ++i) {
    SEAPLAN_RETURN_IF_ERROR(TimeToGroundingSimulator::CheckInputs(samples[i], env));
    const PointRisk pr = Evaluate(samples[i], env, obstacles);
    const double pi = pr.probability[modes[i]] * (1.0 - r.probability);
    if (!interval_p.empty()) interval_p[i] = pi;
    r.probability += pi;
    r.expected_cost += pi * cost;
  }
  return r;
}

}  // namespace seaplan::risk
