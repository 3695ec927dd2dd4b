// Grounding stage 4, instantiation: every reached action instance's
// condition and effects grounded under its binding, simplified against the
// static facts and the reachable set, foralls expanded, disjunctions turned
// into ground DNF variants; then the initial state, timed literals, goal and
// metric. Facts are numbered in atom order (the reachable ones first), ground
// actions in instance order, numeric variables with the :init ones first.
#pragma once

#include <cstddef>
#include <memory>

#include "reachability_internal.h"

namespace seaplan::task::internal {

// A ground formula after simplification (no quantifiers left).
struct GroundFormula {
  enum class Kind { kTrue, kFalse, kLiteral, kComparison, kAnd, kOr };
  Kind kind = Kind::kTrue;
  FactId fact = -1;      // kLiteral
  bool positive = true;  // kLiteral
  pddl::TimeSpec time = pddl::TimeSpec::kNone;
  NumericCondition comparison;          // kComparison
  std::vector<GroundFormula> children;  // kAnd, kOr
};

// One disjunct of a ground DNF: literals and comparisons (into a GroundFormula).
struct GroundConjunction {
  std::vector<const GroundFormula*> leaves;
};

// False when the DNF would have more than kMaxDisjuncts disjuncts.
bool ToGroundDnf(const GroundFormula& formula, std::vector<GroundConjunction>& out);

struct InstantiatedTask {
  std::shared_ptr<GroundTask> task;  // null when grounding failed (diagnostics say why)
  std::size_t atoms_seen = 0;        // reachable and unreachable atoms interned, incl. static ones
};

InstantiatedTask Instantiate(const pddl::Domain& domain, const pddl::Problem& problem,
                             const SymbolTable& symbols, const CompiledSchemas& schemas,
                             ReachableTask reachable, GroundingContext& context);

}  // namespace seaplan::task::internal
