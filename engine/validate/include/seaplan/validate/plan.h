// Temporal plans as values, and their text form (the IPC / VAL format).
//
//   ; comment
//   0.000: (load-cont ship0 port-a cont-x) [60.000]
//   60.001: (move-ship ship0 port-a port-b) [288.888888888889]
//   70: (instantaneous-action a b)
//
// A Plan is a copyable value; it names actions by (name, args) strings and
// never refers to a ground task. The validator (validator.h) maps the steps
// to ground actions.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"

namespace seaplan::validate {

struct PlanStep {
  double start_s = 0.0;
  std::string name;               // lower case (ParsePlan folds case)
  std::vector<std::string> args;  // lower case
  // 0 for instantaneous steps (no "[d]" in the text).
  double duration_s = 0.0;
  // 1-based line in the text the step came from; 0 when built in code.
  int line = 0;

  // "(name arg1 arg2)"
  std::string DisplayName() const;
  double end_s() const { return start_s + duration_s; }

  friend bool operator==(const PlanStep&, const PlanStep&) = default;
};

struct Plan {
  std::vector<PlanStep> steps;

  friend bool operator==(const Plan&, const Plan&) = default;
};

// Parses the IPC plan format, one step a line:
//   <time> [':'] '(' <name> <arg>* ')' ['[' <duration> ']']
// Tolerated: ';' comments (whole line or trailing), blank lines, any case
// (names are folded to lower case), '\r\n' line ends, a UTF-8 byte-order
// mark, steps without "[d]" (instantaneous; duration 0), numbers in any form
// std::from_chars accepts except inf/nan. Steps keep their text order (the
// validator sorts events by time itself).
// Errors are InvalidArgument and say "plan line L, column C: ...".
absl::StatusOr<Plan> ParsePlan(std::string_view text);

// Prints one "<start>: (<name> <args>) [<duration>]" line per step ("[d]"
// left out when the duration is 0).
//
// Numbers are printed in the SHORTEST decimal form that parses back to the
// very same double (std::to_chars round-trip guarantee, fixed notation), so
// ParsePlan(FormatPlan(p)) == p for every finite plan. On a 1e-6 grid that is
// at most 6 decimals with trailing zeros dropped ("60.001", "288.5"); values
// off that grid get up to 17 significant digits ("288.88888888888886").
// Why not a fixed number of decimals: a plan must be valid AS PRINTED. The
// paper's planner STP printed 4 decimals; a move of 288.88888... s became
// 288.8889 and its end landed 0.0008 s after the next action started, so VAL
// rejected the plan. Exact printing makes the printed plan and the validated
// plan the same plan.
std::string FormatPlan(const Plan& plan);

// The shortest round-trip decimal form of `value` used by FormatPlan.
std::string FormatTime(double value);

}  // namespace seaplan::validate
