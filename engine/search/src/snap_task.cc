#include "snap_task.h"

#include <algorithm>

#include "relevance.h"

namespace seaplan::search {
namespace {

void SortUnique(std::vector<std::int32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

void AddExprReads(const task::NumericExpr& expr, std::vector<task::NumericVarId>& out) {
  for (const auto& node : expr.nodes) {
    if (node.op == task::NumericExpr::Op::kVariable) out.push_back(node.var);
  }
}

void AddConditionReads(const task::Condition& c, SnapAction& s) {
  s.reads.insert(s.reads.end(), c.positive.begin(), c.positive.end());
  s.reads.insert(s.reads.end(), c.negative.begin(), c.negative.end());
  for (const auto& n : c.numeric) {
    AddExprReads(n.lhs, s.num_reads);
    AddExprReads(n.rhs, s.num_reads);
  }
}

void AddNumericEffects(const std::vector<task::NumericEffect>& effects, SnapAction& s) {
  for (const auto& e : effects) {
    s.num_writes.push_back(e.var);
    AddExprReads(e.value, s.num_reads);
    // increase/decrease read their target too; mutex rules order them anyway.
  }
}

void AddEffects(const task::Effects& e, SnapAction& s) {
  s.writes.insert(s.writes.end(), e.add.begin(), e.add.end());
  s.writes.insert(s.writes.end(), e.del.begin(), e.del.end());
  AddNumericEffects(e.numeric, s);
  for (const auto& ce : e.conditional) {
    AddConditionReads(ce.condition, s);
    s.writes.insert(s.writes.end(), ce.add.begin(), ce.add.end());
    s.writes.insert(s.writes.end(), ce.del.begin(), ce.del.end());
    AddNumericEffects(ce.numeric, s);
  }
}

bool AnyEffectReadsDuration(const task::Effects& e) {
  for (const auto& n : e.numeric) {
    if (n.value.ReadsDuration()) return true;
  }
  for (const auto& ce : e.conditional) {
    for (const auto& n : ce.numeric) {
      if (n.value.ReadsDuration()) return true;
    }
  }
  return false;
}

// See SnapTask::EagerEnd.
std::vector<bool> EagerEndActions(const task::GroundTask& task) {
  // Facts some condition asks false, a timed literal writes, or an event
  // deletes without asking for them: an end adding one of them may matter
  // for when it happens.
  std::vector<bool> order_matters(task.facts.size(), false);
  auto negated = [&](const task::Condition& c) {
    for (auto f : c.negative) order_matters[f] = true;
  };
  auto deleted = [&](const task::Effects& e, const task::Condition& c) {
    for (auto f : e.del) {
      if (std::find(c.positive.begin(), c.positive.end(), f) == c.positive.end())
        order_matters[f] = true;
    }
    for (const auto& ce : e.conditional) {
      negated(ce.condition);
      for (auto f : ce.del) order_matters[f] = true;
    }
  };
  negated(task.goal);
  for (const auto& action : task.actions) {
    for (const auto* c : {&action.at_start, &action.over_all, &action.at_end}) negated(*c);
    deleted(action.start_effects, action.at_start);
    deleted(action.end_effects, action.at_end);
  }
  for (const auto& til : task.timed_literals) order_matters[til.fact] = true;
  std::vector<bool> eager(task.actions.size(), false);
  for (std::size_t a = 0; a < task.actions.size(); ++a) {
    const task::Action& action = task.actions[a];
    const task::Effects& e = action.end_effects;
    // No at-end condition and no delete: never a window action either.
    if (!action.is_durative || !action.at_end.empty() || !e.del.empty() || !e.numeric.empty() ||
        !e.conditional.empty())
      continue;
    eager[a] =
        std::none_of(e.add.begin(), e.add.end(), [&](task::FactId f) { return order_matters[f]; });
  }
  return eager;
}

}  // namespace

SnapTask::SnapTask(const task::GroundTask& task) : task_(task), envelopes_(task) {
  const std::size_t n = task.actions.size();
  snaps_.resize(2 * n);
  effects_read_duration_.resize(n, false);
  for (std::size_t a = 0; a < n; ++a) {
    const task::Action& action = task.actions[a];
    SnapAction& start = snaps_[2 * a];
    start.action = static_cast<task::ActionId>(a);
    start.is_end = false;
    start.condition = &action.at_start;
    start.effects = &action.start_effects;
    AddConditionReads(action.at_start, start);
    for (const auto& d : action.duration) AddExprReads(d.value, start.num_reads);
    AddEffects(action.start_effects, start);
    SnapAction& end = snaps_[2 * a + 1];
    end.action = static_cast<task::ActionId>(a);
    end.is_end = true;
    end.condition = &action.at_end;
    end.effects = &action.end_effects;
    AddConditionReads(action.at_end, end);
    AddEffects(action.end_effects, end);
    if (action.is_durative) {
      // Over-all conditions belong to neither snap action (validator / VAL):
      // kept apart so the schedule orders them with zero, not epsilon, gaps.
      SnapAction inv;
      AddConditionReads(action.over_all, inv);
      start.inv_reads = end.inv_reads = inv.reads;
      start.inv_num_reads = end.inv_num_reads = inv.num_reads;
    }
    for (SnapAction* s : {&start, &end}) {
      SortUnique(s->inv_reads);
      SortUnique(s->inv_num_reads);
      SortUnique(s->reads);
      SortUnique(s->writes);
      SortUnique(s->num_reads);
      SortUnique(s->num_writes);
    }
    {
      bool window = !action.at_end.empty();
      for (auto f : action.end_effects.del) {
        if (std::find(action.start_effects.add.begin(), action.start_effects.add.end(), f) !=
            action.start_effects.add.end()) {
          window = true;
        }
      }
      window_action_.push_back(action.is_durative && window);
    }
    effects_read_duration_[a] =
        AnyEffectReadsDuration(action.start_effects) || AnyEffectReadsDuration(action.end_effects);
  }

  // Timed literals and fluents at one instant form one event.
  std::vector<double> times;
  for (const auto& til : task.timed_literals) times.push_back(til.time_s);
  for (const auto& tif : task.timed_fluents) times.push_back(tif.time_s);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  tils_.resize(times.size());
  for (std::size_t i = 0; i < times.size(); ++i) tils_[i].time_s = times[i];
  auto index_of = [&](double t) {
    return static_cast<std::size_t>(std::lower_bound(times.begin(), times.end(), t) -
                                    times.begin());
  };
  for (const auto& til : task.timed_literals) {
    TilEvent& ev = tils_[index_of(til.time_s)];
    (til.value ? ev.add : ev.del).push_back(til.fact);
    ev.writes.push_back(til.fact);
  }
  for (const auto& tif : task.timed_fluents) {
    TilEvent& ev = tils_[index_of(tif.time_s)];
    ev.assign.emplace_back(tif.var, tif.value);
    ev.num_writes.push_back(tif.var);
  }
  tils_by_fact_.resize(task.facts.size());
  tils_by_var_.resize(task.numeric_vars.size());
  for (std::size_t i = 0; i < tils_.size(); ++i) {
    SortUnique(tils_[i].writes);
    SortUnique(tils_[i].num_writes);
    for (auto f : tils_[i].writes) tils_by_fact_[f].push_back(static_cast<int>(i));
    for (auto v : tils_[i].num_writes) tils_by_var_[v].push_back(static_cast<int>(i));
  }
  pruned_ = RelevantActions(task);
  for (std::size_t a = 0; a < n; ++a) {
    pruned_[a] = !pruned_[a] || envelopes_.Unschedulable(static_cast<task::ActionId>(a));
  }
  const std::vector<bool> breaks_goal = GoalBreakingActions(task, pruned_);
  for (std::size_t a = 0; a < n; ++a) {
    if (!breaks_goal[a]) continue;
    pruned_[a] = true;
    ++num_goal_breaking_;
  }
  eager_end_ = EagerEndActions(task);
  goal_fact_mask_.assign(task.facts.size(), false);
  for (auto f : task.goal.positive) goal_fact_mask_[f] = true;
  for (auto f : task.goal.negative) goal_fact_mask_[f] = true;
}

}  // namespace seaplan::search
