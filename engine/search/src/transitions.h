// State semantics of snap actions: which events apply in a state and what
// state they lead to (the successor generator of the search).
//
// Start of a: at-start conditions hold, the duration constraints (evaluated
// in the state) leave a non-empty window, a is not already running, the
// concurrency bound is respected; after the start effects the over-all
// conditions of a and of every running action hold. End of a running a:
// at-end and over-all conditions hold; after the end effects the invariants
// of the other running actions hold. Timed literals apply in time order.
// Effects of one event read the state before it (deletes, then adds).
//
// A start is also refused when it would run beside an action whose end and
// its own end each surely delete a fact the other needs over all (a hoist's
// crate dropped and loaded at once: either end deletes the lifting the
// other needs; InvariantEnvelopes::MustEndWithin both ways). Neither could
// ever end first, so every state below is a dead end the delete relaxation
// does not see. No plan this search can build holds such a pair (its events
// are apart, so the two ends cannot happen at one instant).
#pragma once

#include <cstdint>
#include <vector>

#include "snap_task.h"
#include "state_registry.h"
#include "timeline.h"

namespace seaplan::search {

bool ConditionHolds(const task::Condition& condition, const StateData& state,
                    double duration = task::NumericExpr::kUndefined);

class Transitions {
 public:
  Transitions(const SnapTask& task, int max_concurrent_actions, double epsilon_s);

  // Appends the events whose preconditions hold in `state` (starts, ends of
  // running actions, the next timed literal); Apply may still reject them.
  void Candidates(const StateData& state, std::vector<Event>* out) const;
  // Applies `event` (as produced by Candidates) to `state`. Returns false if
  // it is not applicable; `next` is scratch then. Fills the duration bounds
  // of `event` for starts.
  bool Apply(const StateData& state, Event* event, StateData* next) const;
  bool IsGoal(const StateData& state) const;

 private:
  bool DurationWindow(task::ActionId a, const StateData& state, double* min_d, double* max_d) const;
  void ApplyEffects(const task::Effects& effects, const StateData& before, double duration,
                    StateData* next) const;
  bool RunningInvariantsHold(const StateData& state) const;

  const SnapTask& task_;
  int max_concurrent_;
  double epsilon_s_;
  // Starts indexed by the facts that must hold before them: under the most
  // selective one (the key: the fewest starts need it), then in groups by
  // a second such fact, so that a state skips a group whose second fact is
  // false with one test (driverlog: a truck's drives by each of 14 drivers
  // are 14 groups under the truck's place, of which one has its driver
  // aboard). Groups of key f: key_groups_[key_group_begin_[f] ..
  // key_group_begin_[f + 1]); a group's starts: group_actions_[begin ..
  // end), ascending.
  struct StartGroup {
    task::FactId second;  // -1: none (the key is the start's only such fact)
    std::int32_t begin, end;
  };
  std::vector<std::int32_t> key_group_begin_;
  std::vector<StartGroup> key_groups_;
  std::vector<task::ActionId> group_actions_;
  std::vector<task::ActionId> without_fact_pre_;
  mutable std::vector<double> scratch_values_;
};

}  // namespace seaplan::search
