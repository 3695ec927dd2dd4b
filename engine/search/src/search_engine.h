// Step-wise lazy best-first search over snap-action states (Fast Downward's
// search_algorithm shape: Initialize(), then Step() until it says stop).
//
// Successors are checked and scheduled (Timeline) when their parent is
// expanded but only registered when popped (deferred generation: states
// never expanded cost no registry space); the heuristic runs when a state is
// expanded (lazy evaluation), giving its helpful events at the same time. Two open lists:
// all successors, and those reached by helpful events (boosted after
// progress, as in LAMA). In the greedy phase, starts that are not helpful
// are not even applied or scheduled at generation: they are pushed with the
// parent's makespan and bound and checked when popped, which keeps
// expansions cheap when thousands of starts apply (pairs of objects in TMS)
// and the search follows helpful events anyway. Optionally a third list,
// type-based exploration (open_lists/type_based_open_list.h): every
// successor, bucketed by (parent h, depth), popped at random in turn with
// the other two, so that a search stuck on a plateau also expands states
// away from it. Optionally (greedy) LAMA's landmark count
// (heuristics/landmarks.h) with its own two lists, all successors and
// preferred ones, keyed by the parent's count; then a preferred event is
// also one adding a landmark that could be accepted next. Ordering:
//   - greedy (weight < 0): (parent h, makespan so far), or (parent h,
//     newest first) with PlateauOrder::kNewestFirst;
//   - weighted A* (weight >= 0): makespan lower bound + weight * scale * h.
// A bound prunes successors whose makespan lower bound cannot beat it.
//
// Owns nothing shared: the registry, heuristic, transitions and timeline are
// borrowed and must outlive the search. Not thread-safe.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>
#include <random>
#include <span>
#include <utility>
#include <vector>

#include "goal_order.h"
#include "heuristics/landmarks.h"
#include "heuristics/relaxed_plan_heuristic.h"
#include "heuristics/temporal_reachability.h"
#include "object_symmetry.h"
#include "open_lists/tie_breaking_open_list.h"
#include "open_lists/type_based_open_list.h"
#include "seaplan/common/stop_token.h"
#include "snap_task.h"
#include "state_registry.h"
#include "timeline.h"
#include "transitions.h"

namespace seaplan::search {

struct SearchParams {
  double weight = -1;          // < 0: greedy
  double scale_s = 1;          // seconds per heuristic unit (weighted A*)
  double bound_s = kInfinity;  // only plans with makespan < bound - epsilon/2
  double epsilon_s = 0.001;
  std::uint64_t seed = 1;
  // Copies kept per logical state (schedules that do not dominate each
  // other) and whether a copy with a later makespan bound may dominate
  // (false: only equal bounds merge; the retry after an incomplete search).
  int max_variants = 8;
  bool bound_dominance = true;
  // Greedy only: order among successors of equal h. kMakespan prefers the
  // shorter schedule so far (good first makespans); kNewestFirst prefers
  // the latest generated (depth first along a plateau), which escapes the
  // plateaus of sokoban or rtam that the makespan order explores breadth
  // first.
  enum class PlateauOrder { kMakespan, kNewestFirst };
  PlateauOrder plateau_order = PlateauOrder::kMakespan;
  // Greedy only: a third list in the alternation, type-based exploration
  // (types (parent h, depth in events), random pops seeded by `seed`).
  bool type_based_exploration = false;
  // With type-based exploration: schedules of this many search paths kept
  // built at once (1 to 4; 1: the borrowed timeline's only). The same
  // search either way, only the schedules' rebuilding work differs.
  int schedule_paths = 2;
  // Greedy only (may be null; borrowed): LAMA's landmark count beside the
  // relaxed plan. Its own pair of lists (all, preferred) keyed by the
  // parent's count joins the alternation; progress in either estimate
  // boosts both preferred lists; a preferred event is also one adding a
  // landmark that could be accepted next.
  const LandmarkGraph* landmarks = nullptr;
  // Turns a landmark list gives up per pop, against 1 for the others: with
  // 2 each landmark list is popped half as often as each of the relaxed
  // plan's. With equal turns their ties by makespan on a count of a few
  // goal landmarks reach states all over the tree, each a schedule to
  // rebuild: sokoban-2011 p03 lost its plan within 10 CPU s
  // (bench/planner/README.md, "Landmark count").
  int landmark_pop_cost = 2;
  // May be null (borrowed): interchangeable objects. A successor whose
  // image under them (ObjectSymmetry::Canonicalize) is that of another
  // state already expanded, with a bound no later and no window actions
  // running, is dropped like a duplicate.
  const ObjectSymmetry* symmetry = nullptr;
  // May be null (borrowed): states that can reach the goal in neither
  // order of two goals nothing deletes (goal_order.h) are dead ends.
  const GoalOrderDeadEnds* goal_order = nullptr;
  // A state in which the end of a running action with SnapTask::EagerEnd
  // can happen gets that end as its only successor: the other orders of
  // the same events are not searched (a lift's end left pending while the
  // hoist lifts and drops other crates multiplied the states of
  // storage-2011 about ninefold). Complete where the end's facts are false
  // from the action's start to its end, which is not checked: an exhausted
  // search that pruned so is no proof (complete()).
  bool eager_ends = false;
  // May be empty (borrowed): events the search takes first, one after
  // another from the initial state, as the only successor of each state
  // on the way (matched by SnapId, a timed literal's too), so that it searches the
  // completions of that prefix with the prefix's schedule. A prefix event
  // that does not apply where it is due leaves the search without states.
  std::span<const Event> prefix;
};

struct SearchCounters {
  std::size_t expanded = 0, generated = 0, evaluated = 0;
  // Successors dropped because a symmetric state was expanded before.
  std::size_t symmetric_drops = 0;
  // States whose only successor was an eager end (SearchParams::eager_ends)
  // while other events could happen.
  std::size_t eager_ends = 0;
  // States found dead ends by the order of their goals (SearchParams::goal_order).
  std::size_t goal_order_dead_ends = 0;
};

class LazySearch {
 public:
  enum class Status { kInProgress, kSolved, kExhausted };

  LazySearch(const SnapTask& task, StateRegistry& registry, RelaxedPlanHeuristic& heuristic,
             const Transitions& transitions, Timeline& timeline, const SearchParams& params);

  // `stop` (may be null) is also polled inside large expansions so that a
  // cancellation is seen within milliseconds; an interrupted expansion
  // leaves the search unusable (callers stop anyway).
  void SetStopToken(const StopToken* stop) { stop_ = stop; }
  // Optional (may be null; borrowed): prunes states whose timed-literal
  // deadlines can no longer be met, hides snaps that missed theirs from
  // the heuristic, raises h to its time-aware relaxed plan length when
  // longer and takes the helpful events from that plan (the earliest
  // achievers') instead of FF's (as well as FF's when a condition compares
  // numbers, which that plan leaves out). Only used when active().
  void SetTemporalReachability(TemporalReachability* reachability) { reachability_ = reachability; }
  void Initialize(const StateData& initial);
  Status Step();

  // After kSolved: the events of the plan (in search order) and its makespan.
  const std::vector<Event>& plan() const { return plan_; }
  double plan_makespan_s() const { return plan_makespan_s_; }
  // Tightens the bound (after an incumbent); the search may then continue.
  void SetBound(double bound_s) { params_.bound_s = bound_s; }
  // False when a merge of duplicate states or a bound may have hidden plans,
  // so exhaustion proves nothing.
  // Exhaustion proves no plan exists when no dead end was guessed and the
  // explored states are the whole untimed reachable set: either no schedule
  // was ever inconsistent, or no two paths with timing-sensitive states
  // (running actions, timed literals) were merged.
  bool complete() const {
    return !unsafe_dead_end_ && !(stn_pruned_ && merged_timed_) && counters_.eager_ends == 0;
  }
  // Exhaustion under a bound proves the incumbent optimal only when no
  // duplicate was ever merged (merging ignores the schedule).
  bool exhaustive_without_merges() const { return complete() && !merged_any_; }
  const SearchCounters& counters() const { return counters_; }
  // States taken off and put on schedule paths to switch them to another
  // search path (about one event each: the work the extra paths save).
  std::size_t schedule_events_rebuilt() const { return schedule_events_rebuilt_; }
  std::size_t MemoryBytes() const;
  int best_h() const { return best_h_; }

 private:
  struct NodeInfo {
    std::int32_t parent = -1;
    // Position on the path the borrowed timeline holds (paths_[0]: number
    // of events before this state), -1 when not on it. Fills padding: no
    // extra bytes.
    std::int32_t path_index = -1;
    Event event{};
    double g_s = 0;   // makespan of the path's schedule
    double lb_s = 0;  // lower bound on any completion's makespan
    std::int32_t h = -1;
    std::uint8_t status = 0;  // 0 new, 1 open, 2 closed
    // Slack of the running window actions (Timeline::WindowSlack), in
    // slack_pool_: a copy of a state dominates another when its bound is no
    // later and every window leaves at least as much room.
    std::int32_t slack_begin = 0;
    std::int32_t slack_count = 0;
  };
  static_assert(sizeof(NodeInfo) <= 64);

  enum : std::uint8_t { kNew = 0, kOpen = 1, kClosed = 2 };

  NodeInfo& Info(StateId id);
  void ExtractPath(std::int32_t state, std::vector<Event>* out) const;
  // Makes one of the schedule paths (paths_) the path to `state` unless
  // one already is, and that one the active path: walks up the search tree
  // to the nearest state each path shares with `state`'s (their common
  // ancestor) and rebuilds the one that needs the fewest events undone and
  // added from there.
  void EnsureTimeline(std::int32_t state);
  // `state`, whose parent is the active path's last state, becomes its last.
  void AppendToTimelinePath(std::int32_t state);
  // Whether `state` is on path k, and where (its number of events before).
  bool OnPath(std::size_t k, std::int32_t state) const;
  std::size_t PathPosition(std::size_t k, std::int32_t state) const;
  Timeline& ActiveTimeline() { return *paths_[active_].timeline; }
  // The extra schedule paths' own timelines and every path's state list.
  std::size_t ExploreMemoryBytes() const;
  // A lower bound that cannot beat the incumbent (anytime bound).
  bool OverBound(double lower_bound_s) const {
    return lower_bound_s >= params_.bound_s - params_.epsilon_s / 2;
  }
  // Whether an expanded state's bound lets it stand for a new state with
  // bound `new_lb_s`: no later with bound dominance, else the same.
  bool BoundCovers(const NodeInfo& n, double new_lb_s) const {
    return params_.bound_dominance ? n.lb_s <= new_lb_s + 1e-9
                                   : std::abs(n.lb_s - new_lb_s) <= 1e-9;
  }
  bool SlackAtLeast(const NodeInfo& n, const std::vector<double>& slack) const;
  bool SlackAtMost(const NodeInfo& n, const std::vector<double>& slack) const;
  bool IsAncestor(std::int32_t maybe_ancestor, std::int32_t state) const;
  // One per generated successor, so kept small (16 bytes): the event's
  // duration bounds are not stored, Transitions::Apply fixes them again
  // from the parent's state when the record is popped.
  struct Pending {
    // -1: the initial state; kConsumed once popped (the record is in two or
    // three lists, and a second pop would only find the same state again).
    std::int32_t parent;
    SnapId snap;  // Event::snap
    double lb_s;  // lower bound on the makespan of any completion
  };
  static_assert(sizeof(Pending) == 16);
  // Eager ends (SearchParams::eager_ends): makes the first one that applies
  // and keeps the schedule consistent, if any, the only candidate; false
  // when there is none.
  bool TakeEagerEnd(Timeline& timeline);
  // `parent_h` kGoalFirst puts a goal state before everything else.
  void Push(std::int32_t parent, const Event& event, double g_s, double lb_s, bool preferred,
            std::int32_t parent_h, std::int32_t parent_lm_h);
  static constexpr std::int32_t kGoalFirst = -1'000'000'000;
  static constexpr std::int32_t kConsumed = -2;
  static TieBreakingOpenList::KeyOrder KeyOrder(const SearchParams& params);
  // Generates and registers the state of a pending record (deferred, as in
  // Fast Downward's lazy search); -1 when it is a dominated duplicate.
  std::int32_t Materialize(std::int32_t pending_index);
  bool Pop(std::int32_t* state);
  bool TypeBased() const { return params_.type_based_exploration && params_.weight < 0; }
  std::int32_t& Depth(std::int32_t state);
  // The landmarks accepted on the path to `state` (landmark count only).
  std::span<std::uint64_t> Accepted(std::int32_t state) {
    const std::size_t w = landmark_counter_->words();
    return {landmark_accepted_.data() + static_cast<std::size_t>(state) * w, w};
  }

  const SnapTask& task_;
  StateRegistry& registry_;
  RelaxedPlanHeuristic& heuristic_;
  const Transitions& transitions_;
  Timeline& timeline_;
  SearchParams params_;
  std::mt19937_64 rng_;

  std::vector<NodeInfo> info_;
  TieBreakingOpenList open_all_, open_preferred_;
  TypeBasedOpenList open_typed_;
  // Keyed by the landmark count (empty without landmarks).
  TieBreakingOpenList open_landmark_all_, open_landmark_preferred_;
  int priority_all_ = 0, priority_preferred_ = 0, priority_typed_ = 0;
  int priority_landmark_all_ = 0, priority_landmark_preferred_ = 0;
  std::optional<LandmarkCounter> landmark_counter_;
  // Accepted landmarks, LandmarkCounter::words() words per state id.
  std::vector<std::uint64_t> landmark_accepted_;
  int best_landmark_h_ = RelaxedPlanHeuristic::kDeadEnd;
  // Events on the path of each state (type-based exploration only).
  std::vector<std::int32_t> depth_;
  int best_h_ = RelaxedPlanHeuristic::kDeadEnd;
  bool stn_pruned_ = false, merged_timed_ = false, merged_any_ = false, unsafe_dead_end_ = false;
  SearchCounters counters_;
  std::vector<Event> plan_;
  double plan_makespan_s_ = 0;

  // Scratch reused by every expansion.
  StateData current_, next_;
  std::vector<Event> path_, candidates_;
  std::vector<SnapId> preferred_, timed_preferred_, merged_preferred_;
  std::vector<double> slack_scratch_;
  std::vector<double> slack_pool_;
  std::vector<Pending> pending_;
  std::int32_t initial_ = 0;
  // SearchParams::prefix: the pending record of the next state on it (-1
  // once the prefix is behind), and the index of the event due there.
  std::int32_t prefix_pending_ = -1;
  std::size_t prefix_taken_ = 0;
  // Schedules of search paths kept built. paths_[0] is on the borrowed
  // timeline; with type-based exploration a second one, on a timeline of
  // this search's own: a random pop's state mostly shares only the first
  // events with the best-first lists' region, and with one schedule each
  // such pop rebuilt it twice (there, and back for the next best-first
  // pop); with two, the random pops mostly rebuild the second one and
  // the best-first region stays built. Which path holds a state changes
  // nothing but the work: every path's schedule is exact.
  struct SchedulePath {
    Timeline* timeline = nullptr;
    // The states along the path (the initial state first); on path 0 each
    // with its NodeInfo::path_index, on the others told by Depth(). Empty
    // until this search first builds it (the borrowed timeline may still
    // hold another search's path).
    std::vector<std::int32_t> states;
    // The state whose path it holds (Build or Keep), -1 for none: saves
    // rebuilding the schedule of the state about to be expanded and of the
    // parent of the next popped successor (Materialize). Any change of a
    // parent pointer happens in Materialize, which then keeps or rebuilds,
    // so the cached path is never stale (and in the greedy searches, the
    // only ones with a second path, a state's parent never changes).
    std::int32_t path_of = -1;
  };
  static constexpr std::size_t kMaxSchedulePaths = 4;
  std::size_t schedule_events_rebuilt_ = 0;
  std::vector<std::unique_ptr<Timeline>> explore_timelines_;
  std::vector<SchedulePath> paths_;
  std::size_t active_ = 0;            // the path of the state being handled
  std::vector<std::int32_t> branch_;  // scratch of EnsureTimeline
  const StopToken* stop_ = nullptr;
  TemporalReachability* reachability_ = nullptr;
  StateData parent_state_;
  // With params_.symmetry: the states' images, and per image its owner,
  // the expanded state that has it with no window slack and the earliest
  // makespan bound so far (else the first one; -1: none yet).
  std::unique_ptr<StateRegistry> canonical_registry_;
  std::vector<std::int32_t> canonical_owner_;
  StateData canonical_;
  // The image's id in canonical_registry_, and its owner (-1: none).
  std::pair<std::int32_t, std::int32_t> CanonicalOwner(const StateData& state);
};

}  // namespace seaplan::search
