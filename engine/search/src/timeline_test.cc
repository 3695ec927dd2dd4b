#include "timeline.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "seaplan/task/grounder.h"

namespace seaplan::search {
namespace {

// work-a must end after work-b (its end needs done-b) but lasts exactly
// 10 s, so ending it late pushes its start later, and with it work-c,
// which starts after work-a's start (it reads a-started) and lasts 20 s.
constexpr char kDomain[] = R"((define (domain tl)
  (:requirements :durative-actions)
  (:predicates (ready) (a-started) (done-a) (done-b) (done-c))
  (:durative-action work-a :parameters () :duration (= ?duration 10)
    :condition (and (at start (ready)) (at end (done-b)))
    :effect (and (at start (a-started)) (at end (done-a))))
  (:durative-action work-b :parameters () :duration (= ?duration 15)
    :condition (at start (ready))
    :effect (at end (done-b)))
  (:durative-action work-c :parameters () :duration (= ?duration 20)
    :condition (at start (a-started))
    :effect (at end (done-c)))))";

constexpr char kProblem[] = R"((define (problem tl-1) (:domain tl)
  (:init (ready))
  (:goal (and (done-a) (done-c)))))";

class TimelineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = task::LoadTask(kDomain, kProblem);
    ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
    task_ = loaded.task;
    snap_ = std::make_unique<SnapTask>(*task_);
  }
  int Action(const std::string& name) const {
    for (std::size_t a = 0; a < task_->actions.size(); ++a) {
      if (task_->actions[a].name == name) return static_cast<int>(a);
    }
    ADD_FAILURE() << name << " not grounded";
    return 0;
  }
  // start a, start b, start c, end c, end b, end a.
  std::vector<Event> Path() const {
    const int a = Action("work-a"), b = Action("work-b"), c = Action("work-c");
    return {{2 * a, 10, 10},     {2 * b, 15, 15},     {2 * c, 20, 20},
            {2 * c + 1, 20, 20}, {2 * b + 1, 15, 15}, {2 * a + 1, 10, 10}};
  }

  std::shared_ptr<const task::GroundTask> task_;
  std::unique_ptr<SnapTask> snap_;
};

TEST_F(TimelineTest, KeepAfterTryAddEqualsBuildingTheLongerPath) {
  const std::vector<Event> path = Path();
  Timeline incremental(*snap_, 0.001);
  ASSERT_TRUE(incremental.Build(std::span<const Event>(path).first(1)));
  for (std::size_t i = 1; i < path.size(); ++i) {
    // A sibling tried and undone first must leave no trace.
    if (i + 1 < path.size()) {
      Timeline::Outcome sibling;
      incremental.TryAdd(path[i + 1], &sibling);
      incremental.Undo();
    }
    Timeline::Outcome out;
    ASSERT_TRUE(incremental.TryAdd(path[i], &out)) << i;
    Timeline rebuilt(*snap_, 0.001);
    ASSERT_TRUE(rebuilt.Build(std::span<const Event>(path).first(i + 1)));
    // The makespan found from the raised nodes is the full scan's.
    EXPECT_DOUBLE_EQ(out.makespan_s, rebuilt.Current().makespan_s) << i;
    incremental.Keep(path[i]);
    const Timeline::Outcome now = incremental.Current();
    EXPECT_DOUBLE_EQ(now.makespan_s, rebuilt.Current().makespan_s) << i;
    EXPECT_DOUBLE_EQ(now.lower_bound_s, rebuilt.Current().lower_bound_s) << i;
    for (std::size_t k = 0; k <= i; ++k)
      EXPECT_DOUBLE_EQ(incremental.EventTime(k), rebuilt.EventTime(k)) << i << " " << k;
  }
  EXPECT_NEAR(incremental.Current().makespan_s, 25.002, 1e-9);
}

TEST_F(TimelineTest, TryAddMakespanCountsEarlierEventsPushedLater) {
  // Before work-a's end, work-c ends last (at 0.001 + 20). work-a's end
  // comes after work-b's (15.001) and pulls work-a's start to 5.001, hence
  // work-c's start to 5.002 and its end to 25.002: the makespan is an
  // earlier event raised by propagation, not the new one.
  const std::vector<Event> path = Path();
  Timeline t(*snap_, 0.001);
  ASSERT_TRUE(t.Build(std::span<const Event>(path).first(5)));
  EXPECT_NEAR(t.Current().makespan_s, 20.001, 1e-9);
  Timeline::Outcome out;
  ASSERT_TRUE(t.TryAdd(path[5], &out));
  EXPECT_NEAR(out.makespan_s, 25.002, 1e-9);
  EXPECT_NEAR(out.lower_bound_s, 25.002, 1e-9);
  t.Undo();
  EXPECT_NEAR(t.Current().makespan_s, 20.001, 1e-9);
  // The same event again after the undo: the same answer.
  ASSERT_TRUE(t.TryAdd(path[5], &out));
  EXPECT_NEAR(out.makespan_s, 25.002, 1e-9);
  t.Undo();
}

}  // namespace
}  // namespace seaplan::search
