// FF-style relaxed-plan heuristic on the snap-action compilation, with
// Metric-FF interval relaxation of numeric fluents.
//
// Relaxed operators: start(a) needs a's at-start and over-all conditions and
// adds its start effects plus a virtual fact started(a); end(a) needs
// started(a), a's at-end and over-all conditions and adds its end effects
// (the exploration waits only for started(a) and the at-end conditions:
// see Exploration::fact_ops).
// Running actions have started(a) at layer 0, facts of future timed literals
// are free. Deletes and negative conditions are ignored; numeric variables
// become intervals that only widen (each applicable operator widens once per
// layer). The value is the number of snap operators in the extracted relaxed
// plan plus the ends of running actions it does not contain; helpful
// (preferred) events are the plan's operators applicable in the state.
//
// Makespan-aware mode (SetMakespanAware; only in tasks with several agents,
// agent_loads.h): the exploration also times every operator (its
// preconditions' times and, for a start, its agents' ready times on the
// path's schedule, plus durations), and a fact gets, among its achievers
// reached before it is needed, the one that would finish first given the
// durations of the plan's actions already charged to its agents; goals are
// extracted one after another so that each sees the work given out before
// it. Otherwise the plan is FF's (first achiever of each fact).
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
#include "agent_loads.h"

namespace seaplan::search {

// Row i of a table in compressed rows: values[begin[i], begin[i + 1]).
inline std::span<const std::int32_t> CsrRow(const std::vector<std::int32_t>& values,
                                            const std::vector<std::int32_t>& begin, int i) {
  const auto b = static_cast<std::size_t>(begin[static_cast<std::size_t>(i)]);
  return {values.data() + b, static_cast<std::size_t>(begin[static_cast<std::size_t>(i) + 1]) - b};
}

class RelaxedPlanHeuristic {
 public:
  static constexpr int kDeadEnd = 1 << 30;

  RelaxedPlanHeuristic(const SnapTask& task, double epsilon_s);

  // Off by default. Ignored (stays off) in tasks with fewer than two
  // agents. The planner uses it only in bounded searches after its first
  // plan: spreading work makes plans shorter but can mislead the search
  // where the order of work matters more (floortile, depots).
  void SetMakespanAware(bool on);
  bool makespan_aware() const { return makespan_aware_; }
  // Off by default. On: where FF's first achiever of a fact gets there by
  // undoing a goal the evaluated state holds (a sheet turned face down on
  // its way out, a truck driven off its goal) and another operator of the
  // same layer does not, the relaxed plan takes the latter. The delete
  // relaxation cannot tell such a detour from the way on. And each goal
  // fact the state holds that the relaxed plan still deletes adds
  // kUndoneGoalCost: the plan must achieve it again. Without that cost a
  // relaxed plan that drives a truck off with a driver standing on his
  // goal looks one action from the goal, and the search stays on that
  // plateau (a generated driverlog, 11 drivers: 58,000 expansions at
  // h = 4). Ignored in the makespan-aware mode. The planner's second and
  // third first-plan searches use it.
  void SetKeepHeldGoals(bool on) { keep_held_goals_ = on; }
  // Off by default. On: an operator that undoes a goal the evaluated state
  // holds (however many) becomes applicable kGoalUndoerDelayLayers layers
  // after its conditions, so a way through fewer such operators is taken
  // even when it is longer. With generated driverlogshift instances (three trucks to
  // fetch, 120 s of walking), FF's plan drives a truck off its goal to fetch
  // the next one, the next driver never walks, and the search stays on that
  // plateau. An operator the state enables stays helpful. Ignored in the
  // makespan-aware mode. The planner's third first-plan search uses it.
  void SetDelayGoalUndoers(bool on) { delay_goal_undoers_ = on; }
  static constexpr int kGoalUndoerDelayLayers = 16;
  // At least one more action achieves an undone goal again: a start and an
  // end for a durative one (one snap would do for an instantaneous one).
  static constexpr int kUndoneGoalCost = 2;
  // On by default. Ground actions that differ in one positive condition
  // fact only (their "alternative"), with the same negative conditions and
  // the same effects, none conditional or numeric and no numeric
  // condition, are explored as one relaxed action whose condition is "some
  // alternative holds": driverlog's drive-truck by each of 14 drivers is
  // one operator per truck and road, not 14. The relaxed plan's length is
  // the one FF's first achiever gives, up to ties between the members: the
  // alternative reached first decides, where without groups the member
  // first in operator order would; a helpful group start is given as the
  // member whose alternative the state holds. Not used in the
  // makespan-aware mode (the members' agents differ), in tasks with window
  // actions, nor in an evaluation where a member's snap is unusable (its
  // alternative must not enable the group): the exact tables then.
  void SetGroupOperators(bool on) { group_operators_ = on; }
  // Groups of two or more actions found (0: the option changes nothing).
  int num_operator_groups() const { return static_cast<int>(group_begin_.size()) - 1; }

  // Returns the estimate (kDeadEnd when the goal is relaxed-unreachable).
  // `preferred` (may be null) receives the helpful snaps (SnapIds).
  // `window_slack`: for each running window action of `state` (in running
  // order, SnapTask::IsWindowAction), the room left before its end must
  // happen. A fact such an action's end will delete counts as unavailable
  // when nothing needing it over all fits into that room (match cellar:
  // a burning match too short for another mend).
  // `usable` (empty: all): per SnapId, 0 for snaps known not to be able to
  // happen any more (TemporalReachability: their deadlines have passed);
  // the relaxed exploration leaves them out.
  // `schedule` (may be null: every agent free at 0): the timeline built for
  // the state's path, which tells when each agent is free.
  int Evaluate(const StateData& state, std::vector<SnapId>* preferred,
               std::span<const double> window_slack = {}, std::span<const std::uint8_t> usable = {},
               const Timeline* schedule = nullptr);
  // After a kDeadEnd: true when the relaxation proves it (false when the
  // numeric fixpoint was cut off after too many widening layers).
  bool last_dead_end_proven() const { return dead_end_proven_; }
  // Redundant start/end pairs the last evaluation skipped (see PairCheck;
  // a diagnostic for tests and profiling).
  int last_skipped_pairs() const { return skipped_pairs_; }

  // The relaxed operators (SnapId numbering; an end exists only for a
  // durative action, neither for a pruned one) over the relaxed facts
  // (the task's facts, then started(a) = num_facts + a): what landmark
  // generation reads. Numeric and negative conditions are not listed.
  int num_relaxed_facts() const { return num_facts_ + task_.num_actions(); }
  int num_relaxed_ops() const { return num_ops_; }
  bool OpExists(int op) const { return op_exists_[static_cast<std::size_t>(op)]; }
  std::span<const std::int32_t> Preconditions(int op) const {
    return CsrRow(exact_.pre, exact_.pre_begin, op);
  }
  std::span<const std::int32_t> Adds(int op) const { return CsrRow(add_, add_begin_, op); }

 private:
  struct Interval {
    double lo, hi;
  };
  Interval EvalInterval(const task::NumericExpr& expr, const StateData& state, task::ActionId a);
  bool Satisfiable(const task::NumericCondition& c, const StateData& state, task::ActionId a);
  // See PairCheck: true when the start `op` can achieve nothing new now.
  // Takes the raw tables so that the hot loop keeps them in registers.
  struct PairCheck;
  static bool PairRedundant(const PairCheck& c, const std::int32_t* fact_layer,
                            const std::int32_t* pair_facts) {
    if (c.begin < 0 || fact_layer[c.started] >= 0) return false;
    for (const std::int32_t *it = pair_facts + c.begin, *end = pair_facts + c.end; it != end;
         ++it) {
      if (fact_layer[*it] < 0) return false;
    }
    return true;
  }
  void MarkOp(int op);
  // `need_layer`: the layer of the operator needing the fact (the goal
  // layer for goals); with agents, any achiever applicable before it may
  // be chosen (ChooseAchiever).
  void MarkFact(int fact, int need_layer);
  // True when `op` deletes a goal fact the evaluated state holds.
  bool DeletesHeldGoal(int op) const;
  // The goal facts `state` holds that the extracted relaxed plan's
  // operators delete (each once; not a start's delete its own end adds
  // back, as TMS's bake does).
  int CountUndoneGoals(const StateData& state);
  int ChooseAchiever(int fact, int need_layer) const;
  // Earliest time `op`'s effects happen in the exploration, delayed by the
  // durations already charged to its action's agents.
  double FinishEstimate(int op) const;
  // Marks the changers of the condition's variables: the first operator
  // that raised a variable's interval, or lowered it, whichever direction
  // the condition needs (refuel, not the flight that burnt fuel).
  void MarkNumeric(const task::NumericCondition& c, int layer, const StateData& state,
                   task::ActionId a);

  const SnapTask& task_;
  bool dead_end_proven_ = true;
  int skipped_pairs_ = 0;
  int num_facts_;  // real facts; started(a) is num_facts_ + a
  int num_ops_;    // 2 * actions
  // CSR table.
  std::vector<std::int32_t> add_begin_, add_;
  std::vector<std::vector<const task::NumericCondition*>> num_pre_;
  std::vector<std::vector<const task::NumericEffect*>> num_eff_;
  std::vector<bool> op_exists_;
  std::vector<std::uint8_t> has_num_pre_, has_num_eff_;  // compact copies for the hot loop
  double epsilon_s_;
  std::vector<std::vector<task::FactId>> window_facts_;  // per action: start adds deleted at end
  std::vector<double> min_invariant_duration_;  // per fact: shortest action needing it over all
  std::vector<std::uint8_t> suppressed_;
  std::vector<std::int32_t> suppressed_list_;
  // (suppressed fact, end operator of a running action exempted from it).
  std::vector<std::pair<std::int32_t, std::int32_t>> exempt_ends_;
  void ExemptRunningEnds(const StateData& state);
  bool IsExemptEnd(int fact, int op) const;
  std::vector<bool> til_fact_;  // scratch: facts added by pending literals
  // A goal flag per fact, so reaching the goal is a counter, not a scan of
  // the goal per layer.
  std::vector<std::uint8_t> goal_fact_;
  int num_goal_facts_ = 0;
  // Redundant start/end pairs (satellite's turn_to from every direction).
  // For a durative start whose start and end have no numeric effect and
  // whose end has no numeric condition, Exploration::pair_facts[begin, end)
  // lists the real adds of both snaps and the end's conditions other than
  // started(a); begin is -1 for every other operator. When started(a) is
  // not reached yet and all of these are when the start becomes applicable,
  // the pair can achieve nothing: the end would only wait for started(a)
  // and re-add reached facts. It is skipped (no started(a) fact, no end
  // operator), which is exact: the layers, achievers, estimate and helpful
  // events are the same as without it. (Checking again when the start is
  // applied would catch facts reached earlier in the same layer, but costs
  // more than it saves on satellite and elevators.)
  struct PairCheck {
    std::int32_t begin = -1, end = -1;
    std::int32_t started = 0;  // the fact started(a)
  };

  // What the exploration and the extraction read, per operator (SnapId).
  struct Exploration {
    std::vector<std::int32_t> pre_begin, pre;  // CSR: conditions
    // fact -> the operators whose "missing" counter it lowers: pre but for
    // an end's over-all conditions. Those are its start's conditions too,
    // so in the relaxation started(a) implies them; a running action's are
    // in the state (Transitions keeps running invariants true), or
    // suppressed and exempt for its end (ExemptRunningEnds). Leaving them
    // out changes no layer and saves counter updates where over-all
    // conditions are many (driverlog: every load, board and drive).
    // At-end conditions stay: they are not start conditions, so started(a)
    // does not imply them.
    std::vector<std::int32_t> fact_ops_begin, fact_ops;
    // Each operator's initial "missing triggers" count (1 << 30: never
    // applicable), copied in one pass per evaluation.
    std::vector<std::int32_t> op_missing_init;
    std::vector<std::int32_t> no_pre_ops;
    std::vector<PairCheck> pair_check;
    std::vector<std::int32_t> pair_facts;
  };
  // `exists`: per operator, whether the exploration may apply it.
  Exploration BuildExploration(std::vector<std::int32_t> pre_begin, std::vector<std::int32_t> pre,
                               const std::vector<bool>& exists) const;
  // Finds the operator groups (SetGroupOperators) and builds grouped_.
  void GroupOperators();
  // False when a timed literal made some group member's snap unusable: a
  // group's "some alternative" fact could then be reached through that
  // member's alternative, so the evaluation takes the exact tables.
  bool AllGroupMembersUsable(std::span<const std::uint8_t> usable) const;
  // exact_: every operator of the task (what Preconditions() gives);
  // grouped_: a group's members replaced by its representative, the
  // alternative by the group's "some alternative" fact; empty when no
  // group was found.
  Exploration exact_, grouped_;
  bool group_operators_ = true;
  // Relaxed facts past started(a): "some alternative of the set holds",
  // one per distinct set of alternatives (per truck in driverlog), ids
  // from aux_base_.
  int aux_base_ = 0, num_aux_ = 0;
  std::vector<std::int32_t> rep_of_;     // per action: its group's representative, or itself
  std::vector<std::int32_t> alt_fact_;   // per grouped action: its alternative
  std::vector<std::int32_t> group_of_;   // per action: its group, or -1
  std::vector<std::int32_t> group_aux_;  // per group: its "some alternative" fact
  std::vector<std::int32_t> group_begin_{0}, group_members_;  // CSR: group -> actions
  std::vector<std::int32_t> fact_aux_begin_, fact_aux_;       // CSR: real fact -> aux facts
  // Scratch per evaluation: the alternative that first reached each aux
  // fact, and per representative the running member (started(rep) at 0).
  std::vector<std::int32_t> aux_source_, started_by_;

  // Makespan-aware extraction (see the class comment); the tables below
  // exist only when the task has at least two agents.
  AgentLoads agents_;
  bool makespan_aware_ = false;
  std::vector<std::int32_t> adder_begin_, adder_;  // CSR: real fact -> operators adding it
  std::uint32_t stamp_ = 0;
  std::vector<std::uint32_t> op_stamp_;  // == stamp_: applicable in this evaluation
  std::vector<double> op_time_s_;        // when its effects happen (start: start time)
  std::vector<double> fact_time_s_;
  std::vector<double> ready_s_, load_s_;  // per agent: free at, and with charged work

  // CSR: operator -> the goal facts it deletes (SetKeepHeldGoals).
  std::vector<std::int32_t> goal_del_begin_, goal_del_;
  bool keep_held_goals_ = false;
  bool delay_goal_undoers_ = false;

  // Scratch per evaluation.
  std::vector<std::int32_t> fact_layer_, fact_achiever_;
  // Per fact reached: its achiever or one of the operators it needed
  // deletes a goal fact the state holds (set only when some operator
  // deletes a goal fact and not in the makespan-aware mode).
  std::vector<std::uint8_t> undoes_goal_;
  // Keeping held goals: per operator, the evaluation (undo_stamp_) in
  // which a condition of it was reached only by undoing a held goal, set
  // as each fact's operators are counted down, so that an applied operator
  // need not scan its conditions. A stamp, not a flag: nothing to clear.
  std::vector<std::uint32_t> op_undo_stamp_;
  std::uint32_t undo_stamp_ = 0;
  // Scratch of CountUndoneGoals: a flag per fact (all 0 between calls) and
  // the goals flagged.
  std::vector<std::uint8_t> goal_undone_;
  std::vector<std::int32_t> undone_goals_;
  std::vector<std::int32_t> op_layer_, op_missing_;
  std::vector<Interval> interval_, next_interval_;
  std::vector<std::int32_t> raiser_, raise_layer_, lowerer_, lower_layer_;
  std::vector<std::int32_t> applicable_, numeric_waiting_, new_facts_, layer_ops_;
  // With delay_goal_undoers_: operators that undo a held goal, with the
  // layer they become applicable in, in that order.
  struct DelayedOp {
    std::int32_t layer, op;
  };
  std::vector<DelayedOp> delayed_;
  std::vector<std::uint8_t> op_marked_, fact_marked_;
  std::vector<std::int32_t> marked_ops_, marked_facts_, stack_;
  std::vector<Interval> eval_stack_;
};

}  // namespace seaplan::search
