#include "process_memory.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace seaplan::search {
namespace {

void Write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// A cgroup file system of its own: each limit on the way up counts with
// its own cgroup's usage less reclaimable cache, "max" and v1's "no limit"
// do not, and a path the mount does not have is the mount's root.
TEST(ProcessMemoryTest, CgroupLimitsOfTheCgroupAndItsAncestors) {
  const auto root = std::filesystem::temp_directory_path() /
                    ("seaplan-cgroup-test-" + std::to_string(::getpid()));
  std::filesystem::remove_all(root);
  constexpr std::size_t kMb = std::size_t{1} << 20;
  // v2: /a/b has no limit of its own; /a has 500 MB and uses 170 MB, 20 of
  // them reclaimable cache (b and a sibling together).
  Write(root / "proc-v2", "0::/a/b\n");
  Write(root / "sys/a/b/memory.max", "max\n");
  Write(root / "sys/a/b/memory.current", std::to_string(100 * kMb) + "\n");
  Write(root / "sys/a/memory.max", std::to_string(500 * kMb) + "\n");
  Write(root / "sys/a/memory.current", std::to_string(170 * kMb) + "\n");
  Write(root / "sys/a/memory.stat",
        "anon 1000\ninactive_file " + std::to_string(20 * kMb) + "\nactive_file 5\n");
  auto v2 = CgroupHeadroom((root / "proc-v2").string(), (root / "sys").string());
  ASSERT_TRUE(v2);
  EXPECT_EQ(v2->mb, 262u);  // (500 - (170 - 20)) * 3 / 4
  EXPECT_EQ(v2->limit, "cgroup memory.max 500 MB");
  // v1 (a hybrid: the v2 line has no limit): /x unlimited, the root 1 GB
  // using 200 MB.
  Write(root / "proc-v1", "0::/\n4:cpu,memory:/x\n");
  Write(root / "sys/memory/x/memory.limit_in_bytes", "9223372036854771712\n");
  Write(root / "sys/memory/x/memory.usage_in_bytes", std::to_string(150 * kMb) + "\n");
  Write(root / "sys/memory/memory.limit_in_bytes", std::to_string(1024 * kMb) + "\n");
  Write(root / "sys/memory/memory.usage_in_bytes", std::to_string(200 * kMb) + "\n");
  auto v1 = CgroupHeadroom((root / "proc-v1").string(), (root / "sys").string());
  ASSERT_TRUE(v1);
  EXPECT_EQ(v1->mb, 618u);  // (1024 - 200) * 3 / 4
  EXPECT_EQ(v1->limit, "cgroup memory.limit_in_bytes 1024 MB");
  // A container's view: the host's path is not under the mount, whose
  // root is the container's cgroup.
  Write(root / "proc-docker", "4:memory:/docker/0123abcd\n");
  auto docker = CgroupHeadroom((root / "proc-docker").string(), (root / "sys").string());
  ASSERT_TRUE(docker);
  EXPECT_EQ(docker->mb, 618u);
  // No limit anywhere: no room to keep under.
  Write(root / "proc-none", "0::/free\n");
  Write(root / "sys/free/memory.max", "max\n");
  Write(root / "sys/free/memory.current", "4096\n");
  EXPECT_FALSE(CgroupHeadroom((root / "proc-none").string(), (root / "sys").string()));
  std::filesystem::remove_all(root);
}

// Planning runs at once keep one count: each sets its own, the total
// follows (also when a count shrinks), and a finished run's leaves it.
TEST(ProcessMemoryTest, ThePlanningRunsOfAProcessCountTogether) {
  constexpr std::size_t kMb = std::size_t{1} << 20;
  PlanningMemoryLedger ledger;
  {
    PlanningMemoryLedger::Entry first(ledger);
    EXPECT_EQ(first.Update(100 * kMb), 100 * kMb);
    {
      PlanningMemoryLedger::Entry second(ledger);
      EXPECT_EQ(second.Update(50 * kMb), 150 * kMb);
      EXPECT_EQ(first.Update(20 * kMb), 70 * kMb);
      EXPECT_EQ(ledger.total_bytes(), 70 * kMb);
    }
    EXPECT_EQ(ledger.total_bytes(), 20 * kMb);
  }
  EXPECT_EQ(ledger.total_bytes(), 0u);
  // 300 MB of room seen while the others held 400 MB, three quarters of
  // which the room had already lost to them.
  EXPECT_EQ(PlanningMemoryLedger::RoomForAllMb(300, 400 * kMb), 600u);
  EXPECT_EQ(PlanningMemoryLedger::RoomForAllMb(300, 0), 300u);
}

}  // namespace
}  // namespace seaplan::search
