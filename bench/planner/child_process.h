// Runs a planner as a child process, as a user would, under the same limits
// for every planner: wall-clock time (killed at the limit plus a grace
// period) and resident memory (sampled; killed above the limit).
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace seaplan::bench {

struct ChildLimits {
  double time_limit_s = 60;
  double grace_s = 1;  // beyond the limit before SIGKILL (a planner's own limit stops it first)
  double memory_limit_mb = 2048;
};

struct ChildResult {
  bool started = false;
  int exit_code = -1;  // -1 when killed by a signal
  int signal = 0;
  bool killed_for_time = false, killed_for_memory = false;
  double wall_s = 0;  // spawn to exit, as seen by the parent
  double cpu_s = 0;   // user + system of the child (wait4)
  double peak_rss_mb = 0;
  std::string out, err;
};

// Called for each complete line the child writes (`is_stderr`), with the
// wall time since spawn at which the parent read it.
using LineObserver = std::function<void(bool is_stderr, const std::string& line, double at_s)>;

ChildResult RunChild(const std::vector<std::string>& argv, const ChildLimits& limits,
                     const LineObserver& on_line = {});

}  // namespace seaplan::bench
