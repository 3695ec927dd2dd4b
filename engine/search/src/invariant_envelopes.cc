#include "invariant_envelopes.h"

#include <algorithm>
#include <cmath>

namespace seaplan::search {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool Contains(const std::vector<task::FactId>& v, task::FactId f) {
  return std::find(v.begin(), v.end(), f) != v.end();
}

}  // namespace

double MinDurationBound(const task::Action& action) {
  if (!action.is_durative) return 0.0;
  double lo = 0.0;
  for (const auto& c : action.duration) {
    if (!c.value.IsConstant()) continue;
    const double v = c.value.ConstantValue();
    if (c.comparator == task::Comparator::kEqual ||
        c.comparator == task::Comparator::kGreaterEqual ||
        c.comparator == task::Comparator::kGreater) {
      lo = std::max(lo, v);
    }
  }
  return lo;
}

double MaxDurationBound(const task::Action& action) {
  if (!action.is_durative) return 0.0;
  double hi = kInf;
  for (const auto& c : action.duration) {
    if (!c.value.IsConstant()) continue;
    const double v = c.value.ConstantValue();
    if (c.comparator == task::Comparator::kEqual || c.comparator == task::Comparator::kLessEqual ||
        c.comparator == task::Comparator::kLess) {
      hi = std::min(hi, v);
    }
  }
  return hi;
}

InvariantEnvelopes::InvariantEnvelopes(const task::GroundTask& task) {
  const std::size_t num_actions = task.actions.size();
  const std::size_t num_facts = task.facts.size();
  over_all_.resize(num_actions);
  end_deletes_.resize(num_actions);
  unschedulable_.assign(num_actions, false);
  std::vector<bool> needed_over_all(num_facts, false);
  for (std::size_t a = 0; a < num_actions; ++a) {
    const task::Action& action = task.actions[a];
    if (!action.is_durative) continue;
    over_all_[a] = action.over_all.positive;
    std::sort(over_all_[a].begin(), over_all_[a].end());
    over_all_[a].erase(std::unique(over_all_[a].begin(), over_all_[a].end()), over_all_[a].end());
    for (auto f : over_all_[a]) needed_over_all[f] = true;
  }
  // Facts an end deletes for sure: an unconditional delete that no add of
  // the same end (unconditional or conditional) can undo.
  auto end_surely_deletes = [](const task::Action& action, task::FactId f) {
    if (!Contains(action.end_effects.del, f) || Contains(action.end_effects.add, f)) return false;
    for (const auto& ce : action.end_effects.conditional) {
      if (Contains(ce.add, f)) return false;
    }
    return true;
  };
  for (std::size_t a = 0; a < num_actions; ++a) {
    const task::Action& action = task.actions[a];
    if (!action.is_durative) continue;
    for (auto f : action.end_effects.del) {
      if (needed_over_all[f] && end_surely_deletes(action, f)) end_deletes_[a].push_back(f);
    }
    std::sort(end_deletes_[a].begin(), end_deletes_[a].end());
    end_deletes_[a].erase(std::unique(end_deletes_[a].begin(), end_deletes_[a].end()),
                          end_deletes_[a].end());
  }

  std::vector<bool> end_deleted(num_facts, false);
  for (const auto& dels : end_deletes_) {
    for (auto f : dels) end_deleted[f] = true;
  }
  enclosed_needs_.resize(num_actions);
  for (std::size_t a = 0; a < num_actions; ++a) {
    for (auto f : over_all_[a]) {
      if (end_deleted[f]) enclosed_needs_[a].push_back(f);
    }
  }

  // Longest time each envelope-only fact can hold (-1: not envelope-only).
  std::vector<double> max_hold(num_facts, 0.0);
  auto not_envelope_only = [&](task::FactId f) { max_hold[f] = -1.0; };
  for (auto f : task.initial_facts) not_envelope_only(f);
  for (const auto& til : task.timed_literals) {
    if (til.value) not_envelope_only(til.fact);
  }
  for (std::size_t a = 0; a < num_actions; ++a) {
    const task::Action& action = task.actions[a];
    for (const auto& ce : action.start_effects.conditional) {
      for (auto f : ce.add) not_envelope_only(f);
    }
    for (const auto& ce : action.end_effects.conditional) {
      for (auto f : ce.add) not_envelope_only(f);
    }
    if (!action.is_durative) {
      for (auto f : action.start_effects.add) not_envelope_only(f);
      continue;
    }
    for (auto f : action.end_effects.add) not_envelope_only(f);
    const double max_d = MaxDurationBound(action);
    for (auto f : action.start_effects.add) {
      if (max_hold[f] < 0) continue;
      if (!std::isfinite(max_d) || !end_surely_deletes(action, f)) {
        not_envelope_only(f);
      } else {
        max_hold[f] = std::max(max_hold[f], max_d);
      }
    }
  }
  for (std::size_t a = 0; a < num_actions; ++a) {
    const task::Action& action = task.actions[a];
    if (!action.is_durative) continue;
    const double min_d = MinDurationBound(action);
    for (auto f : over_all_[a]) {
      if (max_hold[f] >= 0 && min_d > max_hold[f] + 1e-9) {
        unschedulable_[a] = true;
        ++num_unschedulable_;
        break;
      }
    }
  }
}

bool InvariantEnvelopes::MustEndWithin(task::ActionId inner, task::ActionId outer) const {
  const auto& dels = end_deletes_[static_cast<std::size_t>(outer)];
  if (dels.empty()) return false;
  const auto& needs = over_all_[static_cast<std::size_t>(inner)];
  // Both sorted and short: a merge walk.
  auto i = needs.begin();
  auto j = dels.begin();
  while (i != needs.end() && j != dels.end()) {
    if (*i < *j) {
      ++i;
    } else if (*j < *i) {
      ++j;
    } else {
      return true;
    }
  }
  return false;
}

}  // namespace seaplan::search
