// Earliest-time reachability under timed-initial-literal windows: a
// temporal relaxed planning graph (POPF/OPTIC style) used to prune states
// whose deadlines can no longer be met and to hide, from the relaxed plan
// heuristic, snap actions that can no longer happen in time.
//
// "Window facts" are facts no action adds but timed literals write: a
// delivery deadline (trucks' deliverable), an antenna's visibility window
// (satellite-tw-til). In a state they are true only inside the intervals
// given by the state (true now, since the path last wrote them) and its
// pending literals (each delete closes, each add opens an interval).
// Everything else is relaxed as usual: deletes, negative and numeric
// conditions are ignored and conditional adds assumed.
//
// Earliest times are propagated Dijkstra-style from the state's schedule
// (the path's earliest STN times, see Timeline): a fact of the state is
// available from the time the path last wrote it, a fact a pending literal
// adds from the literal's time, started(a) of a running action from its
// start. Every snap also comes after what the schedule orders before any
// new event like it: the last writers of what it reads or writes and the
// readers of what it writes (a satellite already busy cannot turn at 0). start(a) happens at the
// earliest time, not before its conditions, at which its window facts allow it: at-start ones hold
// then, over-all ones hold for the whole minimum duration, at-end ones somewhere in the duration
// range. end(a) comes no earlier than start + minimum duration, inside its window facts' windows,
// and for a running action before the current window of its over-all window facts closes.
//
// This is a relaxation (epsilon separations are ignored too): a snap with
// no finite time happens in no extension of the path with its schedule,
// and a state is a dead end when a goal fact or the end of a running action
// has no finite time. Durations read at their minimum from static fluents
// only (0 when they depend on fluents that change).
//
// With mutex groups (UseMutexGroups), a start that needs a fact p together
// with a member q of a group also waits for p and q to hold together: p's
// achiever may need another member m of q's group when it adds p (a truck
// loads a package at l1; the package is in the truck, the truck at l1),
// and q then holds no earlier than the shortest way from m to q in the
// group's transitions (the drive from l1 to l3). Without it a truck that is
// at l3 now could unload at l3 what it loads at l1 later, and a deadline it
// cannot meet any more would not show.
//
// Not thread-safe: one instance per planner run; scratch is reused, so an
// evaluation allocates nothing once warmed up.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "../mutex_groups.h"
#include "../snap_task.h"
#include "../state_registry.h"
#include "../timeline.h"
#include "radix_queue.h"

namespace seaplan::search {

class TemporalReachability {
 public:
  explicit TemporalReachability(const SnapTask& task);

  // Adds the pair facts "p while q" described above, for the groups of
  // `mutex` (computed for the same task). A no-op when not active().
  void UseMutexGroups(const MutexGroups& mutex);
  // Pair facts UseMutexGroups added (for the statistics and the tests).
  int num_pair_facts() const { return static_cast<int>(earliest_.size()) - pair_base_; }
  // How often snaps reach them in one evaluation, at most.
  std::size_t num_pair_reaches() const { return op_pairs_.size(); }

  // False when no literal ever deletes a window fact: then no window closes
  // and Evaluate would prune nothing the untimed relaxation does not.
  bool active() const { return active_; }
  // True when some condition or goal compares numbers: the relaxation
  // leaves them out, so RelaxedPlanLength's plan has none of their
  // changers (a refuel).
  bool leaves_out_numbers() const { return leaves_out_numbers_; }

  // `timeline` must be built for the path that reached `state`. Returns
  // false when the state is a dead end (usable_snaps() is then unspecified).
  bool Evaluate(const StateData& state, const Timeline& timeline);

  // After Evaluate: per SnapId, 1 when the snap can still happen.
  std::span<const std::uint8_t> usable_snaps() const { return usable_; }
  // After a successful Evaluate: earliest time (s) of a fact (FactId), or of
  // started(a) at num_facts + a; infinity when unreachable.
  double EarliestTime(int fact) const { return earliest_[static_cast<std::size_t>(fact)]; }

  // After a successful Evaluate: the number of snaps of a relaxed plan
  // extracted backwards from the goal along the earliest achievers (a fact
  // the state holds counts as free only when no snap reaches it earlier, so
  // an image taken too late for its window is taken again), plus the ends
  // of running actions it leaves out. `preferred` (may be null) receives
  // the plan's snaps whose conditions the state or a pending timed literal
  // provides (sorted).
  int RelaxedPlanLength(const StateData& state, std::vector<SnapId>* preferred);

 private:
  // UseMutexGroups leaves tasks with more group members than this alone.
  static constexpr std::size_t kMaxGroupMembers = 200'000;
  // ... and stops looking for the shortest ways in a group past this many
  // edges relaxed, and adds pairs only while their achievers reach at most
  // this many per snap of the task (each is one more Reach per evaluation).
  static constexpr std::size_t kMaxEdgesRelaxed = 20'000'000;
  static constexpr std::size_t kPairReachesPerSnap = 3;

  enum class Kind : std::uint8_t { kAt, kSpan, kRange };
  struct WindowCondition {
    task::FactId fact;
    Kind kind;
  };
  struct Interval {
    double open_s, close_s;
  };
  // Earliest time >= t at which `c` allows snap `op` (infinity if none).
  double NextAllowed(const WindowCondition& c, double t, task::ActionId a) const;
  double OpTime(int op, double t0) const;
  void Reach(int fact, double time_s, int achiever);
  // fact_ops_ from pre_, and the per-fact scratch for `total_facts`.
  void IndexConditions(int total_facts);
  // A fact of the state or of a pending literal: the fact and its pair
  // facts, from `time_s`.
  void ReachFromState(int fact, double time_s);
  // Earliest time the schedule of the path allows a new `op`: after the
  // last writer of what it reads or writes, after the readers of what it
  // writes.
  double ScheduleBound(int op, const Timeline& timeline);
  // Timeline::FactWrittenAt and FactReadUntil of `f`, read once per
  // evaluation: many snaps read one fact (every load by a truck at a place
  // reads where it is), and FactReadUntil walks the fact's readers.
  struct FactTimes {
    double written_s, read_until_s;
  };
  const FactTimes& ScheduleTimes(task::FactId f, const Timeline& timeline);

  const SnapTask& task_;
  bool active_ = false;
  bool leaves_out_numbers_ = false;
  int num_facts_ = 0;
  int num_ops_ = 0;
  std::vector<std::uint8_t> window_fact_;
  std::vector<task::FactId> window_facts_;  // the window facts some snap needs
  // CSR tables per snap: fact preconditions (non-window; started(a) for
  // ends), window conditions, adds (non-window, started(a) for starts).
  std::vector<std::int32_t> pre_begin_, pre_;
  std::vector<std::int32_t> win_begin_;
  std::vector<WindowCondition> win_;
  std::vector<std::int32_t> add_begin_, add_;
  std::vector<std::int32_t> fact_ops_begin_, fact_ops_;
  std::vector<std::int32_t> missing_init_;
  std::vector<std::int32_t> no_pre_ops_;
  std::vector<double> static_min_d_, static_max_d_;  // per action
  // Pair facts (UseMutexGroups) are numbered from pair_base_ (facts, then
  // started(a), then pairs); the relaxed plan extraction skips them. Per
  // fact p, its pairs (CSR); per snap, the pairs it reaches and how long
  // after it happens (CSR).
  int pair_base_ = 0;
  std::vector<std::int32_t> fact_pairs_begin_, fact_pairs_;
  std::vector<std::int32_t> op_pairs_begin_, op_pairs_;
  std::vector<double> op_pair_delay_s_;

  // Scratch per evaluation.
  std::vector<std::vector<Interval>> windows_;  // per fact (window facts only)
  std::vector<double> open_since_;              // per fact: open interval start, or infinity
  std::vector<double> earliest_;
  std::vector<std::int32_t> achiever_;  // per fact: snap that set earliest_, -1 the state
  std::vector<std::uint8_t> op_marked_, fact_marked_;
  std::vector<std::int32_t> marked_ops_, marked_facts_, stack_;
  std::vector<std::int32_t> missing_;
  std::vector<std::uint8_t> usable_;
  std::vector<double> min_d_, max_d_;  // per action; running ones from their record
  std::vector<std::uint8_t> running_;  // per action
  // Per snap (CSR), what ScheduleBound reads: 2 f for a fact it reads
  // (FactWrittenAt), 2 f + 1 for one it writes (FactReadUntil). One array
  // instead of three vectors per SnapAction: the bound is taken for every
  // snap reached in every evaluation, and reading it from the snaps was a
  // cache miss each (a fifth of the search's time on trucks).
  std::vector<std::int32_t> schedule_begin_, schedule_facts_;
  // ScheduleTimes per fact, valid where fact_times_stamp_ is evaluation_.
  std::vector<FactTimes> fact_times_;
  std::vector<std::uint32_t> fact_times_stamp_;
  std::uint32_t evaluation_ = 0;
  // Facts waiting to be popped in time order: those reached at the time
  // being popped (first in, first out) and the others, the state's
  // included (a radix queue: times only grow as they pop).
  using Entry = RadixTimeQueue::Entry;  // id: the fact
  bool PopEarliest(Entry* next);
  std::vector<Entry> now_;
  RadixTimeQueue later_;
  std::size_t next_now_ = 0;
  double now_s_ = 0.0;  // time of the last pop; -infinity while the state goes in
};

}  // namespace seaplan::search
