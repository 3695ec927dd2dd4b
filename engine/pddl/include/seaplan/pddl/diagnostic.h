// Diagnostics produced by the PDDL parser and the grounder.
//
// Every problem found in a domain or problem file is reported as a value
// (never an exception): where it is (file, line, column), what the offending
// symbol was, what was expected instead, and whether it is an error in the
// input (kSyntax, kSemantic) or a valid PDDL construct seaplan does not
// support (kUnsupported). Parsing continues after an error where it can, so
// one call reports every independent problem at once.
#pragma once

#include <string>
#include <vector>

namespace seaplan::pddl {

struct SourceLocation {
  std::string file;  // "domain", "problem" or a path, as passed to the parser
  int line = 0;      // 1-based; 0 when unknown
  int column = 0;    // 1-based, in bytes; 0 when unknown

  // "domain:12:5" ("domain" alone when the line is unknown).
  std::string ToString() const;
};

enum class Severity { kError, kWarning };
enum class DiagnosticKind { kSyntax, kSemantic, kUnsupported };

struct Diagnostic {
  Severity severity = Severity::kError;
  DiagnosticKind kind = DiagnosticKind::kSyntax;
  SourceLocation location;
  std::string symbol;    // the offending symbol as written (lower case); may be empty
  std::string message;   // what is wrong, one line
  std::string expected;  // what was expected instead; may be empty

  // "domain:12:5: error: undeclared predicate (found 'x', expected a predicate
  // declared in :predicates)". kUnsupported prints as "unsupported".
  std::string ToString() const;
};

// True when any diagnostic is an error (of any kind, including kUnsupported).
bool HasErrors(const std::vector<Diagnostic>& diagnostics);
// True when any error is of kind kUnsupported.
bool HasUnsupported(const std::vector<Diagnostic>& diagnostics);
// Every diagnostic's ToString(), one per line.
std::string FormatDiagnostics(const std::vector<Diagnostic>& diagnostics);

}  // namespace seaplan::pddl
