#include "transitions.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace seaplan::search {

namespace {
bool AddedAtStart(const task::Action& action, task::FactId f) {
  for (auto g : action.start_effects.add) {
    if (g == f) return true;
  }
  for (const auto& ce : action.start_effects.conditional) {
    for (auto g : ce.add) {
      if (g == f) return true;
    }
  }
  return false;
}
}  // namespace

bool ConditionHolds(const task::Condition& condition, const StateData& state, double duration) {
  for (auto f : condition.positive) {
    if (!state.Holds(f)) return false;
  }
  for (auto f : condition.negative) {
    if (state.Holds(f)) return false;
  }
  for (const auto& n : condition.numeric) {
    auto lhs = n.lhs.Evaluate(state.values, duration);
    auto rhs = n.rhs.Evaluate(state.values, duration);
    if (!lhs || !rhs || std::isnan(*lhs) || std::isnan(*rhs)) return false;
    if (!task::Compare(*lhs, n.comparator, *rhs)) return false;
  }
  return true;
}

Transitions::Transitions(const SnapTask& task, int max_concurrent_actions, double epsilon_s)
    : task_(task), max_concurrent_(max_concurrent_actions), epsilon_s_(epsilon_s) {
  // Facts that must already hold for a start to apply: its at-start
  // conditions and the over-all ones its start effects do not add.
  auto key_candidates = [&](task::ActionId a, std::vector<task::FactId>* out) {
    out->clear();
    const auto& action = task.task().actions[a];
    out->assign(action.at_start.positive.begin(), action.at_start.positive.end());
    if (!action.is_durative) return;
    for (auto f : action.over_all.positive) {
      if (!AddedAtStart(action, f)) out->push_back(f);
    }
  };
  // Index each start under its most selective such fact (the one the fewest
  // starts need), so a state only looks at starts that may apply: with
  // thousands of starts sharing one fact (every pair of pieces baked in a
  // ready kiln) the first fact would make each expansion scan them all.
  std::vector<int> needed_by(static_cast<std::size_t>(task.num_facts()), 0);
  std::vector<task::FactId> keys;
  for (int a = 0; a < task.num_actions(); ++a) {
    key_candidates(a, &keys);
    for (auto f : keys) ++needed_by[f];
  }
  // (key, second, action) of every start with a key, sorted into groups.
  struct Entry {
    task::FactId key, second;
    task::ActionId action;
  };
  std::vector<Entry> entries;
  for (int a = 0; a < task.num_actions(); ++a) {
    if (task.Pruned(a)) continue;  // no plan needs it
    key_candidates(a, &keys);
    task::FactId key = -1, second = -1;
    for (auto f : keys) {
      if (key < 0 || needed_by[f] < needed_by[key]) key = f;
    }
    for (auto f : keys) {
      if (f != key && (second < 0 || needed_by[f] < needed_by[second])) second = f;
    }
    if (key < 0) {
      without_fact_pre_.push_back(a);
    } else {
      entries.push_back({key, second, a});
    }
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) {
    if (x.key != y.key) return x.key < y.key;
    if (x.second != y.second) return x.second < y.second;
    return x.action < y.action;
  });
  key_group_begin_.assign(static_cast<std::size_t>(task.num_facts()) + 1, 0);
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const Entry& e = entries[i];
    if (i == 0 || e.key != entries[i - 1].key || e.second != entries[i - 1].second) {
      ++key_group_begin_[static_cast<std::size_t>(e.key) + 1];
      const auto at = static_cast<std::int32_t>(group_actions_.size());
      key_groups_.push_back({e.second, at, at});
    }
    group_actions_.push_back(e.action);
    ++key_groups_.back().end;
  }
  for (std::size_t f = 0; f + 1 < key_group_begin_.size(); ++f) {
    key_group_begin_[f + 1] += key_group_begin_[f];
  }
}

void Transitions::Candidates(const StateData& state, std::vector<Event>* out) const {
  // Ends first: closing running actions is usually what is needed.
  for (const auto& r : state.running) {
    out->push_back({2 * r.action + 1, r.min_duration_s, r.max_duration_s});
  }
  if (max_concurrent_ <= 0 || static_cast<int>(state.running.size()) < max_concurrent_) {
    auto consider = [&](task::ActionId a) {
      const auto& action = task_.task().actions[a];
      if (!ConditionHolds(action.at_start, state)) return;
      for (auto f : action.over_all.positive) {
        // Cheap filter; Apply does the exact check after the start effects.
        if (!state.Holds(f) && !AddedAtStart(action, f)) return;
      }
      out->push_back({2 * a, 0.0, 0.0});
    };
    for (std::size_t w = 0; w < state.facts.size(); ++w) {
      std::uint64_t bits = state.facts[w];
      while (bits) {
        const int b = std::countr_zero(bits);
        bits &= bits - 1;
        const auto f = static_cast<std::size_t>(w * 64 + static_cast<std::size_t>(b));
        const std::size_t first = out->size();
        const int groups_end = key_group_begin_[f + 1];
        for (int g = key_group_begin_[f]; g < groups_end; ++g) {
          const StartGroup& group = key_groups_[static_cast<std::size_t>(g)];
          if (group.second >= 0 && !state.Holds(group.second)) continue;
          for (int i = group.begin; i < group.end; ++i) {
            consider(group_actions_[static_cast<std::size_t>(i)]);
          }
        }
        // In action order within a key, whatever the groups: the search
        // shuffles candidates with a seeded generator, so their order is
        // part of what it finds.
        if (out->size() - first > 1 && key_group_begin_[f + 1] - key_group_begin_[f] > 1) {
          std::sort(out->begin() + static_cast<std::ptrdiff_t>(first), out->end(),
                    [](const Event& x, const Event& y) { return x.snap < y.snap; });
        }
      }
    }
    for (auto a : without_fact_pre_) consider(a);
  }
  if (state.next_til < static_cast<int>(task_.tils().size())) {
    out->push_back({~state.next_til, 0.0, 0.0});
  }
}

bool Transitions::DurationWindow(task::ActionId a, const StateData& state, double* min_d,
                                 double* max_d) const {
  const auto& action = task_.task().actions[a];
  double lo = 0.0, hi = kInfinity;
  for (const auto& c : action.duration) {
    auto v = c.value.Evaluate(state.values);
    if (!v || std::isnan(*v)) return false;
    switch (c.comparator) {
      case task::Comparator::kEqual:
        lo = std::max(lo, *v);
        hi = std::min(hi, *v);
        break;
      case task::Comparator::kGreaterEqual:
        lo = std::max(lo, *v);
        break;
      case task::Comparator::kGreater:
        lo = std::max(lo, *v + epsilon_s_);
        break;
      case task::Comparator::kLessEqual:
        hi = std::min(hi, *v);
        break;
      case task::Comparator::kLess:
        hi = std::min(hi, *v - epsilon_s_);
        break;
    }
  }
  // A durative action needs a positive duration (validator); one whose
  // window allows only 0 (zenotravel's zoom from a city to itself) could
  // never end: a trap for the search, not a step.
  if (lo > hi + 1e-9 || hi <= 0) return false;
  if (task_.EffectsReadDuration(a) ||
      action.over_all.numeric.size() + action.at_end.numeric.size() > 0) {
    // One concrete value keeps effects and conditions that read ?duration exact.
    hi = lo;
  }
  *min_d = lo;
  *max_d = hi;
  return true;
}

void Transitions::ApplyEffects(const task::Effects& effects, const StateData& before,
                               double duration, StateData* next) const {
  // Conditional effects read the state before the event.
  for (const auto& ce : effects.conditional) {
    if (!ConditionHolds(ce.condition, before, duration)) continue;
    for (auto f : ce.del) next->Clear(f);
  }
  for (auto f : effects.del) next->Clear(f);
  for (auto f : effects.add) next->Set(f);
  for (const auto& ce : effects.conditional) {
    if (!ConditionHolds(ce.condition, before, duration)) continue;
    for (auto f : ce.add) next->Set(f);
  }
  auto apply_numeric = [&](const task::NumericEffect& e) {
    auto v = e.value.Evaluate(before.values, duration);
    next->values[e.var] =
        v ? task::ApplyAssign(e.op, next->values[e.var], *v) : task::NumericExpr::kUndefined;
  };
  for (const auto& e : effects.numeric) apply_numeric(e);
  for (const auto& ce : effects.conditional) {
    if (!ConditionHolds(ce.condition, before, duration)) continue;
    for (const auto& e : ce.numeric) apply_numeric(e);
  }
}

bool Transitions::RunningInvariantsHold(const StateData& state) const {
  for (const auto& r : state.running) {
    if (!ConditionHolds(task_.task().actions[r.action].over_all, state, r.min_duration_s))
      return false;
  }
  return true;
}

bool Transitions::Apply(const StateData& state, Event* event, StateData* next) const {
  if (event->is_til()) {
    const TilEvent& til = task_.tils()[static_cast<std::size_t>(event->til())];
    *next = state;
    next->variant = 0;
    for (auto f : til.del) next->Clear(f);
    for (auto f : til.add) next->Set(f);
    for (const auto& [v, value] : til.assign) next->values[v] = value;
    next->next_til = state.next_til + 1;
    return RunningInvariantsHold(*next);
  }
  const SnapAction& snap = task_.snap(event->snap);
  const task::ActionId a = snap.action;
  const auto& action = task_.task().actions[a];
  const auto running_it = state.FindRunning(a);
  const bool is_running = running_it != state.running.end() && running_it->action == a;
  if (!snap.is_end) {
    if (is_running) return false;  // no self-overlap
    // Refused before the state is copied: it depends on the running set only.
    const InvariantEnvelopes& envelopes = task_.envelopes();
    if (envelopes.IsEnvelope(a)) {
      for (const auto& r : state.running) {
        if (envelopes.MustEndWithin(r.action, a) && envelopes.MustEndWithin(a, r.action))
          return false;
      }
    }
    if (!ConditionHolds(action.at_start, state)) return false;
    double min_d = 0.0, max_d = 0.0;
    if (action.is_durative && !DurationWindow(a, state, &min_d, &max_d)) return false;
    event->min_duration_s = min_d;
    event->max_duration_s = max_d;
    *next = state;
    next->variant = 0;
    ApplyEffects(action.start_effects, state, min_d, next);
    if (action.is_durative) {
      if (!ConditionHolds(action.over_all, *next, min_d)) return false;
      const auto offset = running_it - state.running.begin();
      next->running.insert(next->running.begin() + offset, RunningAction{a, min_d, max_d});
    }
    return RunningInvariantsHold(*next);
  }
  if (!is_running) return false;
  const double duration = running_it->min_duration_s;
  if (!ConditionHolds(action.at_end, state, duration)) return false;
  if (!ConditionHolds(action.over_all, state, duration)) return false;
  event->min_duration_s = running_it->min_duration_s;
  event->max_duration_s = running_it->max_duration_s;
  *next = state;
  next->variant = 0;
  next->running.erase(next->running.begin() + (running_it - state.running.begin()));
  ApplyEffects(action.end_effects, state, duration, next);
  return RunningInvariantsHold(*next);
}

bool Transitions::IsGoal(const StateData& state) const {
  if (!state.running.empty()) return false;
  if (!ConditionHolds(task_.task().goal, state)) return false;
  // PDDL 2.2: the goal must still hold after the remaining timed literals.
  const auto& tils = task_.tils();
  for (std::size_t k = static_cast<std::size_t>(state.next_til); k < tils.size(); ++k) {
    for (auto f : tils[k].writes) {
      if (task_.goal_fact_mask()[f]) return false;
    }
    if (!tils[k].num_writes.empty() && !task_.task().goal.numeric.empty()) return false;
  }
  return true;
}

}  // namespace seaplan::search
