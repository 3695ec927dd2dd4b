// Grounding stage 3, reachability: a relaxed exploration (Datalog-style, as
// Fast Downward's translator) from the initial state. A queue of reached
// atoms; popping an atom triggers every precondition disjunct with a
// positive atom of that predicate, which is joined with the other positive
// atoms reached so far (most selective first: bound positions are looked up
// in per-argument indexes). Static atoms are reached from the start, so
// static preconditions act as filters. Negative fluent literals and numeric
// conditions over changing fluents are optimistic; static ones are
// evaluated. Every add effect of a reached instance (conditional ones
// included) is reached, as is every atom a timed literal adds.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "schema_internal.h"
#include "tuple_set_internal.h"

namespace seaplan::task::internal {

// Ground atoms interned as (predicate, objects...), with the reached flag
// the exploration sets. Later stages intern more atoms (goals and timed
// literals nothing reaches); those are never reached.
class AtomTable {
 public:
  // The atom's id; `inserted` (when given) tells whether it is new.
  AtomId Intern(PredicateId predicate, std::span<const ObjectId> args, bool* inserted = nullptr);
  // None() when the atom was never interned.
  AtomId Find(PredicateId predicate, std::span<const ObjectId> args);

  std::size_t size() const { return atoms_.size(); }
  PredicateId predicate(AtomId atom) const { return PredicateId(atoms_.Get(atom.value())[0]); }
  std::vector<ObjectId> arguments(AtomId atom) const;
  // (predicate, objects...) as stored, for the join's inner loops.
  std::span<const std::int32_t> packed(AtomId atom) const { return atoms_.Get(atom.value()); }

  bool reached(AtomId atom) const { return reached_[atom.index()] != 0; }
  // Reached and `atom` valid: true in the relaxed fixpoint.
  bool IsReached(AtomId atom) const { return atom.valid() && reached(atom); }
  void MarkReached(AtomId atom) { reached_[atom.index()] = 1; }

 private:
  void PackKey(PredicateId predicate, std::span<const ObjectId> args);

  TupleSet atoms_;
  std::vector<std::uint8_t> reached_;  // by AtomId
  std::vector<std::int32_t> key_;      // scratch
};

// Ground function terms interned as (function, objects...), with their
// values in :init (NaN when undefined).
class FunctionTermTable {
 public:
  FunctionTermId Intern(FunctionId function, std::span<const ObjectId> args,
                        bool* inserted = nullptr);
  // Value in :init of (function args); NaN when undefined.
  double InitialValue(FunctionId function, std::span<const ObjectId> args);
  void SetInitialValue(FunctionId function, std::span<const ObjectId> args, double value);

  std::size_t size() const { return terms_.size(); }
  FunctionId function(FunctionTermId term) const { return FunctionId(terms_.Get(term.value())[0]); }
  std::vector<ObjectId> arguments(FunctionTermId term) const;
  double initial_value(FunctionTermId term) const { return initial_values_[term.index()]; }

 private:
  void PackKey(FunctionId function, std::span<const ObjectId> args);

  TupleSet terms_;
  std::vector<double> initial_values_;  // by FunctionTermId
  std::vector<std::int32_t> key_;       // scratch
};

// Reached action instances: (disjunct, binding of every schema variable).
// The order of insertion is the order of the ground actions.
class InstanceTable {
 public:
  // True when new.
  bool Insert(DisjunctId disjunct, const Binding& binding);
  std::size_t size() const { return instances_.size(); }
  DisjunctId disjunct(std::size_t instance) const {
    return DisjunctId(instances_.Get(static_cast<std::int32_t>(instance))[0]);
  }
  Binding binding(std::size_t instance) const;

 private:
  TupleSet instances_;
  std::vector<std::int32_t> key_;  // scratch
};

// The stage's value, handed (moved) to instantiation.
struct ReachableTask {
  AtomTable atoms;  // every atom seen; reached() = true in the relaxed fixpoint
  FunctionTermTable function_terms;
  std::vector<AtomId> initial_atoms;        // fluent atoms of :init, in order
  std::vector<AtomId> timed_literal_atoms;  // one per problem timed literal
  InstanceTable instances;
  std::size_t static_true_atoms = 0;  // distinct static atoms of :init
};

// Loads :init (static atoms reached at once, fluent atoms queued) and runs
// the fixpoint. nullopt when a budget is spent or the stop token fired.
std::optional<ReachableTask> ExploreReachability(const SymbolTable& symbols,
                                                 const CompiledSchemas& schemas,
                                                 const pddl::Problem& problem,
                                                 GroundingContext& context);

// Value of a numeric expression over static fluents under `binding`; NaN
// when a fluent read is undefined, the expression reads ?duration or
// total-time, or a division is by zero.
double EvaluateStatic(const SchemaExpression& expression, const Binding& binding,
                      FunctionTermTable& function_terms);

}  // namespace seaplan::task::internal
