#include "process_memory.h"

#include <charconv>
#include <fstream>

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

// The lowest limit on the cgroup at `path` (under `root`) and its
// ancestors, and the cgroup's own usage.
std::optional<MemoryHeadroom> CgroupRoom(const std::string& root, std::string path,
                                         const char* limit_file, const char* usage_file,
                                         const char* name) {
  const auto usage = ReadNumber(root + path + "/" + usage_file);
  if (!usage) return std::nullopt;
  std::optional<std::size_t> lowest;
  while (true) {
    const auto limit = ReadNumber(root + path + "/" + limit_file);
    if (limit && *limit < kUnlimited && (!lowest || *limit < *lowest)) lowest = limit;
    if (path.empty() || path == "/") break;
    path.resize(path.rfind('/'));
  }
  if (!lowest) return std::nullopt;
  const std::size_t left = *lowest > *usage ? *lowest - *usage : 0;
  return MemoryHeadroom{left / 4 * 3 / kMb,
                        std::string(name) + " " + std::to_string(*lowest / kMb) + " MB"};
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
      room = CgroupRoom(cgroup_root, path, "memory.max", "memory.current", "cgroup memory.max");
    } else if (controllers.find(",memory,") != std::string::npos) {
      room = CgroupRoom(cgroup_root + "/memory", path, "memory.limit_in_bytes",
                        "memory.usage_in_bytes", "cgroup memory.limit_in_bytes");
    }
    if (room && (!tightest || room->mb < tightest->mb)) tightest = room;
  }
  return tightest;
}

std::optional<MemoryHeadroom> ProcessMemoryHeadroom() {
  return CgroupHeadroom();
}

}  // namespace seaplan::search
