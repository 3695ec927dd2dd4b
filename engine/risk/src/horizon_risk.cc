#include "seaplan/risk/horizon_risk.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace seaplan::risk {

Status GroundingCost::Validate() const {
  for (double c :
       {ship_eur, recovery_eur, cargo_eur, environment_eur, infrastructure_eur, reputation_eur}) {
    if (!(c >= 0.0) || !std::isfinite(c)) {
      return absl::InvalidArgumentError(
          absl::StrCat("GroundingCost: every component must be finite and >= 0, got ", c));
    }
  }
  return absl::OkStatus();
}

StatusOr<HorizonRisk> AccumulateOverHorizon(std::span<const double> conditional_p,
                                            std::span<const double> cost,
                                            std::span<double> interval_p) {
  if (cost.size() != 1 && cost.size() != conditional_p.size()) {
    return absl::InvalidArgumentError(absl::StrCat("AccumulateOverHorizon: ", cost.size(),
                                                   " costs for ", conditional_p.size(),
                                                   " intervals (need 1 or one per interval)"));
  }
  if (!interval_p.empty() && interval_p.size() != conditional_p.size()) {
    return absl::InvalidArgumentError(absl::StrCat("AccumulateOverHorizon: interval output has ",
                                                   interval_p.size(), " entries for ",
                                                   conditional_p.size(), " intervals"));
  }
  HorizonRisk r;
  for (size_t i = 0; i < conditional_p.size(); ++i) {
    const double p = conditional_p[i];
    if (!(p >= 0.0 && p <= 1.0)) {
      return absl::InvalidArgumentError(
          absl::StrCat("AccumulateOverHorizon: probability[", i, "] = ", p, " not in [0, 1]"));
    }
    const double c = cost.size() == 1 ? cost[0] : cost[i];
    if (!std::isfinite(c)) {
      return absl::InvalidArgumentError(
          absl::StrCat("AccumulateOverHorizon: cost[", i, "] not finite"));
    }
    const double pi = p * (1.0 - r.probability);
    if (!interval_p.empty()) interval_p[i] = pi;
    r.probability += pi;
    r.expected_cost += pi * c;
  }
  return r;
}

}  // namespace seaplan::risk
