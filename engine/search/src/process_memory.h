// How much more memory this process may take before the system kills it:
// what the planner's memory limit must stay under.
//
// Benchmark runners and containers limit a planner in one of two ways: its
// address space (setrlimit's RLIMIT_AS, `ulimit -v`) or its cgroup's memory
// (v2 memory.max, v1 memory.limit_in_bytes). Past the first an allocation
// fails, which the planner survives with the plan found so far (SolveTask),
// keeping all of the room: so only the second, past which the kernel kills
// the process, counts here. The planner's own limit counts its tables'
// capacity and polls every few steps; a table that doubles holds its old
// and new storage at once, and the process holds more than the tables (the
// task, the heuristic's tables, libraries): three quarters of the memory
// the cgroup has left. Planning runs at once (a server's) each see the
// same room: the limit then bounds each, not their sum.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace seaplan::search {

struct MemoryHeadroom {
  std::size_t mb = 0;  // what the planner's tables may take, after the discount
  std::string limit;   // which limit it comes from, for the log
};

// The room this process's cgroup leaves, or nullopt when no memory limit
// is set (or none can be read: not Linux, no cgroup file system).
std::optional<MemoryHeadroom> ProcessMemoryHeadroom();

// The same read from other files (tests): for the cgroup `proc_cgroup`
// names (under `cgroup_root`, or the mount's root when that path is not
// there, as in a container) and each ancestor with a memory limit, the
// limit less that cgroup's usage but reclaimable page cache (memory.stat's
// inactive_file), three quarters of the least; cgroup v2 and v1.
std::optional<MemoryHeadroom> CgroupHeadroom(const std::string& proc_cgroup = "/proc/self/cgroup",
                                             const std::string& cgroup_root = "/sys/fs/cgroup");

}  // namespace seaplan::search
