#include <algorithm>
#include <utility>

#include "schema_internal.h"

namespace seaplan::task::internal {
namespace {

using pddl::TimeSpec;
using ConditionKind = SchemaCondition::Kind;

pddl::Comparator Negate(pddl::Comparator c) {
  switch (c) {
    case pddl::Comparator::kLess:
      return pddl::Comparator::kGreaterEqual;
    case pddl::Comparator::kLessEqual:
      return pddl::Comparator::kGreater;
    case pddl::Comparator::kGreaterEqual:
      return pddl::Comparator::kLess;
    case pddl::Comparator::kGreater:
      return pddl::Comparator::kLessEqual;
    case pddl::Comparator::kEqual:
      return pddl::Comparator::kEqual;  // handled by the caller
  }
  return c;
}

// Converts one schema's (or the goal's) PDDL into ids. Variables are looked
// up in `scope_`, innermost first, as quantifiers open and close.
class SchemaCompiler {
 public:
  SchemaCompiler(const SymbolTable& symbols, Schema& schema) : symbols_(symbols), schema_(schema) {}

  VariableSlot AddVariable(const pddl::TypedName& v) {
    SchemaVariable variable;
    variable.name = v.name;
    variable.allowed.assign(symbols_.object_count(), 0);
    for (const auto& type_name : v.types) {
      const TypeId type = symbols_.FindType(type_name);
      if (!type.valid()) continue;
      for (ObjectId o : symbols_.objects_of_type[type.index()]) {
        if (!variable.allowed[o.index()]) {
          variable.allowed[o.index()] = 1;
          variable.objects.push_back(o);
        }
      }
    }
    std::sort(variable.objects.begin(), variable.objects.end());
    schema_.variables.push_back(std::move(variable));
    const VariableSlot slot(schema_.variables.size() - 1);
    scope_.push_back({v.name, slot});
    return slot;
  }

  SchemaExpression ConvertExpression(const pddl::NumExpr& e) {
    SchemaExpression out;
    using Kind = SchemaExpression::Kind;
    switch (e.kind) {
      case pddl::NumExpr::Kind::kNumber:
        out.kind = Kind::kNumber;
        out.number = e.value;
        return out;
      case pddl::NumExpr::Kind::kDuration:
        out.kind = Kind::kDuration;
        return out;
      case pddl::NumExpr::Kind::kTotalTime:
        out.kind = Kind::kTotalTime;
        return out;
      case pddl::NumExpr::Kind::kFluent:
        out.kind = Kind::kFluent;
        out.function = symbols_.FindFunction(e.function);
        for (const auto& a : e.args) out.args.push_back(ConvertTerm(a));
        return out;
      case pddl::NumExpr::Kind::kNeg:
        out.kind = Kind::kNegate;
        out.children.push_back(ConvertExpression(e.children[0]));
        return out;
      case pddl::NumExpr::Kind::kAdd:
      case pddl::NumExpr::Kind::kSub:
      case pddl::NumExpr::Kind::kMul:
      case pddl::NumExpr::Kind::kDiv: {
        const Kind kind = e.kind == pddl::NumExpr::Kind::kAdd   ? Kind::kAdd
                          : e.kind == pddl::NumExpr::Kind::kSub ? Kind::kSub
                          : e.kind == pddl::NumExpr::Kind::kMul ? Kind::kMul
                                                                : Kind::kDiv;
        // n-ary + and * become a balanced tree (depth log n, so recursion
        // stays shallow on inputs with thousands of operands).
        std::vector<SchemaExpression> level;
        for (const auto& child : e.children) level.push_back(ConvertExpression(child));
        while (level.size() > 1) {
          std::vector<SchemaExpression> next;
          for (std::size_t i = 0; i + 1 < level.size(); i += 2) {
            SchemaExpression parent;
            parent.kind = kind;
            parent.children.push_back(std::move(level[i]));
            parent.children.push_back(std::move(level[i + 1]));
            next.push_back(std::move(parent));
          }
          if (level.size() % 2 == 1) next.push_back(std::move(level.back()));
          level = std::move(next);
        }
        return std::move(level[0]);
      }
    }
    return out;
  }

  // `c` in negation normal form; `time` is the enclosing time specifier.
  SchemaCondition ConvertCondition(const pddl::Condition& c, bool negated, TimeSpec time) {
    SchemaCondition out;
    out.time = time;
    using PddlKind = pddl::Condition::Kind;
    switch (c.kind) {
      case PddlKind::kTrue:
        out.kind = negated ? ConditionKind::kFalse : ConditionKind::kTrue;
        return out;
      case PddlKind::kAtom:
        if (c.atom.predicate == "=") {
          out.kind = ConditionKind::kEquality;
        } else {
          out.kind = ConditionKind::kAtom;
          out.predicate = symbols_.FindPredicate(c.atom.predicate);
        }
        out.positive = !negated;
        for (const auto& a : c.atom.args) out.args.push_back(ConvertTerm(a));
        return out;
      case PddlKind::kNot:
        return ConvertCondition(c.children[0], !negated, time);
      case PddlKind::kAnd:
      case PddlKind::kOr:
        out.kind =
            ((c.kind == PddlKind::kAnd) != negated) ? ConditionKind::kAnd : ConditionKind::kOr;
        for (const auto& child : c.children)
          out.children.push_back(ConvertCondition(child, negated, time));
        return out;
      case PddlKind::kImply:
        // a -> b  ==  (not a) or b;  not (a -> b)  ==  a and (not b)
        out.kind = negated ? ConditionKind::kAnd : ConditionKind::kOr;
        out.children.push_back(ConvertCondition(c.children[0], !negated, time));
        out.children.push_back(ConvertCondition(c.children[1], negated, time));
        return out;
      case PddlKind::kExists:
      case PddlKind::kForall: {
        out.kind = ((c.kind == PddlKind::kExists) != negated) ? ConditionKind::kExists
                                                              : ConditionKind::kForall;
        const std::size_t mark = scope_.size();
        for (const auto& v : c.variables) out.quantified.push_back(AddVariable(v));
        out.children.push_back(ConvertCondition(c.children[0], negated, time));
        scope_.resize(mark);
        return out;
      }
      case PddlKind::kCompare: {
        SchemaExpression lhs = ConvertExpression(c.lhs);
        SchemaExpression rhs = ConvertExpression(c.rhs);
        if (negated && c.comparator == pddl::Comparator::kEqual) {
          out.kind = ConditionKind::kOr;
          SchemaCondition less;
          less.kind = ConditionKind::kComparison;
          less.time = time;
          less.comparator = pddl::Comparator::kLess;
          less.lhs = lhs;
          less.rhs = rhs;
          SchemaCondition greater = less;
          greater.comparator = pddl::Comparator::kGreater;
          out.children.push_back(std::move(less));
          out.children.push_back(std::move(greater));
          return out;
        }
        out.kind = ConditionKind::kComparison;
        out.comparator = negated ? Negate(c.comparator) : c.comparator;
        out.lhs = std::move(lhs);
        out.rhs = std::move(rhs);
        return out;
      }
      case PddlKind::kTimed:
        return ConvertCondition(c.children[0], negated, c.time);
    }
    return out;
  }

  // Appends every add, delete and numeric effect under `e` to the schema,
  // each with its enclosing forall variables and when conditions.
  void FlattenEffect(const pddl::Effect& e, TimeSpec time) {
    using EffectKind = pddl::Effect::Kind;
    switch (e.kind) {
      case EffectKind::kAnd:
        for (const auto& child : e.children) FlattenEffect(child, time);
        return;
      case EffectKind::kTimed:
        FlattenEffect(e.children[0], e.time);
        return;
      case EffectKind::kForall: {
        const std::size_t mark = scope_.size();
        const std::size_t forall_mark = forall_variables_.size();
        for (const auto& v : e.variables) forall_variables_.push_back(AddVariable(v));
        FlattenEffect(e.children[0], time);
        forall_variables_.resize(forall_mark);
        scope_.resize(mark);
        return;
      }
      case EffectKind::kWhen:
        when_conditions_.push_back({&e.condition, time});
        FlattenEffect(e.children[0], time);
        when_conditions_.pop_back();
        return;
      case EffectKind::kAdd:
      case EffectKind::kDelete:
      case EffectKind::kNumeric: {
        SchemaEffect effect;
        effect.time = time;
        effect.forall_variables = forall_variables_;
        effect.location = e.location;
        if (!when_conditions_.empty()) {
          effect.condition.kind = ConditionKind::kAnd;
          for (const auto& [condition, condition_time] : when_conditions_) {
            effect.condition.children.push_back(
                ConvertCondition(*condition, false, condition_time));
          }
        }
        if (e.kind == EffectKind::kNumeric) {
          effect.kind = SchemaEffect::Kind::kNumeric;
          effect.op = e.op;
          effect.function = symbols_.FindFunction(e.fluent.function);
          for (const auto& a : e.fluent.args) effect.function_args.push_back(ConvertTerm(a));
          effect.value = ConvertExpression(e.value);
        } else {
          effect.kind =
              e.kind == EffectKind::kAdd ? SchemaEffect::Kind::kAdd : SchemaEffect::Kind::kDelete;
          effect.predicate = symbols_.FindPredicate(e.atom.predicate);
          for (const auto& a : e.atom.args) effect.args.push_back(ConvertTerm(a));
        }
        schema_.effects.push_back(std::move(effect));
        return;
      }
    }
  }

 private:
  Term ConvertTerm(const pddl::Term& t) const {
    if (t.IsVariable()) {
      for (auto it = scope_.rbegin(); it != scope_.rend(); ++it) {
        if (it->first == t.name) return Term::Variable(it->second);
      }
      return Term::Variable(VariableSlot(0));  // unreachable for checked input
    }
    return Term::Object(symbols_.FindObject(t.name));
  }

  const SymbolTable& symbols_;
  Schema& schema_;
  std::vector<std::pair<std::string, VariableSlot>> scope_;
  std::vector<VariableSlot> forall_variables_;
  std::vector<std::pair<const pddl::Condition*, TimeSpec>> when_conditions_;
};

// Schema-level DNF: each disjunct a list of items; exists variables are
// recorded as extra variables to bind.
struct Disjunct {
  std::vector<const SchemaCondition*> items;
  std::vector<VariableSlot> exists_variables;
};

// False when the DNF would have more than kMaxDisjuncts disjuncts.
bool ToDnf(const SchemaCondition& c, std::vector<Disjunct>& out) {
  switch (c.kind) {
    case ConditionKind::kTrue:
      out.push_back({});
      return true;
    case ConditionKind::kFalse:
      return true;
    case ConditionKind::kAtom:
    case ConditionKind::kEquality:
    case ConditionKind::kComparison:
    case ConditionKind::kForall:
      out.push_back({{&c}, {}});
      return true;
    case ConditionKind::kExists: {
      std::vector<Disjunct> body;
      if (!ToDnf(c.children[0], body)) return false;
      for (auto& d : body) {
        d.exists_variables.insert(d.exists_variables.end(), c.quantified.begin(),
                                  c.quantified.end());
      }
      out.insert(out.end(), body.begin(), body.end());
      return true;
    }
    case ConditionKind::kOr:
      for (const auto& child : c.children) {
        if (!ToDnf(child, out)) return false;
        if (out.size() > kMaxDisjuncts) return false;
      }
      return true;
    case ConditionKind::kAnd: {
      std::vector<Disjunct> product(1);
      for (const auto& child : c.children) {
        std::vector<Disjunct> part;
        if (!ToDnf(child, part)) return false;
        const bool fits = MultiplyOut(product, part, [](Disjunct& into, const Disjunct& from) {
          into.items.insert(into.items.end(), from.items.begin(), from.items.end());
          into.exists_variables.insert(into.exists_variables.end(), from.exists_variables.begin(),
                                       from.exists_variables.end());
        });
        if (!fits) return false;
      }
      out.insert(out.end(), product.begin(), product.end());
      return true;
    }
  }
  return true;
}

bool CompileAction(const pddl::Action& action, const SymbolTable& symbols,
                   CompiledSchemas& compiled, GroundingContext& context) {
  auto schema = std::make_unique<Schema>();
  Schema& s = *schema;
  s.action = &action;
  SchemaCompiler compiler(symbols, s);
  for (const auto& p : action.parameters) compiler.AddVariable(p);
  s.parameter_count = static_cast<int>(action.parameters.size());
  s.condition = compiler.ConvertCondition(action.condition, false, TimeSpec::kNone);
  compiler.FlattenEffect(action.effect, TimeSpec::kNone);
  for (const auto& d : action.duration)
    s.duration.push_back({d.comparator, compiler.ConvertExpression(d.value)});

  std::vector<Disjunct> disjuncts;
  if (!ToDnf(s.condition, disjuncts)) {
    context.Error(pddl::DiagnosticKind::kUnsupported, action.location, action.name,
                  "the precondition's disjunctive normal form has more than " +
                      std::to_string(kMaxDisjuncts) + " disjuncts");
    return false;
  }
  const SchemaId schema_id(compiled.schemas.size());
  for (auto& d : disjuncts) {
    PreconditionDisjunct disjunct;
    disjunct.schema = schema_id;
    disjunct.items = std::move(d.items);
    for (int v = 0; v < s.parameter_count; ++v) disjunct.free_variables.push_back(VariableSlot(v));
    for (VariableSlot v : d.exists_variables) disjunct.free_variables.push_back(v);
    for (std::size_t i = 0; i < disjunct.items.size(); ++i) {
      const SchemaCondition& item = *disjunct.items[i];
      if (item.kind == ConditionKind::kAtom && item.positive) {
        disjunct.join_atoms.push_back(static_cast<int>(i));
        if (!symbols.IsStatic(item.predicate)) disjunct.has_fluent_atom = true;
      }
    }
    s.disjuncts.push_back(DisjunctId(compiled.disjuncts.size()));
    compiled.disjuncts.push_back(std::move(disjunct));
  }
  compiled.schemas.push_back(std::move(schema));
  return true;
}

}  // namespace

bool IsStaticExpression(const SchemaExpression& e, const SymbolTable& symbols) {
  using Kind = SchemaExpression::Kind;
  if (e.kind == Kind::kFluent) return symbols.IsStatic(e.function);
  if (e.kind == Kind::kDuration || e.kind == Kind::kTotalTime) return false;
  for (const auto& child : e.children) {
    if (!IsStaticExpression(child, symbols)) return false;
  }
  return true;
}

std::optional<CompiledSchemas> CompileSchemas(const pddl::Domain& domain,
                                              const pddl::Problem& problem,
                                              const SymbolTable& symbols,
                                              GroundingContext& context) {
  CompiledSchemas compiled;
  for (const auto& action : domain.actions) {
    if (!CompileAction(action, symbols, compiled, context)) return std::nullopt;
    if (context.StopRequested()) return std::nullopt;
  }
  compiled.goal = std::make_unique<Schema>();
  {
    SchemaCompiler compiler(symbols, *compiled.goal);
    compiled.goal->condition = compiler.ConvertCondition(problem.goal, false, TimeSpec::kNone);
  }
  if (problem.metric.present) {
    Schema no_variables;
    SchemaCompiler compiler(symbols, no_variables);
    compiled.metric = compiler.ConvertExpression(problem.metric.expression);
  }
  return compiled;
}

}  // namespace seaplan::task::internal
