#include <algorithm>
#include <cstdint>

#include "symbols_internal.h"

namespace seaplan::task::internal {
namespace {

template <typename Id>
Id FindIn(const std::unordered_map<std::string, Id>& ids, const std::string& name) {
  auto it = ids.find(name);
  return it == ids.end() ? Id::None() : it->second;
}

void InternNames(const pddl::Domain& domain, const pddl::Problem& problem, SymbolTable& symbols) {
  symbols.type_ids.emplace("object", TypeId(0));
  symbols.type_names.push_back("object");
  for (const auto& t : domain.types) {
    if (symbols.type_ids.emplace(t.name, TypeId(symbols.type_names.size())).second)
      symbols.type_names.push_back(t.name);
  }
  auto add_object = [&](const pddl::TypedName& o) {
    if (symbols.object_ids.emplace(o.name, ObjectId(symbols.object_names.size())).second) {
      symbols.object_names.push_back(o.name);
      symbols.object_declared_types.push_back(o.types);
    }
  };
  for (const auto& c : domain.constants) add_object(c);
  for (const auto& o : problem.objects) add_object(o);
  symbols.objects_of_type =
      ObjectsOfEachType(domain, symbols.type_ids, symbols.object_declared_types);
  for (const auto& p : domain.predicates) {
    symbols.predicate_ids[p.name] = PredicateId(symbols.predicate_names.size());
    symbols.predicate_names.push_back(p.name);
    symbols.predicate_arity.push_back(static_cast<int>(p.parameters.size()));
  }
  symbols.predicate_is_static.assign(symbols.predicate_names.size(), true);
  for (const auto& f : domain.functions) {
    symbols.function_ids[f.name] = FunctionId(symbols.function_names.size());
    symbols.function_names.push_back(f.name);
  }
  symbols.function_is_static.assign(symbols.function_names.size(), true);
}

// Ground() accepts ASTs built or edited by code (e.g. a replanning loop
// updating :init), not only parser output: check what the grounder indexes
// by, so a mismatch is a diagnostic rather than an out-of-range access.
bool ProblemMatchesDomain(const pddl::Domain& domain, const pddl::Problem& problem,
                          const SymbolTable& symbols, GroundingContext& context) {
  bool ok = true;
  auto unknown_object = [&](const pddl::SourceLocation& at, const std::string& name) {
    context.Error(pddl::DiagnosticKind::kSemantic, at, name, "unknown object", "a declared object");
    ok = false;
  };
  auto check_atom = [&](const pddl::Atom& atom) {
    const PredicateId predicate = symbols.FindPredicate(atom.predicate);
    if (!predicate.valid() ||
        symbols.predicate_arity[predicate.index()] != static_cast<int>(atom.args.size())) {
      context.Error(pddl::DiagnosticKind::kSemantic, atom.location, atom.predicate,
                    "initial atom does not match a predicate of the domain",
                    "a declared predicate with its arity");
      ok = false;
      return;
    }
    for (const auto& t : atom.args) {
      if (!symbols.FindObject(t.name).valid()) unknown_object(t.location, t.name);
    }
  };
  auto check_numeric = [&](const pddl::NumericInit& n) {
    const FunctionId function = symbols.FindFunction(n.function);
    if (!function.valid() ||
        domain.functions[function.index()].parameters.size() != n.args.size()) {
      context.Error(pddl::DiagnosticKind::kSemantic, n.location, n.function,
                    "numeric initialisation does not match a function of the domain",
                    "a declared function");
      ok = false;
      return;
    }
    for (const auto& a : n.args) {
      if (!symbols.FindObject(a).valid()) unknown_object(n.location, a);
    }
  };
  for (const auto& atom : problem.init) check_atom(atom);
  for (const auto& til : problem.timed_literals) check_atom(til.atom);
  // Goal and metric: names must exist (variables are bound by quantifiers).
  std::vector<const pddl::NumExpr*> expressions;
  std::vector<const pddl::Condition*> todo{&problem.goal};
  if (problem.metric.present) expressions.push_back(&problem.metric.expression);
  while (!todo.empty()) {
    const pddl::Condition* c = todo.back();
    todo.pop_back();
    if (c->kind == pddl::Condition::Kind::kAtom) {
      if (c->atom.predicate != "=" && !symbols.FindPredicate(c->atom.predicate).valid()) {
        context.Error(pddl::DiagnosticKind::kSemantic, c->atom.location, c->atom.predicate,
                      "goal uses an unknown predicate", "a declared predicate");
        ok = false;
      }
      for (const auto& t : c->atom.args) {
        if (!t.IsVariable() && !symbols.FindObject(t.name).valid())
          unknown_object(t.location, t.name);
      }
    } else if (c->kind == pddl::Condition::Kind::kCompare) {
      expressions.push_back(&c->lhs);
      expressions.push_back(&c->rhs);
    }
    for (const auto& child : c->children) todo.push_back(&child);
  }
  while (!expressions.empty()) {
    const pddl::NumExpr* e = expressions.back();
    expressions.pop_back();
    if (e->kind == pddl::NumExpr::Kind::kFluent && !symbols.FindFunction(e->function).valid()) {
      context.Error(pddl::DiagnosticKind::kSemantic, e->location, e->function, "unknown function",
                    "a declared function");
      ok = false;
    }
    for (const auto& child : e->children) expressions.push_back(&child);
  }
  for (const auto& n : problem.numeric_init) check_numeric(n);
  for (const auto& n : problem.timed_numeric_init) check_numeric(n.init);
  return ok;
}

void MarkChangedByEffect(const pddl::Effect& e, SymbolTable& symbols) {
  switch (e.kind) {
    case pddl::Effect::Kind::kAdd:
    case pddl::Effect::Kind::kDelete: {
      const PredicateId predicate = symbols.FindPredicate(e.atom.predicate);
      if (predicate.valid()) symbols.predicate_is_static[predicate.index()] = false;
      break;
    }
    case pddl::Effect::Kind::kNumeric: {
      const FunctionId function = symbols.FindFunction(e.fluent.function);
      if (function.valid()) symbols.function_is_static[function.index()] = false;
      break;
    }
    default:
      break;
  }
  for (const auto& child : e.children) MarkChangedByEffect(child, symbols);
}

void FindStatics(const pddl::Domain& domain, const pddl::Problem& problem, SymbolTable& symbols) {
  for (const auto& a : domain.actions) MarkChangedByEffect(a.effect, symbols);
  for (const auto& til : problem.timed_literals) {
    const PredicateId predicate = symbols.FindPredicate(til.atom.predicate);
    if (predicate.valid()) symbols.predicate_is_static[predicate.index()] = false;
  }
  for (const auto& tif : problem.timed_numeric_init) {
    const FunctionId function = symbols.FindFunction(tif.init.function);
    if (function.valid()) symbols.function_is_static[function.index()] = false;
  }
}

}  // namespace

TypeId SymbolTable::FindType(const std::string& name) const {
  return FindIn(type_ids, name);
}
ObjectId SymbolTable::FindObject(const std::string& name) const {
  return FindIn(object_ids, name);
}
PredicateId SymbolTable::FindPredicate(const std::string& name) const {
  return FindIn(predicate_ids, name);
}
FunctionId SymbolTable::FindFunction(const std::string& name) const {
  return FindIn(function_ids, name);
}

bool SymbolTable::HasType(ObjectId object, TypeId type) const {
  const auto& members = objects_of_type[type.index()];
  return std::binary_search(members.begin(), members.end(), object);
}

std::vector<std::vector<ObjectId>> ObjectsOfEachType(
    const pddl::Domain& domain, const std::unordered_map<std::string, TypeId>& type_ids,
    const std::vector<std::vector<std::string>>& object_declared_types) {
  const std::size_t type_count = type_ids.size();
  // Ancestors of every type once (types x types), then each object's
  // membership from its declared types: linear in objects.
  std::vector<std::vector<TypeId>> parents(type_count);
  for (const auto& t : domain.types) {
    const TypeId child = FindIn(type_ids, t.name);
    for (const auto& p : t.parents) {
      const TypeId parent = FindIn(type_ids, p);
      if (child.valid() && parent.valid() && parent != child)
        parents[child.index()].push_back(parent);
    }
  }
  std::vector<std::vector<std::uint8_t>> is_ancestor(type_count,
                                                     std::vector<std::uint8_t>(type_count, 0));
  for (std::size_t t = 0; t < type_count; ++t) {
    std::vector<TypeId> todo{TypeId(t)};
    is_ancestor[t][t] = 1;
    is_ancestor[t][0] = 1;  // everything is an object
    while (!todo.empty()) {
      const TypeId type = todo.back();
      todo.pop_back();
      for (TypeId parent : parents[type.index()]) {
        if (!is_ancestor[t][parent.index()]) {
          is_ancestor[t][parent.index()] = 1;
          todo.push_back(parent);
        }
      }
    }
  }
  const std::size_t object_count = object_declared_types.size();
  std::vector<std::vector<ObjectId>> objects_of_type(type_count);
  std::vector<std::vector<std::uint8_t>> is_member(type_count,
                                                   std::vector<std::uint8_t>(object_count, 0));
  for (std::size_t o = 0; o < object_count; ++o) {
    for (const auto& declared : object_declared_types[o]) {
      const TypeId declared_type = FindIn(type_ids, declared);
      if (!declared_type.valid()) continue;
      for (std::size_t t = 0; t < type_count; ++t) {
        if (is_ancestor[declared_type.index()][t] && !is_member[t][o]) {
          is_member[t][o] = 1;
          objects_of_type[t].push_back(ObjectId(o));
        }
      }
    }
  }
  return objects_of_type;
}

std::optional<SymbolTable> BuildSymbols(const pddl::Domain& domain, const pddl::Problem& problem,
                                        GroundingContext& context) {
  SymbolTable symbols;
  InternNames(domain, problem, symbols);
  if (!ProblemMatchesDomain(domain, problem, symbols, context)) return std::nullopt;
  FindStatics(domain, problem, symbols);
  return symbols;
}

}  // namespace seaplan::task::internal
