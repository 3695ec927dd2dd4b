// What every grounding stage shares: typed ids for the things the stages
// name, the encoding of schema arguments (an object or a variable slot), and
// the context that carries the options, the diagnostics, the work budget and
// the StopToken through the stages.
//
// The stages (see grounder.cc for the pipeline) are:
//   symbols_internal.h       names -> ids, static predicates and functions
//   schema_internal.h        action schemas -> NNF conditions, DNF disjuncts
//   reachability_internal.h  relaxed exploration: reachable atoms, instances
//   instantiation_internal.h reachable instances -> GroundTask
//   explanation_internal.h   why an action is not in the ground task
#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "seaplan/common/stop_token.h"
#include "seaplan/pddl/diagnostic.h"
#include "seaplan/pddl/parser.h"
#include "seaplan/task/grounder.h"

namespace seaplan::task::internal {

// A dense index into one table of the grounder; the tag keeps an object id
// from being passed where a predicate id is expected. -1 means "none".
template <typename Tag>
class Index {
 public:
  constexpr Index() = default;
  constexpr explicit Index(std::int32_t value) : value_(value) {}
  constexpr explicit Index(std::size_t value) : value_(static_cast<std::int32_t>(value)) {}
  static constexpr Index None() { return Index(); }

  constexpr std::int32_t value() const { return value_; }
  // For indexing vectors.
  constexpr std::size_t index() const { return static_cast<std::size_t>(value_); }
  constexpr bool valid() const { return value_ >= 0; }
  // NOLINTNEXTLINE(modernize-use-nullptr): clang-tidy 14 sees a 0 in the defaulted <=>.
  constexpr auto operator<=>(const Index&) const = default;

 private:
  std::int32_t value_ = -1;
};

using ObjectId = Index<struct ObjectTag>;              // objects and constants
using TypeId = Index<struct TypeTag>;                  // 0 is `object`
using PredicateId = Index<struct PredicateTag>;        // domain predicates
using FunctionId = Index<struct FunctionTag>;          // domain functions
using AtomId = Index<struct AtomTag>;                  // interned (predicate, objects...)
using FunctionTermId = Index<struct FunctionTermTag>;  // interned (function, objects...)
using SchemaId = Index<struct SchemaTag>;              // one per domain action
using DisjunctId = Index<struct DisjunctTag>;          // one per precondition DNF disjunct
using VariableSlot = Index<struct VariableSlotTag>;  // a schema's parameter or quantified variable

// An argument of a schema atom or function term: an object, or a variable of
// the schema (packed in one int32: >= 0 object, < 0 slot -1 - value).
class Term {
 public:
  static Term Object(ObjectId object) { return Term(object.value()); }
  static Term Variable(VariableSlot slot) { return Term(-1 - slot.value()); }

  bool is_variable() const { return packed_ < 0; }
  ObjectId object() const { return ObjectId(packed_); }
  VariableSlot slot() const { return VariableSlot(-1 - packed_); }

 private:
  explicit Term(std::int32_t packed) : packed_(packed) {}
  std::int32_t packed_;
};

// Objects bound to a schema's variable slots (ObjectId::None() when unbound).
using Binding = std::vector<ObjectId>;

inline ObjectId Resolve(Term term, const Binding& binding) {
  return term.is_variable() ? binding[term.slot().index()] : term.object();
}

inline constexpr double kUndefinedValue = std::numeric_limits<double>::quiet_NaN();
// Cap on DNF sizes (schema level and ground level): beyond it the input is
// reported as unsupported rather than exploding.
inline constexpr std::size_t kMaxDisjuncts = 256;

// Replaces the DNF `product` by its conjunction with the DNF `part`: every
// pair of disjuncts (product's outer, part's inner), joined by
// append(into, from). False when that would exceed kMaxDisjuncts.
template <typename Disjunct, typename Append>
bool MultiplyOut(std::vector<Disjunct>& product, const std::vector<Disjunct>& part, Append append) {
  std::vector<Disjunct> next;
  for (const auto& a : product) {
    for (const auto& b : part) {
      Disjunct d = a;
      append(d, b);
      next.push_back(std::move(d));
    }
  }
  if (next.size() > kMaxDisjuncts) return false;
  product = std::move(next);
  return true;
}

Comparator ToTask(pddl::Comparator comparator);
AssignOp ToTask(pddl::AssignOp op);

// Carried through every stage: options, diagnostics, the work budget and the
// stop token. Not shared between threads (one per Ground call).
class GroundingContext {
 public:
  GroundingContext(const pddl::Problem& problem, const GroundingOptions& options,
                   const StopToken& stop, std::vector<pddl::Diagnostic>& diagnostics)
      : problem_(problem), options_(options), stop_(stop), diagnostics_(diagnostics) {}

  const GroundingOptions& options() const { return options_; }

  void Error(pddl::DiagnosticKind kind, const pddl::SourceLocation& at, std::string symbol,
             std::string message, std::string expected = "") {
    diagnostics_.push_back({pddl::Severity::kError, kind, at, std::move(symbol), std::move(message),
                            std::move(expected)});
  }
  void Warn(const pddl::SourceLocation& at, std::string symbol, std::string message) {
    diagnostics_.push_back({pddl::Severity::kWarning, pddl::DiagnosticKind::kSemantic, at,
                            std::move(symbol), std::move(message), ""});
  }
  // Reports a spent budget (`message` says which): one error per run,
  // however many loops notice it.
  void BudgetExceeded(const std::string& message, const std::string& expected) {
    if (!budget_exceeded_) {
      Error(pddl::DiagnosticKind::kSemantic, problem_.location, "", message, expected);
    }
    budget_exceeded_ = true;
  }
  bool budget_exceeded() const { return budget_exceeded_; }

  // Counts one elementary step; false once the work budget is spent or the
  // stop token fired (checked every kStopPollSteps steps, so a stage loop
  // notices a deadline within about a millisecond).
  bool Tick() {
    ++work_;
    if (work_ > options_.max_work) {
      BudgetExceeded(
          "grounding exceeds the work budget of " + std::to_string(options_.max_work) + " steps",
          "a smaller problem or a larger GroundingOptions::max_work");
      return false;
    }
    if (work_ % kStopPollSteps == 0) return !StopRequested();
    return stop_reason_ == StopReason::kNone;
  }
  // Polls the stop token (between stages and in loops without Tick).
  bool StopRequested() {
    if (stop_reason_ == StopReason::kNone) stop_reason_ = stop_.Reason();
    return stop_reason_ != StopReason::kNone;
  }
  StopReason stop_reason() const { return stop_reason_; }
  // False when a stage must end now (budget spent or stopped).
  bool ok() const { return !budget_exceeded_ && stop_reason_ == StopReason::kNone; }

 private:
  static constexpr std::size_t kStopPollSteps = 4096;

  const pddl::Problem& problem_;
  const GroundingOptions& options_;
  const StopToken& stop_;
  std::vector<pddl::Diagnostic>& diagnostics_;
  std::size_t work_ = 0;
  bool budget_exceeded_ = false;
  StopReason stop_reason_ = StopReason::kNone;
};

}  // namespace seaplan::task::internal
