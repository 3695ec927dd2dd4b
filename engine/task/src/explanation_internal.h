// Grounding stage 5, explanation: why an action instance is not in the
// ground task, in PDDL terms, from the values of the first three stages
// (ExplainMissingAction in grounder.h runs them and calls this).
#pragma once

#include <span>
#include <string>

#include "reachability_internal.h"

namespace seaplan::task::internal {

// The first reason (per precondition disjunct, in order) why `schema` bound
// to `parameters` is not grounded: a false equality, a false static literal,
// an unreachable fluent literal, a false or undefined static comparison, an
// undefined duration. When none is found: a sentence saying so, which
// depends on whether the instance was looked up in a ground task
// (`task_given`). `call` is "(name args...)", the sentence's start.
std::string ExplainInstance(const SymbolTable& symbols, const CompiledSchemas& schemas,
                            ReachableTask& reachable, SchemaId schema,
                            std::span<const ObjectId> parameters, const std::string& call,
                            bool task_given);

}  // namespace seaplan::task::internal
