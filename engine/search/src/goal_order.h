// Dead ends that only the order of goals shows. A goal fact nothing deletes
// stays true once reached, and the facts in a mutex group with it
// (mutex_groups.h) stay false from then on. An achiever of goal g that needs,
// at its start, a fact goal g' rules out (and, while an achiever of g' runs,
// one that its running rules out) must start before g' is started: g' is in
// its `before` set. Goal g' must precede g when every achiever of g' that can
// still start has g in its `before` set. An achiever that must start
// before a goal that must precede its own can never be the first to reach
// its goal, so it is dropped, and the orders are found again among the
// achievers left, until nothing changes. A state is a dead end when some
// pending goal g has no achiever left (floortile: a run of tiles in a
// column, each paintable only from another of them or from the tile
// painted at its end). The delete relaxation does not see these dead ends.
//
// Sound for the search's model of states (events one at a time, the running
// actions part of the state): a state it calls a dead end has no path to the
// goal. Goals a timed literal or a conditional effect adds are left out.
#pragma once

#include <cstdint>
#include <vector>

#include "mutex_groups.h"
#include "state_registry.h"

namespace seaplan::search {

class GoalOrderDeadEnds {
 public:
  // Above this many (achiever, goal) checks at construction, it stays off.
  static constexpr std::size_t kMaxPairChecks = 5'000'000;

  GoalOrderDeadEnds(const task::GroundTask& task, const MutexGroups& mutex);

  // The distinct goals it would watch (nothing deletes them, only actions
  // add them), without the mutex groups: with fewer than two there is no
  // order to find, and the planner does not build the check.
  static std::size_t NumWatchableGoals(const task::GroundTask& task);

  // False when no achiever has a `before` goal: nothing to check.
  bool active() const { return active_; }
  // Goals watched (nothing deletes them, only actions add them).
  std::size_t num_goals() const { return goals_.size(); }
  bool DeadEnd(const StateData& state) const;

 private:
  struct Achiever {
    task::ActionId action = -1;
    std::vector<task::FactId> killers;  // permanent facts ruling out its start
    std::vector<std::int32_t> before;   // goals (indices) it must start before
  };
  struct Goal {
    task::FactId fact = -1;
    // Indices into achievers_: one per class of achievers with the same
    // killers and `before` goals (floortile: a paint by any robot in any
    // colour), which the check cannot tell apart.
    std::vector<std::int32_t> achievers;
    std::vector<task::ActionId> actions;  // every achiever: one running, the goal is on its way
  };

  bool Live(const Achiever& a, const StateData& state) const;

  std::vector<Achiever> achievers_;
  std::vector<Goal> goals_;
  bool active_ = false;
  // Scratch for DeadEnd, so one object serves one search at a time: per
  // goal 0 unknown, 1 pending, 2 not; per achiever 0 unknown, 1 live, 2 not.
  mutable std::vector<std::uint8_t> pending_, live_;
};

}  // namespace seaplan::search
