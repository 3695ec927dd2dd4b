// Grounding stage 1, symbols: the domain's and problem's names interned to
// dense ids, each object's type membership (the type hierarchy walked once),
// and which predicates and functions are static (changed by no effect, no
// timed literal and no timed fluent), which the later stages fold away.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "grounding_internal.h"

namespace seaplan::task::internal {

// Immutable once built; the later stages read it.
struct SymbolTable {
  std::unordered_map<std::string, TypeId> type_ids;
  std::vector<std::string> type_names;  // by TypeId; 0 is "object"
  std::unordered_map<std::string, ObjectId> object_ids;
  std::vector<std::string> object_names;                        // by ObjectId
  std::vector<std::vector<std::string>> object_declared_types;  // by ObjectId
  std::vector<std::vector<ObjectId>> objects_of_type;           // by TypeId, incl. subtypes
  std::unordered_map<std::string, PredicateId> predicate_ids;
  std::vector<std::string> predicate_names;  // by PredicateId
  std::vector<int> predicate_arity;          // by PredicateId
  std::vector<bool> predicate_is_static;     // by PredicateId
  std::unordered_map<std::string, FunctionId> function_ids;
  std::vector<std::string> function_names;  // by FunctionId
  std::vector<bool> function_is_static;     // by FunctionId

  // None() when the name is not declared.
  TypeId FindType(const std::string& name) const;
  ObjectId FindObject(const std::string& name) const;
  PredicateId FindPredicate(const std::string& name) const;
  FunctionId FindFunction(const std::string& name) const;

  std::size_t object_count() const { return object_names.size(); }
  // True when `object` is of `type` or one of its subtypes.
  bool HasType(ObjectId object, TypeId type) const;
  bool IsStatic(PredicateId predicate) const { return predicate_is_static[predicate.index()]; }
  bool IsStatic(FunctionId function) const { return function_is_static[function.index()]; }
  const std::string& Name(ObjectId object) const { return object_names[object.index()]; }
  const std::string& Name(PredicateId predicate) const {
    return predicate_names[predicate.index()];
  }
  const std::string& Name(FunctionId function) const { return function_names[function.index()]; }
};

// Interns every symbol, checks that the problem's :init, timed literals,
// goal and metric use only declared names (Ground() accepts edited ASTs, not
// only parser output) and finds the static predicates and functions.
// nullopt when the problem does not match the domain (diagnostics say where).
std::optional<SymbolTable> BuildSymbols(const pddl::Domain& domain, const pddl::Problem& problem,
                                        GroundingContext& context);

// The objects of each type, subtypes included, in ascending ObjectId order
// per type (objects_of_type). The one place the grounder walks the type
// hierarchy: ancestors of every type once, then each object's membership
// from its declared types, linear in objects.
std::vector<std::vector<ObjectId>> ObjectsOfEachType(
    const pddl::Domain& domain, const std::unordered_map<std::string, TypeId>& type_ids,
    const std::vector<std::vector<std::string>>& object_declared_types);

}  // namespace seaplan::task::internal
