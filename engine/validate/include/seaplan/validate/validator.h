// The temporal plan validator: does a plan solve a ground task under PDDL 2.1
// semantics, and if not, what is the first thing that goes wrong?
//
//   validate::Validator validator = *validate::Validator::Create(task);
//   validate::ValidationResult r = validator.Validate(plan);
//   if (!r.valid) log::Warn("{}", r.ToString());
//
// Semantics (PDDL 2.1 level 3, Fox & Long 2003, as VAL implements it):
//   - A durative step (t, a, d) is a start snap action at t (conditions: the
//     at-start ones; effects: the start effects), an end snap action at t+d
//     (the at-end conditions and end effects) and an invariant (the over-all
//     conditions) on the open interval (t, t+d). An instantaneous step is one
//     event at t. Timed initial literals and fluents are events at their
//     absolute times. Events at the same time (same nanosecond, see below)
//     form one happening. Events are processed in time order; each event's
//     conditions are checked in the state just before it and its effects are
//     computed from that state too (the mutex rule below makes this the same
//     as applying a happening's events simultaneously).
//   - At-start conditions and duration constraints (`?duration op value`,
//     value evaluated in the state before the start) are checked at the start;
//     at-end conditions at the end, before the end effects.
//   - Over-all conditions must hold in every state strictly inside (t, t+d):
//     they are checked in the state after each happening from the one at t
//     (after ALL its events, so another event at exactly t may add the
//     invariant, and one that deletes it fails it) up to, not including, the
//     one at t+d. They are not needed in the state before t nor after the
//     happening at t+d: an event at exactly t+d may delete them, one at
//     t+d - 0.0005 may not (it is inside the interval).
//   - Effects of one event: all numeric operands are evaluated in the state
//     before the event, then deletes are applied, then adds, then numeric
//     updates. An action that adds and deletes the same fact leaves it TRUE
//     ("add wins", VAL's EffectsRecord::enact order). ?duration may be read in
//     effects. Conditional effects fire when their condition holds at their
//     condition time (at start or at end, in the state before that event).
//   - Mutual exclusion: two events of different steps (or a step and a timed
//     literal) closer than `epsilon_s` (including exactly simultaneous ones)
//     must not interfere. They interfere when one adds a fact the other
//     deletes, when one changes (adds/deletes) a fact the other reads, when
//     one changes a numeric variable the other reads, or when one assigns or
//     scales a variable the other also updates. Two increase/decrease effects
//     on the same variable commute and do not interfere; two adds (or two
//     deletes) of the same fact do not interfere (VAL's Ownership rules).
//     What an event "reads": its own conditions (at start or at end), the
//     variables its numeric effects and duration constraints read, and its
//     conditional-effect conditions. Over-all conditions are part of neither
//     snap action (VAL's Ownership only marks a happening's start/end actions'
//     conditions and effects), so they take no part in the mutex rule: an
//     event may change an invariant's fact at or within epsilon of the
//     interval's ends, and the invariant rule above alone decides whether
//     that is valid. A step never interferes with itself.
//     DNF variants of one (name, args) count with the union of what they touch.
//     Two timed literals are never checked against each other (the task's
//     own business). A violation is reported at the earlier event's time.
//   - DNF variants (Action::variant): a step is fine while at least one of
//     its variants has had all its conditions hold so far; effects come from
//     the first variant alive at the start (variants share effects).
//   - Undefined numeric values: a comparison reading one is false; an
//     increase/decrease/scale of one, or a division by zero, fails the event
//     (kind kEffect).
//   - The goal must hold after the last event (including every timed literal,
//     also those after the last action).
//   - Event times are ordered on a 1 ns grid (rounded to whole nanoseconds:
//     "the same time" and "strictly inside" are exact and transitive).
//     Separations are compared with epsilon on the real times less a slack of
//     1 ns (plus 1e-15 of the time), so "0.001 apart" computed or parsed in
//     floating point (0.000999999999999) counts as epsilon.
//   - A durative step needs a duration of at least 1 ns (PDDL 2.1: start and
//     end are distinct happenings); an instantaneous step must have none.
//
// Which failure is "first": structural problems (a step that names no ground
// action, a negative or missing duration, a negative start time) are reported
// first, in step order, before anything is simulated. Otherwise the failure
// is the first event, in time order, at which something fails; at one event
// the mutex check comes before the event's own conditions (a missing
// separation is the more basic fault than the condition it then breaks).
// Invariants are checked once the whole happening has been applied, so a
// failure of an event in the happening comes before an over-all failure
// there; an over-all failure names the event of the happening that made the
// condition false (other_step_index), when there is one.
//
// Cost: mapping steps to actions is done once per plan (Validator: hash
// lookups in an index built once per task; ValidatePlan: one pass over the
// task's actions). Simulation is O(events * (open steps + epsilon
// neighbours)) with no string work unless a failure is formatted.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "seaplan/common/status.h"
#include "seaplan/task/ground_task.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/plan.h"

namespace seaplan::validate {

// Says in one sentence why (name args) is not a ground action of the task.
using MissingActionExplainer =
    std::function<std::string(std::string_view name, std::span<const std::string> args)>;

struct ValidationOptions {
  // Minimum separation of interfering events (PDDL 2.1 epsilon), seconds.
  // Events closer than this that interfere make the plan invalid. Default
  // 0.001: the separation the project's planner uses (the paper's plans used
  // 0.2, VAL's default tolerance is 0.01). 0 still forbids interfering events
  // at exactly the same time.
  double epsilon_s = 0.001;
  // How far a step's duration may be from a duration constraint's value,
  // seconds (|d - v| <= tol for '=', d <= v + tol for '<=', d >= v - tol for
  // '>='; strict '<' and '>' are exact). Default 0.001 accepts durations
  // printed with 3 decimals (OPTIC, POPF); the project's own plans print
  // exactly (FormatPlan), so 0 works for them. A rounded duration is still
  // taken as printed for the end time, like VAL.
  double duration_tolerance_s = 0.001;
  // Optional: explains steps that name no ground action (e.g.
  // task::ExplainMissingAction bound to the parsed domain and problem; see
  // ExplainerFor). Without it the validator says what it can from the task.
  MissingActionExplainer explain_missing_action;

  absl::Status Validate() const;
};

struct ValidationFailure {
  enum class Kind : std::uint8_t {
    kInvalidOptions,  // ValidationOptions::Validate() failed (reason says why)
    kUnknownAction,   // the step names no ground action
    kBadStep,         // negative/non-finite time, bad or missing duration
    kDuration,        // a duration constraint is violated
    kAtStart,         // an at-start condition (or an instantaneous action's precondition)
    kOverAll,         // an over-all condition on the open interval
    kAtEnd,           // an at-end condition
    kEffect,          // a numeric effect reads or produces an undefined value
    kMutex,           // two interfering events closer than epsilon
    kGoal,            // the goal does not hold after the last event
  };
  Kind kind = Kind::kAtStart;
  double time_s = 0.0;    // when it fails (the event's time)
  int step_index = -1;    // index into Plan::steps; -1 for the goal or a timed literal
  std::string action;     // "(name args)" of that step, "" for the goal
  std::string condition;  // the failing literal/comparison, or the contested fact/variable
  std::string reason;     // one sentence for a user
  // kMutex and over-all failures caused by another event: the other side
  // (-1 / "" when it is a timed literal or there is none).
  int other_step_index = -1;
  std::string other_action;
};

const char* KindName(ValidationFailure::Kind kind);  // "at-start condition", ...

struct ValidationResult {
  bool valid = false;
  std::optional<ValidationFailure> first_failure;  // set iff !valid
  double makespan_s = 0.0;                         // latest step end (0 for an empty plan)
  std::size_t action_count = 0;                    // steps in the plan
  std::optional<double> metric_value;              // the task's metric, set iff valid and defined

  // "valid plan: 13 actions, makespan 2403.33733 s, metric 2403.33733" or
  // "invalid plan: t=60.2 step 1 (move-ship ship0 port-a port-b): duration
  // constraint (= ?duration 288.889) violated: ..."
  std::string ToString() const;
};

// Validates plans against one task; indexes the task's actions once.
// Immutable after Create; Validate is const and thread-safe.
class Validator {
 public:
  // InvalidArgument for bad options or a null task.
  static absl::StatusOr<Validator> Create(std::shared_ptr<const task::GroundTask> task,
                                          ValidationOptions options = {});

  ValidationResult Validate(const Plan& plan) const;

  const task::GroundTask& task() const { return *task_; }
  const ValidationOptions& options() const { return options_; }

  Validator(Validator&&) noexcept;
  Validator& operator=(Validator&&) noexcept;
  Validator(const Validator&) = delete;
  Validator& operator=(const Validator&) = delete;
  ~Validator();

 private:
  Validator(std::shared_ptr<const task::GroundTask> task, ValidationOptions options);

  std::shared_ptr<const task::GroundTask> task_;
  ValidationOptions options_;
  std::unique_ptr<const task::ActionIndex> index_;
};

// One-shot validation (no index kept; maps the steps with one pass over the
// task's actions). Invalid options give an invalid result of kind kInvalidOptions.
ValidationResult ValidatePlan(const task::GroundTask& task, const Plan& plan,
                              const ValidationOptions& options = {});

// An explainer backed by the grounder's task::ExplainMissingAction on the
// parsed domain and problem kept in `loaded` (empty function when they are
// absent). Holds shared ownership of them.
MissingActionExplainer ExplainerFor(const task::LoadResult& loaded);

}  // namespace seaplan::validate
