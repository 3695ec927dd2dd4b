// From parsed PDDL to a GroundTask: the one entry point every component uses.
//
//   auto loaded = seaplan::task::LoadTask(domain_text, problem_text);
//   if (!loaded.ok()) { /* loaded.diagnostics says what and where */ }
//   const GroundTask& task = *loaded.task;
//
// Grounding runs in stages, each handing a value to the next (as Fast
// Downward's translator): symbols (names to ids, static predicates and
// functions), schema compilation (conditions in negation normal form,
// preconditions in DNF), reachability (a Datalog-style relaxed fixpoint: an
// action instance is generated only when all its positive fact
// preconditions are reachable, found by joining the precondition atoms
// most-selective-first, never by enumerating all parameter combinations),
// and instantiation (the ground task). Static predicates (changed by no
// effect and no timed literal) are folded away, static fluents are folded
// into constants, quantifiers and conditional effects are expanded,
// disjunctions are compiled into DNF copies (Action::variant), equality is
// evaluated. Numeric conditions are treated optimistically during
// reachability unless they are fully static. Facts added by timed initial
// literals count as reachable. A goal that is statically false is kept (as
// a fact nothing achieves) so that the planner proves unsolvability instead
// of the grounder silently dropping it; a warning says so. The StopToken is
// polled between stages and inside their long loops: a stopped run returns
// no task and no error, with LoadResult::stop_reason set.
//
// Generated names (e.g. the never-true fact standing for a statically false
// goal) contain '@', which no PDDL name can, so they never clash.
//
// What stays in the task: facts = reachable atoms of predicates some effect
// or timed literal changes (plus goal and timed-literal atoms nothing
// reaches); numeric variables = fluents some effect or timed fluent changes;
// durations are constants when they read only static fluents, expressions
// over the numeric variables otherwise (e.g. rovers' recharge). Ground
// actions whose duration or effect reads a static fluent with no value in
// :init are dropped (they can never be applied).
//
// Ground() expects a domain and problem from ParseDomain/ParseProblem (or
// edited copies): a problem that no longer matches the domain (unknown
// object, predicate or function) is reported as a diagnostic.
//
// Thread-safety: all functions are pure; the result task is immutable.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/pddl/diagnostic.h"
#include "seaplan/pddl/parser.h"
#include "seaplan/task/ground_task.h"

namespace seaplan::task {

struct GroundingOptions {
  // Budgets: exceeding one ends grounding with an error diagnostic instead of
  // unbounded memory use. max_facts also bounds the per-argument reachability
  // index (4 cells per allowed fact, plus 1M).
  std::size_t max_actions = 5'000'000;
  std::size_t max_facts = 5'000'000;
  // Elementary grounding steps (join candidates, quantifier and forall
  // expansions) before giving up with an error: bounds time and memory on
  // inputs such as a forall over many variables. About 1e8 steps per second.
  std::size_t max_work = 400'000'000;

  absl::Status Validate() const;
};

// Wall-clock time of each grounding stage, ms (0 for a stage not run).
struct GroundingStageTimes {
  double symbols_ms = 0.0;        // interning, problem/domain check, statics
  double schemas_ms = 0.0;        // NNF conditions, DNF disjuncts, goal and metric
  double reachability_ms = 0.0;   // :init and the relaxed fixpoint
  double instantiation_ms = 0.0;  // ground actions, initial state, goal, metric
};

struct GroundingStats {
  double parse_ms = 0.0;   // both files (LoadTask only)
  double ground_ms = 0.0;  // every grounding stage (the sum of `stages`, and overhead)
  GroundingStageTimes stages;
  std::size_t reachable_atoms = 0;  // atoms interned, incl. static and unreachable ones
  std::size_t static_atoms = 0;     // true static atoms (folded away)
  TaskSize size;                    // same as task->Size()
};

struct LoadResult {
  std::shared_ptr<const GroundTask> task;     // null when grounding failed
  std::vector<pddl::Diagnostic> diagnostics;  // errors and warnings of every stage
  GroundingStats stats;
  // The parsed inputs (set by LoadTask when parsing succeeded), for callers
  // that need to explain things in PDDL terms (ExplainMissingAction).
  std::shared_ptr<const pddl::Domain> domain;
  std::shared_ptr<const pddl::Problem> problem;
  // kDeadline or kCancelled when the StopToken ended grounding (task null,
  // no error diagnostic: a result, not an input error).
  StopReason stop_reason = StopReason::kNone;
  // LoadTask only: an allocation failed (an address-space limit) while
  // parsing or grounding (task null, no diagnostic: a result, as a search
  // that runs out of memory is).
  bool memory_ran_out = false;

  bool stopped() const { return stop_reason != StopReason::kNone; }
  bool ok() const { return task != nullptr && !pddl::HasErrors(diagnostics); }
  bool unsupported() const { return pddl::HasUnsupported(diagnostics); }
  // Every diagnostic, one per line (empty when none).
  std::string ErrorText() const { return pddl::FormatDiagnostics(diagnostics); }
};

// Grounds a parsed, checked domain and problem; stops early (stop_reason
// set) when `stop` fires.
LoadResult Ground(const pddl::Domain& domain, const pddl::Problem& problem,
                  const GroundingOptions& options = {}, const StopToken& stop = StopToken());

// Parses both texts and grounds. Diagnostics name the texts `domain_file`
// and `problem_file` ("domain" and "problem" unless given).
LoadResult LoadTask(std::string_view domain_text, std::string_view problem_text,
                    const GroundingOptions& options = {}, std::string_view domain_file = "domain",
                    std::string_view problem_file = "problem");
// The same, polling `stop` while grounding (parsing is linear and not polled).
// A failed allocation is a result (memory_ran_out), not an exception: the
// callers ground on worker threads, where it would end the process.
LoadResult LoadTask(std::string_view domain_text, std::string_view problem_text,
                    const GroundingOptions& options, const StopToken& stop,
                    std::string_view domain_file = "domain",
                    std::string_view problem_file = "problem");

// Reads both files and calls LoadTask (diagnostics name the paths). An
// unreadable file is an error diagnostic, not an exception.
LoadResult LoadTaskFromFiles(const std::string& domain_path, const std::string& problem_path,
                             const GroundingOptions& options = {});

// Finds ground actions by (name, args) in O(log n) (names lower case). Build
// once per task; holds a reference to the task (it must outlive the index).
// Sorted (hash, action) pairs, with candidates checked against the task's
// names: building allocates no string per action (it used to dominate the
// planner's setup on large tasks, e.g. 13 M instructions for 7 k actions).
class ActionIndex {
 public:
  explicit ActionIndex(const GroundTask& task);

  // Every ground action (all DNF variants) with this name and these
  // arguments, in ascending order; empty when none. Case-insensitive.
  std::vector<ActionId> Find(std::string_view name, std::span<const std::string> args) const;
  // The one with this name, these arguments and this DNF variant
  // (Action::variant); -1 when none. Allocates nothing.
  ActionId Find(std::string_view name, std::span<const std::string> args, int variant) const;

 private:
  const GroundTask* task_;
  std::vector<std::pair<std::uint64_t, ActionId>> by_hash_;  // sorted
};

// Finds ground facts by (predicate, args), as ActionIndex finds actions.
class FactIndex {
 public:
  explicit FactIndex(const GroundTask& task);

  // The fact with this predicate and these arguments; -1 when the task has
  // none (static and unreachable atoms are not facts). Case-insensitive.
  FactId Find(std::string_view predicate, std::span<const std::string> args) const;

 private:
  const GroundTask* task_;
  std::vector<std::pair<std::uint64_t, FactId>> by_hash_;  // sorted
};

// Why (name args) is not an action of the ground task, in one sentence for a
// user: unknown action, wrong number of arguments, unknown object, an
// argument of the wrong type, a static precondition that is false (which
// one, e.g. "(connects r1 port-a port-b) is false and never changes"), an
// equality that fails, or "its preconditions are not reachable from the
// initial state" (e.g. (at ship0 port-x) is never true). Returns "" when the
// action is in fact grounded (when `task` is given) or no reason is found.
std::string ExplainMissingAction(const pddl::Domain& domain, const pddl::Problem& problem,
                                 std::string_view name, std::span<const std::string> args,
                                 const GroundTask* task = nullptr);

}  // namespace seaplan::task
