#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "seaplan/task/grounder.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::task {
namespace {

// Every bench domain+problem (p01-p05) parses and grounds, or is reported
// as UNSUPPORTED / invalid with a clear diagnostic (never a crash or a silent
// empty task).
TEST(GrounderDataTest, EveryBenchProblemGroundsOrIsClearlyRejected) {
  SEAPLAN_REQUIRE_SHARED(bench, "bench");
  int grounded = 0;
  for (const auto& entry : std::filesystem::directory_iterator(bench)) {
    if (!entry.is_directory()) continue;
    for (int k = 1; k <= 5; ++k) {
      const std::string name = "p0" + std::to_string(k) + ".pddl";  // k < 10
      const auto problem = entry.path() / name;
      if (!std::filesystem::exists(problem)) continue;
      auto domain = entry.path() / ("domain-" + std::to_string(k) + ".pddl");
      if (!std::filesystem::exists(domain)) domain = entry.path() / "domain.pddl";
      auto r = LoadTask(seaplan::testing::ReadFile(domain), seaplan::testing::ReadFile(problem));
      const std::string where = entry.path().filename().string() + "/" + name;
      if (entry.path().filename() == "tms-2011") {
        // Known-invalid instances (INDEX.md): kiln0 declared with two types.
        EXPECT_FALSE(r.ok()) << where;
        EXPECT_NE(r.ErrorText().find("kiln0"), std::string::npos) << where << "\n" << r.ErrorText();
        continue;
      }
      if (r.unsupported()) {
        ADD_FAILURE() << where << " unsupported (no bench domain is expected to be):\n"
                      << r.ErrorText();
        continue;
      }
      ASSERT_TRUE(r.ok()) << where << "\n" << r.ErrorText();
      EXPECT_GT(r.task->actions.size(), 0u) << where;
      EXPECT_GT(r.task->facts.size(), 0u) << where;
      EXPECT_FALSE(r.task->goal.empty()) << where;
      ++grounded;
    }
  }
  EXPECT_GE(grounded, 160);
}

}  // namespace
}  // namespace seaplan::task
