// The snap-action view of a GroundTask (internal to the search).
//
// Every durative action a becomes two snap actions: start(a) = 2a and
// end(a) = 2a + 1 (instantaneous actions only use 2a). Timed initial
// literals are extra events the search applies in time order. For each snap
// the read and write sets (facts and numeric variables) drive the
// interference orderings of the schedule: a later event that writes what an
// earlier one reads or writes, or reads what it writes, is ordered at least
// epsilon after it (VAL's mutex rule). Over-all conditions are NOT reads of
// either snap (PDDL 2.1 / VAL: they hold on the open interval and take no
// part in the mutex rule); they are kept in inv_reads / inv_num_reads so the
// schedule can order their achiever at or before the start and any later
// change at or after the end, with zero gaps.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "invariant_envelopes.h"
#include "seaplan/task/ground_task.h"

namespace seaplan::search {

using SnapId = std::int32_t;  // 2 * action (+1 for the end)

inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct SnapAction {
  task::ActionId action = -1;
  bool is_end = false;
  const task::Condition* condition = nullptr;  // at start / at end
  const task::Effects* effects = nullptr;
  std::vector<task::FactId> reads;             // sorted, unique
  std::vector<task::FactId> writes;            // sorted, unique
  std::vector<task::NumericVarId> num_reads;   // sorted, unique
  std::vector<task::NumericVarId> num_writes;  // sorted, unique
  // The action's over-all facts (positive and negative) and the variables
  // its over-all numeric conditions read; same on start and end snaps.
  std::vector<task::FactId> inv_reads;            // sorted, unique
  std::vector<task::NumericVarId> inv_num_reads;  // sorted, unique
};

struct TilEvent {
  double time_s = 0.0;
  std::vector<task::FactId> add, del;
  std::vector<std::pair<task::NumericVarId, double>> assign;
  std::vector<task::FactId> writes;            // sorted
  std::vector<task::NumericVarId> num_writes;  // sorted
};

class SnapTask {
 public:
  explicit SnapTask(const task::GroundTask& task);

  const task::GroundTask& task() const { return task_; }
  int num_actions() const { return static_cast<int>(task_.actions.size()); }
  int num_facts() const { return static_cast<int>(task_.facts.size()); }
  int num_vars() const { return static_cast<int>(task_.numeric_vars.size()); }
  const SnapAction& snap(SnapId id) const { return snaps_[static_cast<std::size_t>(id)]; }
  const std::vector<TilEvent>& tils() const { return tils_; }
  // TIL indices (ascending) that write each fact / variable.
  const std::vector<int>& TilsWritingFact(task::FactId f) const { return tils_by_fact_[f]; }
  const std::vector<int>& TilsWritingVar(task::NumericVarId v) const { return tils_by_var_[v]; }
  // True when any effect of the action reads ?duration (its duration is then fixed to one value).
  bool EffectsReadDuration(task::ActionId a) const { return effects_read_duration_[a]; }
  // True for "window" actions (envelopes like light-match or a work shift):
  // their end has conditions, or deletes what their start added, so the
  // latest time their end may happen matters to what can still run inside.
  bool IsWindowAction(task::ActionId a) const { return window_action_[a]; }
  // Facts (positive or negative in the goal) for the goal-after-TILs rule.
  const std::vector<bool>& goal_fact_mask() const { return goal_fact_mask_; }
  // Over-all envelopes (required concurrency); actions it finds
  // unschedulable are never started by the search nor used by heuristics.
  const InvariantEnvelopes& envelopes() const { return envelopes_; }
  // True for actions no plan needs (unschedulable, or irrelevant to the
  // goal: relevance.h) or can contain (they delete a goal fact nothing adds
  // back: GoalBreakingActions): never started by the search nor used by
  // heuristics.
  bool Pruned(task::ActionId a) const { return pruned_[static_cast<std::size_t>(a)]; }
  // True for durative actions whose end only adds facts, has no at-end
  // condition, and adds nothing that a condition asks false, a timed
  // literal writes or an event deletes without requiring it (a hoist's
  // lift, whose end frees the area it lifted from). Applying such an end as
  // soon as it can happen loses no plan when, besides, its facts are false
  // from the action's start to its end (no event can then need or delete
  // them in between): the search may apply it at once and branch on
  // nothing else (SearchParams::eager_ends). The schedule orders events
  // by what they read and write, not by their place in the path: the early
  // end orders after it only the later events touching what it adds,
  // which under that condition had to wait for it anyway.
  bool EagerEnd(task::ActionId a) const { return eager_end_[static_cast<std::size_t>(a)]; }
  // How many of the pruned actions break the goal for good.
  int num_goal_breaking() const { return num_goal_breaking_; }

 private:
  const task::GroundTask& task_;
  std::vector<SnapAction> snaps_;
  std::vector<TilEvent> tils_;
  std::vector<std::vector<int>> tils_by_fact_;
  std::vector<std::vector<int>> tils_by_var_;
  std::vector<bool> effects_read_duration_;
  std::vector<bool> goal_fact_mask_;
  std::vector<bool> window_action_;
  InvariantEnvelopes envelopes_;
  std::vector<bool> pruned_;
  std::vector<bool> eager_end_;
  int num_goal_breaking_ = 0;
};

}  // namespace seaplan::search
