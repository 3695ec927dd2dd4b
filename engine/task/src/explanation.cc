#include <algorithm>
#include <cmath>
#include <vector>

#include "explanation_internal.h"

namespace seaplan::task {
namespace internal {
namespace {

using ConditionKind = SchemaCondition::Kind;

std::string Lower(std::string_view in) {
  std::string out(in);
  for (auto& c : out) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return out;
}

// "(pred a ?x)": objects by name, unbound variables by their PDDL name.
std::string ShowAtom(const SymbolTable& symbols, const Schema& s, const SchemaCondition& item,
                     const Binding& b) {
  std::string out = "(" + (item.kind == ConditionKind::kEquality ? std::string("=")
                                                                 : symbols.Name(item.predicate));
  for (Term t : item.args) {
    const ObjectId o = Resolve(t, b);
    out += " " + (o.valid() ? symbols.Name(o) : s.variable(t.slot()).name);
  }
  return out + ")";
}

std::string ShowLiteral(const SymbolTable& symbols, const Schema& s, const SchemaCondition& item,
                        const Binding& b) {
  const std::string atom = ShowAtom(symbols, s, item, b);
  return item.positive ? atom : "(not " + atom + ")";
}

bool AllBound(const SchemaCondition& item, const Binding& b) {
  return std::all_of(item.args.begin(), item.args.end(),
                     [&](Term t) { return Resolve(t, b).valid(); });
}

// Why one disjunct does not hold for the parameters; "" when no reason is found.
std::string DisjunctReason(const SymbolTable& symbols, const Schema& s,
                           const PreconditionDisjunct& disjunct, ReachableTask& reachable,
                           const Binding& b) {
  const bool parameters_bound =
      std::all_of(b.begin(), b.begin() + s.parameter_count, [](ObjectId o) { return o.valid(); });
  for (const SchemaCondition* item : disjunct.items) {
    if (item->kind == ConditionKind::kEquality && AllBound(*item, b)) {
      const bool same = Resolve(item->args[0], b) == Resolve(item->args[1], b);
      if (same != item->positive)
        return "the precondition " + ShowLiteral(symbols, s, *item, b) + " is false";
    } else if (item->kind == ConditionKind::kAtom && AllBound(*item, b)) {
      std::vector<ObjectId> args;
      for (Term t : item->args) args.push_back(Resolve(t, b));
      const bool reached = reachable.atoms.IsReached(reachable.atoms.Find(item->predicate, args));
      if (symbols.IsStatic(item->predicate) && reached != item->positive) {
        return "the precondition " + ShowLiteral(symbols, s, *item, b) +
               " is false and never changes (static)";
      }
      if (!symbols.IsStatic(item->predicate) && item->positive && !reached) {
        return "the precondition " + ShowAtom(symbols, s, *item, b) +
               " can never become true (unreachable from the initial state)";
      }
    } else if (item->kind == ConditionKind::kComparison && IsStaticExpression(item->lhs, symbols) &&
               IsStaticExpression(item->rhs, symbols) && parameters_bound) {
      const double l = EvaluateStatic(item->lhs, b, reachable.function_terms);
      const double r = EvaluateStatic(item->rhs, b, reachable.function_terms);
      if (std::isnan(l) || std::isnan(r))
        return "a numeric precondition reads a function with no value in :init";
      if (!Compare(l, ToTask(item->comparator), r)) {
        return "a numeric precondition over static functions is false (" + std::to_string(l) + " " +
               pddl::ComparatorSymbol(item->comparator) + " " + std::to_string(r) + ")";
      }
    }
  }
  for (const auto& d : s.duration) {
    if (IsStaticExpression(d.value, symbols) &&
        std::isnan(EvaluateStatic(d.value, b, reachable.function_terms)))
      return "its duration reads a function with no value in :init";
  }
  return "";
}

}  // namespace

std::string ExplainInstance(const SymbolTable& symbols, const CompiledSchemas& schemas,
                            ReachableTask& reachable, SchemaId schema_id,
                            std::span<const ObjectId> parameters, const std::string& call,
                            bool task_given) {
  const Schema& s = schemas.schema(schema_id);
  Binding b(s.variables.size(), ObjectId::None());
  std::copy(parameters.begin(), parameters.end(), b.begin());
  std::string first_reason;
  for (DisjunctId id : s.disjuncts) {
    const std::string reason = DisjunctReason(symbols, s, schemas.disjunct(id), reachable, b);
    if (reason.empty()) {
      if (!task_given) {
        return call +
               ": no reason found: its static preconditions hold and its fact preconditions are "
               "reachable";
      }
      return call +
             ": its preconditions cannot hold together (a quantified, numeric or duration "
             "condition is false or undefined for these arguments; pruned by grounding)";
    }
    if (first_reason.empty()) first_reason = reason;
  }
  if (first_reason.empty()) first_reason = "its precondition is always false";
  return call + ": " + first_reason;
}

}  // namespace internal

std::string ExplainMissingAction(const pddl::Domain& domain, const pddl::Problem& problem,
                                 std::string_view name_in, std::span<const std::string> args_in,
                                 const GroundTask* task) {
  using namespace internal;
  const std::string name = Lower(name_in);
  std::vector<std::string> args;
  for (const auto& a : args_in) args.push_back(Lower(a));

  const pddl::Action* action = domain.FindAction(name);
  std::string call = "(" + name;
  for (const auto& a : args) call += " " + a;
  call += ")";
  if (action == nullptr) {
    std::string known;
    for (const auto& a : domain.actions) known += (known.empty() ? "" : ", ") + a.name;
    return call + ": unknown action '" + name + "' (the domain has: " + known + ")";
  }
  if (args.size() != action->parameters.size()) {
    std::string parameters;
    for (const auto& p : action->parameters) parameters += (parameters.empty() ? "" : " ") + p.name;
    return call + ": wrong number of arguments: " + std::to_string(args.size()) + " given, '" +
           action->name + "' takes " + std::to_string(action->parameters.size()) + " (" +
           parameters + ")";
  }
  std::vector<pddl::Diagnostic> diagnostics;
  const GroundingOptions options;
  const StopToken never;
  GroundingContext context(problem, options, never, diagnostics);
  std::optional<SymbolTable> symbols = BuildSymbols(domain, problem, context);
  if (!symbols) return call + ": the problem does not match the domain";
  std::vector<ObjectId> objects;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const ObjectId o = symbols->FindObject(args[i]);
    if (!o.valid()) return call + ": unknown object '" + args[i] + "'";
    const auto& wanted = action->parameters[i].types;
    const bool fits = std::any_of(wanted.begin(), wanted.end(), [&](const std::string& type) {
      const TypeId t = symbols->FindType(type);
      return t.valid() && symbols->HasType(o, t);
    });
    if (!fits) {
      std::string have, want;
      for (const auto& t : symbols->object_declared_types[o.index()])
        have += (have.empty() ? "" : " or ") + t;
      for (const auto& t : wanted) want += (want.empty() ? "" : " or ") + t;
      std::string message = call;
      message.append(": type mismatch: argument ").append(std::to_string(i + 1)).append(" '");
      message.append(args[i]).append("' is a ").append(have).append(", but ");
      message.append(action->parameters[i].name).append(" must be a ").append(want);
      return message;
    }
    objects.push_back(o);
  }
  std::optional<CompiledSchemas> schemas = CompileSchemas(domain, problem, *symbols, context);
  if (!schemas) return call + ": unsupported construct in the domain";
  std::optional<ReachableTask> reachable =
      ExploreReachability(*symbols, *schemas, problem, context);
  if (!reachable) return call + ": grounding budget exceeded";
  if (task != nullptr) {
    for (const auto& a : task->actions) {
      if (a.name == action->name &&
          std::equal(a.args.begin(), a.args.end(), args.begin(), args.end()))
        return "";
    }
  }
  SchemaId schema_id(std::size_t{0});
  while (schemas->schema(schema_id).action != action) schema_id = SchemaId(schema_id.value() + 1);
  return ExplainInstance(*symbols, *schemas, *reachable, schema_id, objects, call, task != nullptr);
}

}  // namespace seaplan::task
