// TODO(#3): stub while the real grounder is written.
#include "seaplan/task/grounder.h"

namespace seaplan::task {

absl::Status GroundingOptions::Validate() const {
  if (max_actions == 0 || max_facts == 0) return absl::InvalidArgumentError("grounding budgets must be > 0");
  return absl::OkStatus();
}

LoadResult Ground(const pddl::Domain&, const pddl::Problem&, const GroundingOptions&) {
  LoadResult result;
  result.diagnostics.push_back({pddl::Severity::kError, pddl::DiagnosticKind::kUnsupported,
                                {"problem", 0, 0}, "", "grounder not implemented yet", ""});
  return result;
}

LoadResult LoadTask(std::string_view domain_text, std::string_view problem_text,
                    const GroundingOptions& options) {
  auto d = pddl::ParseDomain(domain_text);
  LoadResult result;
  result.diagnostics = d.diagnostics;
  if (!d.domain) return result;
  auto p = pddl::ParseProblem(problem_text, *d.domain);
  result.diagnostics.insert(result.diagnostics.end(), p.diagnostics.begin(), p.diagnostics.end());
  if (!p.problem) return result;
  (void)options;
  return result;
}

ActionIndex::ActionIndex(const GroundTask& task) {
  for (std::size_t i = 0; i < task.actions.size(); ++i) {
    by_key_[Key(task.actions[i].name, task.actions[i].args)].push_back(static_cast<ActionId>(i));
  }
}

std::string ActionIndex::Key(std::string_view name, std::span<const std::string> args) {
  std::string key(name);
  for (const auto& a : args) {
    key += ' ';
    key += a;
  }
  for (auto& c : key) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return key;
}

std::vector<ActionId> ActionIndex::Find(std::string_view name, std::span<const std::string> args) const {
  auto it = by_key_.find(Key(name, args));
  return it == by_key_.end() ? std::vector<ActionId>{} : it->second;
}

std::string ExplainMissingAction(const pddl::Domain&, const pddl::Problem&, std::string_view,
                                 std::span<const std::string>, const GroundTask*) {
  return "";
}

}  // namespace seaplan::task
