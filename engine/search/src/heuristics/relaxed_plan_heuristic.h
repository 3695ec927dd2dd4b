// FF-style relaxed-plan heuristic on the snap-action compilation, with
// Metric-FF interval relaxation of numeric fluents.
//
// Relaxed operators: start(a) needs a's at-start and over-all conditions and
// adds its start effects plus a virtual fact started(a); end(a) needs
// started(a), a's at-end and over-all conditions and adds its end effects.
// Running actions have started(a) at layer 0, facts of future timed literals
// are free. Deletes and negative conditions are ignored; numeric variables
// become intervals that only widen (each applicable operator widens once per
// layer). The value is the number of snap operators in the extracted relaxed
// plan plus the ends of running actions it does not contain; helpful
// (preferred) events are the plan's operators applicable in the state.
//
// Not thread-safe: one instance per search (scratch arrays are reused, so an
// evaluation allocates nothing once warmed up).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../snap_task.h"
#include "../state_registry.h"
#include "../timeline.h"

namespace seaplan::search {

class RelaxedPlanHeuristic {
 public:
  static constexpr int kDeadEnd = 1 << 30;

  RelaxedPlanHeuristic(const SnapTask& task, double epsilon_s);

  // Returns the estimate (kDeadEnd when the goal is relaxed-unreachable).
  // `preferred` (may be null) receives the helpful snaps (SnapIds).
  // `window_slack`: for each running window action of `state` (in running
  // order, SnapTask::IsWindowAction), the room left before its end must
  // happen. A fact such an action's end will delete counts as unavailable
  // when nothing needing it over all fits into that room (match cellar:
  // a burning match too short for another mend).
  int Evaluate(const StateData& state, std::vector<SnapId>* preferred,
               std::span<const double> window_slack = {});
  // After a kDeadEnd: true when the relaxation proves it (false when the
  // numeric fixpoint was cut off after too many widening layers).
  bool last_dead_end_proven() const { return dead_end_proven_; }

 private:
  struct Interval {
    double lo, hi;
  };
  Interval EvalInterval(const task::NumericExpr& expr, const StateData& state, task::ActionId a);
  bool Satisfiable(const task::NumericCondition& c, const StateData& state, task::ActionId a);
  void MarkOp(int op);
  void MarkFact(int fact);
  void MarkNumeric(const task::NumericCondition& c, int layer);

  const SnapTask& task_;
  bool dead_end_proven_ = true;
  int num_facts_;    // real facts; started(a) is num_facts_ + a
  int num_ops_;      // 2 * actions
  // CSR tables.
  std::vector<std::int32_t> pre_begin_, pre_;
  std::vector<std::int32_t> add_begin_, add_;
  std::vector<std::int32_t> fact_ops_begin_, fact_ops_;
  std::vector<std::vector<const task::NumericCondition*>> num_pre_;
  std::vector<std::vector<const task::NumericEffect*>> num_eff_;
  std::vector<bool> op_exists_;
  std::vector<std::int32_t> no_pre_ops_;
  std::vector<std::uint8_t> has_num_pre_, has_num_eff_;  // compact copies for the hot loop
  double epsilon_s_;
  std::vector<std::vector<task::FactId>> window_facts_;  // per action: start adds deleted at end
  std::vector<double> min_invariant_duration_;           // per fact: shortest action needing it over all
  std::vector<std::uint8_t> suppressed_;
  std::vector<std::int32_t> suppressed_list_;
  // (suppressed fact, end operator of a running action exempted from it).
  std::vector<std::pair<std::int32_t, std::int32_t>> exempt_ends_;
  void ExemptRunningEnds(const StateData& state);
  void PayBackExemptEnds(int fact);
  bool IsExemptEnd(int fact, int op) const;
  std::vector<bool> til_fact_;  // scratch: facts added by pending literals
  // Static per-task tables hoisted out of Evaluate: the initial "missing
  // preconditions" counter of every operator (copied in one pass) and a
  // goal flag per fact, so reaching the goal is a counter, not a scan of
  // the goal per layer.
  std::vector<std::int32_t> op_missing_init_;
  std::vector<std::uint8_t> goal_fact_;
  int num_goal_facts_ = 0;

  // Scratch per evaluation.
  std::vector<std::int32_t> fact_layer_, fact_achiever_;
  std::vector<std::int32_t> op_layer_, op_missing_;
  std::vector<Interval> interval_, next_interval_;
  std::vector<std::int32_t> var_changer_, var_change_layer_;
  std::vector<std::int32_t> applicable_, numeric_waiting_, new_facts_, layer_ops_;
  std::vector<std::uint8_t> op_marked_, fact_marked_;
  std::vector<std::int32_t> marked_ops_, marked_facts_, stack_;
  std::vector<Interval> eval_stack_;
};

}  // namespace seaplan::search
