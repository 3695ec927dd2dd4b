// The fjord example missions (examples/fjord) through the real parser and
// grounder, and the paper's case A plan (Table 3) against the validator.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "seaplan/task/grounder.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/validate/plan.h"
#include "seaplan/validate/validator.h"

namespace seaplan::validate {
namespace {

using ::testing::HasSubstr;
using Kind = ValidationFailure::Kind;

std::string Example(const std::string& name) {
  return seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "examples" / "fjord" / name);
}

task::LoadResult LoadExample(const std::string& domain, const std::string& problem) {
  task::LoadResult loaded = task::LoadTask(Example(domain), Example(problem));
  EXPECT_TRUE(loaded.ok()) << loaded.ErrorText();
  return loaded;
}

Plan PlanFile(const std::string& name) {
  auto plan = ParsePlan(Example(name));
  EXPECT_TRUE(plan.ok()) << plan.status();
  return plan.ok() ? *plan : Plan{};
}

TEST(FjordExamplesTest, EveryMissionGroundsWithoutErrors) {
  for (const auto& [domain, problem] : std::vector<std::pair<std::string, std::string>>{
           {"domain.pddl", "case-a.pddl"},
           {"domain.pddl", "case-b.pddl"},
           {"domain-fuel.pddl", "case-c.pddl"},
           {"domain-numeric.pddl", "case-c-numeric.pddl"}}) {
    const task::LoadResult loaded = task::LoadTask(Example(domain), Example(problem));
    EXPECT_TRUE(loaded.ok()) << domain << " + " << problem << ":\n" << loaded.ErrorText();
    if (!loaded.ok()) continue;
    EXPECT_GT(loaded.task->actions.size(), 0u) << problem;
    EXPECT_FALSE(loaded.task->goal.empty()) << problem;
  }
}

TEST(FjordExamplesTest, PaperTable3AsPrintedIsRejected) {
  const task::LoadResult loaded = LoadExample("domain.pddl", "case-a.pddl");
  ASSERT_TRUE(loaded.ok());
  const Plan paper = PlanFile("case-a-paper.plan");
  ASSERT_EQ(paper.steps.size(), 13u);
  const ValidationResult r = ValidatePlan(*loaded.task, paper);
  ASSERT_FALSE(r.valid);
  // Computed, not assumed: under PDDL 2.1 the first thing that goes wrong is
  // the rounded duration of the first move (288.8 where the domain says
  // 52 / 0.18 = 288.889), at its start, 60.2 s. (The unload at 348.8 before
  // the ship arrives would only come next; see the following test.)
  const ValidationFailure& f = *r.first_failure;
  EXPECT_EQ(f.kind, Kind::kDuration) << r.ToString();
  EXPECT_EQ(f.step_index, 1);
  EXPECT_EQ(f.action, "(move-ship ship0 port-a port-b)");
  EXPECT_DOUBLE_EQ(f.time_s, 60.2);
  // The grounder folds the static fluents (distance, speed) into a constant.
  EXPECT_EQ(f.condition, "(= ?duration 288.8888889)");
  EXPECT_THAT(f.reason, HasSubstr("288.888889"));
}

TEST(FjordExamplesTest, PaperTable3WithExactMoveDurationsStillFailsAtTheFirstUnload) {
  // Give the moves their exact durations but keep the printed start times:
  // the ship reaches port-b at 60.2 + 288.889 = 349.089, the unload starts at
  // 348.8, so its over-all (at ship0 port-b) is false just after it starts.
  const task::LoadResult loaded = LoadExample("domain.pddl", "case-a.pddl");
  ASSERT_TRUE(loaded.ok());
  Plan plan = PlanFile("case-a-paper.plan");
  const double lengths[] = {52, 102, 107, 87};
  int next = 0;
  for (PlanStep& step : plan.steps) {
    if (step.name == "move-ship") step.duration_s = lengths[next++] / 0.18;
  }
  ASSERT_EQ(next, 4);
  const ValidationResult r = ValidatePlan(*loaded.task, plan);
  ASSERT_FALSE(r.valid);
  const ValidationFailure& f = *r.first_failure;
  EXPECT_EQ(f.kind, Kind::kOverAll) << r.ToString();
  EXPECT_EQ(f.step_index, 2);
  EXPECT_EQ(f.action, "(unload-cont cont-x port-b ship0)");
  EXPECT_EQ(f.condition, "(at ship0 port-b)");
  EXPECT_DOUBLE_EQ(f.time_s, 348.8);
}

TEST(FjordExamplesTest, RepairedCaseAPlanIsAccepted) {
  const task::LoadResult loaded = LoadExample("domain.pddl", "case-a.pddl");
  ASSERT_TRUE(loaded.ok());
  const Plan plan = PlanFile("case-a-repaired.plan");
  auto validator = Validator::Create(loaded.task);
  ASSERT_TRUE(validator.ok());
  const ValidationResult r = validator->Validate(plan);
  EXPECT_TRUE(r.valid) << r.ToString();
  EXPECT_EQ(r.action_count, 13u);
  // 348 / 0.18 s of moves + 470 s of port work, all forced into sequence,
  // + 4 separations of 1 ms (3 unload -> load, last move -> repair/refuel).
  EXPECT_NEAR(r.makespan_s, 348 / 0.18 + 470 + 0.004, 1e-9);
  ASSERT_TRUE(r.metric_value.has_value());
  EXPECT_DOUBLE_EQ(*r.metric_value, r.makespan_s);
  // It is printed the way FormatPlan prints it, and stays valid read back.
  std::string steps;
  for (const absl::string_view line : absl::StrSplit(Example("case-a-repaired.plan"), '\n')) {
    if (!line.empty() && line[0] != ';') absl::StrAppend(&steps, line, "\n");
  }
  EXPECT_EQ(steps, FormatPlan(plan));
  const auto reparsed = ParsePlan(FormatPlan(plan));
  ASSERT_TRUE(reparsed.ok());
  EXPECT_TRUE(validator->Validate(*reparsed).valid);
}

TEST(FjordExamplesTest, RepairedCaseAPlanIsTight) {
  // Every zero separation is exact and every 1 ms one is needed: moving any
  // step earlier by 0.5 ms (less than epsilon) breaks the plan.
  const task::LoadResult loaded = LoadExample("domain.pddl", "case-a.pddl");
  ASSERT_TRUE(loaded.ok());
  const Plan plan = PlanFile("case-a-repaired.plan");
  ASSERT_EQ(plan.steps.size(), 13u);
  auto validator = Validator::Create(loaded.task);
  ASSERT_TRUE(validator.ok());
  for (std::size_t i = 1; i < plan.steps.size(); ++i) {
    Plan earlier = plan;
    earlier.steps[i].start_s -= 0.0005;
    EXPECT_FALSE(validator->Validate(earlier).valid) << "step " << i << " 0.5 ms earlier";
  }
  // The move leaves when the load ends; 0.5 ms earlier it breaks the load's
  // invariant (at ship0 port-a).
  Plan early_move = plan;
  early_move.steps[1].start_s -= 0.0005;
  const ValidationResult m = validator->Validate(early_move);
  ASSERT_FALSE(m.valid);
  EXPECT_EQ(m.first_failure->kind, Kind::kOverAll) << m.ToString();
  EXPECT_EQ(m.first_failure->step_index, 0);
  EXPECT_EQ(m.first_failure->other_step_index, 1);
  EXPECT_EQ(m.first_failure->condition, "(at ship0 port-a)");
  // The next load needs (available ship0), which the unload's end adds: with
  // zero separation the two snap actions interfere.
  Plan touching_load = plan;
  touching_load.steps[3].start_s = touching_load.steps[2].end_s();
  const ValidationResult l = validator->Validate(touching_load);
  ASSERT_FALSE(l.valid);
  EXPECT_EQ(l.first_failure->kind, Kind::kMutex) << l.ToString();
  EXPECT_EQ(l.first_failure->step_index, 2);
  EXPECT_EQ(l.first_failure->condition, "(available ship0)");
  // Repair and refuel need the ship at E at their starts, which the last
  // move's end adds: with zero separation they interfere too.
  Plan touching = plan;
  touching.steps[11].start_s = touching.steps[10].end_s();
  touching.steps[12].start_s = touching.steps[10].end_s();
  const ValidationResult t = validator->Validate(touching);
  ASSERT_FALSE(t.valid);
  EXPECT_EQ(t.first_failure->kind, Kind::kMutex) << t.ToString();
  EXPECT_EQ(t.first_failure->step_index, 10);
  EXPECT_EQ(t.first_failure->condition, "(at ship0 port-e)");
}

TEST(FjordExamplesTest, CaseBReplanIsAccepted) {
  const task::LoadResult loaded = LoadExample("domain.pddl", "case-b.pddl");
  ASSERT_TRUE(loaded.ok());
  const Plan plan = PlanFile("case-b.plan");
  const ValidationResult r = ValidatePlan(*loaded.task, plan);
  EXPECT_TRUE(r.valid) << r.ToString();
  EXPECT_EQ(r.action_count, 12u);                      // the paper: 12 actions after the replan
  EXPECT_NEAR(plan.steps[0].duration_s, 66.67, 0.01);  // port-s -> port-b, 12 / 0.18
  // Case A's first move does not exist any more: the ship is not at port-a.
  Plan stale = plan;
  stale.steps[0].args = {"ship0", "port-a", "port-b"};
  const ValidationResult s = ValidatePlan(*loaded.task, stale);
  ASSERT_FALSE(s.valid);
  EXPECT_EQ(s.first_failure->step_index, 0) << s.ToString();
}

TEST(FjordExamplesTest, StepsOutsideTheTaskAreExplainedByTheGrounder) {
  const task::LoadResult loaded = LoadExample("domain.pddl", "case-a.pddl");
  ASSERT_TRUE(loaded.ok());
  Plan plan = PlanFile("case-a-repaired.plan");
  // No route from A to C in case A.
  plan.steps[1].args = {"ship0", "port-a", "port-c"};
  ValidationOptions options;
  options.explain_missing_action = ExplainerFor(loaded);
  const ValidationResult r = ValidatePlan(*loaded.task, plan, options);
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.first_failure->kind, Kind::kUnknownAction) << r.ToString();
  EXPECT_EQ(r.first_failure->step_index, 1);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("(move-ship ship0 port-a port-c)"));
  EXPECT_THAT(r.first_failure->reason, HasSubstr("connected")) << r.ToString();
}

TEST(FjordExamplesTest, NumericCaseCPlanIsAcceptedAndRunningDryIsRejected) {
  const task::LoadResult loaded = LoadExample("domain-numeric.pddl", "case-c-numeric.pddl");
  ASSERT_TRUE(loaded.ok());
  const Plan plan = PlanFile("case-c-numeric.plan");
  const ValidationResult r = ValidatePlan(*loaded.task, plan);
  EXPECT_TRUE(r.valid) << r.ToString();
  // Without the second refuel the ship cannot leave C for D.
  Plan dry = plan;
  dry.steps.erase(dry.steps.begin() + 6);  // the refuel during unload/load at B
  const ValidationResult d = ValidatePlan(*loaded.task, dry);
  ASSERT_FALSE(d.valid);
  EXPECT_EQ(d.first_failure->kind, Kind::kAtStart) << d.ToString();
  EXPECT_EQ(d.first_failure->action, "(move-ship ship0 port-c port-d)");
  EXPECT_EQ(d.first_failure->condition, "(>= (fuel-level ship0) 15)");
}

}  // namespace
}  // namespace seaplan::validate
