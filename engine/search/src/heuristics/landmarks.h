// Fact landmarks of the delete relaxation of the snap task, disjunctive
// ones found backwards from them, and LAMA's landmark count (Richter and
// Westphal 2010).
//
// Generation (LandmarkGraph, once per task): Zhu and Givan's label
// propagation over the relaxed operators of RelaxedPlanHeuristic (a start
// needs its at-start and over-all facts and adds started(a); the end needs
// started(a), its at-end and over-all facts). A fact's label is the fact
// itself plus the intersection, over its achievers, of the union of their
// preconditions' labels, to a fixed point; the goal facts' labels are the
// fact landmarks. Facts true initially or added by a timed literal are
// their own label. Numeric conditions and negative ones are ignored (more
// achievers, so fewer landmarks: still sound). Then, backwards from each
// landmark, as LAMA's RHW method does: its first achievers are those whose
// preconditions' labels hold none of its facts (they could add it while it
// is false); the preconditions they all share are ordered greedy-necessary
// before it (p -> l: p holds right before l is first added); of the others,
// facts of one predicate (started(a): of one schema, and only below a goal
// or a disjunction) of which every first achiever needs at least one form a
// disjunctive landmark of 2 to kMaxDisjunctionSize facts, none true at the
// start, ordered the same way and searched backwards in turn ("some ship
// holds container c" before "c unloaded at its port": whichever ship it is,
// one must load it, which no fact landmark says). Reasonable orderings into
// goals, from mutex groups, are added after construction
// (AddReasonableOrderings).
//
// Counting (LandmarkCounter): the landmarks accepted on a path are the
// parent's accepted ones plus those true in the state (a disjunctive one:
// any of its facts) whose ordering parents the parent had all accepted;
// h = landmarks not accepted + accepted ones required again (a goal false
// now, or false with a greedy-necessary child not accepted yet).
// Path-dependent, so the search stores one bitset per state.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../mutex_groups.h"
#include "../snap_task.h"
#include "../state_registry.h"
#include "relaxed_plan_heuristic.h"
#include "seaplan/common/stop_token.h"

namespace seaplan::search {

class LandmarkGraph {
 public:
  // AddReasonableOrderings stops after about this many mutex lookups.
  static constexpr std::size_t kMaxReasonableChecks = 5'000'000;
  // Disjunctions of more facts are not kept: each costs a test per fact in
  // every state and says little (LAMA keeps at most 4; 8 keeps "some ship
  // holds c" for fleets of up to 8, "some truck holds crate c" in depots).
  static constexpr std::size_t kMaxDisjunctionSize = 8;
  // At most this many disjunctive landmarks are kept beside the fact ones.
  static constexpr std::size_t kMaxDisjunctiveLandmarks = 20'000;

  // `stop` (may be null) is polled during the propagation; stopped, the
  // graph is empty.
  LandmarkGraph(const SnapTask& task, const RelaxedPlanHeuristic& relaxed,
                const StopToken* stop = nullptr);

  // Reasonable orderings into goal landmarks (Hoffmann, Porteous and
  // Sebastia 2004, as LAMA uses them): landmark a before goal b when
  // reaching a once b holds would make b false again, because a itself,
  // a fact every achiever of a adds, or a greedy-necessary parent of a
  // cannot hold with b (`mutex`). Depots: a crate goes on its
  // target before another crate goes on it. Only orderings that close no
  // cycle are kept. They join the parents a landmark needs accepted; the
  // children that make an accepted landmark required again stay the
  // greedy-necessary ones. Returns how many were added.
  int AddReasonableOrderings(const RelaxedPlanHeuristic& relaxed, const MutexGroups& mutex,
                             const StopToken* stop = nullptr);

  int size() const { return static_cast<int>(is_goal_.size()); }
  int num_orderings() const { return static_cast<int>(parents_.size()); }
  int num_disjunctive() const { return num_disjunctive_; }
  // Relaxed fact ids of landmark i (a fact, or num_facts + a for
  // started(a)), sorted: one for a fact landmark, more for a disjunctive
  // one (true when any is).
  std::span<const std::int32_t> members(int i) const { return CsrRow(members_, member_begin_, i); }
  // Fact landmark index of a relaxed fact id, -1 when it is none.
  int IndexOf(std::int32_t relaxed_fact) const {
    return index_of_[static_cast<std::size_t>(relaxed_fact)];
  }
  bool is_goal(int i) const { return is_goal_[static_cast<std::size_t>(i)] != 0; }
  // Parents of landmark i (greedy-necessary: must be true right before l is
  // first added; and reasonable ones) and its greedy-necessary children.
  std::span<const std::int32_t> parents(int i) const { return CsrRow(parents_, parent_begin_, i); }
  std::span<const std::int32_t> children(int i) const { return CsrRow(children_, child_begin_, i); }
  // Landmarks a snap adds (SnapId order, the relaxed operators' numbering).
  std::span<const std::int32_t> added_by(SnapId snap) const {
    return CsrRow(added_by_, added_by_begin_, snap);
  }
  // True when landmark i holds in `state` (a fact, or its action running;
  // a disjunctive one: any of its members).
  bool Holds(int i, const StateData& state) const;

 private:
  int num_facts_;
  int num_disjunctive_ = 0;  // the last ones, after the fact landmarks
  std::vector<std::int32_t> member_begin_, members_, index_of_;
  std::vector<std::uint8_t> is_goal_;
  std::vector<std::int32_t> parent_begin_, parents_, child_begin_, children_;
  std::vector<std::int32_t> added_by_begin_, added_by_;
  std::vector<std::int32_t> achiever_begin_, achievers_;  // relaxed ops adding landmark i
};

// Accepted sets and counts for one search (scratch reused: not thread-safe).
class LandmarkCounter {
 public:
  explicit LandmarkCounter(const LandmarkGraph& graph);

  // 64-bit words of one accepted set.
  std::size_t words() const { return words_; }
  // Fills `accepted` (words() words) for `state` reached from a state whose
  // accepted set is `parent_accepted` (empty: the initial state, which
  // accepts every landmark true in it) and returns h.
  int Update(std::span<const std::uint64_t> parent_accepted, const StateData& state,
             std::span<std::uint64_t> accepted) const;
  // True when `snap` adds a landmark that is not accepted, false in
  // `state` and whose parents are all accepted: one that could be
  // accepted next (LAMA's preferred operators from landmarks).
  bool AddsNextLandmark(std::span<const std::uint64_t> accepted, const StateData& state,
                        SnapId snap) const;

 private:
  static bool Test(std::span<const std::uint64_t> bits, int i) {
    return (bits[static_cast<std::size_t>(i) >> 6] >> (i & 63)) & 1u;
  }
  bool ParentsAccepted(std::span<const std::uint64_t> accepted, int i) const;

  const LandmarkGraph& graph_;
  std::size_t words_;
};

}  // namespace seaplan::search
