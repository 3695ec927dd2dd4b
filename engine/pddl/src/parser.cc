// TODO(#3): stub while the real parser is written.
#include "seaplan/pddl/parser.h"

namespace seaplan::pddl {

DomainParseResult ParseDomain(std::string_view, std::string_view file_name) {
  DomainParseResult result;
  result.diagnostics.push_back({Severity::kError, DiagnosticKind::kUnsupported,
                                {std::string(file_name), 0, 0}, "", "parser not implemented yet", ""});
  return result;
}

ProblemParseResult ParseProblem(std::string_view, const Domain&, std::string_view file_name) {
  ProblemParseResult result;
  result.diagnostics.push_back({Severity::kError, DiagnosticKind::kUnsupported,
                                {std::string(file_name), 0, 0}, "", "parser not implemented yet", ""});
  return result;
}

}  // namespace seaplan::pddl
