#include "relevance.h"

namespace seaplan::search {
namespace {

void AddExprVars(const task::NumericExpr& expr, std::vector<bool>& vars) {
  for (const auto& node : expr.nodes) {
    if (node.op == task::NumericExpr::Op::kVariable)
      vars[static_cast<std::size_t>(node.var)] = true;
  }
}

}  // namespace

std::vector<bool> RelevantActions(const task::GroundTask& task) {
  const std::size_t num_facts = task.facts.size();
  std::vector<bool> need_true(num_facts, false), need_false(num_facts, false);
  std::vector<bool> read_var(task.numeric_vars.size(), false);
  auto add_condition = [&](const task::Condition& c) {
    for (auto f : c.positive) need_true[static_cast<std::size_t>(f)] = true;
    for (auto f : c.negative) need_false[static_cast<std::size_t>(f)] = true;
    for (const auto& n : c.numeric) {
      AddExprVars(n.lhs, read_var);
      AddExprVars(n.rhs, read_var);
    }
  };
  add_condition(task.goal);
  AddExprVars(task.metric.expression, read_var);

  auto effects_matter = [&](const task::Effects& e) {
    auto any = [](const std::vector<task::FactId>& facts, const std::vector<bool>& mask) {
      for (auto f : facts) {
        if (mask[static_cast<std::size_t>(f)]) return true;
      }
      return false;
    };
    auto numeric = [&](const std::vector<task::NumericEffect>& effects) {
      for (const auto& n : effects) {
        if (read_var[static_cast<std::size_t>(n.var)]) return true;
      }
      return false;
    };
    if (any(e.add, need_true) || any(e.del, need_false) || numeric(e.numeric)) return true;
    for (const auto& ce : e.conditional) {
      if (any(ce.add, need_true) || any(ce.del, need_false) || numeric(ce.numeric)) return true;
    }
    return false;
  };
  auto mark_reads = [&](const task::Action& a) {
    add_condition(a.at_start);
    add_condition(a.over_all);
    add_condition(a.at_end);
    for (const auto& d : a.duration) AddExprVars(d.value, read_var);
    for (const task::Effects* e : {&a.start_effects, &a.end_effects}) {
      for (const auto& n : e->numeric) AddExprVars(n.value, read_var);
      for (const auto& ce : e->conditional) {
        add_condition(ce.condition);
        for (const auto& n : ce.numeric) AddExprVars(n.value, read_var);
      }
    }
  };

  std::vector<bool> relevant(task.actions.size(), false);
  // Simple fixpoint: few rounds in practice (one per level of the goal's
  // regression), each linear in the task.
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t a = 0; a < task.actions.size(); ++a) {
      if (relevant[a]) continue;
      const task::Action& action = task.actions[a];
      if (!effects_matter(action.start_effects) && !effects_matter(action.end_effects)) continue;
      relevant[a] = true;
      mark_reads(action);
      changed = true;
    }
  }
  return relevant;
}

std::vector<bool> GoalBreakingActions(const task::GroundTask& task,
                                      const std::vector<bool>& excluded) {
  const std::size_t num_facts = task.facts.size();
  std::vector<bool> goal_true(num_facts, false), goal_false(num_facts, false);
  for (auto f : task.goal.positive) goal_true[static_cast<std::size_t>(f)] = true;
  for (auto f : task.goal.negative) goal_false[static_cast<std::size_t>(f)] = true;
  // Whether a timed literal makes each fact true or false at some point.
  std::vector<bool> til_adds(num_facts, false), til_dels(num_facts, false);
  for (const auto& til : task.timed_literals) {
    (til.value ? til_adds : til_dels)[static_cast<std::size_t>(til.fact)] = true;
  }
  std::vector<bool> breaks(task.actions.size(), false);
  auto out = [&](std::size_t a) { return breaks[a] || (!excluded.empty() && excluded[a]); };
  for (bool changed = true; changed;) {
    changed = false;
    // Adders and deleters among the actions still in, any effect kind.
    std::vector<bool> added = til_adds, deleted = til_dels;
    for (std::size_t a = 0; a < task.actions.size(); ++a) {
      if (out(a)) continue;
      for (const task::Effects* e :
           {&task.actions[a].start_effects, &task.actions[a].end_effects}) {
        for (auto f : e->add) added[static_cast<std::size_t>(f)] = true;
        for (auto f : e->del) deleted[static_cast<std::size_t>(f)] = true;
        for (const auto& ce : e->conditional) {
          for (auto f : ce.add) added[static_cast<std::size_t>(f)] = true;
          for (auto f : ce.del) deleted[static_cast<std::size_t>(f)] = true;
        }
      }
    }
    for (std::size_t a = 0; a < task.actions.size(); ++a) {
      if (out(a)) continue;
      bool broken = false;
      for (const task::Effects* e :
           {&task.actions[a].start_effects, &task.actions[a].end_effects}) {
        for (auto f : e->del) {
          const auto i = static_cast<std::size_t>(f);
          if (goal_true[i] && !added[i]) broken = true;
        }
        for (auto f : e->add) {
          const auto i = static_cast<std::size_t>(f);
          if (goal_false[i] && !deleted[i]) broken = true;
        }
      }
      if (broken) {
        breaks[a] = true;
        changed = true;
      }
    }
  }
  return breaks;
}

}  // namespace seaplan::search
