// Parses the "Every run" table of peers.md and planners' printed plans, and
// computes IPC scores.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

namespace seaplan::bench {

struct Run {
  std::string domain, problem, planner;
  bool solved = false;
  double time_s = -1;  // first plan if given, else wall time
  double makespan = -1;
  int actions = -1;
};

// Rows of the "## Every run" table; unknown or malformed rows are skipped.
std::vector<Run> ParsePeerRuns(const std::string& markdown);

// Whether `line` is a step of an IPC plan, "12.5: (action a b) [3.0]" (the
// format every planner prints).
bool IsPlanLine(const std::string& line);

// The last block of consecutive plan lines in `text` (planners that improve
// their plan print each one, separated by other lines; the last is the
// best), "" when there is none.
std::string LastPlan(const std::string& text);

// IPC time score of one run: 1 if t <= 1 s, else 1 - log(t)/log(limit); 0 if unsolved or t > limit.
double TimeScore(const Run& run, double limit_s);

}  // namespace seaplan::bench
