// Mutex groups: sets of facts of which at most one is true in any state the
// task can reach (invariant synthesis in the style of Fast Downward's
// translator, Helmert 2009, on the ground task).
//
// A candidate is a set of (predicate, position) and (action schema,
// position) pairs; its instance for an object o holds every ground fact of
// such a predicate with o at that position, and the "running" marker of every
// ground durative action of such a schema with o at that position (a move
// into tile x holds x's token from its start to its end). The candidate is
// an invariant when at most one member of each instance is true initially,
// no timed literal adds a member, and every snap that adds a member of an
// instance also deletes one it requires (the end of an action requires its
// at-end and over-all conditions, which the search checks before it
// applies the end, and requires and deletes its own running marker). Candidates grow from one pair
// by adding, for a snap that breaks them, a pair of a fact it requires and deletes; the search over
// candidates is bounded (kMaxPairs, kMaxCandidates, kMaxSnapChecks).
//
// On floortile: for each tile x, at most one of (clear x), (robot-at ?r x),
// (painted x ?c) and a move into x or a paint of x running.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "seaplan/task/ground_task.h"

namespace seaplan::search {

// A member of a group: a fact (>= 0) or the running marker of action a,
// encoded as -1 - a.
using GroupMember = std::int32_t;
inline GroupMember RunningMember(task::ActionId a) {
  return -1 - a;
}
inline bool IsRunningMember(GroupMember m) {
  return m < 0;
}
inline task::ActionId ActionOfRunning(GroupMember m) {
  return -1 - m;
}

class MutexGroups {
 public:
  static constexpr int kMaxPairs = 16;
  static constexpr int kMaxCandidates = 2000;
  // Candidates times snaps checked, at most (about 0.2 s on a large task).
  static constexpr std::size_t kMaxSnapChecks = 20'000'000;

  explicit MutexGroups(const task::GroundTask& task);

  // The groups with two members or more, each sorted.
  const std::vector<std::vector<GroupMember>>& groups() const { return groups_; }
  // True when `a` and `b` (distinct) share a group: never both true.
  bool Mutex(GroupMember a, GroupMember b) const;
  // The groups `m` is in (indices into groups()).
  std::span<const std::int32_t> GroupsOf(GroupMember m) const;
  // Candidates checked (for the statistics and the tests).
  int candidates_checked() const { return candidates_checked_; }

 private:
  std::size_t Slot(GroupMember m) const;

  int num_facts_ = 0;
  std::vector<std::vector<GroupMember>> groups_;
  // Per member slot (facts, then running markers): its groups.
  std::vector<std::int32_t> member_groups_begin_;
  std::vector<std::int32_t> member_groups_;
  int candidates_checked_ = 0;
};

}  // namespace seaplan::search
