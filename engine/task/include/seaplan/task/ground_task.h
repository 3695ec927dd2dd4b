// The ground temporal task: what every planner component, heuristic and the
// validator read, the same way (Fast Downward's lesson). It is produced by the
// grounder (seaplan/task/grounder.h) from a parsed PDDL domain and problem and
// never refers back to parser structures.
//
// Shape:
//   - facts: ground atoms that can change (static atoms are folded away);
//   - numeric variables: ground fluents that can change (static fluents are
//     folded into constants inside expressions);
//   - actions: durative actions (instantaneous PDDL actions have
//     `is_durative == false`, zero duration and only start parts), each with
//     conjunctive at-start / over-all / at-end conditions and start / end
//     effects. Disjunctive conditions are compiled into several ground
//     actions with the same name and arguments (`variant` tells them apart);
//   - timed initial literals, the goal and the metric.
//
// All ids are dense indices into the vectors below. A GroundTask is an
// immutable value once built; share it as std::shared_ptr<const GroundTask>.
// Being immutable, it may be read from any number of threads at once.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace seaplan::task {

using FactId = std::int32_t;        // index into GroundTask::facts
using NumericVarId = std::int32_t;  // index into GroundTask::numeric_vars
using ActionId = std::int32_t;      // index into GroundTask::actions

enum class Comparator : std::uint8_t { kLess, kLessEqual, kEqual, kGreaterEqual, kGreater };

// A numeric expression as a flat tree: children precede parents, the root is
// the last node. Kept flat so it copies cheaply and evaluates without
// recursion or allocation.
struct NumericExpr {
  enum class Op : std::uint8_t {
    kConstant,   // value
    kVariable,   // var
    kDuration,   // ?duration of the enclosing action
    kTotalTime,  // total-time (metrics only)
    kAdd,        // lhs + rhs
    kSub,        // lhs - rhs
    kMul,        // lhs * rhs
    kDiv,        // lhs / rhs
    kNeg,        // -lhs
  };
  struct Node {
    Op op = Op::kConstant;
    double value = 0.0;     // kConstant
    NumericVarId var = -1;  // kVariable
    std::int32_t lhs = -1;  // child node index
    std::int32_t rhs = -1;  // child node index
  };
  std::vector<Node> nodes;

  static NumericExpr Constant(double value);
  static NumericExpr Variable(NumericVarId var);

  // True when the expression has a single constant node.
  bool IsConstant() const { return nodes.size() == 1 && nodes[0].op == Op::kConstant; }
  // True when no node reads a variable, ?duration or total-time.
  bool IsGround() const;
  // Value of a constant expression (CHECKs IsConstant()).
  double ConstantValue() const;
  // Evaluates with `values` indexed by NumericVarId. Returns nullopt when a
  // variable read is undefined (NaN), when dividing by zero, or when a
  // ?duration/total-time node is read and the corresponding argument is NaN.
  std::optional<double> Evaluate(std::span<const double> values, double duration = kUndefined,
                                 double total_time = kUndefined) const;
  // The variables this expression reads, in node order (may repeat).
  std::vector<NumericVarId> Variables() const;
  bool ReadsDuration() const;

  static constexpr double kUndefined = __builtin_nan("");
};

// lhs `comparator` rhs.
struct NumericCondition {
  NumericExpr lhs;
  Comparator comparator = Comparator::kGreaterEqual;
  NumericExpr rhs;
};

// A conjunction of fact literals and numeric comparisons.
struct Condition {
  std::vector<FactId> positive;
  std::vector<FactId> negative;
  std::vector<NumericCondition> numeric;

  bool empty() const { return positive.empty() && negative.empty() && numeric.empty(); }
};

enum class AssignOp : std::uint8_t { kAssign, kIncrease, kDecrease, kScaleUp, kScaleDown };

struct NumericEffect {
  NumericVarId var = -1;
  AssignOp op = AssignOp::kAssign;
  NumericExpr value;  // may read ?duration
};

enum class TimePoint : std::uint8_t { kStart, kEnd };

// `(when condition effect)`. For durative actions the condition is checked at
// `condition_time`; the effect happens at the time of the Effects it sits in.
struct ConditionalEffect {
  Condition condition;
  TimePoint condition_time = TimePoint::kStart;
  std::vector<FactId> add;
  std::vector<FactId> del;
  std::vector<NumericEffect> numeric;
};

struct Effects {
  std::vector<FactId> add;
  std::vector<FactId> del;
  std::vector<NumericEffect> numeric;
  std::vector<ConditionalEffect> conditional;

  bool empty() const {
    return add.empty() && del.empty() && numeric.empty() && conditional.empty();
  }
};

// ?duration `comparator` value, with value evaluated in the state at start.
struct DurationConstraint {
  Comparator comparator = Comparator::kEqual;
  NumericExpr value;
};

struct Action {
  std::string name;               // schema name, lower case
  std::vector<std::string> args;  // object names, lower case
  int variant = 0;                // > 0 for extra DNF copies of one (name, args)
  bool is_durative = true;

  // Empty means any duration >= 0 (durative) or exactly 0 (instantaneous).
  std::vector<DurationConstraint> duration;
  Condition at_start;
  Condition over_all;
  Condition at_end;
  Effects start_effects;
  Effects end_effects;

  // "(name arg1 arg2)"
  std::string DisplayName() const;
  // The duration when every constraint is an equality to a constant; nullopt otherwise.
  std::optional<double> ConstantDuration() const;
};

struct Fact {
  std::string predicate;
  std::vector<std::string> args;
  std::string DisplayName() const;  // "(at ship0 port-a)"
};

struct NumericVar {
  std::string function;
  std::vector<std::string> args;
  std::string DisplayName() const;  // "(fuel ship0)"
};

// `(at time literal)` in :init.
struct TimedInitialLiteral {
  double time_s = 0.0;
  FactId fact = -1;
  bool value = true;  // true: becomes true; false: becomes false
};

// `(at time (= (f ...) v))` in :init (timed initial fluent; rarely used).
struct TimedInitialFluent {
  double time_s = 0.0;
  NumericVarId var = -1;
  double value = 0.0;
};

struct Metric {
  bool minimize = true;
  // Reads kTotalTime and/or numeric variables. Default: total-time.
  NumericExpr expression;
};

struct TaskSize {
  std::size_t facts = 0;
  std::size_t numeric_vars = 0;
  std::size_t actions = 0;
  std::size_t timed_literals = 0;
};

struct GroundTask {
  std::string domain_name;
  std::string problem_name;

  std::vector<Fact> facts;
  std::vector<NumericVar> numeric_vars;
  std::vector<Action> actions;

  std::vector<FactId> initial_facts;                // true at time 0; every other fact is false
  std::vector<double> initial_values;               // per NumericVarId; NaN when undefined
  std::vector<TimedInitialLiteral> timed_literals;  // sorted by time
  std::vector<TimedInitialFluent> timed_fluents;    // sorted by time

  Condition goal;
  Metric metric;

  TaskSize Size() const {
    return {facts.size(), numeric_vars.size(), actions.size(), timed_literals.size()};
  }
};

// Helpers shared by the search, the validator and the tools.
bool Compare(double lhs, Comparator comparator, double rhs);
const char* ComparatorSymbol(Comparator comparator);  // "<", "<=", "=", ">=", ">"
// Applies `op` to `current` with operand `value`.
double ApplyAssign(AssignOp op, double current, double value);
// Renders an expression for messages, naming variables from `task`.
std::string ToString(const NumericExpr& expr, const GroundTask& task);
std::string ToString(const NumericCondition& condition, const GroundTask& task);

}  // namespace seaplan::task
