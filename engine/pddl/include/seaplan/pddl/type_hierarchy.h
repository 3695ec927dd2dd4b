// The PDDL type hierarchy of a domain, walked once: every other library asks
// it rather than walking TypeDecl::parents itself (the parser's argument type
// checks, the grounder's object membership and its explanations for the
// validator, the mission action model's object lists).
//
// Ids: "object" is 0, then the declared types in declaration order (a type
// declared twice keeps its first id, its parents are merged), then parents
// that have no declaration of their own. A parent equal to its child is
// ignored. The reflexive-transitive ancestor relation is
// computed in the constructor (types x types bits), so IsSubtype is O(1).
// A cyclic declaration is not an error here: FindCycle reports it (the parser
// turns it into a diagnostic) and IsSubtype answers along the cycle.
//
// Thread-safety: immutable after construction; every const method is safe to
// call concurrently.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/pddl/parser.h"

namespace seaplan::pddl {

class TypeHierarchy {
 public:
  TypeHierarchy() : TypeHierarchy(std::span<const TypeDecl>{}) {}
  explicit TypeHierarchy(std::span<const TypeDecl> types);

  int size() const { return static_cast<int>(names_.size()); }
  // The id of a declared type ("object" is always 0), or -1.
  int Id(std::string_view type) const;
  bool Known(std::string_view type) const { return Id(type) >= 0; }
  const std::string& Name(int id) const { return names_[static_cast<std::size_t>(id)]; }

  // True when `type` is `ancestor` or a (transitive) subtype of it.
  bool IsSubtype(int type, int ancestor) const;
  // Same by name; every name (declared or not) is a subtype of itself and of
  // "object", an undeclared one of nothing else.
  bool IsSubtype(std::string_view type, std::string_view ancestor) const;

  // The first declared type (declaration order) that is its own proper
  // ancestor, or "" when the hierarchy is a tree below object.
  std::string FindCycle() const;

 private:
  std::vector<std::string> names_;
  std::map<std::string, int, std::less<>> index_;
  std::vector<std::vector<int>> parents_;  // by id, without self-parents
  std::size_t words_per_row_ = 0;
  std::vector<std::uint64_t> ancestor_bits_;  // row t, bit a: a is an ancestor of t
};

}  // namespace seaplan::pddl
