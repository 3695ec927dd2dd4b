// Fact landmarks of the delete relaxation of the snap task and LAMA's
// landmark count (Richter and Westphal 2010).
//
// Generation (LandmarkGraph, once per task): Zhu and Givan's label
// propagation over the relaxed operators of RelaxedPlanHeuristic (a start
// needs its at-start and over-all facts and adds started(a); the end needs
// started(a), its at-end and over-all facts). A fact's label is the fact
// itself plus the intersection, over its achievers, of the union of their
// preconditions' labels, to a fixed point; the goal facts' labels are the
// landmarks. Facts true initially or added by a timed literal are their own
// label. Numeric conditions and negative ones are ignored (more achievers,
// so fewer landmarks: still sound). Greedy-necessary orderings p -> l: p is
// a precondition of every first achiever of l, i.e. of every achiever whose
// own label does not contain l (one that could add l before l is true).
// Reasonable orderings into goals, from mutex groups, are added after
// construction (AddReasonableOrderings).
//
// Counting (LandmarkCounter): the landmarks accepted on a path are the
// parent's accepted ones plus those true in the state whose ordering parents
// the parent had all accepted; h = landmarks not accepted + accepted ones
// required again (a goal false now, or false with a greedy-necessary child
// not accepted yet). Path-dependent, so the search stores one bitset per
// state.
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

  int size() const { return static_cast<int>(facts_.size()); }
  int num_orderings() const { return static_cast<int>(parents_.size()); }
  // Relaxed fact id of landmark i: a fact, or num_facts + a for started(a).
  std::int32_t fact(int i) const { return facts_[static_cast<std::size_t>(i)]; }
  // Landmark index of a relaxed fact id, -1 when it is none.
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
  // True when landmark i holds in `state` (a fact, or its action running).
  bool Holds(int i, const StateData& state) const;

 private:
  int num_facts_;
  std::vector<std::int32_t> facts_, index_of_;
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
