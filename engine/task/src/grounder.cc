// The grounding pipeline (see grounder.h for the contract): each stage takes
// the previous stage's value and returns its own, timed, with the StopToken
// polled between stages (and inside the long loops of each, via the
// GroundingContext):
//   1. symbols (symbols.cc): names interned to ids; the objects of each type;
//      static predicates (no effect and no timed literal touches them) and
//      static functions (no numeric effect, no timed fluent);
//   2. schema compilation (schema.cc): each action schema's condition in NNF,
//      then schema-level DNF disjuncts (conjunctions of literals,
//      equalities, comparisons and opaque forall items; exists variables
//      become extra variables to bind); the goal and metric likewise;
//   3. reachability (reachability.cc): the relaxed exploration from :init,
//      producing the reachable atoms and the reached action instances;
//   4. instantiation (instantiation.cc): each reached instance's condition
//      and effects grounded, simplified against the static facts and the
//      reachable set, foralls expanded, turned into ground DNF variants;
//   5. explanation (explanation.cc): ExplainMissingAction, from stages 1-3.
#include "seaplan/task/grounder.h"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <new>
#include <optional>
#include <sstream>
#include <utility>

#include "instantiation_internal.h"

namespace seaplan::task {

namespace internal {

Comparator ToTask(pddl::Comparator c) {
  switch (c) {
    case pddl::Comparator::kLess:
      return Comparator::kLess;
    case pddl::Comparator::kLessEqual:
      return Comparator::kLessEqual;
    case pddl::Comparator::kEqual:
      return Comparator::kEqual;
    case pddl::Comparator::kGreaterEqual:
      return Comparator::kGreaterEqual;
    case pddl::Comparator::kGreater:
      return Comparator::kGreater;
  }
  return Comparator::kEqual;
}

AssignOp ToTask(pddl::AssignOp op) {
  switch (op) {
    case pddl::AssignOp::kAssign:
      return AssignOp::kAssign;
    case pddl::AssignOp::kIncrease:
      return AssignOp::kIncrease;
    case pddl::AssignOp::kDecrease:
      return AssignOp::kDecrease;
    case pddl::AssignOp::kScaleUp:
      return AssignOp::kScaleUp;
    case pddl::AssignOp::kScaleDown:
      return AssignOp::kScaleDown;
  }
  return AssignOp::kAssign;
}

}  // namespace internal

namespace {

double Millis(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - since)
      .count();
}

// Runs `stage` and adds its wall-clock time to `ms`.
template <typename Stage>
auto Timed(double& ms, Stage&& stage) {
  const auto start = std::chrono::steady_clock::now();
  auto value = stage();
  ms += Millis(start);
  return value;
}

// The stages in order, each timed; result.task stays null when one failed
// or the stop token fired.
void RunStages(const pddl::Domain& domain, const pddl::Problem& problem,
               internal::GroundingContext& context, LoadResult& result) {
  using namespace internal;
  GroundingStageTimes& times = result.stats.stages;
  std::optional<SymbolTable> symbols =
      Timed(times.symbols_ms, [&] { return BuildSymbols(domain, problem, context); });
  if (!symbols || context.StopRequested()) return;
  std::optional<CompiledSchemas> schemas =
      Timed(times.schemas_ms, [&] { return CompileSchemas(domain, problem, *symbols, context); });
  if (!schemas || context.StopRequested()) return;
  std::optional<ReachableTask> reachable = Timed(times.reachability_ms, [&] {
    return ExploreReachability(*symbols, *schemas, problem, context);
  });
  if (!reachable || context.StopRequested()) return;
  result.stats.static_atoms = reachable->static_true_atoms;
  InstantiatedTask instantiated = Timed(times.instantiation_ms, [&] {
    return Instantiate(domain, problem, *symbols, *schemas, std::move(*reachable), context);
  });
  result.stats.reachable_atoms = instantiated.atoms_seen;
  if (instantiated.task != nullptr && context.ok() && !pddl::HasErrors(result.diagnostics))
    result.task = std::move(instantiated.task);
}

}  // namespace

absl::Status GroundingOptions::Validate() const {
  if (max_actions == 0 || max_facts == 0 || max_work == 0) {
    return absl::InvalidArgumentError(
        "GroundingOptions: max_actions, max_facts and max_work must be > 0");
  }
  return absl::OkStatus();
}

LoadResult Ground(const pddl::Domain& domain, const pddl::Problem& problem,
                  const GroundingOptions& options, const StopToken& stop) {
  LoadResult result;
  if (absl::Status status = options.Validate(); !status.ok()) {
    // Filled in place: for a braced temporary here, GCC 12 at -O3 warns that
    // its location.file "may be used uninitialized" (a false positive).
    pddl::Diagnostic& error = result.diagnostics.emplace_back();
    error.severity = pddl::Severity::kError;
    error.kind = pddl::DiagnosticKind::kSemantic;
    error.message = std::string(status.message());
    return result;
  }
  const auto start = std::chrono::steady_clock::now();
  internal::GroundingContext context(problem, options, stop, result.diagnostics);
  RunStages(domain, problem, context, result);
  result.stop_reason = context.stop_reason();
  result.stats.ground_ms = Millis(start);
  if (result.task) result.stats.size = result.task->Size();
  return result;
}

LoadResult LoadTask(std::string_view domain_text, std::string_view problem_text,
                    const GroundingOptions& options, std::string_view domain_file,
                    std::string_view problem_file) {
  return LoadTask(domain_text, problem_text, options, StopToken(), domain_file, problem_file);
}

namespace {

LoadResult ParseAndGround(std::string_view domain_text, std::string_view problem_text,
                          const GroundingOptions& options, const StopToken& stop,
                          std::string_view domain_file, std::string_view problem_file) {
  LoadResult result;
  const auto start = std::chrono::steady_clock::now();
  auto parsed_domain = pddl::ParseDomain(domain_text, domain_file);
  result.diagnostics = std::move(parsed_domain.diagnostics);
  if (!parsed_domain.domain) {
    result.stats.parse_ms = Millis(start);
    return result;
  }
  auto domain = std::make_shared<const pddl::Domain>(std::move(*parsed_domain.domain));
  auto parsed_problem = pddl::ParseProblem(problem_text, *domain, problem_file);
  result.diagnostics.insert(result.diagnostics.end(), parsed_problem.diagnostics.begin(),
                            parsed_problem.diagnostics.end());
  result.stats.parse_ms = Millis(start);
  result.domain = domain;
  if (!parsed_problem.problem) return result;
  auto problem = std::make_shared<const pddl::Problem>(std::move(*parsed_problem.problem));
  result.problem = problem;
  LoadResult grounded = Ground(*domain, *problem, options, stop);
  result.diagnostics.insert(result.diagnostics.end(), grounded.diagnostics.begin(),
                            grounded.diagnostics.end());
  result.task = std::move(grounded.task);
  result.stop_reason = grounded.stop_reason;
  const double parse_ms = result.stats.parse_ms;
  result.stats = grounded.stats;
  result.stats.parse_ms = parse_ms;
  return result;
}

}  // namespace

LoadResult LoadTask(std::string_view domain_text, std::string_view problem_text,
                    const GroundingOptions& options, const StopToken& stop,
                    std::string_view domain_file, std::string_view problem_file) {
  try {
    return ParseAndGround(domain_text, problem_text, options, stop, domain_file, problem_file);
  } catch (const std::bad_alloc&) {
    LoadResult result;
    result.memory_ran_out = true;
    return result;
  }
}

LoadResult LoadTaskFromFiles(const std::string& domain_path, const std::string& problem_path,
                             const GroundingOptions& options) {
  auto read = [](const std::string& path, std::string& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) return false;
    std::ostringstream ss;
    ss << in.rdbuf();
    out = ss.str();
    return true;
  };
  std::string domain_text, problem_text;
  LoadResult result;
  for (const auto* path : {&domain_path, &problem_path}) {
    if (!read(*path, path == &domain_path ? domain_text : problem_text)) {
      pddl::Diagnostic& error = result.diagnostics.emplace_back();  // in place: see Ground()
      error.severity = pddl::Severity::kError;
      error.kind = pddl::DiagnosticKind::kSyntax;
      error.location.file = *path;
      error.symbol = *path;
      error.message = "cannot read the file";
      error.expected = "a readable PDDL file";
    }
  }
  if (pddl::HasErrors(result.diagnostics)) return result;
  return LoadTask(domain_text, problem_text, options, domain_path, problem_path);
}

namespace {

char AsciiLower(char c) {
  return static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
}

bool EqualsLowered(std::string_view query, std::string_view lower) {
  if (query.size() != lower.size()) return false;
  for (std::size_t i = 0; i < query.size(); ++i) {
    if (AsciiLower(query[i]) != lower[i]) return false;
  }
  return true;
}

// FNV-1a over the lower-cased "name arg1 arg2 ...".
std::uint64_t NameArgsHash(std::string_view name, std::span<const std::string> args) {
  std::uint64_t h = 1469598103934665603ull;
  auto add = [&h](char c) {
    h ^= static_cast<unsigned char>(AsciiLower(c));
    h *= 1099511628211ull;
  };
  for (char c : name) add(c);
  for (const auto& a : args) {
    add(' ');
    for (char c : a) add(c);
  }
  return h;
}

// (hash, id) of every item of `items` (ground actions or facts, whose name
// `name_of` reads), sorted.
template <typename Id, typename Item, typename NameOf>
std::vector<std::pair<std::uint64_t, Id>> HashNames(const std::vector<Item>& items,
                                                    NameOf name_of) {
  std::vector<std::pair<std::uint64_t, Id>> by_hash;
  by_hash.reserve(items.size());
  for (std::size_t i = 0; i < items.size(); ++i)
    by_hash.emplace_back(NameArgsHash(name_of(items[i]), items[i].args), static_cast<Id>(i));
  std::sort(by_hash.begin(), by_hash.end());
  return by_hash;
}

// Calls `found(id)` for every item of `by_hash` named (name args).
template <typename Id, typename Item, typename NameOf, typename Found>
void FindByName(const std::vector<std::pair<std::uint64_t, Id>>& by_hash,
                const std::vector<Item>& items, NameOf name_of, std::string_view name,
                std::span<const std::string> args, Found found) {
  const std::uint64_t h = NameArgsHash(name, args);
  auto it = std::lower_bound(by_hash.begin(), by_hash.end(), std::make_pair(h, Id{0}),
                             [](const auto& x, const auto& y) { return x.first < y.first; });
  for (; it != by_hash.end() && it->first == h; ++it) {
    const Item& item = items[static_cast<std::size_t>(it->second)];
    if (item.args.size() != args.size() || !EqualsLowered(name, name_of(item))) continue;
    bool same = true;
    for (std::size_t k = 0; k < args.size() && same; ++k)
      same = EqualsLowered(args[k], item.args[k]);
    if (same) found(it->second);
  }
}

const std::string& ActionName(const Action& action) {
  return action.name;
}
const std::string& FactPredicate(const Fact& fact) {
  return fact.predicate;
}

}  // namespace

ActionIndex::ActionIndex(const GroundTask& task)
    : task_(&task), by_hash_(HashNames<ActionId>(task.actions, ActionName)) {}

std::vector<ActionId> ActionIndex::Find(std::string_view name,
                                        std::span<const std::string> args) const {
  std::vector<ActionId> out;
  FindByName(by_hash_, task_->actions, ActionName, name, args,
             [&out](ActionId a) { out.push_back(a); });
  return out;
}

ActionId ActionIndex::Find(std::string_view name, std::span<const std::string> args,
                           int variant) const {
  ActionId out = -1;
  FindByName(by_hash_, task_->actions, ActionName, name, args, [&](ActionId a) {
    if (out < 0 && task_->actions[static_cast<std::size_t>(a)].variant == variant) out = a;
  });
  return out;
}

FactIndex::FactIndex(const GroundTask& task)
    : task_(&task), by_hash_(HashNames<FactId>(task.facts, FactPredicate)) {}

FactId FactIndex::Find(std::string_view predicate, std::span<const std::string> args) const {
  FactId out = -1;
  FindByName(by_hash_, task_->facts, FactPredicate, predicate, args, [&out](FactId f) { out = f; });
  return out;
}

}  // namespace seaplan::task
