// Test-only: builds small GroundTasks by hand, naming facts and variables by
// their display text ("(at ship0 port-a)"), so validator tests read like PDDL.
#pragma once

#include <map>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "absl/strings/str_split.h"
#include "seaplan/task/ground_task.h"

namespace seaplan::validate::testing {

using task::Action;
using task::NumericExpr;

// "(p a b)" -> {"p", {"a", "b"}}
inline std::pair<std::string, std::vector<std::string>> SplitAtom(std::string_view text) {
  if (!text.empty() && text.front() == '(') text.remove_prefix(1);
  if (!text.empty() && text.back() == ')') text.remove_suffix(1);
  std::vector<std::string> parts =
      absl::StrSplit(absl::string_view(text.data(), text.size()), ' ', absl::SkipEmpty());
  std::string head = parts.empty() ? "" : parts.front();
  if (!parts.empty()) parts.erase(parts.begin());
  return {head, parts};
}

// lhs `op` rhs as one flat expression.
inline NumericExpr Binary(NumericExpr::Op op, const NumericExpr& lhs, const NumericExpr& rhs) {
  NumericExpr out = lhs;
  const auto lhs_root = static_cast<std::int32_t>(out.nodes.size() - 1);
  const auto offset = static_cast<std::int32_t>(out.nodes.size());
  for (auto node : rhs.nodes) {
    if (node.lhs >= 0) node.lhs += offset;
    if (node.rhs >= 0) node.rhs += offset;
    out.nodes.push_back(node);
  }
  const auto rhs_root = static_cast<std::int32_t>(out.nodes.size() - 1);
  NumericExpr::Node root;
  root.op = op;
  root.lhs = lhs_root;
  root.rhs = rhs_root;
  out.nodes.push_back(root);
  return out;
}

inline NumericExpr DurationExpr() {
  NumericExpr e;
  NumericExpr::Node node;
  node.op = NumericExpr::Op::kDuration;
  e.nodes.push_back(node);
  return e;
}

inline NumericExpr TotalTimeExpr() {
  NumericExpr e;
  NumericExpr::Node node;
  node.op = NumericExpr::Op::kTotalTime;
  e.nodes.push_back(node);
  return e;
}

class TaskBuilder {
 public:
  TaskBuilder() { task_.metric.expression = TotalTimeExpr(); }

  task::FactId Fact(std::string_view text) {
    const std::string key(text);
    auto it = facts_.find(key);
    if (it != facts_.end()) return it->second;
    auto [head, args] = SplitAtom(text);
    const auto id = static_cast<task::FactId>(task_.facts.size());
    task_.facts.push_back({head, args});
    facts_.emplace(key, id);
    return id;
  }

  task::NumericVarId Var(std::string_view text, double initial = NumericExpr::kUndefined) {
    const std::string key(text);
    auto it = vars_.find(key);
    if (it != vars_.end()) return it->second;
    auto [head, args] = SplitAtom(text);
    const auto id = static_cast<task::NumericVarId>(task_.numeric_vars.size());
    task_.numeric_vars.push_back({head, args});
    task_.initial_values.push_back(initial);
    vars_.emplace(key, id);
    return id;
  }
  NumericExpr VarExpr(std::string_view text) { return NumericExpr::Variable(Var(text)); }

  void Init(std::string_view fact) { task_.initial_facts.push_back(Fact(fact)); }
  void Goal(std::string_view fact) { task_.goal.positive.push_back(Fact(fact)); }
  void Til(double t, std::string_view fact, bool value) {
    task_.timed_literals.push_back({t, Fact(fact), value});
  }

  // A durative action "(name args)" with (= ?duration duration_s).
  static Action Durative(std::string_view display, double duration_s) {
    Action a;
    auto [head, args] = SplitAtom(display);
    a.name = head;
    a.args = args;
    a.is_durative = true;
    a.duration.push_back({task::Comparator::kEqual, NumericExpr::Constant(duration_s)});
    return a;
  }
  static Action Instant(std::string_view display) {
    Action a;
    auto [head, args] = SplitAtom(display);
    a.name = head;
    a.args = args;
    a.is_durative = false;
    return a;
  }
  task::ActionId Add(Action a) {
    task_.actions.push_back(std::move(a));
    return static_cast<task::ActionId>(task_.actions.size() - 1);
  }

  task::GroundTask& task() { return task_; }

 private:
  task::GroundTask task_;
  std::map<std::string, task::FactId> facts_;
  std::map<std::string, task::NumericVarId> vars_;
};

}  // namespace seaplan::validate::testing
