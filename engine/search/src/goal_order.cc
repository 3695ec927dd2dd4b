#include "goal_order.h"

#include <algorithm>

namespace seaplan::search {
namespace {

// What an action needs true at its start.
std::vector<task::FactId> StartNeeds(const task::Action& a) {
  std::vector<task::FactId> out = a.at_start.positive;
  out.insert(out.end(), a.over_all.positive.begin(), a.over_all.positive.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

bool AnyMutex(const MutexGroups& mutex, const std::vector<task::FactId>& needs, GroupMember m) {
  for (auto f : needs) {
    if (mutex.Mutex(f, m)) return true;
  }
  return false;
}

bool Contains(const std::vector<task::FactId>& v, task::FactId f) {
  return std::find(v.begin(), v.end(), f) != v.end();
}

// Per fact: `deleted` when an action, a conditional effect or a timed
// literal deletes it; `unsafe` when something else than an action's plain
// effect adds it (a timed literal, a conditional effect). A goal is watched
// only when neither.
struct FactChanges {
  std::vector<std::uint8_t> deleted, unsafe;
};

FactChanges ChangesOf(const task::GroundTask& task) {
  FactChanges c;
  c.deleted.assign(task.facts.size(), 0);
  c.unsafe.assign(task.facts.size(), 0);
  for (const auto& a : task.actions) {
    for (const task::Effects* e : {&a.start_effects, &a.end_effects}) {
      for (auto f : e->del) c.deleted[static_cast<std::size_t>(f)] = 1;
      for (const auto& ce : e->conditional) {
        for (auto f : ce.del) c.deleted[static_cast<std::size_t>(f)] = 1;
        for (auto f : ce.add) c.unsafe[static_cast<std::size_t>(f)] = 1;
      }
    }
  }
  for (const auto& til : task.timed_literals) {
    (til.value ? c.unsafe : c.deleted)[static_cast<std::size_t>(til.fact)] = 1;
  }
  return c;
}

bool Watchable(const FactChanges& c, task::FactId g) {
  return !c.deleted[static_cast<std::size_t>(g)] && !c.unsafe[static_cast<std::size_t>(g)];
}

}  // namespace

std::size_t GoalOrderDeadEnds::NumWatchableGoals(const task::GroundTask& task) {
  const FactChanges changes = ChangesOf(task);
  std::vector<task::FactId> goals;
  for (auto g : task.goal.positive) {
    if (Watchable(changes, g)) goals.push_back(g);
  }
  std::sort(goals.begin(), goals.end());
  return static_cast<std::size_t>(std::unique(goals.begin(), goals.end()) - goals.begin());
}

GoalOrderDeadEnds::GoalOrderDeadEnds(const task::GroundTask& task, const MutexGroups& mutex) {
  if (mutex.groups().empty()) return;
  const FactChanges changes = ChangesOf(task);
  const auto permanent = [&](task::FactId f) {
    return !changes.deleted[static_cast<std::size_t>(f)];
  };
  std::vector<std::vector<task::FactId>> needs;
  std::vector<std::uint8_t> adds_at_end;
  for (auto g : task.goal.positive) {
    if (!Watchable(changes, g)) continue;
    Goal goal;
    goal.fact = g;
    for (task::ActionId a = 0; a < static_cast<task::ActionId>(task.actions.size()); ++a) {
      const task::Action& action = task.actions[static_cast<std::size_t>(a)];
      const bool at_start = Contains(action.start_effects.add, g);
      const bool at_end = Contains(action.end_effects.add, g);
      if (!at_start && !at_end) continue;
      Achiever achiever;
      achiever.action = a;
      std::vector<task::FactId> need = StartNeeds(action);
      for (auto r : need) {
        for (auto group : mutex.GroupsOf(r)) {
          for (GroupMember m : mutex.groups()[static_cast<std::size_t>(group)]) {
            if (!IsRunningMember(m) && m != r && permanent(m)) achiever.killers.push_back(m);
          }
        }
      }
      std::sort(achiever.killers.begin(), achiever.killers.end());
      achiever.killers.erase(std::unique(achiever.killers.begin(), achiever.killers.end()),
                             achiever.killers.end());
      goal.achievers.push_back(static_cast<std::int32_t>(achievers_.size()));
      achievers_.push_back(std::move(achiever));
      needs.push_back(std::move(need));
      adds_at_end.push_back(at_end && !at_start && action.is_durative);
    }
    goals_.push_back(std::move(goal));
  }
  if (achievers_.size() * goals_.size() > kMaxPairChecks) {
    goals_.clear();
    achievers_.clear();
    return;
  }
  // a must start before goal j is started: what a needs at its start is
  // ruled out by j's fact and, while an achiever of j runs, by its running.
  for (std::size_t a = 0; a < achievers_.size(); ++a) {
    for (std::size_t j = 0; j < goals_.size(); ++j) {
      const Goal& g = goals_[j];
      // An action that also achieves j starts both goals at once: no order.
      const task::ActionId action = achievers_[a].action;
      if (std::any_of(g.achievers.begin(), g.achievers.end(), [&](std::int32_t b) {
            return achievers_[static_cast<std::size_t>(b)].action == action;
          }))
        continue;
      if (!AnyMutex(mutex, needs[a], g.fact)) continue;
      bool shut = true;
      for (auto b : g.achievers) {
        if (adds_at_end[static_cast<std::size_t>(b)] &&
            !AnyMutex(mutex, needs[a],
                      RunningMember(achievers_[static_cast<std::size_t>(b)].action))) {
          shut = false;
          break;
        }
      }
      if (!shut) continue;
      achievers_[a].before.push_back(static_cast<std::int32_t>(j));
      active_ = true;
    }
  }
  // One achiever of each class is enough for the check (it reads their
  // killers and `before` goals only); the actions stay, for `pending`.
  std::vector<Achiever> classes;
  for (Goal& goal : goals_) {
    std::vector<std::int32_t> kept;
    for (auto a : goal.achievers) {
      Achiever& achiever = achievers_[static_cast<std::size_t>(a)];
      goal.actions.push_back(achiever.action);
      const bool seen = std::any_of(kept.begin(), kept.end(), [&](std::int32_t k) {
        const Achiever& other = classes[static_cast<std::size_t>(k)];
        return other.killers == achiever.killers && other.before == achiever.before;
      });
      if (seen) continue;
      kept.push_back(static_cast<std::int32_t>(classes.size()));
      classes.push_back(std::move(achiever));
    }
    goal.achievers = std::move(kept);
  }
  achievers_ = std::move(classes);
  pending_.assign(goals_.size(), 0);
  live_.assign(achievers_.size(), 0);
}

bool GoalOrderDeadEnds::Live(const Achiever& a, const StateData& state) const {
  for (auto k : a.killers) {
    if (state.Holds(k)) return false;
  }
  return true;
}

bool GoalOrderDeadEnds::DeadEnd(const StateData& state) const {
  // Pending: false, with no achiever running (one running is on its way).
  const auto pending = [&](std::size_t j) {
    if (pending_[j] == 0) {
      bool p = !state.Holds(goals_[j].fact);
      for (auto a : goals_[j].actions) {
        if (!p) break;
        if (state.IsRunning(a)) p = false;
      }
      pending_[j] = p ? 1 : 2;
    }
    return pending_[j] == 1;
  };
  const auto live = [&](std::int32_t a) {
    auto& known = live_[static_cast<std::size_t>(a)];
    if (known == 0) known = Live(achievers_[static_cast<std::size_t>(a)], state) ? 1 : 2;
    return known == 1;
  };
  // Goal j must precede goal g: every achiever of j that can still start
  // must start before g.
  const auto must_precede = [&](std::size_t j, std::int32_t g) {
    for (auto a : goals_[j].achievers) {
      const Achiever& achiever = achievers_[static_cast<std::size_t>(a)];
      if (!live(a)) continue;
      if (std::find(achiever.before.begin(), achiever.before.end(), g) == achiever.before.end())
        return false;
    }
    return true;
  };
  std::fill(pending_.begin(), pending_.end(), 0);
  std::fill(live_.begin(), live_.end(), 0);
  // An achiever that must start before a goal that must precede its own
  // can never be the first to reach its goal. Dropping it may make more
  // goals precede others (fewer achievers left to order), so repeat until
  // nothing changes: a run of four or more tiles shows itself only then.
  bool dropped = true;
  while (dropped) {
    dropped = false;
    for (std::size_t g = 0; g < goals_.size(); ++g) {
      if (!pending(g)) continue;
      bool reachable = false;
      for (auto a : goals_[g].achievers) {
        if (!live(a)) continue;
        const Achiever& achiever = achievers_[static_cast<std::size_t>(a)];
        const bool blocked =
            std::any_of(achiever.before.begin(), achiever.before.end(), [&](std::int32_t j) {
              return pending(static_cast<std::size_t>(j)) &&
                     must_precede(static_cast<std::size_t>(j), static_cast<std::int32_t>(g));
            });
        if (blocked) {
          live_[static_cast<std::size_t>(a)] = 2;
          dropped = true;
        } else {
          reachable = true;
        }
      }
      if (!reachable) return true;
    }
  }
  return false;
}

}  // namespace seaplan::search
