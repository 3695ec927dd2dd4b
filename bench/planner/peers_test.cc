#include "peers.h"

#include <gtest/gtest.h>

namespace seaplan::bench {
namespace {

TEST(PlanOutputTest, RecognisesIpcPlanLines) {
  EXPECT_TRUE(IsPlanLine("0.000: (sail ferry quay-a quay-b) [10.000]"));
  EXPECT_TRUE(IsPlanLine("  12.5 :  (load c1 s1 p1)  [3]"));
  EXPECT_FALSE(IsPlanLine("; makespan: 10.000"));
  EXPECT_FALSE(IsPlanLine("improved plan: makespan 10 s after 0.01 s"));
  EXPECT_FALSE(IsPlanLine("10: not an action"));
  EXPECT_FALSE(IsPlanLine(""));
}

TEST(PlanOutputTest, TakesTheLastPlanPrinted) {
  const std::string out =
      "; Plan found with metric 20\n"
      "0.000: (a x) [10.000]\n"
      "10.001: (b x) [10.000]\n"
      "\n"
      "Searching for a better plan\n"
      "; Plan found with metric 12\n"
      "0.000: (c x) [5.000]\n"
      "5.001: (d x) [7.000]\n"
      "; Plan found with metric 9\n"
      "0.000: (e x) [9.000]\n";
  EXPECT_EQ(LastPlan(out), "0.000: (e x) [9.000]\n");
  EXPECT_EQ(LastPlan("0.000: (c x) [5.000]\n5.001: (d x) [7.000]\n"),
            "0.000: (c x) [5.000]\n5.001: (d x) [7.000]\n");
  EXPECT_EQ(LastPlan("no plan\n;; search failed\n"), "");
}

TEST(PeerRunsTest, ReadsTheEveryRunTable) {
  const std::string markdown =
      "## Coverage\n| domain | optic |\n|---|---|\n| d | 1/1 |\n"
      "## Every run\n"
      "| domain | problem | planner | status | wall s | first plan s | makespan | actions |\n"
      "|---|---|---|---|---|---|---|---|\n"
      "| depots | p01 | optic | solved | 0.50 | - | 30.000 | 12 |\n"
      "| depots | p01 | stp2 | solved | 60.00 | 8.50 | 28.000 | 11 |\n"
      "| depots | p02 | tfd | timeout | 60.00 | - | - | - |\n";
  const auto runs = ParsePeerRuns(markdown);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_EQ(runs[0].planner, "optic");
  EXPECT_TRUE(runs[0].solved);
  EXPECT_DOUBLE_EQ(runs[0].time_s, 0.5);  // wall time when no first-plan time
  EXPECT_DOUBLE_EQ(runs[1].time_s, 8.5);  // first-plan time when given
  EXPECT_EQ(runs[1].actions, 11);
  EXPECT_FALSE(runs[2].solved);
}

TEST(PeerRunsTest, TimeScoreFollowsTheIpcFormula) {
  bench::Run run;
  run.solved = true;
  run.time_s = 0.5;
  EXPECT_DOUBLE_EQ(TimeScore(run, 10), 1.0);
  run.time_s = 10;
  EXPECT_NEAR(TimeScore(run, 100), 0.5, 1e-12);
  run.time_s = 11;
  EXPECT_DOUBLE_EQ(TimeScore(run, 10), 0.0);
  run.solved = false;
  run.time_s = 0.5;
  EXPECT_DOUBLE_EQ(TimeScore(run, 10), 0.0);
}

}  // namespace
}  // namespace seaplan::bench
