// Grounding cost and accumulation of interval probabilities over a
// prediction horizon (DGRM AccumulatedRiskInPredictionHorizon; SHIP_MODEL.md
// §7; paper 002 eq. 4–6).
//
// The horizon is cut into n risk intervals; for interval i the risk model
// gives p_i = P(G_i | no grounding earlier). Then
//     P_i = p_i * (1 - sum_{j<i} P_j),   P(G) = sum_i P_i,
//     Risk = sum_i P_i * C_i.
// (MISSION.md writes the survival factor as prod_{j<i}(1 - P_j); the two agree
// for two intervals and differ at O(P^2) from the third on. We follow the
// public code and SHIP_MODEL.md §7.)
#pragma once

#include <span>

#include "seaplan/common/status.h"

namespace seaplan::risk {

// Cost of one grounding, C_G = sum of the components (paper 002 eq. 6; the
// paper keeps it constant and gives no figures). Defaults are illustrative
// order-of-magnitude values in EUR for a 5 000 t coastal cargo ship on a
// rocky Norwegian shore, NOT from the paper: set them per deployment.
struct GroundingCost {
  double ship_eur = 2.0e6;            // hull and machinery repair, off-hire
  double recovery_eur = 1.5e6;        // salvage, towing, refloating
  double cargo_eur = 0.5e6;           // damaged or lost cargo
  double environment_eur = 3.0e6;     // oil spill response and damage
  double infrastructure_eur = 0.5e6;  // quays, fish farms, cables hit
  double reputation_eur = 1.0e6;      // lost business
  double Total() const {
    return ship_eur + recovery_eur + cargo_eur + environment_eur + infrastructure_eur +
           reputation_eur;
  }
  Status Validate() const;
};

struct HorizonRisk {
  double probability = 0.0;    // P(G) over the horizon
  double expected_cost = 0.0;  // sum_i P_i C_i
};

// `conditional_p[i]` = p_i in [0, 1]; `cost[i]` = C_i (size 1 means the same
// cost for every interval). If `interval_p` is non-empty it must have the
// size of conditional_p and receives P_i. No allocation.
StatusOr<HorizonRisk> AccumulateOverHorizon(std::span<const double> conditional_p,
                                            std::span<const double> cost,
                                            std::span<double> interval_p = {});

// Unchecked version for hot loops (sizes and ranges are the caller's
// invariant): constant cost.
inline HorizonRisk AccumulateOverHorizonUnchecked(std::span<const double> conditional_p,
                                                  double cost) {
  HorizonRisk r;
  for (double p : conditional_p) {
    const double pi = p * (1.0 - r.probability);
    r.probability += pi;
    r.expected_cost += pi * cost;
  }
  return r;
}

}  // namespace seaplan::risk
