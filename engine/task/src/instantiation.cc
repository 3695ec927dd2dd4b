#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

#include "instantiation_internal.h"

namespace seaplan::task::internal {

using pddl::TimeSpec;
using ConditionKind = SchemaCondition::Kind;
using GroundKind = GroundFormula::Kind;

bool ToGroundDnf(const GroundFormula& g, std::vector<GroundConjunction>& out) {
  switch (g.kind) {
    case GroundKind::kTrue:
      out.push_back({});
      return true;
    case GroundKind::kFalse:
      return true;
    case GroundKind::kLiteral:
    case GroundKind::kComparison:
      out.push_back({{&g}});
      return true;
    case GroundKind::kOr:
      for (const auto& child : g.children) {
        if (!ToGroundDnf(child, out) || out.size() > kMaxDisjuncts) return false;
      }
      return true;
    case GroundKind::kAnd: {
      std::vector<GroundConjunction> product(1);
      for (const auto& child : g.children) {
        std::vector<GroundConjunction> part;
        if (!ToGroundDnf(child, part)) return false;
        if (part.size() == 1) {
          for (auto& a : product)
            a.leaves.insert(a.leaves.end(), part[0].leaves.begin(), part[0].leaves.end());
          continue;
        }
        const bool fits =
            MultiplyOut(product, part, [](GroundConjunction& into, const GroundConjunction& from) {
              into.leaves.insert(into.leaves.end(), from.leaves.begin(), from.leaves.end());
            });
        if (!fits) return false;
      }
      out.insert(out.end(), product.begin(), product.end());
      return true;
    }
  }
  return true;
}

namespace {

// Adds a child to an and/or node; false once the node is decided
// (a false child of an and, a true child of an or).
bool AddChild(GroundFormula& node, GroundFormula child, bool is_and) {
  const GroundKind absorbing = is_and ? GroundKind::kFalse : GroundKind::kTrue;
  const GroundKind neutral = is_and ? GroundKind::kTrue : GroundKind::kFalse;
  if (node.children.size() == 1 && node.children[0].kind == absorbing) return false;
  if (child.kind == neutral) return true;
  if (child.kind == absorbing) {
    node.children.clear();
    node.children.push_back(std::move(child));
    return false;
  }
  if (child.kind == node.kind) {
    for (auto& g : child.children) node.children.push_back(std::move(g));
  } else {
    node.children.push_back(std::move(child));
  }
  return true;
}

// An and/or node with no child is its neutral value, with one child that child.
GroundFormula Collapse(GroundFormula node, bool is_and) {
  if (node.children.empty()) {
    GroundFormula out;
    out.kind = is_and ? GroundKind::kTrue : GroundKind::kFalse;
    return out;
  }
  if (node.children.size() == 1) return std::move(node.children[0]);
  return node;
}

void AddLeaf(Condition& c, const GroundFormula& leaf) {
  if (leaf.kind == GroundKind::kLiteral) {
    auto& list = leaf.positive ? c.positive : c.negative;
    if (std::find(list.begin(), list.end(), leaf.fact) == list.end()) list.push_back(leaf.fact);
  } else {
    c.numeric.push_back(leaf.comparison);
  }
}

// Fills the action's conditions from one ground disjunct; false when it is
// contradictory (p and not p at the same time point).
bool FillConditions(Action& a, const GroundConjunction& conjunction) {
  for (const GroundFormula* leaf : conjunction.leaves) {
    switch (leaf->time) {
      case TimeSpec::kNone:
      case TimeSpec::kAtStart:
        AddLeaf(a.at_start, *leaf);
        break;
      case TimeSpec::kOverAll:
        AddLeaf(a.over_all, *leaf);
        break;
      case TimeSpec::kAtEnd:
        AddLeaf(a.at_end, *leaf);
        break;
    }
  }
  for (const Condition* c : {&a.at_start, &a.over_all, &a.at_end}) {
    for (FactId f : c->positive) {
      if (std::find(c->negative.begin(), c->negative.end(), f) != c->negative.end()) return false;
    }
  }
  return true;
}

NumericExpr TotalTime() {
  NumericExpr out;
  out.nodes.push_back({NumericExpr::Op::kTotalTime, 0.0, -1, -1, -1});
  return out;
}

class Instantiator {
 public:
  Instantiator(const pddl::Domain& domain, const pddl::Problem& problem, const SymbolTable& symbols,
               const CompiledSchemas& schemas, ReachableTask reachable, GroundingContext& context)
      : domain_(domain),
        problem_(problem),
        symbols_(symbols),
        schemas_(schemas),
        reachable_(std::move(reachable)),
        atoms_(reachable_.atoms),
        function_terms_(reachable_.function_terms),
        context_(context) {}

  InstantiatedTask Run() {
    InstantiatedTask out;
    out.task = Build();
    out.atoms_seen = atoms_.size();
    return out;
  }

 private:
  std::shared_ptr<GroundTask> Build() {
    task_ = std::make_shared<GroundTask>();
    task_->domain_name = domain_.name;
    task_->problem_name = problem_.name;
    NumberReachableFacts();
    reachable_facts_ = task_->facts.size();
    // Numeric variables: every changing fluent defined in :init first, so
    // that initial values line up; others appear as actions read them.
    for (std::size_t id = 0; id < function_terms_.size(); ++id) {
      const FunctionTermId term(id);
      if (symbols_.IsStatic(function_terms_.function(term))) continue;
      VariableOf(function_terms_.function(term), function_terms_.arguments(term));
    }
    if (!BuildActions()) return nullptr;
    for (AtomId atom : reachable_.initial_atoms) {
      const FactId f = FactOf(atom);
      if (f >= 0) task_->initial_facts.push_back(f);
    }
    std::sort(task_->initial_facts.begin(), task_->initial_facts.end());
    task_->initial_facts.erase(
        std::unique(task_->initial_facts.begin(), task_->initial_facts.end()),
        task_->initial_facts.end());
    for (std::size_t i = 0; i < problem_.timed_literals.size(); ++i) {
      const auto& til = problem_.timed_literals[i];
      const AtomId atom = reachable_.timed_literal_atoms[i];
      TimedInitialLiteral t;
      t.time_s = til.time;
      t.fact = ForceFact(atoms_.predicate(atom), atoms_.arguments(atom));
      t.value = til.positive;
      task_->timed_literals.push_back(t);
    }
    std::stable_sort(task_->timed_literals.begin(), task_->timed_literals.end(),
                     [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
    for (const auto& tif : problem_.timed_numeric_init) {
      std::vector<ObjectId> args;
      for (const auto& a : tif.init.args) args.push_back(symbols_.FindObject(a));
      TimedInitialFluent t;
      t.time_s = tif.time;
      t.var = VariableOf(symbols_.FindFunction(tif.init.function), args);
      t.value = tif.init.value;
      task_->timed_fluents.push_back(t);
    }
    std::stable_sort(task_->timed_fluents.begin(), task_->timed_fluents.end(),
                     [](const auto& a, const auto& b) { return a.time_s < b.time_s; });
    if (!BuildGoal()) return nullptr;
    BuildMetric();
    if (task_->facts.size() > context_.options().max_facts) {
      context_.Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
                     "grounding exceeds the fact budget of " +
                         std::to_string(context_.options().max_facts) + " facts",
                     "a smaller problem or a larger GroundingOptions::max_facts");
      return nullptr;
    }
    return task_;
  }

  // ---- facts and numeric variables ---------------------------------------------------

  // Reached atoms of changing predicates become the first facts, in atom order.
  void NumberReachableFacts() {
    fact_of_atom_.assign(atoms_.size(), -1);
    for (std::size_t id = 0; id < atoms_.size(); ++id) {
      const AtomId atom(id);
      const PredicateId predicate = atoms_.predicate(atom);
      if (symbols_.IsStatic(predicate) || !atoms_.reached(atom)) continue;
      fact_of_atom_[id] = NewFact(predicate, atoms_.arguments(atom));
    }
  }

  FactId NewFact(PredicateId predicate, std::span<const ObjectId> args) {
    const auto fact = static_cast<FactId>(task_->facts.size());
    Fact f;
    f.predicate = symbols_.Name(predicate);
    for (ObjectId o : args) f.args.push_back(symbols_.Name(o));
    task_->facts.push_back(std::move(f));
    return fact;
  }

  // -1 for an atom that is no fact (static, unreachable, never interned).
  FactId FactOf(AtomId atom) const {
    return atom.valid() && atom.index() < fact_of_atom_.size() ? fact_of_atom_[atom.index()] : -1;
  }

  // A fact for an atom that no action can reach (goals, timed literals).
  FactId ForceFact(PredicateId predicate, std::span<const ObjectId> args) {
    const AtomId atom = atoms_.Intern(predicate, args);
    if (atom.index() >= fact_of_atom_.size()) fact_of_atom_.resize(atoms_.size(), -1);
    FactId& fact = fact_of_atom_[atom.index()];
    if (fact < 0) fact = NewFact(predicate, args);
    return fact;
  }

  NumericVarId VariableOf(FunctionId function, std::span<const ObjectId> args) {
    const FunctionTermId term = function_terms_.Intern(function, args);
    if (numeric_var_of_term_.size() < function_terms_.size())
      numeric_var_of_term_.resize(function_terms_.size(), -1);
    NumericVarId& var = numeric_var_of_term_[term.index()];
    if (var < 0) {
      var = static_cast<NumericVarId>(task_->numeric_vars.size());
      NumericVar v;
      v.function = symbols_.Name(function);
      for (ObjectId o : args) v.args.push_back(symbols_.Name(o));
      task_->numeric_vars.push_back(std::move(v));
      task_->initial_values.push_back(function_terms_.initial_value(term));
    }
    return var;
  }

  void ResolveArgs(const std::vector<Term>& terms, const Binding& b) {
    args_.clear();
    for (Term t : terms) args_.push_back(Resolve(t, b));
  }

  // ---- expressions and formulas -------------------------------------------------------

  // Emits `e` into `out` (children first), folding constants; false when a
  // static fluent it reads is undefined or a constant division is by zero.
  bool EmitExpression(const SchemaExpression& e, const Binding& b, NumericExpr& out) {
    using Op = NumericExpr::Op;
    using Kind = SchemaExpression::Kind;
    NumericExpr::Node node;
    switch (e.kind) {
      case Kind::kNumber:
        node.op = Op::kConstant;
        node.value = e.number;
        break;
      case Kind::kDuration:
        node.op = Op::kDuration;
        break;
      case Kind::kTotalTime:
        node.op = Op::kTotalTime;
        break;
      case Kind::kFluent: {
        std::vector<ObjectId> args;
        args.reserve(e.args.size());
        for (Term t : e.args) args.push_back(Resolve(t, b));
        if (symbols_.IsStatic(e.function)) {
          const double v = function_terms_.InitialValue(e.function, args);
          if (std::isnan(v)) return false;
          node.op = Op::kConstant;
          node.value = v;
        } else {
          node.op = Op::kVariable;
          node.var = VariableOf(e.function, args);
        }
        break;
      }
      case Kind::kNegate: {
        if (!EmitExpression(e.children[0], b, out)) return false;
        auto& last = out.nodes.back();
        if (last.op == Op::kConstant) {
          last.value = -last.value;
          return true;
        }
        node.op = Op::kNeg;
        node.lhs = static_cast<std::int32_t>(out.nodes.size()) - 1;
        break;
      }
      case Kind::kAdd:
      case Kind::kSub:
      case Kind::kMul:
      case Kind::kDiv: {
        if (!EmitExpression(e.children[0], b, out)) return false;
        const auto lhs = static_cast<std::int32_t>(out.nodes.size()) - 1;
        if (!EmitExpression(e.children[1], b, out)) return false;
        const auto rhs = static_cast<std::int32_t>(out.nodes.size()) - 1;
        node.op = e.kind == Kind::kAdd   ? Op::kAdd
                  : e.kind == Kind::kSub ? Op::kSub
                  : e.kind == Kind::kMul ? Op::kMul
                                         : Op::kDiv;
        node.lhs = lhs;
        node.rhs = rhs;
        const auto& l = out.nodes[static_cast<std::size_t>(lhs)];
        const auto& r = out.nodes[static_cast<std::size_t>(rhs)];
        if (l.op == Op::kConstant && r.op == Op::kConstant) {
          double v = 0;
          switch (node.op) {
            case Op::kAdd:
              v = l.value + r.value;
              break;
            case Op::kSub:
              v = l.value - r.value;
              break;
            case Op::kMul:
              v = l.value * r.value;
              break;
            default:
              if (r.value == 0.0) return false;
              v = l.value / r.value;
              break;
          }
          out.nodes.pop_back();
          out.nodes.pop_back();
          node = {};
          node.op = Op::kConstant;
          node.value = v;
        }
        break;
      }
    }
    out.nodes.push_back(node);
    return true;
  }

  // Grounds a formula under binding `b`. In goal mode, atoms no action can
  // reach become facts (so the goal stays visibly unreachable) instead of false.
  GroundFormula GroundCondition(const SchemaCondition& c, Binding& b, const Schema& s,
                                bool goal_mode) {
    GroundFormula out;
    out.time = c.time;
    switch (c.kind) {
      case ConditionKind::kTrue:
        out.kind = GroundKind::kTrue;
        return out;
      case ConditionKind::kFalse:
        out.kind = GroundKind::kFalse;
        return out;
      case ConditionKind::kEquality: {
        const bool same = Resolve(c.args[0], b) == Resolve(c.args[1], b);
        out.kind = (same == c.positive) ? GroundKind::kTrue : GroundKind::kFalse;
        return out;
      }
      case ConditionKind::kAtom: {
        std::vector<ObjectId> args;
        args.reserve(c.args.size());
        for (Term t : c.args) args.push_back(Resolve(t, b));
        const AtomId atom = atoms_.Find(c.predicate, args);
        if (symbols_.IsStatic(c.predicate)) {
          const bool known_true = atoms_.IsReached(atom);
          if (goal_mode && c.positive && !known_true) {
            out.kind = GroundKind::kLiteral;
            out.fact = ForceFact(c.predicate, args);
            out.positive = true;
            return out;
          }
          out.kind = (known_true == c.positive) ? GroundKind::kTrue : GroundKind::kFalse;
          return out;
        }
        const FactId fact = FactOf(atom);
        if (fact < 0) {
          if (goal_mode && c.positive) {
            out.kind = GroundKind::kLiteral;
            out.fact = ForceFact(c.predicate, args);
            out.positive = true;
            return out;
          }
          // Never reachable: false as a positive literal, true as a negative one.
          out.kind = c.positive ? GroundKind::kFalse : GroundKind::kTrue;
          return out;
        }
        out.kind = GroundKind::kLiteral;
        out.fact = fact;
        out.positive = c.positive;
        return out;
      }
      case ConditionKind::kComparison: {
        NumericCondition comparison;
        comparison.comparator = ToTask(c.comparator);
        if (!EmitExpression(c.lhs, b, comparison.lhs) ||
            !EmitExpression(c.rhs, b, comparison.rhs)) {
          out.kind = GroundKind::kFalse;  // reads an undefined static fluent
          return out;
        }
        if (comparison.lhs.IsConstant() && comparison.rhs.IsConstant()) {
          out.kind = Compare(comparison.lhs.ConstantValue(), comparison.comparator,
                             comparison.rhs.ConstantValue())
                         ? GroundKind::kTrue
                         : GroundKind::kFalse;
          return out;
        }
        out.kind = GroundKind::kComparison;
        out.comparison = std::move(comparison);
        return out;
      }
      case ConditionKind::kAnd:
      case ConditionKind::kOr: {
        const bool is_and = c.kind == ConditionKind::kAnd;
        out.kind = is_and ? GroundKind::kAnd : GroundKind::kOr;
        for (const auto& child : c.children) {
          if (!AddChild(out, GroundCondition(child, b, s, goal_mode), is_and)) break;
        }
        return Collapse(std::move(out), is_and);
      }
      case ConditionKind::kForall:
      case ConditionKind::kExists: {
        const bool is_and = c.kind == ConditionKind::kForall;
        out.kind = is_and ? GroundKind::kAnd : GroundKind::kOr;
        Quantify(c, 0, b, s, goal_mode, out, is_and);
        for (VariableSlot v : c.quantified) b[v.index()] = ObjectId::None();
        return Collapse(std::move(out), is_and);
      }
    }
    return out;
  }

  bool Quantify(const SchemaCondition& c, std::size_t i, Binding& b, const Schema& s,
                bool goal_mode, GroundFormula& out, bool is_and) {
    if (i == c.quantified.size())
      return AddChild(out, GroundCondition(c.children[0], b, s, goal_mode), is_and);
    const VariableSlot slot = c.quantified[i];
    for (ObjectId o : s.variable(slot).objects) {
      b[slot.index()] = o;
      if (!context_.Tick() || !Quantify(c, i + 1, b, s, goal_mode, out, is_and)) return false;
    }
    return true;
  }

  // ---- effects ------------------------------------------------------------------------

  void UnsupportedEffect(const SchemaEffect& effect, std::string message) {
    context_.Error(pddl::DiagnosticKind::kUnsupported, effect.location, "", std::move(message));
  }

  // Grounds the effects into `a`; false on an unsupported construct.
  bool GroundEffects(const Schema& s, Binding& b, Action& a) {
    for (const auto& effect : s.effects) {
      if (!GroundEffect(s, effect, b, 0, a)) return false;
    }
    return true;
  }

  bool GroundEffect(const Schema& s, const SchemaEffect& effect, Binding& b, std::size_t i,
                    Action& a) {
    if (i < effect.forall_variables.size()) {
      const VariableSlot slot = effect.forall_variables[i];
      for (ObjectId o : s.variable(slot).objects) {
        b[slot.index()] = o;
        if (!context_.Tick() || !GroundEffect(s, effect, b, i + 1, a)) return false;
      }
      b[slot.index()] = ObjectId::None();
      return true;
    }
    Effects& target = effect.time == TimeSpec::kAtEnd ? a.end_effects : a.start_effects;
    constexpr const char* kExistsVariableInEffect =
        "an effect uses a variable bound only by an existential precondition";
    if (effect.kind != SchemaEffect::Kind::kNumeric &&
        effect.condition.kind == ConditionKind::kTrue) {
      // Fast path (most effects): an unconditional add or delete.
      ResolveArgs(effect.args, b);
      for (ObjectId o : args_) {
        if (!o.valid()) {
          UnsupportedEffect(effect, kExistsVariableInEffect);
          return false;
        }
      }
      FactId fact = FactOf(atoms_.Find(effect.predicate, args_));
      if (effect.kind == SchemaEffect::Kind::kAdd) {
        if (fact < 0) fact = ForceFact(effect.predicate, args_);
        target.add.push_back(fact);
      } else if (fact >= 0) {
        target.del.push_back(fact);
      }
      return true;
    }
    std::vector<FactId> add, del;
    std::vector<NumericEffect> numeric;
    if (effect.kind == SchemaEffect::Kind::kNumeric) {
      std::vector<ObjectId> args;
      for (Term t : effect.function_args) args.push_back(Resolve(t, b));
      NumericEffect ne;
      ne.op = ToTask(effect.op);
      ne.var = VariableOf(effect.function, args);
      if (!EmitExpression(effect.value, b, ne.value)) {
        // Reads an undefined static fluent: the action can never be applied.
        effect_reads_undefined_ = true;
        return true;
      }
      numeric.push_back(std::move(ne));
    } else {
      std::vector<ObjectId> args;
      for (Term t : effect.args) args.push_back(Resolve(t, b));
      for (ObjectId o : args) {
        if (!o.valid()) {
          UnsupportedEffect(effect, kExistsVariableInEffect);
          return false;
        }
      }
      FactId fact = FactOf(atoms_.Find(effect.predicate, args));
      if (effect.kind == SchemaEffect::Kind::kAdd) {
        // Every add effect was reached by the exploration; forced for safety.
        if (fact < 0) fact = ForceFact(effect.predicate, args);
        add.push_back(fact);
      } else if (fact >= 0) {
        del.push_back(fact);
      } else {
        return true;  // deleting a never-true atom does nothing
      }
    }
    if (effect.condition.kind == ConditionKind::kTrue) {
      target.add.insert(target.add.end(), add.begin(), add.end());
      target.del.insert(target.del.end(), del.begin(), del.end());
      for (auto& n : numeric) target.numeric.push_back(std::move(n));
      return true;
    }
    const GroundFormula condition = GroundCondition(effect.condition, b, s, false);
    std::vector<GroundConjunction> dnf;
    if (!ToGroundDnf(condition, dnf)) {
      UnsupportedEffect(effect,
                        "conditional effect condition too large in disjunctive normal form");
      return false;
    }
    if (dnf.size() > 1 && !numeric.empty()) {
      UnsupportedEffect(effect, "numeric conditional effect with a disjunctive condition");
      return false;
    }
    for (const auto& conjunction : dnf) {
      if (conjunction.leaves.empty()) {  // condition is always true
        target.add.insert(target.add.end(), add.begin(), add.end());
        target.del.insert(target.del.end(), del.begin(), del.end());
        for (auto& n : numeric) target.numeric.push_back(n);
        continue;
      }
      ConditionalEffect ce;
      std::optional<TimeSpec> time;
      for (const GroundFormula* leaf : conjunction.leaves) {
        const TimeSpec t = leaf->time == TimeSpec::kNone ? TimeSpec::kAtStart : leaf->time;
        if (t == TimeSpec::kOverAll || (time && *time != t)) {
          UnsupportedEffect(effect,
                            "conditional effect whose condition mixes time points or uses "
                            "'over all'");
          return false;
        }
        time = t;
        AddLeaf(ce.condition, *leaf);
      }
      if (time == TimeSpec::kAtEnd && effect.time != TimeSpec::kAtEnd) {
        UnsupportedEffect(effect, "conditional effect at start whose condition is checked at end");
        return false;
      }
      ce.condition_time = time == TimeSpec::kAtEnd ? TimePoint::kEnd : TimePoint::kStart;
      ce.add = add;
      ce.del = del;
      ce.numeric = numeric;
      target.conditional.push_back(std::move(ce));
    }
    return true;
  }

  // ---- actions ------------------------------------------------------------------------

  // For a disjunct of plain literals and equalities (the common case), fills
  // the action's conditions directly, without building a ground formula.
  // Returns false when the disjunct needs the general path (quantifiers,
  // comparisons); `holds` is false when a literal is statically false.
  bool SimpleConditions(const PreconditionDisjunct& disjunct, const Binding& b, Action& a,
                        bool& holds) {
    for (const SchemaCondition* item : disjunct.items) {
      if (item->kind != ConditionKind::kAtom && item->kind != ConditionKind::kEquality)
        return false;
    }
    holds = true;
    for (const SchemaCondition* item : disjunct.items) {
      if (item->kind == ConditionKind::kEquality) {
        const bool same = Resolve(item->args[0], b) == Resolve(item->args[1], b);
        if (same != item->positive) holds = false;
        continue;
      }
      ResolveArgs(item->args, b);
      const AtomId atom = atoms_.Find(item->predicate, args_);
      if (symbols_.IsStatic(item->predicate)) {
        if (atoms_.IsReached(atom) != item->positive) holds = false;
        continue;
      }
      const FactId fact = FactOf(atom);
      if (fact < 0) {
        if (item->positive) holds = false;  // unreachable; a negative literal on it is true
        continue;
      }
      Condition& c = item->time == TimeSpec::kOverAll ? a.over_all
                     : item->time == TimeSpec::kAtEnd ? a.at_end
                                                      : a.at_start;
      auto& list = item->positive ? c.positive : c.negative;
      if (std::find(list.begin(), list.end(), fact) == list.end()) list.push_back(fact);
    }
    return true;
  }

  bool ActionBudgetExceeded() {
    if (task_->actions.size() <= context_.options().max_actions) return false;
    context_.Error(pddl::DiagnosticKind::kSemantic, problem_.location, "",
                   "grounding exceeds the action budget of " +
                       std::to_string(context_.options().max_actions) + " actions",
                   "a smaller problem or a larger GroundingOptions::max_actions");
    return true;
  }

  bool BuildActions() {
    // (schema, parameters...) -> next variant number, for schemas whose
    // instances can share a name.
    TupleSet names;
    std::vector<int> next_variant;
    std::vector<std::int32_t> name_key;
    task_->actions.reserve(reachable_.instances.size());
    for (std::size_t instance = 0; instance < reachable_.instances.size(); ++instance) {
      if (instance % 1024 == 0 && context_.StopRequested()) return false;
      const PreconditionDisjunct& disjunct =
          schemas_.disjunct(reachable_.instances.disjunct(instance));
      const Schema& s = schemas_.schema_of(disjunct);
      Binding b = reachable_.instances.binding(instance);
      Action simple;
      bool simple_holds = true;
      const bool is_simple = SimpleConditions(disjunct, b, simple, simple_holds);
      if (is_simple && !simple_holds) continue;
      // Condition: the disjunct's items, grounded.
      GroundFormula condition;
      condition.kind = GroundKind::kAnd;
      for (const SchemaCondition* item : disjunct.items) {
        if (is_simple) break;
        if (!AddChild(condition, GroundCondition(*item, b, s, false), true)) break;
      }
      condition = Collapse(std::move(condition), true);
      if (!context_.ok()) return false;
      if (condition.kind == GroundKind::kFalse) continue;
      std::vector<GroundConjunction> dnf;
      if (is_simple) {
        dnf.emplace_back();  // conditions already in `simple`
      } else if (!ToGroundDnf(condition, dnf)) {
        context_.Error(pddl::DiagnosticKind::kUnsupported, s.action->location, s.action->name,
                       "ground precondition too large in disjunctive normal form");
        return false;
      }
      if (dnf.empty()) continue;
      Action base = std::move(simple);
      base.name = s.action->name;
      for (int p = 0; p < s.parameter_count; ++p)
        base.args.push_back(symbols_.Name(b[static_cast<std::size_t>(p)]));
      base.is_durative = s.action->durative;
      bool duration_defined = true;
      for (const auto& d : s.duration) {
        DurationConstraint dc;
        dc.comparator = ToTask(d.comparator);
        if (!EmitExpression(d.value, b, dc.value)) {
          duration_defined = false;
          break;
        }
        base.duration.push_back(std::move(dc));
      }
      if (!duration_defined) continue;
      effect_reads_undefined_ = false;
      Binding effect_binding = b;
      if (!GroundEffects(s, effect_binding, base)) return false;
      if (effect_reads_undefined_) continue;
      // Variant numbers: only schemas with several disjuncts or existential
      // variables can produce one (name, args) twice, so only they pay for
      // the lookup.
      int* variant = nullptr;
      int local_variant = 0;
      if (s.disjuncts.size() > 1 ||
          disjunct.free_variables.size() > static_cast<std::size_t>(s.parameter_count)) {
        name_key.clear();
        name_key.push_back(disjunct.schema.value());
        for (int p = 0; p < s.parameter_count; ++p)
          name_key.push_back(b[static_cast<std::size_t>(p)].value());
        auto [name_id, fresh] = names.Insert(name_key);
        if (fresh) next_variant.push_back(0);
        variant = &next_variant[static_cast<std::size_t>(name_id)];
      } else {
        variant = &local_variant;
      }
      for (std::size_t v = 0; v < dnf.size(); ++v) {
        // NOLINTNEXTLINE(bugprone-use-after-move): base is moved only on the last pass.
        Action a = v + 1 == dnf.size() ? std::move(base) : base;
        if (!FillConditions(a, dnf[v])) continue;
        a.variant = (*variant)++;
        task_->actions.push_back(std::move(a));
        if (ActionBudgetExceeded()) return false;
      }
    }
    return true;
  }

  // ---- goal and metric ----------------------------------------------------------------

  bool BuildGoal() {
    const Schema& goal = *schemas_.goal;
    Binding b(goal.variables.size(), ObjectId::None());
    const GroundFormula g = GroundCondition(goal.condition, b, goal, true);
    if (!context_.ok()) return false;
    if (g.kind == GroundKind::kFalse) {
      context_.Warn(problem_.goal.location, "",
                    "the goal is statically false (it contradicts facts that never change); the "
                    "task has no solution");
      // A fact nothing achieves stands for the impossible goal.
      task_->goal.positive.push_back(static_cast<FactId>(task_->facts.size()));
      task_->facts.push_back({"@false", {}});
      return true;
    }
    std::vector<GroundConjunction> dnf;
    if (!ToGroundDnf(g, dnf)) {
      context_.Error(pddl::DiagnosticKind::kUnsupported, problem_.goal.location, "",
                     "goal too large in disjunctive normal form");
      return false;
    }
    if (dnf.size() > 1) {
      context_.Error(pddl::DiagnosticKind::kUnsupported, problem_.goal.location, "",
                     "disjunctive goal (a goal with 'or', 'imply' or 'exists' that does not "
                     "simplify to a conjunction)");
      return false;
    }
    for (const GroundFormula* leaf : dnf[0].leaves) AddLeaf(task_->goal, *leaf);
    for (FactId f : task_->goal.positive) {
      if (f >= static_cast<FactId>(reachable_facts_)) {
        context_.Warn(problem_.goal.location,
                      task_->facts[static_cast<std::size_t>(f)].DisplayName(),
                      "goal fact is unreachable: no action or timed literal can make it true");
      }
    }
    return true;
  }

  void BuildMetric() {
    task_->metric.minimize = !problem_.metric.present || problem_.metric.minimize;
    if (!schemas_.metric) {
      task_->metric.expression = TotalTime();
      return;
    }
    NumericExpr out;
    if (!EmitExpression(*schemas_.metric, Binding{}, out)) {
      context_.Warn(problem_.metric.location, "",
                    "metric reads an undefined fluent; using total-time");
      out = TotalTime();
    }
    task_->metric.expression = std::move(out);
  }

  const pddl::Domain& domain_;
  const pddl::Problem& problem_;
  const SymbolTable& symbols_;
  const CompiledSchemas& schemas_;
  ReachableTask reachable_;
  AtomTable& atoms_;                   // reachable_.atoms (ForceFact interns more)
  FunctionTermTable& function_terms_;  // reachable_.function_terms
  GroundingContext& context_;

  std::shared_ptr<GroundTask> task_;
  std::vector<FactId> fact_of_atom_;               // by AtomId; -1 when no fact
  std::vector<NumericVarId> numeric_var_of_term_;  // by FunctionTermId; -1 when none yet
  std::size_t reachable_facts_ = 0;                // facts numbered before any forced one
  bool effect_reads_undefined_ = false;            // set by GroundEffect for the current action
  std::vector<ObjectId> args_;                     // scratch
};

}  // namespace

InstantiatedTask Instantiate(const pddl::Domain& domain, const pddl::Problem& problem,
                             const SymbolTable& symbols, const CompiledSchemas& schemas,
                             ReachableTask reachable, GroundingContext& context) {
  return Instantiator(domain, problem, symbols, schemas, std::move(reachable), context).Run();
}

}  // namespace seaplan::task::internal
