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
// the cgroup has left. Planning runs at once (a server's) would each see
// the same room, so they also keep a count together (PlanningMemoryLedger)
// that must stay under it.
#pragma once

#include <atomic>
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

// The memory the planning runs of one process count at once (each its
// tables, as it last polled). A run's room under a cgroup limit
// (ProcessMemoryHeadroom) is measured at its start, when the usage already
// holds the other runs' tables; the room for all of them is that plus the
// part of it their count takes (RoomForAllMb), and the runs stop, with the
// plan found so far, once their total reaches it. Without it two runs
// started at once would each count on all of the room.
class PlanningMemoryLedger {
 public:
  // One run's line; its count leaves the total when it is destroyed.
  class Entry {
   public:
    explicit Entry(PlanningMemoryLedger& ledger) : ledger_(ledger) {}
    Entry(const Entry&) = delete;
    Entry& operator=(const Entry&) = delete;
    ~Entry() { ledger_.total_bytes_.fetch_sub(bytes_); }
    // Sets this run's count and returns the total of all runs.
    std::size_t Update(std::size_t bytes) {
      const std::size_t before = ledger_.total_bytes_.fetch_add(bytes - bytes_);
      const std::size_t total = before + bytes - bytes_;
      bytes_ = bytes;
      return total;
    }
    std::size_t bytes() const { return bytes_; }

   private:
    PlanningMemoryLedger& ledger_;
    std::size_t bytes_ = 0;
  };

  // The ledger of this process's runs.
  static PlanningMemoryLedger& OfProcess();

  std::size_t total_bytes() const { return total_bytes_.load(); }
  // The room for all runs' tables, given the room one run saw at its start
  // (`room_mb`, already discounted to three quarters) and, at that moment,
  // the other runs' total (`others_bytes`, inside the usage that room was
  // measured against).
  static std::size_t RoomForAllMb(std::size_t room_mb, std::size_t others_bytes) {
    return room_mb + (others_bytes >> 20) * 3 / 4;
  }

 private:
  std::atomic<std::size_t> total_bytes_{0};  // unsigned wrap-around cancels in the sum
};

}  // namespace seaplan::search
