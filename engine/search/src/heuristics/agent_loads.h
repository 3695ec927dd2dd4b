// Who performs each action, for a makespan-aware relaxed plan.
//
// An FF relaxed plan is chosen to have few actions, not a short makespan:
// when several ships can carry a container, it gives the container to the
// ship the relaxation reaches first, usually the one already working
// nearby, and the search follows it, so one ship does most of the work
// while the others wait. Charging each relaxed-plan action's duration to
// the objects that perform it lets the extraction give a fact to the
// achiever that would finish it first given the work already charged to
// its performer (list scheduling), so the plan's helpful events spread the
// work over the ships.
//
// The performers ("agents") of a durative action are found from the ground
// task alone: the action's arguments that are the first argument of a fact
// of two or more arguments that its start deletes or that it needs over all
// (a ship's position, a container's place or ship). Such facts are held for
// the whole interval, so two actions of one agent cannot overlap. Objects
// only read at the start (a repair team, a port) are not agents.
//
// Immutable after construction; ReadyTimes writes only the caller's vector.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "../snap_task.h"
#include "../state_registry.h"
#include "../timeline.h"

namespace seaplan::search {

class AgentLoads {
 public:
  explicit AgentLoads(const SnapTask& task);

  int num_agents() const { return static_cast<int>(agent_facts_begin_.size()) - 1; }
  // True when work can be spread: at least two agents.
  bool active() const { return num_agents() >= 2; }
  // Agent indices of an action (empty for instantaneous and pruned actions).
  std::span<const std::int32_t> AgentsOf(task::ActionId a) const {
    return {agents_.data() + agents_begin_[static_cast<std::size_t>(a)],
            agents_.data() + agents_begin_[static_cast<std::size_t>(a) + 1]};
  }
  // The duration charged for an action: its constant duration, else 0.
  double DurationOf(task::ActionId a) const { return duration_s_[static_cast<std::size_t>(a)]; }
  // Per agent, the earliest time it is free in `state` on the schedule of
  // the state's path (`schedule` built for it; null: every agent at 0): the
  // latest write or read of a true fact about it, and the earliest end of
  // its running actions. `ready_s` is resized to num_agents().
  void ReadyTimes(const StateData& state, const Timeline* schedule,
                  std::vector<double>* ready_s) const;

 private:
  std::vector<std::int32_t> agents_begin_, agents_;            // CSR per action
  std::vector<std::int32_t> agent_facts_begin_, agent_facts_;  // CSR per agent
  std::vector<double> duration_s_;                             // per action
};

}  // namespace seaplan::search
