#include "action_model.h"

#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_join.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission::internal {
namespace {

using pddl::Condition;
using pddl::Effect;
using pddl::NumExpr;
using pddl::TimeSpec;

void CollectEffectHeads(const Effect& e, std::set<std::string, std::less<>>* preds,
                        std::set<std::string, std::less<>>* funcs) {
  switch (e.kind) {
    case Effect::Kind::kAdd:
    case Effect::Kind::kDelete:
      preds->insert(e.atom.predicate);
      break;
    case Effect::Kind::kNumeric:
      funcs->insert(e.fluent.function);
      break;
    default:
      break;
  }
  for (const Effect& c : e.children) CollectEffectHeads(c, preds, funcs);
}

bool CompareValues(double lhs, pddl::Comparator c, double rhs) {
  switch (c) {
    case pddl::Comparator::kLess:
      return lhs < rhs;
    case pddl::Comparator::kLessEqual:
      return lhs <= rhs;
    case pddl::Comparator::kEqual:
      return std::abs(lhs - rhs) <= 1e-9 * (1 + std::abs(rhs));
    case pddl::Comparator::kGreaterEqual:
      return lhs >= rhs;
    case pddl::Comparator::kGreater:
      return lhs > rhs;
  }
  return false;
}

}  // namespace

std::string AtomKey(std::string_view predicate, const std::vector<std::string>& args) {
  std::string key = "(" + std::string(predicate);
  for (const std::string& a : args) absl::StrAppend(&key, " ", a);
  key += ")";
  return key;
}

StatusOr<ActionModel> ActionModel::Create(std::string_view domain_text,
                                          std::string_view problem_text) {
  pddl::DomainParseResult d = pddl::ParseDomain(domain_text);
  if (!d.domain) {
    return absl::InvalidArgumentError(
        absl::StrCat("domain does not parse: ", pddl::FormatDiagnostics(d.diagnostics)));
  }
  pddl::ProblemParseResult p = pddl::ParseProblem(problem_text, *d.domain);
  if (!p.problem) {
    return absl::InvalidArgumentError(
        absl::StrCat("problem does not parse: ", pddl::FormatDiagnostics(p.diagnostics)));
  }
  ActionModel m;
  m.domain_ = std::move(*d.domain);
  m.problem_ = std::move(*p.problem);
  m.types_ = pddl::TypeHierarchy(m.domain_.types);
  for (const pddl::Action& a : m.domain_.actions) {
    CollectEffectHeads(a.effect, &m.changed_predicates_, &m.changed_functions_);
  }
  return m;
}

WorldState ActionModel::InitialState() const {
  WorldState s;
  for (const pddl::Atom& a : problem_.init) {
    std::vector<std::string> args;
    for (const pddl::Term& t : a.args) args.push_back(t.name);
    s.facts.insert(AtomKey(a.predicate, args));
  }
  for (const pddl::NumericInit& n : problem_.numeric_init) {
    s.fluents[AtomKey(n.function, n.args)] = n.value;
  }
  return s;
}

std::vector<std::string> ActionModel::ObjectsOfType(std::string_view type) const {
  std::vector<std::string> out;
  auto consider = [&](const pddl::TypedName& o) {
    for (const std::string& t : o.types) {
      if (types_.IsSubtype(t, type)) {
        out.push_back(o.name);
        return;
      }
    }
  };
  for (const pddl::TypedName& o : domain_.constants) consider(o);
  for (const pddl::TypedName& o : problem_.objects) consider(o);
  return out;
}

std::string ActionModel::TypeOf(std::string_view object) const {
  for (const auto* list : {&problem_.objects, &domain_.constants}) {
    for (const pddl::TypedName& o : *list) {
      if (o.name == object && !o.types.empty()) return o.types.front();
    }
  }
  return "";
}

bool ActionModel::IsStaticPredicate(std::string_view predicate) const {
  return !changed_predicates_.contains(predicate);
}
bool ActionModel::IsStaticFunction(std::string_view function) const {
  return !changed_functions_.contains(function);
}

namespace {
bool Mentions(const Condition& c, std::string_view predicate) {
  if (c.kind == Condition::Kind::kAtom && c.atom.predicate == predicate) return true;
  for (const Condition& ch : c.children) {
    if (Mentions(ch, predicate)) return true;
  }
  return false;
}
}  // namespace

bool ActionModel::PredicateInConditions(std::string_view predicate) const {
  for (const pddl::Action& a : domain_.actions) {
    if (Mentions(a.condition, predicate)) return true;
  }
  return false;
}

std::string ActionModel::Resolve(const pddl::Term& t, const Binding& b) const {
  if (!t.IsVariable()) return t.name;
  auto it = b.find(t.name);
  return it == b.end() ? t.name : it->second;
}

std::vector<std::string> ActionModel::Resolve(const std::vector<pddl::Term>& ts,
                                              const Binding& b) const {
  std::vector<std::string> out;
  out.reserve(ts.size());
  for (const pddl::Term& t : ts) out.push_back(Resolve(t, b));
  return out;
}

std::vector<Binding> ActionModel::Expand(const std::vector<pddl::TypedName>& vars,
                                         const Binding& b) const {
  std::vector<Binding> out = {b};
  for (const pddl::TypedName& v : vars) {
    std::vector<std::string> objects;
    for (const std::string& t : v.types) {
      for (std::string& o : ObjectsOfType(t)) objects.push_back(std::move(o));
    }
    std::vector<Binding> next;
    for (const Binding& partial : out) {
      for (const std::string& o : objects) {
        Binding nb = partial;
        nb[v.name] = o;
        next.push_back(std::move(nb));
      }
    }
    out = std::move(next);
  }
  return out;
}

StatusOr<ActionInstance> ActionModel::Instantiate(std::string_view name,
                                                  const std::vector<std::string>& args) const {
  const pddl::Action* schema = domain_.FindAction(name);
  if (schema == nullptr) {
    return absl::InvalidArgumentError(
        absl::StrCat("plan action '", std::string(name), "' is not in the domain"));
  }
  if (schema->parameters.size() != args.size()) {
    return absl::InvalidArgumentError(absl::StrCat("plan action '", std::string(name), "' has ",
                                                   args.size(), " arguments, the domain declares ",
                                                   schema->parameters.size()));
  }
  ActionInstance inst;
  inst.schema = schema;
  inst.name = std::string(name);
  inst.args = args;
  for (size_t i = 0; i < args.size(); ++i) inst.binding[schema->parameters[i].name] = args[i];
  // A durative action's conditions carry their own time (at start, over all, at end).
  CollectReads(schema->condition, inst.binding, TimeSpec::kAtStart, &inst);
  for (const pddl::DurationConstraint& d : schema->duration) {
    CollectExprReads(d.value, inst.binding, &inst.reads_start);
  }
  CollectWrites(schema->effect, inst.binding,
                schema->durative ? TimeSpec::kAtEnd : TimeSpec::kAtStart, &inst);
  return inst;
}

void ActionModel::CollectExprReads(const NumExpr& e, const Binding& b,
                                   std::set<std::string>* out) const {
  if (e.kind == NumExpr::Kind::kFluent) out->insert(AtomKey(e.function, Resolve(e.args, b)));
  for (const NumExpr& c : e.children) CollectExprReads(c, b, out);
}

void ActionModel::CollectReads(const Condition& c, const Binding& b, TimeSpec time,
                               ActionInstance* out) const {
  std::set<std::string>* bucket = time == TimeSpec::kOverAll ? &out->reads_overall
                                  : time == TimeSpec::kAtEnd ? &out->reads_end
                                                             : &out->reads_start;
  switch (c.kind) {
    case Condition::Kind::kTrue:
      return;
    case Condition::Kind::kAtom:
      if (c.atom.predicate != "=")
        bucket->insert(AtomKey(c.atom.predicate, Resolve(c.atom.args, b)));
      return;
    case Condition::Kind::kCompare:
      CollectExprReads(c.lhs, b, bucket);
      CollectExprReads(c.rhs, b, bucket);
      return;
    case Condition::Kind::kTimed:
      for (const Condition& ch : c.children) CollectReads(ch, b, c.time, out);
      return;
    case Condition::Kind::kExists:
    case Condition::Kind::kForall:
      for (const Binding& nb : Expand(c.variables, b)) {
        for (const Condition& ch : c.children) CollectReads(ch, nb, time, out);
      }
      return;
    default:
      for (const Condition& ch : c.children) CollectReads(ch, b, time, out);
      return;
  }
}

void ActionModel::CollectWrites(const Effect& e, const Binding& b, TimeSpec time,
                                ActionInstance* out) const {
  std::set<std::string>* bucket =
      time == TimeSpec::kAtStart ? &out->writes_start : &out->writes_end;
  switch (e.kind) {
    case Effect::Kind::kAdd:
    case Effect::Kind::kDelete:
      bucket->insert(AtomKey(e.atom.predicate, Resolve(e.atom.args, b)));
      return;
    case Effect::Kind::kNumeric: {
      bucket->insert(AtomKey(e.fluent.function, Resolve(e.fluent.args, b)));
      std::set<std::string>* reads =
          time == TimeSpec::kAtStart ? &out->reads_start : &out->reads_end;
      CollectExprReads(e.value, b, reads);
      return;
    }
    case Effect::Kind::kTimed:
      for (const Effect& ch : e.children) CollectWrites(ch, b, e.time, out);
      return;
    case Effect::Kind::kForall:
      for (const Binding& nb : Expand(e.variables, b)) {
        for (const Effect& ch : e.children) CollectWrites(ch, nb, time, out);
      }
      return;
    case Effect::Kind::kWhen:
      CollectReads(e.condition, b, time == TimeSpec::kAtEnd ? TimeSpec::kAtEnd : TimeSpec::kAtStart,
                   out);
      for (const Effect& ch : e.children) CollectWrites(ch, b, time, out);
      return;
    case Effect::Kind::kAnd:
      for (const Effect& ch : e.children) CollectWrites(ch, b, time, out);
      return;
  }
}

StatusOr<double> ActionModel::Eval(const NumExpr& e, const Binding& b, const WorldState& s,
                                   double duration_s) const {
  switch (e.kind) {
    case NumExpr::Kind::kNumber:
      return e.value;
    case NumExpr::Kind::kDuration:
      return duration_s;
    case NumExpr::Kind::kTotalTime:
      return 0.0;
    case NumExpr::Kind::kFluent: {
      std::string key = AtomKey(e.function, Resolve(e.args, b));
      auto it = s.fluents.find(key);
      if (it == s.fluents.end()) {
        return absl::FailedPreconditionError(absl::StrCat("numeric fluent ", key, " is undefined"));
      }
      return it->second;
    }
    case NumExpr::Kind::kNeg: {
      if (e.children.empty()) return absl::InvalidArgumentError("empty negation");
      SEAPLAN_ASSIGN_OR_RETURN(double v, Eval(e.children[0], b, s, duration_s));
      return -v;
    }
    default:
      break;
  }
  if (e.children.empty()) return absl::InvalidArgumentError("arithmetic with no operands");
  SEAPLAN_ASSIGN_OR_RETURN(double acc, Eval(e.children[0], b, s, duration_s));
  for (size_t i = 1; i < e.children.size(); ++i) {
    SEAPLAN_ASSIGN_OR_RETURN(double v, Eval(e.children[i], b, s, duration_s));
    switch (e.kind) {
      case NumExpr::Kind::kAdd:
        acc += v;
        break;
      case NumExpr::Kind::kSub:
        acc -= v;
        break;
      case NumExpr::Kind::kMul:
        acc *= v;
        break;
      case NumExpr::Kind::kDiv:
        if (v == 0.0) return absl::FailedPreconditionError("division by zero");
        acc /= v;
        break;
      default:
        break;
    }
  }
  return acc;
}

bool ActionModel::Holds(const Condition& c, const Binding& b, const WorldState& s,
                        double duration_s) const {
  switch (c.kind) {
    case Condition::Kind::kTrue:
      return true;
    case Condition::Kind::kAtom: {
      std::vector<std::string> args = Resolve(c.atom.args, b);
      if (c.atom.predicate == "=") return args.size() == 2 && args[0] == args[1];
      return s.facts.contains(AtomKey(c.atom.predicate, args));
    }
    case Condition::Kind::kNot:
      return !Holds(c.children.at(0), b, s, duration_s);
    case Condition::Kind::kAnd:
    case Condition::Kind::kTimed:
      for (const Condition& ch : c.children) {
        if (!Holds(ch, b, s, duration_s)) return false;
      }
      return true;
    case Condition::Kind::kOr:
      for (const Condition& ch : c.children) {
        if (Holds(ch, b, s, duration_s)) return true;
      }
      return false;
    case Condition::Kind::kImply:
      return !Holds(c.children.at(0), b, s, duration_s) ||
             Holds(c.children.at(1), b, s, duration_s);
    case Condition::Kind::kExists:
      for (const Binding& nb : Expand(c.variables, b)) {
        if (Holds(c.children.at(0), nb, s, duration_s)) return true;
      }
      return false;
    case Condition::Kind::kForall:
      for (const Binding& nb : Expand(c.variables, b)) {
        if (!Holds(c.children.at(0), nb, s, duration_s)) return false;
      }
      return true;
    case Condition::Kind::kCompare: {
      auto l = Eval(c.lhs, b, s, duration_s);
      auto r = Eval(c.rhs, b, s, duration_s);
      return l.ok() && r.ok() && CompareValues(*l, c.comparator, *r);
    }
  }
  return false;
}

Status ActionModel::ApplyEffect(const Effect& e, const Binding& b, bool at_end, bool durative,
                                TimeSpec inherited, const WorldState& before, double duration_s,
                                std::vector<std::string>* add, std::vector<std::string>* del,
                                std::vector<std::pair<std::string, double>>* assign) const {
  // Instantaneous actions: everything happens "at start".
  const bool here = !durative ? !at_end
                              : (inherited == TimeSpec::kAtEnd     ? at_end
                                 : inherited == TimeSpec::kAtStart ? !at_end
                                                                   : at_end);
  switch (e.kind) {
    case Effect::Kind::kAdd:
      if (here) add->push_back(AtomKey(e.atom.predicate, Resolve(e.atom.args, b)));
      return absl::OkStatus();
    case Effect::Kind::kDelete:
      if (here) del->push_back(AtomKey(e.atom.predicate, Resolve(e.atom.args, b)));
      return absl::OkStatus();
    case Effect::Kind::kNumeric: {
      if (!here) return absl::OkStatus();
      std::string key = AtomKey(e.fluent.function, Resolve(e.fluent.args, b));
      SEAPLAN_ASSIGN_OR_RETURN(double v, Eval(e.value, b, before, duration_s));
      double current = 0.0;
      if (auto it = before.fluents.find(key); it != before.fluents.end()) {
        current = it->second;
      } else if (e.op != pddl::AssignOp::kAssign) {
        return absl::FailedPreconditionError(absl::StrCat("numeric fluent ", key, " is undefined"));
      }
      double result = v;
      switch (e.op) {
        case pddl::AssignOp::kAssign:
          result = v;
          break;
        case pddl::AssignOp::kIncrease:
          result = current + v;
          break;
        case pddl::AssignOp::kDecrease:
          result = current - v;
          break;
        case pddl::AssignOp::kScaleUp:
          result = current * v;
          break;
        case pddl::AssignOp::kScaleDown:
          result = v == 0 ? current : current / v;
          break;
      }
      assign->emplace_back(std::move(key), result);
      return absl::OkStatus();
    }
    case Effect::Kind::kTimed:
      for (const Effect& ch : e.children) {
        SEAPLAN_RETURN_IF_ERROR(
            ApplyEffect(ch, b, at_end, durative, e.time, before, duration_s, add, del, assign));
      }
      return absl::OkStatus();
    case Effect::Kind::kForall:
      for (const Binding& nb : Expand(e.variables, b)) {
        for (const Effect& ch : e.children) {
          SEAPLAN_RETURN_IF_ERROR(ApplyEffect(ch, nb, at_end, durative, inherited, before,
                                              duration_s, add, del, assign));
        }
      }
      return absl::OkStatus();
    case Effect::Kind::kWhen:
      if (!Holds(e.condition, b, before, duration_s)) return absl::OkStatus();
      for (const Effect& ch : e.children) {
        SEAPLAN_RETURN_IF_ERROR(
            ApplyEffect(ch, b, at_end, durative, inherited, before, duration_s, add, del, assign));
      }
      return absl::OkStatus();
    case Effect::Kind::kAnd:
      for (const Effect& ch : e.children) {
        SEAPLAN_RETURN_IF_ERROR(
            ApplyEffect(ch, b, at_end, durative, inherited, before, duration_s, add, del, assign));
      }
      return absl::OkStatus();
  }
  return absl::OkStatus();
}

Status ActionModel::Apply(const ActionInstance& action, bool at_end, double duration_s,
                          WorldState* state) const {
  if (action.schema == nullptr) return absl::InvalidArgumentError("action not instantiated");
  std::vector<std::string> add, del;
  std::vector<std::pair<std::string, double>> assign;
  SEAPLAN_RETURN_IF_ERROR(ApplyEffect(action.schema->effect, action.binding, at_end,
                                      action.schema->durative, TimeSpec::kNone, *state, duration_s,
                                      &add, &del, &assign));
  for (const std::string& f : del) state->facts.erase(f);
  for (std::string& f : add) state->facts.insert(std::move(f));
  for (auto& [k, v] : assign) state->fluents[k] = v;
  return absl::OkStatus();
}

namespace {
const char* OpName(NumExpr::Kind k) {
  switch (k) {
    case NumExpr::Kind::kAdd:
      return "+";
    case NumExpr::Kind::kSub:
      return "-";
    case NumExpr::Kind::kMul:
      return "*";
    case NumExpr::Kind::kDiv:
      return "/";
    case NumExpr::Kind::kNeg:
      return "-";
    default:
      return "?";
  }
}
std::string AtomText(const pddl::Atom& a) {
  std::string s = "(" + a.predicate;
  for (const pddl::Term& t : a.args) s += " " + t.name;
  return s + ")";
}
std::string VarsText(const std::vector<pddl::TypedName>& vars) {
  std::vector<std::string> parts;
  for (const pddl::TypedName& v : vars) {
    std::string type =
        v.types.size() == 1 ? v.types[0] : "(either " + absl::StrJoin(v.types, " ") + ")";
    parts.push_back(v.name + " - " + type);
  }
  return absl::StrJoin(parts, " ");
}
}  // namespace

std::string ToPddl(const NumExpr& e) {
  switch (e.kind) {
    case NumExpr::Kind::kNumber:
      return validate::FormatTime(e.value);
    case NumExpr::Kind::kDuration:
      return "?duration";
    case NumExpr::Kind::kTotalTime:
      return "total-time";
    case NumExpr::Kind::kFluent: {
      std::string s = "(" + e.function;
      for (const pddl::Term& t : e.args) s += " " + t.name;
      return s + ")";
    }
    default:
      break;
  }
  std::string s = absl::StrCat("(", OpName(e.kind));
  for (const NumExpr& c : e.children) s += " " + ToPddl(c);
  return s + ")";
}

std::string ToPddl(const Condition& c) {
  auto children = [&](const char* head) {
    std::string s = absl::StrCat("(", head);
    for (const Condition& ch : c.children) s += " " + ToPddl(ch);
    return s + ")";
  };
  switch (c.kind) {
    case Condition::Kind::kTrue:
      return "(and)";
    case Condition::Kind::kAtom:
      return AtomText(c.atom);
    case Condition::Kind::kNot:
      return children("not");
    case Condition::Kind::kAnd:
      return children("and");
    case Condition::Kind::kOr:
      return children("or");
    case Condition::Kind::kImply:
      return children("imply");
    case Condition::Kind::kExists:
      return "(exists (" + VarsText(c.variables) + ") " + ToPddl(c.children.at(0)) + ")";
    case Condition::Kind::kForall:
      return "(forall (" + VarsText(c.variables) + ") " + ToPddl(c.children.at(0)) + ")";
    case Condition::Kind::kCompare:
      return absl::StrCat("(", pddl::ComparatorSymbol(c.comparator), " ", ToPddl(c.lhs), " ",
                          ToPddl(c.rhs), ")");
    case Condition::Kind::kTimed:
      return absl::StrCat("(", pddl::TimeSpecName(c.time), " ", ToPddl(c.children.at(0)), ")");
  }
  return "(and)";
}

}  // namespace seaplan::mission::internal
