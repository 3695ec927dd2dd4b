#include "seaplan/validate/validator.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"

namespace seaplan::validate {
namespace {

using task::Action;
using task::ActionId;
using task::Comparator;
using task::Condition;
using task::Effects;
using task::FactId;
using task::GroundTask;
using task::NumericVarId;
using Kind = ValidationFailure::Kind;

// Times are compared on a 1 ns grid (see validator.h). kMaxTimeS keeps the
// nanosecond counts far inside int64 and rejects absurd inputs early.
constexpr double kNsPerS = 1e9;
constexpr double kMaxTimeS = 1e9;

std::int64_t ToNs(double seconds) {
  return std::llround(seconds * kNsPerS);
}

// Seconds for messages: short and readable (not the exact round-trip form).
std::string Secs(double seconds) {
  return absl::StrFormat("%.9g", seconds);
}

// Sort rank of events at the same nanosecond: ends, then timed literals, then
// starts. Any order is correct for non-interfering events (and interfering
// ones are a mutex failure); this one reads naturally ("end, then start").
enum class EventKind : std::uint8_t { kEnd = 0, kTimedLiteral = 1, kTimedFluent = 2, kStart = 3 };

struct Event {
  std::int64_t t_ns = 0;
  double t = 0.0;
  EventKind kind = EventKind::kStart;
  std::int32_t index = 0;  // step index, or index into timed_literals / timed_fluents

  bool IsStep() const { return kind == EventKind::kStart || kind == EventKind::kEnd; }
};

// What an event reads and writes, for the mutex test (sorted, unique).
struct Footprint {
  std::vector<FactId> read, add, del;
  std::vector<NumericVarId> num_read, num_additive, num_assign;

  void ReadCondition(const Condition& c) {
    read.insert(read.end(), c.positive.begin(), c.positive.end());
    read.insert(read.end(), c.negative.begin(), c.negative.end());
    for (const auto& n : c.numeric) {
      ReadExpr(n.lhs);
      ReadExpr(n.rhs);
    }
  }
  void ReadExpr(const task::NumericExpr& e) {
    for (const auto& node : e.nodes) {
      if (node.op == task::NumericExpr::Op::kVariable) num_read.push_back(node.var);
    }
  }
  void WriteNumeric(const std::vector<task::NumericEffect>& effects) {
    for (const auto& n : effects) {
      ReadExpr(n.value);
      if (n.op == task::AssignOp::kIncrease || n.op == task::AssignOp::kDecrease) {
        num_additive.push_back(n.var);
      } else {
        num_assign.push_back(n.var);
      }
    }
  }
  void Write(const std::vector<FactId>& adds, const std::vector<FactId>& dels,
             const std::vector<task::NumericEffect>& numeric) {
    add.insert(add.end(), adds.begin(), adds.end());
    del.insert(del.end(), dels.begin(), dels.end());
    WriteNumeric(numeric);
  }
  void Normalize() {
    for (auto* v : {&read, &add, &del, &num_read, &num_additive, &num_assign}) {
      std::sort(v->begin(), v->end());
      v->erase(std::unique(v->begin(), v->end()), v->end());
    }
  }
};

// First common element of two sorted vectors, or -1.
std::int32_t FirstCommon(const std::vector<std::int32_t>& a, const std::vector<std::int32_t>& b) {
  auto i = a.begin();
  auto j = b.begin();
  while (i != a.end() && j != b.end()) {
    if (*i < *j) {
      ++i;
    } else if (*j < *i) {
      ++j;
    } else {
      return *i;
    }
  }
  return -1;
}

struct Conflict {
  bool numeric = false;
  std::int32_t id = -1;
  std::string how;  // "deleted by the first, added by the second", ...
};

std::optional<Conflict> Interfere(const Footprint& a, const Footprint& b) {
  auto fact = [](std::int32_t id, const char* how) { return Conflict{false, id, how}; };
  auto var = [](std::int32_t id, const char* how) { return Conflict{true, id, how}; };
  std::int32_t id;
  if ((id = FirstCommon(a.add, b.del)) >= 0)
    return fact(id, "added by the first and deleted by the second");
  if ((id = FirstCommon(a.del, b.add)) >= 0)
    return fact(id, "deleted by the first and added by the second");
  if ((id = FirstCommon(a.add, b.read)) >= 0)
    return fact(id, "added by the first and read by the second");
  if ((id = FirstCommon(a.del, b.read)) >= 0)
    return fact(id, "deleted by the first and read by the second");
  if ((id = FirstCommon(a.read, b.add)) >= 0)
    return fact(id, "read by the first and added by the second");
  if ((id = FirstCommon(a.read, b.del)) >= 0)
    return fact(id, "read by the first and deleted by the second");
  if ((id = FirstCommon(a.num_additive, b.num_read)) >= 0)
    return var(id, "updated by the first and read by the second");
  if ((id = FirstCommon(a.num_assign, b.num_read)) >= 0)
    return var(id, "assigned by the first and read by the second");
  if ((id = FirstCommon(a.num_read, b.num_additive)) >= 0)
    return var(id, "read by the first and updated by the second");
  if ((id = FirstCommon(a.num_read, b.num_assign)) >= 0)
    return var(id, "read by the first and assigned by the second");
  if ((id = FirstCommon(a.num_assign, b.num_assign)) >= 0) return var(id, "assigned by both");
  if ((id = FirstCommon(a.num_assign, b.num_additive)) >= 0)
    return var(id, "assigned by the first and updated by the second");
  if ((id = FirstCommon(a.num_additive, b.num_assign)) >= 0)
    return var(id, "updated by the first and assigned by the second");
  return std::nullopt;
}

// The first literal of a condition that is false.
struct LiteralFailure {
  enum class Type : std::uint8_t { kPositive, kNegative, kNumeric } type = Type::kPositive;
  std::size_t index = 0;
  bool undefined = false;  // a numeric comparison read an undefined value
  double lhs = 0.0, rhs = 0.0;
};

struct State {
  std::vector<std::uint8_t> facts;
  std::vector<double> values;
};

std::optional<LiteralFailure> FirstFailing(const Condition& c, const State& s, double duration) {
  for (std::size_t i = 0; i < c.positive.size(); ++i) {
    if (!s.facts[static_cast<std::size_t>(c.positive[i])]) {
      return LiteralFailure{LiteralFailure::Type::kPositive, i};
    }
  }
  for (std::size_t i = 0; i < c.negative.size(); ++i) {
    if (s.facts[static_cast<std::size_t>(c.negative[i])]) {
      return LiteralFailure{LiteralFailure::Type::kNegative, i};
    }
  }
  for (std::size_t i = 0; i < c.numeric.size(); ++i) {
    const auto& n = c.numeric[i];
    const auto lhs = n.lhs.Evaluate(s.values, duration);
    const auto rhs = n.rhs.Evaluate(s.values, duration);
    if (!lhs || !rhs) return LiteralFailure{LiteralFailure::Type::kNumeric, i, true};
    if (!task::Compare(*lhs, n.comparator, *rhs)) {
      return LiteralFailure{LiteralFailure::Type::kNumeric, i, false, *lhs, *rhs};
    }
  }
  return std::nullopt;
}

std::string DescribeLiteral(const GroundTask& task, const Condition& c, const LiteralFailure& f) {
  switch (f.type) {
    case LiteralFailure::Type::kPositive:
      return task.facts[static_cast<std::size_t>(c.positive[f.index])].DisplayName();
    case LiteralFailure::Type::kNegative:
      return "(not " + task.facts[static_cast<std::size_t>(c.negative[f.index])].DisplayName() +
             ")";
    case LiteralFailure::Type::kNumeric:
      return task::ToString(c.numeric[f.index], task);
  }
  return "?";
}

std::string WhyFalse(const LiteralFailure& f) {
  switch (f.type) {
    case LiteralFailure::Type::kPositive:
      return "is false";
    case LiteralFailure::Type::kNegative:
      return "is false (the fact is true)";
    case LiteralFailure::Type::kNumeric:
      if (f.undefined) return "reads an undefined value";
      return absl::StrCat("is false (", Secs(f.lhs), " vs ", Secs(f.rhs), ")");
  }
  return "is false";
}

bool DurationOk(double d, Comparator cmp, double v, double tol) {
  switch (cmp) {
    case Comparator::kEqual:
      return std::fabs(d - v) <= tol;
    case Comparator::kLessEqual:
      return d <= v + tol;
    case Comparator::kGreaterEqual:
      return d >= v - tol;
    case Comparator::kLess:
      return d < v;
    case Comparator::kGreater:
      return d > v;
  }
  return false;
}

// The sentence for a step that maps to no ground action, from the task alone.
std::string FallbackExplanation(const GroundTask& task, const PlanStep& step) {
  bool name_known = false;
  std::size_t arity = 0;
  bool arity_matches = false;
  for (const auto& a : task.actions) {
    if (a.name != step.name) continue;
    name_known = true;
    arity = a.args.size();
    if (a.args.size() == step.args.size()) arity_matches = true;
  }
  if (!name_known) {
    return absl::StrCat("the task has no action named '", step.name,
                        "' (unknown action, or no instance of it is reachable)");
  }
  if (!arity_matches) {
    return absl::StrCat("'", step.name, "' takes ", arity, " argument(s), the step gives ",
                        step.args.size());
  }
  return "no ground action has these arguments: an object is unknown or of the wrong type, "
         "a static precondition is false, or its preconditions are unreachable";
}

// Steps mapped to ground actions: candidates[i] lists every DNF variant.
using StepCandidates = std::vector<std::vector<ActionId>>;

class Run {
 public:
  Run(const GroundTask& task, const Plan& plan, const ValidationOptions& options,
      const StepCandidates& candidates)
      : task_(task), plan_(plan), options_(options), candidates_(candidates) {}

  ValidationResult Execute();

 private:
  struct StepState {
    std::int64_t start_ns = 0;
    std::int64_t end_ns = 0;
    ActionId effects_from = -1;                // variant whose effects apply
    std::vector<std::uint8_t> alive;           // per candidate variant
    std::vector<std::uint8_t> end_cond_fired;  // end conditional effects decided at start
  };

  ValidationResult Fail(ValidationFailure failure) {
    result_.valid = false;
    result_.first_failure = std::move(failure);
    return result_;
  }
  ValidationFailure StepFailure(Kind kind, double t, int step) const {
    ValidationFailure f;
    f.kind = kind;
    f.time_s = t;
    f.step_index = step;
    f.action = plan_.steps[static_cast<std::size_t>(step)].DisplayName();
    return f;
  }
  const Action& action(ActionId id) const { return task_.actions[static_cast<std::size_t>(id)]; }

  std::optional<ValidationFailure> CheckStructure();
  std::string DescribeEvent(const Event& e) const;
  // Computes the footprint of events_[event_index] once (footprint_of_event_).
  void FootprintOf(std::size_t event_index);
  std::optional<ValidationFailure> CheckMutex(std::size_t event_index);
  // Keeps the variants of `step` whose `part` holds; on none, the failure
  // (and, if `failed` is given, the literal it reports).
  struct FailedLiteral {
    const Condition* condition = nullptr;
    LiteralFailure literal;
  };
  std::optional<ValidationFailure> Filter(int step, Condition Action::*part, Kind kind, double t,
                                          const char* when, FailedLiteral* failed = nullptr);
  // After the happening at events_[last] (every event at that nanosecond
  // applied): the over-all conditions of the steps open in the state it
  // leaves, i.e. started at or before it and ending after it.
  std::optional<ValidationFailure> CheckInvariants(std::size_t last);
  // The event of the current happening that made `failed` false, when it
  // held in the state before the happening; -1 otherwise.
  std::int32_t Culprit(const FailedLiteral& failed, double duration);
  // State writes, logged in changes_ so that Culprit can tell who broke what.
  void SetFact(FactId f, std::uint8_t value);
  void SetValue(NumericVarId var, double value);
  std::optional<ValidationFailure> Start(const Event& e);
  std::optional<ValidationFailure> End(const Event& e);
  // Applies `effects` of `source` (for messages) in the current state.
  std::optional<std::string> Apply(const Effects& effects, task::TimePoint point,
                                   const std::vector<std::uint8_t>* decided, double duration);

  const GroundTask& task_;
  const Plan& plan_;
  const ValidationOptions& options_;
  const StepCandidates& candidates_;

  ValidationResult result_;
  State state_;
  std::vector<StepState> steps_;
  std::vector<Event> events_;
  std::vector<std::int32_t> footprint_of_event_;  // -1 until computed
  std::vector<Footprint> footprints_;
  std::vector<int> open_;  // steps started and not ended
  struct PendingUpdate {
    NumericVarId var;
    task::AssignOp op;
    double operand;
  };
  std::vector<PendingUpdate> updates_;  // scratch, reused by every event
  // Every change of a fact or numeric value in the current happening, in
  // order, with the value before it (cleared at each new happening; at most
  // one entry per effect, so no cost beyond applying the effects).
  struct Change {
    bool numeric = false;
    std::int32_t id = -1;
    double old_value = 0.0;
    std::int32_t event = -1;  // index into events_
  };
  std::vector<Change> changes_;
  std::int32_t current_event_ = -1;
};

std::optional<ValidationFailure> Run::CheckStructure() {
  for (std::size_t i = 0; i < plan_.steps.size(); ++i) {
    const PlanStep& step = plan_.steps[i];
    const int si = static_cast<int>(i);
    auto bad = [&](Kind kind, std::string reason) {
      ValidationFailure f = StepFailure(kind, std::isfinite(step.start_s) ? step.start_s : 0.0, si);
      f.reason = std::move(reason);
      if (step.line > 0) f.reason += absl::StrCat(" (plan line ", step.line, ")");
      return f;
    };
    if (!std::isfinite(step.start_s) || step.start_s < 0.0 || step.start_s > kMaxTimeS) {
      return bad(Kind::kBadStep, absl::StrCat("start time ", Secs(step.start_s), " is not in [0, ",
                                              Secs(kMaxTimeS), "] s"));
    }
    if (!std::isfinite(step.duration_s) || step.duration_s < 0.0 || step.duration_s > kMaxTimeS) {
      return bad(Kind::kBadStep, absl::StrCat("duration ", Secs(step.duration_s), " is not in [0, ",
                                              Secs(kMaxTimeS), "] s"));
    }
    if (candidates_[i].empty()) {
      std::string why = options_.explain_missing_action
                            ? options_.explain_missing_action(step.name, step.args)
                            : std::string();
      if (why.empty()) why = FallbackExplanation(task_, step);
      // The grounder's sentence may start with the action itself; say it once.
      const std::string prefix = step.DisplayName() + ": ";
      if (why.compare(0, prefix.size(), prefix) == 0) why.erase(0, prefix.size());
      return bad(Kind::kUnknownAction,
                 absl::StrCat(step.DisplayName(), " is not an action of the task: ", why));
    }
    const Action& a = action(candidates_[i].front());
    if (a.is_durative) {
      if (ToNs(step.start_s + step.duration_s) <= ToNs(step.start_s)) {
        return bad(
            Kind::kBadStep,
            "a durative action needs a positive duration (\"[d]\" with d >= 1 ns); the "
            "step has " +
                (step.duration_s == 0.0 ? std::string("none") : "[" + Secs(step.duration_s) + "]"));
      }
    } else if (step.duration_s != 0.0) {
      return bad(Kind::kBadStep,
                 absl::StrCat("an instantaneous action takes no duration; the step has [",
                              Secs(step.duration_s), "]"));
    }
  }
  return std::nullopt;
}

std::string Run::DescribeEvent(const Event& e) const {
  switch (e.kind) {
    case EventKind::kStart: {
      const auto& step = plan_.steps[static_cast<std::size_t>(e.index)];
      const bool durative =
          action(candidates_[static_cast<std::size_t>(e.index)].front()).is_durative;
      return absl::StrCat(step.DisplayName(), durative ? " start" : "", " at t=", Secs(e.t));
    }
    case EventKind::kEnd:
      return absl::StrCat(plan_.steps[static_cast<std::size_t>(e.index)].DisplayName(),
                          " end at t=", Secs(e.t));
    case EventKind::kTimedLiteral: {
      const auto& til = task_.timed_literals[static_cast<std::size_t>(e.index)];
      const std::string fact = task_.facts[static_cast<std::size_t>(til.fact)].DisplayName();
      return absl::StrCat("timed initial literal (at ", Secs(til.time_s), " ",
                          til.value ? fact : "(not " + fact + ")", ")");
    }
    case EventKind::kTimedFluent: {
      const auto& tif = task_.timed_fluents[static_cast<std::size_t>(e.index)];
      return absl::StrCat("timed initial fluent (at ", Secs(tif.time_s), " (= ",
                          task_.numeric_vars[static_cast<std::size_t>(tif.var)].DisplayName(), " ",
                          Secs(tif.value), "))");
    }
  }
  return "?";
}

void Run::FootprintOf(std::size_t event_index) {
  std::int32_t& slot = footprint_of_event_[event_index];
  if (slot >= 0) return;
  const Event& e = events_[event_index];
  Footprint fp;
  switch (e.kind) {
    case EventKind::kStart:
    case EventKind::kEnd:
      for (ActionId id : candidates_[static_cast<std::size_t>(e.index)]) {
        const Action& a = action(id);
        if (e.kind == EventKind::kStart) {
          fp.ReadCondition(a.at_start);
          for (const auto& d : a.duration) fp.ReadExpr(d.value);
          fp.Write(a.start_effects.add, a.start_effects.del, a.start_effects.numeric);
          for (const auto& ce : a.start_effects.conditional) {
            fp.ReadCondition(ce.condition);
            fp.Write(ce.add, ce.del, ce.numeric);
          }
          for (const auto& ce : a.end_effects.conditional) {
            if (ce.condition_time == task::TimePoint::kStart) fp.ReadCondition(ce.condition);
          }
        } else {
          fp.ReadCondition(a.at_end);
          fp.Write(a.end_effects.add, a.end_effects.del, a.end_effects.numeric);
          for (const auto& ce : a.end_effects.conditional) {
            if (ce.condition_time == task::TimePoint::kEnd) fp.ReadCondition(ce.condition);
            fp.Write(ce.add, ce.del, ce.numeric);
          }
        }
        // Over-all conditions are not part of either snap action (PDDL 2.1,
        // VAL's Ownership): they are checked on the open interval instead.
      }
      break;
    case EventKind::kTimedLiteral: {
      const auto& til = task_.timed_literals[static_cast<std::size_t>(e.index)];
      (til.value ? fp.add : fp.del).push_back(til.fact);
      break;
    }
    case EventKind::kTimedFluent:
      fp.num_assign.push_back(task_.timed_fluents[static_cast<std::size_t>(e.index)].var);
      break;
  }
  fp.Normalize();
  slot = static_cast<std::int32_t>(footprints_.size());
  footprints_.push_back(std::move(fp));
}

std::optional<ValidationFailure> Run::CheckMutex(std::size_t i) {
  const Event& a = events_[i];
  // Closer than epsilon, judged on the real times with a slack of a few
  // rounding errors (1 ns, more for huge times) so that a separation of
  // exactly epsilon computed in floating point (10.001 - 10 =
  // 0.00099999999999945) counts as epsilon. Comparing rounded nanoseconds
  // here instead could turn such a gap into 999999 ns when the two times sit
  // on either side of a half-nanosecond. Exactly simultaneous events (same
  // nanosecond) are always checked, even with epsilon 0.
  const double limit = options_.epsilon_s - (1e-9 + std::fabs(a.t) * 1e-15);
  for (std::size_t k = i + 1; k < events_.size(); ++k) {
    const Event& b = events_[k];
    if (b.t_ns != a.t_ns && !(b.t - a.t < limit)) break;  // events are sorted by time
    if (a.IsStep() && b.IsStep() && a.index == b.index)
      continue;                                // a step never conflicts with itself
    if (!a.IsStep() && !b.IsStep()) continue;  // timed literals are the task's own business
    // FootprintOf may grow footprints_, so take both references afterwards.
    FootprintOf(i);
    FootprintOf(k);
    const auto conflict = Interfere(footprints_[static_cast<std::size_t>(footprint_of_event_[i])],
                                    footprints_[static_cast<std::size_t>(footprint_of_event_[k])]);
    if (!conflict) continue;
    ValidationFailure f;
    f.kind = Kind::kMutex;
    f.time_s = a.t;
    f.step_index = a.IsStep() ? a.index : -1;
    f.action = a.IsStep() ? plan_.steps[static_cast<std::size_t>(a.index)].DisplayName()
                          : DescribeEvent(a);
    f.other_step_index = b.IsStep() ? b.index : -1;
    f.other_action = b.IsStep() ? plan_.steps[static_cast<std::size_t>(b.index)].DisplayName()
                                : DescribeEvent(b);
    f.condition = conflict->numeric
                      ? task_.numeric_vars[static_cast<std::size_t>(conflict->id)].DisplayName()
                      : task_.facts[static_cast<std::size_t>(conflict->id)].DisplayName();
    f.reason = absl::StrCat(DescribeEvent(a), " and ", DescribeEvent(b), " are ", Secs(b.t - a.t),
                            " s apart (less than epsilon ", Secs(options_.epsilon_s),
                            " s) and interfere: ", f.condition, " is ", conflict->how);
    return f;
  }
  return std::nullopt;
}

std::optional<ValidationFailure> Run::Filter(int step, Condition Action::*part, Kind kind, double t,
                                             const char* when, FailedLiteral* failed) {
  StepState& ss = steps_[static_cast<std::size_t>(step)];
  const auto& cands = candidates_[static_cast<std::size_t>(step)];
  const double duration = plan_.steps[static_cast<std::size_t>(step)].duration_s;
  std::optional<ValidationFailure> last;
  bool any = false;
  for (std::size_t v = 0; v < cands.size(); ++v) {
    if (!ss.alive[v]) continue;
    const Condition& c = action(cands[v]).*part;
    const auto failing = FirstFailing(c, state_, duration);
    if (!failing) {
      any = true;
      continue;
    }
    ss.alive[v] = 0;
    if (!last) {
      last = StepFailure(kind, t, step);
      last->condition = DescribeLiteral(task_, c, *failing);
      last->reason =
          absl::StrCat(KindName(kind), " ", last->condition, " ", WhyFalse(*failing), " ", when);
      if (failed != nullptr) *failed = FailedLiteral{&c, *failing};
    }
  }
  if (any) return std::nullopt;
  return last;
}

std::optional<std::string> Run::Apply(const Effects& effects, task::TimePoint point,
                                      const std::vector<std::uint8_t>* decided, double duration) {
  // Operands and conditional-effect conditions read the state before the event.
  updates_.clear();
  auto collect =
      [&](const std::vector<task::NumericEffect>& numeric) -> std::optional<std::string> {
    for (const auto& n : numeric) {
      const auto operand = n.value.Evaluate(state_.values, duration);
      if (!operand) {
        return absl::StrCat("the numeric effect on ",
                            task_.numeric_vars[static_cast<std::size_t>(n.var)].DisplayName(),
                            " reads an undefined value (", task::ToString(n.value, task_), ")");
      }
      updates_.push_back({n.var, n.op, *operand});
    }
    return std::nullopt;
  };
  if (auto err = collect(effects.numeric)) return err;
  // Which conditional effects fire (allocates only for actions that have some).
  std::vector<std::uint8_t> fired(effects.conditional.size(), 0);
  for (std::size_t i = 0; i < effects.conditional.size(); ++i) {
    const auto& ce = effects.conditional[i];
    if (ce.condition_time != point && decided != nullptr && i < decided->size()) {
      fired[i] = (*decided)[i];
    } else {
      fired[i] = !FirstFailing(ce.condition, state_, duration).has_value();
    }
    if (fired[i]) {
      if (auto err = collect(ce.numeric)) return err;
    }
  }
  for (FactId f : effects.del) SetFact(f, 0);
  for (std::size_t i = 0; i < effects.conditional.size(); ++i) {
    if (!fired[i]) continue;
    for (FactId f : effects.conditional[i].del) SetFact(f, 0);
  }
  // Adds after deletes: an action that adds and deletes a fact leaves it true (VAL).
  for (FactId f : effects.add) SetFact(f, 1);
  for (std::size_t i = 0; i < effects.conditional.size(); ++i) {
    if (!fired[i]) continue;
    for (FactId f : effects.conditional[i].add) SetFact(f, 1);
  }
  for (const auto& u : updates_) {
    const double value = state_.values[static_cast<std::size_t>(u.var)];
    if (std::isnan(value) && u.op != task::AssignOp::kAssign) {
      return absl::StrCat("the numeric effect updates ",
                          task_.numeric_vars[static_cast<std::size_t>(u.var)].DisplayName(),
                          ", which is undefined");
    }
    const double next = task::ApplyAssign(u.op, value, u.operand);
    if (!std::isfinite(next)) {
      return absl::StrCat("the numeric effect on ",
                          task_.numeric_vars[static_cast<std::size_t>(u.var)].DisplayName(),
                          " gives a non-finite value (division by zero?)");
    }
    SetValue(u.var, next);
  }
  return std::nullopt;
}

void Run::SetFact(FactId f, std::uint8_t value) {
  std::uint8_t& slot = state_.facts[static_cast<std::size_t>(f)];
  if (slot == value) return;
  changes_.push_back({false, f, static_cast<double>(slot), current_event_});
  slot = value;
}

void Run::SetValue(NumericVarId var, double value) {
  double& slot = state_.values[static_cast<std::size_t>(var)];
  // Bitwise-equal values (including both undefined) are no change.
  if (slot == value || (std::isnan(slot) && std::isnan(value))) return;
  changes_.push_back({true, var, slot, current_event_});
  slot = value;
}

std::int32_t Run::Culprit(const FailedLiteral& failed, double duration) {
  const Condition& c = *failed.condition;
  const LiteralFailure& lf = failed.literal;
  if (lf.type != LiteralFailure::Type::kNumeric) {
    const bool positive = lf.type == LiteralFailure::Type::kPositive;
    const FactId f = positive ? c.positive[lf.index] : c.negative[lf.index];
    const Change* first = nullptr;
    const Change* last = nullptr;
    for (const Change& ch : changes_) {
      if (ch.numeric || ch.id != f) continue;
      if (first == nullptr) first = &ch;
      last = &ch;
    }
    if (first == nullptr) return -1;
    const bool held_before = positive ? first->old_value != 0.0 : first->old_value == 0.0;
    return held_before ? last->event : -1;
  }
  // A comparison: evaluate it again with the values from before the
  // happening put back for a moment.
  const auto& n = c.numeric[lf.index];
  auto reads = [&](NumericVarId var) {
    for (const auto* e : {&n.lhs, &n.rhs}) {
      for (const auto& node : e->nodes) {
        if (node.op == task::NumericExpr::Op::kVariable && node.var == var) return true;
      }
    }
    return false;
  };
  std::int32_t culprit = -1;
  std::vector<std::pair<NumericVarId, double>> restore;  // only on a failure path
  for (const Change& ch : changes_) {
    if (!ch.numeric || !reads(ch.id)) continue;
    culprit = ch.event;
    const bool seen = std::any_of(restore.begin(), restore.end(),
                                  [&](const auto& r) { return r.first == ch.id; });
    if (!seen) restore.emplace_back(ch.id, ch.old_value);
  }
  if (culprit < 0) return -1;
  for (auto& [var, value] : restore) std::swap(state_.values[static_cast<std::size_t>(var)], value);
  const auto lhs = n.lhs.Evaluate(state_.values, duration);
  const auto rhs = n.rhs.Evaluate(state_.values, duration);
  const bool held_before = lhs && rhs && task::Compare(*lhs, n.comparator, *rhs);
  for (auto& [var, value] : restore) std::swap(state_.values[static_cast<std::size_t>(var)], value);
  return held_before ? culprit : -1;
}

std::optional<ValidationFailure> Run::CheckInvariants(std::size_t last) {
  const Event& h = events_[last];
  for (const int s : open_) {
    const StepState& ss = steps_[static_cast<std::size_t>(s)];
    const PlanStep& step = plan_.steps[static_cast<std::size_t>(s)];
    FailedLiteral failed;
    auto f = Filter(s, &Action::over_all, Kind::kOverAll, h.t, "", &failed);
    if (!f) continue;
    const bool just_started = ss.start_ns == h.t_ns;
    const std::int32_t culprit = Culprit(failed, step.duration_s);
    const std::string what = absl::StrCat(KindName(Kind::kOverAll), " ", f->condition);
    const Event* other = culprit >= 0 ? &events_[static_cast<std::size_t>(culprit)] : nullptr;
    if (other != nullptr && other->IsStep() && other->index == s) other = nullptr;  // its own start
    if (just_started) f->time_s = step.start_s;
    if (other != nullptr) {
      f->time_s = other->t;
      f->reason =
          just_started
              ? absl::StrCat(what,
                             " is false just after the action starts: ", DescribeEvent(*other),
                             ", in the same happening, breaks it")
              : absl::StrCat(what, " of the running action is broken by ", DescribeEvent(*other));
      if (other->IsStep()) {
        f->other_step_index = other->index;
        f->other_action = plan_.steps[static_cast<std::size_t>(other->index)].DisplayName();
      }
    } else if (just_started) {
      f->reason =
          absl::StrCat(what, " ", WhyFalse(failed.literal),
                       culprit >= 0 ? " just after the action starts (its own start effects "
                                      "break it)"
                                    : " just after the action starts (invariants hold on "
                                      "the open interval)");
    } else {
      f->reason = absl::StrCat(what, " ", WhyFalse(failed.literal),
                               " after the happening at t=", Secs(h.t));
    }
    return f;
  }
  return std::nullopt;
}

std::optional<ValidationFailure> Run::Start(const Event& e) {
  const int s = e.index;
  StepState& ss = steps_[static_cast<std::size_t>(s)];
  const auto& cands = candidates_[static_cast<std::size_t>(s)];
  const PlanStep& step = plan_.steps[static_cast<std::size_t>(s)];
  const bool durative = action(cands.front()).is_durative;
  // At-start conditions, then duration constraints (both in the state before the start).
  if (auto f = Filter(s, &Action::at_start, Kind::kAtStart, e.t,
                      durative ? "when the action starts" : "when the action happens")) {
    return f;
  }
  std::optional<ValidationFailure> duration_failure;
  bool any = false;
  for (std::size_t v = 0; v < cands.size(); ++v) {
    if (!ss.alive[v]) continue;
    const Action& a = action(cands[v]);
    for (const auto& dc : a.duration) {
      const auto value = dc.value.Evaluate(state_.values);
      const bool ok = value && DurationOk(step.duration_s, dc.comparator, *value,
                                          options_.duration_tolerance_s);
      if (ok) continue;
      ss.alive[v] = 0;
      if (!duration_failure) {
        ValidationFailure f = StepFailure(Kind::kDuration, e.t, s);
        f.condition = absl::StrCat("(", task::ComparatorSymbol(dc.comparator), " ?duration ",
                                   task::ToString(dc.value, task_), ")");
        f.reason = value ? absl::StrCat("duration ", Secs(step.duration_s), " violates ",
                                        f.condition, ": the value at start is ", Secs(*value),
                                        " (tolerance ", Secs(options_.duration_tolerance_s), " s)")
                         : absl::StrCat("the duration constraint ", f.condition,
                                        " reads an undefined value at start");
        duration_failure = std::move(f);
      }
      break;
    }
    if (ss.alive[v]) any = true;
  }
  if (!any) return duration_failure;

  for (std::size_t v = 0; v < cands.size(); ++v) {
    if (ss.alive[v]) {
      ss.effects_from = cands[v];
      break;
    }
  }
  const Action& a = action(ss.effects_from);
  // End effects whose condition is decided at start.
  ss.end_cond_fired.assign(a.end_effects.conditional.size(), 0);
  for (std::size_t i = 0; i < a.end_effects.conditional.size(); ++i) {
    const auto& ce = a.end_effects.conditional[i];
    if (ce.condition_time == task::TimePoint::kStart) {
      ss.end_cond_fired[i] = !FirstFailing(ce.condition, state_, step.duration_s).has_value();
    }
  }
  if (auto err = Apply(a.start_effects, task::TimePoint::kStart, nullptr, step.duration_s)) {
    ValidationFailure f = StepFailure(Kind::kEffect, e.t, s);
    f.reason = *err;
    return f;
  }
  // The invariant is checked after the whole happening (CheckInvariants).
  if (durative) open_.push_back(s);
  return std::nullopt;
}

std::optional<ValidationFailure> Run::End(const Event& e) {
  const int s = e.index;
  StepState& ss = steps_[static_cast<std::size_t>(s)];
  const PlanStep& step = plan_.steps[static_cast<std::size_t>(s)];
  open_.erase(std::find(open_.begin(), open_.end(), s));
  if (auto f = Filter(s, &Action::at_end, Kind::kAtEnd, e.t, "when the action ends")) return f;
  const Action& a = action(ss.effects_from);
  if (auto err = Apply(a.end_effects, task::TimePoint::kEnd, &ss.end_cond_fired, step.duration_s)) {
    ValidationFailure f = StepFailure(Kind::kEffect, e.t, s);
    f.reason = *err;
    return f;
  }
  return std::nullopt;
}

ValidationResult Run::Execute() {
  result_.action_count = plan_.steps.size();
  if (auto f = CheckStructure()) return Fail(std::move(*f));

  // Events.
  steps_.resize(plan_.steps.size());
  events_.reserve(plan_.steps.size() * 2 + task_.timed_literals.size() +
                  task_.timed_fluents.size());
  for (std::size_t i = 0; i < plan_.steps.size(); ++i) {
    const PlanStep& step = plan_.steps[i];
    StepState& ss = steps_[i];
    ss.alive.assign(candidates_[i].size(), 1);
    ss.start_ns = ToNs(step.start_s);
    ss.end_ns = ToNs(step.start_s + step.duration_s);
    result_.makespan_s = std::max(result_.makespan_s, step.start_s + step.duration_s);
    const auto index = static_cast<std::int32_t>(i);
    events_.push_back({ss.start_ns, step.start_s, EventKind::kStart, index});
    if (action(candidates_[i].front()).is_durative) {
      events_.push_back({ss.end_ns, step.start_s + step.duration_s, EventKind::kEnd, index});
    }
  }
  for (std::size_t i = 0; i < task_.timed_literals.size(); ++i) {
    const double t = task_.timed_literals[i].time_s;
    events_.push_back({ToNs(t), t, EventKind::kTimedLiteral, static_cast<std::int32_t>(i)});
  }
  for (std::size_t i = 0; i < task_.timed_fluents.size(); ++i) {
    const double t = task_.timed_fluents[i].time_s;
    events_.push_back({ToNs(t), t, EventKind::kTimedFluent, static_cast<std::int32_t>(i)});
  }
  std::sort(events_.begin(), events_.end(), [](const Event& x, const Event& y) {
    if (x.t_ns != y.t_ns) return x.t_ns < y.t_ns;
    if (x.kind != y.kind) return x.kind < y.kind;
    return x.index < y.index;
  });
  footprint_of_event_.assign(events_.size(), -1);

  // Initial state.
  state_.facts.assign(task_.facts.size(), 0);
  for (FactId f : task_.initial_facts) state_.facts[static_cast<std::size_t>(f)] = 1;
  state_.values = task_.initial_values;
  state_.values.resize(task_.numeric_vars.size(), task::NumericExpr::kUndefined);

  double last_event_s = 0.0;
  for (std::size_t i = 0; i < events_.size(); ++i) {
    const Event& e = events_[i];
    last_event_s = e.t;
    if (i == 0 || events_[i - 1].t_ns != e.t_ns) changes_.clear();  // a new happening
    current_event_ = static_cast<std::int32_t>(i);
    if (auto f = CheckMutex(i)) return Fail(std::move(*f));
    switch (e.kind) {
      case EventKind::kStart:
        if (auto f = Start(e)) return Fail(std::move(*f));
        break;
      case EventKind::kEnd:
        if (auto f = End(e)) return Fail(std::move(*f));
        break;
      case EventKind::kTimedLiteral: {
        const auto& til = task_.timed_literals[static_cast<std::size_t>(e.index)];
        SetFact(til.fact, til.value ? 1 : 0);
        break;
      }
      case EventKind::kTimedFluent: {
        const auto& tif = task_.timed_fluents[static_cast<std::size_t>(e.index)];
        SetValue(tif.var, tif.value);
        break;
      }
    }
    // Once the whole happening is applied, the state it leaves holds until
    // the next one: every step open in it needs its invariant there.
    if (i + 1 == events_.size() || events_[i + 1].t_ns != e.t_ns) {
      if (auto f = CheckInvariants(i)) return Fail(std::move(*f));
    }
  }

  // Goal after the last event.
  if (const auto failing = FirstFailing(task_.goal, state_, task::NumericExpr::kUndefined)) {
    ValidationFailure f;
    f.kind = Kind::kGoal;
    f.time_s = last_event_s;
    f.condition = DescribeLiteral(task_, task_.goal, *failing);
    f.reason = absl::StrCat("goal ", f.condition, " ", WhyFalse(*failing), " after the last event");
    return Fail(std::move(f));
  }

  result_.valid = true;
  if (task_.metric.expression.nodes.empty()) {
    result_.metric_value = result_.makespan_s;
  } else {
    result_.metric_value = task_.metric.expression.Evaluate(
        state_.values, task::NumericExpr::kUndefined, result_.makespan_s);
  }
  return result_;
}

ValidationResult InvalidOptions(const absl::Status& status, const Plan& plan) {
  ValidationResult r;
  r.action_count = plan.steps.size();
  ValidationFailure f;
  f.kind = Kind::kInvalidOptions;
  f.reason = std::string(status.message());
  r.first_failure = std::move(f);
  return r;
}

}  // namespace

const char* KindName(ValidationFailure::Kind kind) {
  switch (kind) {
    case Kind::kInvalidOptions:
      return "invalid options";
    case Kind::kUnknownAction:
      return "unknown action";
    case Kind::kBadStep:
      return "bad step";
    case Kind::kDuration:
      return "duration constraint";
    case Kind::kAtStart:
      return "at-start condition";
    case Kind::kOverAll:
      return "over-all condition";
    case Kind::kAtEnd:
      return "at-end condition";
    case Kind::kEffect:
      return "effect";
    case Kind::kMutex:
      return "mutex";
    case Kind::kGoal:
      return "goal";
  }
  return "?";
}

absl::Status ValidationOptions::Validate() const {
  if (!std::isfinite(epsilon_s) || epsilon_s < 0.0 || epsilon_s > 60.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("epsilon_s must be in [0, 60] s, got ", epsilon_s));
  }
  if (!std::isfinite(duration_tolerance_s) || duration_tolerance_s < 0.0 ||
      duration_tolerance_s > 60.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("duration_tolerance_s must be in [0, 60] s, got ", duration_tolerance_s));
  }
  return absl::OkStatus();
}

std::string ValidationResult::ToString() const {
  if (valid) {
    std::string out =
        absl::StrCat("valid plan: ", action_count, " actions, makespan ", Secs(makespan_s), " s");
    if (metric_value) absl::StrAppend(&out, ", metric ", Secs(*metric_value));
    return out;
  }
  if (!first_failure) return "invalid plan";
  const ValidationFailure& f = *first_failure;
  std::string out = absl::StrCat("invalid plan: ", KindName(f.kind), " at t=", Secs(f.time_s));
  if (f.step_index >= 0) absl::StrAppend(&out, ", step ", f.step_index, " ", f.action);
  absl::StrAppend(&out, ": ", f.reason);
  return out;
}

Validator::Validator(std::shared_ptr<const task::GroundTask> task, ValidationOptions options)
    : task_(std::move(task)),
      options_(std::move(options)),
      index_(std::make_unique<const task::ActionIndex>(*task_)) {}

Validator::Validator(Validator&&) noexcept = default;
Validator& Validator::operator=(Validator&&) noexcept = default;
Validator::~Validator() = default;

absl::StatusOr<Validator> Validator::Create(std::shared_ptr<const task::GroundTask> task,
                                            ValidationOptions options) {
  if (task == nullptr) return absl::InvalidArgumentError("Validator needs a ground task");
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  return Validator(std::move(task), std::move(options));
}

ValidationResult Validator::Validate(const Plan& plan) const {
  StepCandidates candidates(plan.steps.size());
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    candidates[i] = index_->Find(plan.steps[i].name, plan.steps[i].args);
  }
  return Run(*task_, plan, options_, candidates).Execute();
}

ValidationResult ValidatePlan(const task::GroundTask& task, const Plan& plan,
                              const ValidationOptions& options) {
  if (const absl::Status s = options.Validate(); !s.ok()) return InvalidOptions(s, plan);
  // One pass over the task's actions, comparing names first: cheaper than
  // building a full index for a single plan.
  std::vector<std::string> names(plan.steps.size());
  std::vector<std::vector<std::string>> args(plan.steps.size());
  absl::flat_hash_map<std::string_view, std::vector<std::size_t>> steps_by_name;
  for (std::size_t i = 0; i < plan.steps.size(); ++i) {
    names[i] = absl::AsciiStrToLower(plan.steps[i].name);
    for (const auto& arg : plan.steps[i].args) args[i].push_back(absl::AsciiStrToLower(arg));
  }
  for (std::size_t i = 0; i < plan.steps.size(); ++i) steps_by_name[names[i]].push_back(i);
  StepCandidates candidates(plan.steps.size());
  for (std::size_t a = 0; a < task.actions.size(); ++a) {
    const auto it = steps_by_name.find(task.actions[a].name);
    if (it == steps_by_name.end()) continue;
    for (const std::size_t s : it->second) {
      if (args[s] == task.actions[a].args) candidates[s].push_back(static_cast<ActionId>(a));
    }
  }
  return Run(task, plan, options, candidates).Execute();
}

MissingActionExplainer ExplainerFor(const task::LoadResult& loaded) {
  if (loaded.domain == nullptr || loaded.problem == nullptr) return {};
  return [domain = loaded.domain, problem = loaded.problem, task = loaded.task](
             std::string_view name, std::span<const std::string> args) {
    return task::ExplainMissingAction(*domain, *problem, name, args, task.get());
  };
}

}  // namespace seaplan::validate
