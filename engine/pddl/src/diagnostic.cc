#include "seaplan/pddl/diagnostic.h"

namespace seaplan::pddl {

std::string SourceLocation::ToString() const {
  std::string out = file.empty() ? std::string("<input>") : file;
  if (line > 0) {
    out += ":" + std::to_string(line);
    if (column > 0) out += ":" + std::to_string(column);
  }
  return out;
}

std::string Diagnostic::ToString() const {
  std::string out = location.ToString();
  if (severity == Severity::kWarning) {
    out += ": warning: ";
  } else if (kind == DiagnosticKind::kUnsupported) {
    out += ": unsupported: ";
  } else {
    out += ": error: ";
  }
  out += message;
  if (!symbol.empty() || !expected.empty()) {
    out += " (";
    if (!symbol.empty()) out += "found '" + symbol + "'";
    if (!symbol.empty() && !expected.empty()) out += ", ";
    if (!expected.empty()) out += "expected " + expected;
    out += ")";
  }
  return out;
}

bool HasErrors(const std::vector<Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics) {
    if (d.severity == Severity::kError) return true;
  }
  return false;
}

bool HasUnsupported(const std::vector<Diagnostic>& diagnostics) {
  for (const auto& d : diagnostics) {
    if (d.severity == Severity::kError && d.kind == DiagnosticKind::kUnsupported) return true;
  }
  return false;
}

std::string FormatDiagnostics(const std::vector<Diagnostic>& diagnostics) {
  std::string out;
  for (const auto& d : diagnostics) {
    out += d.ToString();
    out += '\n';
  }
  return out;
}

}  // namespace seaplan::pddl
