#include "seaplan/task/ground_task.h"

#include <cassert>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "seaplan/pddl/parser.h"

namespace seaplan::task {
namespace {

std::string Parenthesised(const std::string& head, const std::vector<std::string>& args) {
  std::string out = "(" + head;
  for (const auto& arg : args) out += " " + arg;
  return out + ")";
}

std::string FormatNumber(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

}  // namespace

NumericExpr NumericExpr::Constant(double value) {
  NumericExpr expr;
  expr.nodes.push_back({Op::kConstant, value, -1, -1, -1});
  return expr;
}

NumericExpr NumericExpr::Variable(NumericVarId var) {
  NumericExpr expr;
  expr.nodes.push_back({Op::kVariable, 0.0, var, -1, -1});
  return expr;
}

bool NumericExpr::IsGround() const {
  for (const auto& node : nodes) {
    if (node.op == Op::kVariable || node.op == Op::kDuration || node.op == Op::kTotalTime) {
      return false;
    }
  }
  return true;
}

double NumericExpr::ConstantValue() const {
  if (!IsConstant()) std::abort();  // invariant: callers check IsConstant() first
  return nodes[0].value;
}

std::optional<double> NumericExpr::Evaluate(std::span<const double> values, double duration,
                                            double total_time) const {
  if (nodes.empty()) return std::nullopt;
  // Small expressions dominate; a fixed stack avoids allocation in the hot path.
  constexpr std::size_t kInline = 32;
  double inline_results[kInline];
  std::vector<double> heap_results;
  double* results = inline_results;
  if (nodes.size() > kInline) {
    heap_results.resize(nodes.size());
    results = heap_results.data();
  }
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& node = nodes[i];
    double r = 0.0;
    switch (node.op) {
      case Op::kConstant:
        r = node.value;
        break;
      case Op::kVariable:
        if (node.var < 0 || static_cast<std::size_t>(node.var) >= values.size())
          return std::nullopt;
        r = values[static_cast<std::size_t>(node.var)];
        break;
      case Op::kDuration:
        r = duration;
        break;
      case Op::kTotalTime:
        r = total_time;
        break;
      case Op::kAdd:
        r = results[node.lhs] + results[node.rhs];
        break;
      case Op::kSub:
        r = results[node.lhs] - results[node.rhs];
        break;
      case Op::kMul:
        r = results[node.lhs] * results[node.rhs];
        break;
      case Op::kDiv:
        if (results[node.rhs] == 0.0) return std::nullopt;
        r = results[node.lhs] / results[node.rhs];
        break;
      case Op::kNeg:
        r = -results[node.lhs];
        break;
    }
    if (std::isnan(r)) return std::nullopt;
    results[i] = r;
  }
  return results[nodes.size() - 1];
}

std::vector<NumericVarId> NumericExpr::Variables() const {
  std::vector<NumericVarId> vars;
  for (const auto& node : nodes) {
    if (node.op == Op::kVariable) vars.push_back(node.var);
  }
  return vars;
}

bool NumericExpr::ReadsDuration() const {
  for (const auto& node : nodes) {
    if (node.op == Op::kDuration) return true;
  }
  return false;
}

std::string Action::DisplayName() const {
  return Parenthesised(name, args);
}

std::optional<double> Action::ConstantDuration() const {
  if (!is_durative) return 0.0;
  if (duration.empty()) return std::nullopt;
  std::optional<double> value;
  for (const auto& constraint : duration) {
    if (constraint.comparator != Comparator::kEqual || !constraint.value.IsConstant()) {
      return std::nullopt;
    }
    const double v = constraint.value.ConstantValue();
    if (value && *value != v) return std::nullopt;
    value = v;
  }
  return value;
}

std::string Fact::DisplayName() const {
  return Parenthesised(predicate, args);
}
std::string NumericVar::DisplayName() const {
  return Parenthesised(function, args);
}

bool Compare(double lhs, Comparator comparator, double rhs) {
  switch (comparator) {
    case Comparator::kLess:
      return lhs < rhs;
    case Comparator::kLessEqual:
      return lhs <= rhs;
    case Comparator::kEqual:
      return lhs == rhs;
    case Comparator::kGreaterEqual:
      return lhs >= rhs;
    case Comparator::kGreater:
      return lhs > rhs;
  }
  return false;
}

// task::Comparator is its own small enum (uint8_t, so search never sees parser
// types), but it lists the same comparators in the same order as
// pddl::Comparator; the spelling lives once, in the parser.
static_assert(static_cast<int>(Comparator::kLess) == static_cast<int>(pddl::Comparator::kLess));
static_assert(static_cast<int>(Comparator::kLessEqual) ==
              static_cast<int>(pddl::Comparator::kLessEqual));
static_assert(static_cast<int>(Comparator::kEqual) == static_cast<int>(pddl::Comparator::kEqual));
static_assert(static_cast<int>(Comparator::kGreaterEqual) ==
              static_cast<int>(pddl::Comparator::kGreaterEqual));
static_assert(static_cast<int>(Comparator::kGreater) ==
              static_cast<int>(pddl::Comparator::kGreater));

const char* ComparatorSymbol(Comparator comparator) {
  return pddl::ComparatorSymbol(static_cast<pddl::Comparator>(comparator));
}

double ApplyAssign(AssignOp op, double current, double value) {
  switch (op) {
    case AssignOp::kAssign:
      return value;
    case AssignOp::kIncrease:
      return current + value;
    case AssignOp::kDecrease:
      return current - value;
    case AssignOp::kScaleUp:
      return current * value;
    case AssignOp::kScaleDown:
      return current / value;
  }
  return value;
}

std::string ToString(const NumericExpr& expr, const GroundTask& task) {
  if (expr.nodes.empty()) return "<empty>";
  std::vector<std::string> parts(expr.nodes.size());
  for (std::size_t i = 0; i < expr.nodes.size(); ++i) {
    const auto& node = expr.nodes[i];
    using Op = NumericExpr::Op;
    switch (node.op) {
      case Op::kConstant:
        parts[i] = FormatNumber(node.value);
        break;
      case Op::kVariable:
        parts[i] = node.var >= 0 && static_cast<std::size_t>(node.var) < task.numeric_vars.size()
                       ? task.numeric_vars[static_cast<std::size_t>(node.var)].DisplayName()
                       : "<var?>";
        break;
      case Op::kDuration:
        parts[i] = "?duration";
        break;
      case Op::kTotalTime:
        parts[i] = "(total-time)";
        break;
      case Op::kAdd:
        parts[i] = "(+ " + parts[node.lhs] + " " + parts[node.rhs] + ")";
        break;
      case Op::kSub:
        parts[i] = "(- " + parts[node.lhs] + " " + parts[node.rhs] + ")";
        break;
      case Op::kMul:
        parts[i] = "(* " + parts[node.lhs] + " " + parts[node.rhs] + ")";
        break;
      case Op::kDiv:
        parts[i] = "(/ " + parts[node.lhs] + " " + parts[node.rhs] + ")";
        break;
      case Op::kNeg:
        parts[i] = "(- " + parts[node.lhs] + ")";
        break;
    }
  }
  return parts.back();
}

std::string ToString(const NumericCondition& condition, const GroundTask& task) {
  return std::string("(") + ComparatorSymbol(condition.comparator) + " " +
         ToString(condition.lhs, task) + " " + ToString(condition.rhs, task) + ")";
}

}  // namespace seaplan::task
