#include "seaplan/mission/search_planner.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "test_util.h"

namespace seaplan::mission {
namespace {

using testing::ReadTestData;

double Makespan(const validate::Plan& plan) {
  double end = 0;
  for (const auto& s : plan.steps) end = std::max(end, s.start_s + s.duration_s);
  return end;
}

search::PlannerOptions Options(bool anytime) {
  search::PlannerOptions o;
  o.time_limit_s = 20;
  o.anytime = anytime;
  return o;
}

TEST(SearchPlannerTest, QualityFollowsTheSearchStatus) {
  const std::string domain = ReadTestData("domain.pddl");
  const std::string problem = ReadTestData("case-a.pddl");
  for (bool anytime : {false, true}) {
    const search::PlannerOptions options = Options(anytime);
    auto out = SearchPlanner(options, PlanningPhase::kInitial)(domain, problem, StopToken());
    ASSERT_TRUE(out.ok()) << out.status();
    ASSERT_TRUE(out->solved) << out->status;
    const search::PlanResult direct = search::Solve(domain, problem, options, StopToken());
    EXPECT_EQ(out->status, search::ToString(direct.status));
    EXPECT_EQ(out->quality == PlanQuality::kOptimal,
              direct.status == search::PlanStatus::kSolvedOptimally);
    EXPECT_EQ(out->plan.steps.size(), direct.plan.steps.size());
  }
}

TEST(SearchPlannerTest, ReplanKeepsTheFirstPlanOrABetterOne) {
  const std::string domain = ReadTestData("domain.pddl");
  const std::string problem = ReadTestData("case-a.pddl");
  auto first = SearchPlanner(Options(false), PlanningPhase::kInitial)(domain, problem, StopToken());
  auto replan = SearchPlanner(Options(true), PlanningPhase::kReplan)(domain, problem, StopToken());
  ASSERT_TRUE(first.ok() && replan.ok());
  ASSERT_TRUE(first->solved && replan->solved);
  EXPECT_LE(Makespan(replan->plan), Makespan(first->plan) + 1e-9);
}

// Under an expansion limit the replan's improvement search is bounded by
// expansions too (twice the first search's), not by time: the same replan
// every time, and never longer than the first plan.
TEST(SearchPlannerTest, ReplanUnderAnExpansionLimitIsTheSameEveryTime) {
  const std::string domain = ReadTestData("domain.pddl");
  const std::string problem = ReadTestData("case-a.pddl");
  search::PlannerOptions limited = Options(true);
  limited.max_expansions = 5000;
  auto first = SearchPlanner(Options(false), PlanningPhase::kInitial)(domain, problem, StopToken());
  auto a = SearchPlanner(limited, PlanningPhase::kReplan)(domain, problem, StopToken());
  auto b = SearchPlanner(limited, PlanningPhase::kReplan)(domain, problem, StopToken());
  ASSERT_TRUE(first.ok() && a.ok() && b.ok());
  ASSERT_TRUE(first->solved && a->solved && b->solved);
  EXPECT_EQ(validate::FormatPlan(a->plan), validate::FormatPlan(b->plan));
  EXPECT_LE(Makespan(a->plan), Makespan(first->plan) + 1e-9);
}

TEST(SearchPlannerTest, BadInputIsAnError) {
  auto out =
      SearchPlanner(Options(false), PlanningPhase::kInitial)("(define", "(define", StopToken());
  EXPECT_TRUE(absl::IsInvalidArgument(out.status())) << out.status();
}

}  // namespace
}  // namespace seaplan::mission
