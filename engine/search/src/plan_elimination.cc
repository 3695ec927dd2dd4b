#include "plan_elimination.h"

#include <algorithm>
#include <utility>

namespace seaplan::search {

std::vector<Event> EliminateRedundantSteps(const Transitions& transitions, const StateData& initial,
                                           std::span<const Event> events,
                                           std::size_t max_replayed) {
  std::vector<Event> kept(events.begin(), events.end());
  // states[k]: the state before kept[k] (states[kept.size()] the last one).
  std::vector<StateData> states(kept.size() + 1);
  // Replays kept[from...] from states[from] (the states before it stand).
  auto replay_from = [&](std::size_t from) {
    states.resize(kept.size() + 1);
    for (std::size_t k = from; k < kept.size(); ++k) {
      if (!transitions.Apply(states[k], &kept[k], &states[k + 1])) return false;
    }
    return true;
  };
  // Not a plan from `initial`: left as it is.
  states[0] = initial;
  if (!replay_from(0) || !transitions.IsGoal(states.back())) return kept;

  std::vector<char> dropped;
  std::vector<task::ActionId> open_drops;  // dropped starts whose end is still ahead
  StateData state, next;
  std::size_t replayed = 0;
  std::size_t i = 0;
  while (i < kept.size()) {
    const Event& step = kept[i];
    if (step.is_til() || (step.snap & 1) != 0) {  // ends go with their starts
      ++i;
      continue;
    }
    if (replayed + (kept.size() - i) > max_replayed) break;
    // Try the plan without the step started at i: replay from the state
    // before it, dropping what no longer applies.
    dropped.assign(kept.size(), 0);
    dropped[i] = 1;
    open_drops.assign(1, step.snap >> 1);
    state = states[i];
    bool ok = true;
    for (std::size_t k = i + 1; k < kept.size() && ok; ++k) {
      ++replayed;
      Event e = kept[k];
      const bool is_end = !e.is_til() && (e.snap & 1) != 0;
      if (is_end) {
        // The first end of a dropped start's action after it is its own.
        auto it = std::find(open_drops.begin(), open_drops.end(), e.snap >> 1);
        if (it != open_drops.end()) {
          open_drops.erase(it);
          dropped[k] = 1;
          continue;
        }
      }
      if (transitions.Apply(state, &e, &next)) {
        std::swap(state, next);
        continue;
      }
      if (e.is_til() || is_end) {
        ok = false;  // a timed literal or a running action's end must stay
      } else {
        dropped[k] = 1;
        open_drops.push_back(e.snap >> 1);
      }
    }
    if (!ok || !transitions.IsGoal(state)) {
      ++i;
      continue;
    }
    std::size_t out = 0;
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (dropped[k] == 0) kept[out++] = kept[k];
    }
    kept.resize(out);
    // The states after i changed, and so may the duration bounds of the
    // starts after it: replay from i (it cannot fail, the try just did it).
    // The event now at i is tried next.
    replay_from(i);
  }
  return kept;
}

}  // namespace seaplan::search
