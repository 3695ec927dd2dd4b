// Test helper for the grounding stage tests: parses small PDDL texts and
// holds what every stage takes (domain, problem, a context).
#pragma once

#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "grounding_internal.h"

namespace seaplan::task::internal {

class StageFixture {
 public:
  StageFixture(const std::string& domain_text, const std::string& problem_text,
               const GroundingOptions& options = {}, const StopToken& stop = StopToken())
      : options_(options), stop_(stop) {
    auto d = pddl::ParseDomain(domain_text);
    EXPECT_TRUE(d.domain.has_value()) << pddl::FormatDiagnostics(d.diagnostics);
    if (d.domain) domain_ = std::move(*d.domain);
    auto p = pddl::ParseProblem(problem_text, domain_);
    EXPECT_TRUE(p.problem.has_value()) << pddl::FormatDiagnostics(p.diagnostics);
    if (p.problem) problem_ = std::move(*p.problem);
    context_.emplace(problem_, options_, stop_, diagnostics_);
  }

  StageFixture(const StageFixture&) = delete;
  StageFixture& operator=(const StageFixture&) = delete;

  const pddl::Domain& domain() const { return domain_; }
  const pddl::Problem& problem() const { return problem_; }
  pddl::Problem& mutable_problem() { return problem_; }
  GroundingContext& context() { return *context_; }
  const std::vector<pddl::Diagnostic>& diagnostics() const { return diagnostics_; }
  std::string DiagnosticText() const { return pddl::FormatDiagnostics(diagnostics_); }

 private:
  GroundingOptions options_;
  StopToken stop_;
  pddl::Domain domain_;
  pddl::Problem problem_;
  std::vector<pddl::Diagnostic> diagnostics_;
  std::optional<GroundingContext> context_;
};

}  // namespace seaplan::task::internal
