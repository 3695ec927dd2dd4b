#include "process_memory.h"

#include <charconv>
#include <fstream>
#include <string_view>
#include <utility>

namespace seaplan::search {
namespace {

constexpr std::size_t kMb = std::size_t{1} << 20;
// cgroup v1 writes "no limit" as a page-rounded 2^63 - 1.
constexpr std::size_t kUnlimited = std::size_t{1} << 62;

// The first word of a file as a number; nullopt for "max" (v2's no limit)
// or a file that cannot be read.
std::optional<std::size_t> ReadNumber(const std::string& path) {
  std::ifstream in(path);
  std::string word;
  if (!(in >> word)) return std::nullopt;
  std::size_t value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size()) return std::nullopt;
  return value;
}

// The value of `key` in a memory.stat file (0 when absent).
std::size_t StatValue(const std::string& path, std::string_view key) {
  std::ifstream in(path);
  std::string name;
  std::size_t value = 0;
  while (in >> name >> value) {
    if (name == key) return value;
  }
  return 0;
}

struct CgroupFiles {
  const char* limit;
  const char* usage;
  const char* inactive_key;  // in memory.stat: reclaimable page cache
  const char* name;
};
constexpr CgroupFiles kCgroupV2{"memory.max", "memory.current", "inactive_file",
                                "cgroup memory.max"};
constexpr CgroupFiles kCgroupV1{"memory.limit_in_bytes", "memory.usage_in_bytes",
                                "total_inactive_file", "cgroup memory.limit_in_bytes"};

// The least room under the limits of the cgroup at `path` (under `root`)
// and its ancestors: each limit less what its own cgroup uses (its
// children's use included) but reclaimable page cache, as kubelet counts
// a working set.
std::optional<MemoryHeadroom> CgroupRoom(const std::string& root, std::string path,
                                         const CgroupFiles& files) {
  // In a container the process's cgroup is often the mount's root, though
  // /proc/self/cgroup names its path on the host.
  if (!ReadNumber(root + path + "/" + files.usage)) path.clear();
  std::optional<MemoryHeadroom> tightest;
  while (true) {
    const std::string dir = root + path + "/";
    const auto limit = ReadNumber(dir + files.limit);
    const auto usage = ReadNumber(dir + files.usage);
    if (limit && usage && *limit < kUnlimited) {
      const std::size_t inactive = StatValue(dir + "memory.stat", files.inactive_key);
      const std::size_t used = *usage > inactive ? *usage - inactive : 0;
      const std::size_t left = *limit > used ? *limit - used : 0;
      MemoryHeadroom room{left / 4 * 3 / kMb,
                          std::string(files.name) + " " + std::to_string(*limit / kMb) + " MB"};
      if (!tightest || room.mb < tightest->mb) tightest = std::move(room);
    }
    if (path.empty() || path == "/") break;
    path.resize(path.rfind('/'));
  }
  return tightest;
}

}  // namespace

std::optional<MemoryHeadroom> CgroupHeadroom(const std::string& proc_cgroup,
                                             const std::string& cgroup_root) {
  // Lines: "0::/path" (v2), "4:memory:/path" (v1, controllers comma-separated).
  std::ifstream in(proc_cgroup);
  std::string line;
  std::optional<MemoryHeadroom> tightest;
  while (std::getline(in, line)) {
    const auto first = line.find(':');
    const auto second = first == std::string::npos ? first : line.find(':', first + 1);
    if (second == std::string::npos) continue;
    const std::string controllers = "," + line.substr(first + 1, second - first - 1) + ",";
    const std::string path = line.substr(second + 1);
    std::optional<MemoryHeadroom> room;
    if (controllers == ",,") {
      room = CgroupRoom(cgroup_root, path, kCgroupV2);
    } else if (controllers.find(",memory,") != std::string::npos) {
      room = CgroupRoom(cgroup_root + "/memory", path, kCgroupV1);
    }
    if (room && (!tightest || room->mb < tightest->mb)) tightest = room;
  }
  return tightest;
}

std::optional<MemoryHeadroom> ProcessMemoryHeadroom() {
  return CgroupHeadroom();
}

PlanningMemoryLedger& PlanningMemoryLedger::OfProcess() {
  static PlanningMemoryLedger ledger;
  return ledger;
}

}  // namespace seaplan::search
