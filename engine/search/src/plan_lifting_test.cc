#include "plan_lifting.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "plan_builder.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/plan.h"

namespace seaplan::search {
namespace {

// work-a and work-b are independent (both only read ready and both add
// flag); work-c needs work-a's result at start.
constexpr char kDomain[] = R"((define (domain lift)
  (:requirements :durative-actions)
  (:predicates (ready) (done-a) (done-b) (done-c) (flag))
  (:durative-action work-a :parameters () :duration (= ?duration 10)
    :condition (at start (ready))
    :effect (and (at end (done-a)) (at end (flag))))
  (:durative-action work-b :parameters () :duration (= ?duration 5)
    :condition (at start (ready))
    :effect (and (at end (done-b)) (at end (flag))))
  (:durative-action work-c :parameters () :duration (= ?duration 3)
    :condition (and (at start (done-a)) (over all (ready)))
    :effect (at end (done-c)))))";

constexpr char kProblem[] = R"((define (problem lift-1) (:domain lift)
  (:init (ready))
  (:goal (and (done-b) (done-c) (flag)))))";

struct Fixture {
  std::shared_ptr<const task::GroundTask> task;
  int Action(const std::string& name) const {
    for (std::size_t a = 0; a < task->actions.size(); ++a) {
      if (task->actions[a].name == name) return static_cast<int>(a);
    }
    ADD_FAILURE() << name << " not grounded";
    return 0;
  }
};

Fixture Load() {
  auto loaded = task::LoadTask(kDomain, kProblem);
  EXPECT_TRUE(loaded.ok()) << loaded.ErrorText();
  return {loaded.task};
}

// A durative step as two events plus their times.
void AddStep(int action, double start, double d, std::vector<Event>& events,
             std::vector<double>& times) {
  events.push_back({2 * action, d, d});
  times.push_back(start);
  events.push_back({2 * action + 1, d, d});
  times.push_back(start + d);
}

validate::Plan ToPlan(const task::GroundTask& task, const std::vector<Event>& events,
                      const std::vector<double>& times) {
  validate::Plan plan;
  for (std::size_t i = 0; i < events.size(); i += 2) {
    const auto& action = task.actions[static_cast<std::size_t>(events[i].snap / 2)];
    validate::PlanStep step;
    step.start_s = times[i];
    step.duration_s = events[i].min_duration_s;
    step.name = action.name;
    step.args = action.args;
    plan.steps.push_back(step);
  }
  return plan;
}

// a from 0 to 10, then b, then c, each epsilon after the last one's end,
// as a total-order schedule would have them.
class SequencedStepsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    f = Load();
    ASSERT_TRUE(f.task);
    snap = std::make_unique<SnapTask>(*f.task);
    AddStep(f.Action("work-a"), 0, 10, events, times);
    AddStep(f.Action("work-b"), 10.001, 5, events, times);
    AddStep(f.Action("work-c"), 15.002, 3, events, times);
  }
  Fixture f;
  std::unique_ptr<SnapTask> snap;
  std::vector<Event> events;
  std::vector<double> times;
};

TEST_F(SequencedStepsTest, IndependentActionsRunInParallel) {
  const PlanValidator validator(*f.task, 0.001);
  const auto before = validator.Validate(ToPlan(*f.task, events, times));
  ASSERT_TRUE(before.valid) << before.ToString();

  const auto lifted = LiftAndReschedule(*snap, events, times, 0.001);
  ASSERT_TRUE(lifted.has_value());
  // b shares nothing with a but what both only read or both add: it starts at 0.
  EXPECT_DOUBLE_EQ((*lifted)[2], 0.0);
  // c needs done-a from a's end: epsilon after it, not after b.
  EXPECT_NEAR((*lifted)[4], 10.001, 1e-9);
  const auto after = validator.Validate(ToPlan(*f.task, events, *lifted));
  EXPECT_TRUE(after.valid) << after.ToString();
  EXPECT_NEAR(after.makespan_s, 13.001, 1e-9);
  EXPECT_LT(after.makespan_s, before.makespan_s);
}

TEST(PlanLiftingTest, TightPlanStaysValidAndNoLonger) {
  const Fixture f = Load();
  ASSERT_TRUE(f.task);
  const SnapTask snap(*f.task);
  std::vector<Event> events;
  std::vector<double> times;
  AddStep(f.Action("work-a"), 0, 10, events, times);
  AddStep(f.Action("work-c"), 10.001, 3, events, times);
  AddStep(f.Action("work-b"), 0, 5, events, times);
  const PlanValidator validator(*f.task, 0.001);
  const auto before = validator.Validate(ToPlan(*f.task, events, times));
  ASSERT_TRUE(before.valid) << before.ToString();
  const auto lifted = LiftAndReschedule(snap, events, times, 0.001);
  ASSERT_TRUE(lifted.has_value());
  const auto after = validator.Validate(ToPlan(*f.task, events, *lifted));
  EXPECT_TRUE(after.valid) << after.ToString();
  EXPECT_LE(after.makespan_s, before.makespan_s + 1e-9);
  // c still needs a's result: never moved before a's end + epsilon.
  EXPECT_GE((*lifted)[2], (*lifted)[1] + 0.001 - 1e-9);
}

TEST_F(SequencedStepsTest, WithTheConcurrencyBoundEveryStartStaysAfterTheEndsBeforeIt) {
  const auto lifted = LiftAndReschedule(*snap, events, times, 0.001, /*bound_concurrency=*/true);
  ASSERT_TRUE(lifted.has_value());
  // b shares nothing with a, but starts after a's end, and c after b's.
  EXPECT_NEAR((*lifted)[2], (*lifted)[1] + 0.001, 1e-9);
  EXPECT_NEAR((*lifted)[4], (*lifted)[3] + 0.001, 1e-9);
}

TEST_F(SequencedStepsTest, APlanNeedingMorePairsThanTheBoundIsLeftAsFound) {
  EXPECT_FALSE(LiftAndReschedule(*snap, events, times, 0.001, false, /*max_pairs=*/1).has_value());
  EXPECT_TRUE(LiftAndReschedule(*snap, events, times, 0.001, false, /*max_pairs=*/100).has_value());
}

}  // namespace
}  // namespace seaplan::search
