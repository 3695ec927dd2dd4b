// Envelope reasoning on over-all conditions (required concurrency).
//
// An action `outer` whose end unconditionally deletes a fact f (and does not
// add it again) is an envelope for every action `inner` that needs f over
// all: if the two run at the same time, inner must end no later than outer
// (the search rejects outer's end while inner runs, and the schedule then
// orders end(inner) <= end(outer)). Two consequences, both sound:
//
//  - Dynamic (Timeline): as soon as inner and outer run together, the
//    schedule may already require end(inner) <= start(outer) + max_dur(outer),
//    written over nodes that exist (start(inner) + min_dur(inner) at the start
//    of inner). A path that cannot fit inner into outer is pruned when inner
//    starts instead of never (outer's end would never be applicable, and the
//    search would keep expanding beneath it).
//  - Static: f is envelope-only when it is false initially, no timed literal
//    adds it, and every adder is the start of a durative action whose end
//    deletes it with a bounded duration. f then never holds for longer than
//    the longest such action, so an action needing f over all with a longer
//    minimum duration can never be part of a plan (a 15-unit bake in a kiln
//    fired for 8 units). Such actions are unschedulable: the search and the
//    heuristic drop them, which keeps the relaxed plan from counting on them.
//
// Immutable after construction; thread-safe for reads.
#pragma once

#include <vector>

#include "seaplan/task/ground_task.h"

namespace seaplan::search {

class InvariantEnvelopes {
 public:
  explicit InvariantEnvelopes(const task::GroundTask& task);

  // True when `inner` needs over all a fact that the end of `outer` deletes.
  bool MustEndWithin(task::ActionId inner, task::ActionId outer) const;
  // True when the end of `a` deletes a fact some action needs over all.
  bool IsEnvelope(task::ActionId a) const {
    return !end_deletes_[static_cast<std::size_t>(a)].empty();
  }
  // True when `a` needs over all some fact over a longer time than that fact can hold.
  bool Unschedulable(task::ActionId a) const { return unschedulable_[static_cast<std::size_t>(a)]; }
  // Sorted facts the end of `a` deletes that some action needs over all.
  const std::vector<task::FactId>& EndDeletes(task::ActionId a) const {
    return end_deletes_[static_cast<std::size_t>(a)];
  }
  // Sorted over-all facts of `a` that the end of some action deletes.
  const std::vector<task::FactId>& EnclosedNeeds(task::ActionId a) const {
    return enclosed_needs_[static_cast<std::size_t>(a)];
  }
  int num_unschedulable() const { return num_unschedulable_; }

 private:
  // Per action, sorted: positive over-all facts; facts the end deletes
  // unconditionally without adding them, restricted to facts some action
  // needs over all (empty for most actions, which keeps the checks cheap).
  std::vector<std::vector<task::FactId>> over_all_;
  std::vector<std::vector<task::FactId>> end_deletes_;
  std::vector<std::vector<task::FactId>> enclosed_needs_;
  std::vector<bool> unschedulable_;
  int num_unschedulable_ = 0;
};

// Static bounds of an action's duration: constant constraints only (others
// give [0, inf)); instantaneous actions give [0, 0].
double MinDurationBound(const task::Action& action);
double MaxDurationBound(const task::Action& action);

}  // namespace seaplan::search
