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

// Build keeps the prefix a new path shares with the one built before and
// undoes the rest: every answer must be the one of a fresh build.
TEST_F(TimelineTest, BuildFromAnotherBranchEqualsBuildingFromScratch) {
  const int a = Action("work-a"), b = Action("work-b"), c = Action("work-c");
  const std::vector<Event> first = Path();
  // Shares its first two events with `first`, then ends b and a before c starts.
  const std::vector<Event> second = {{2 * a, 10, 10},     {2 * b, 15, 15}, {2 * b + 1, 15, 15},
                                     {2 * a + 1, 10, 10}, {2 * c, 20, 20}, {2 * c + 1, 20, 20}};
  auto expect_same = [&](const Timeline& t, std::span<const Event> path) {
    Timeline fresh(*snap_, 0.001);
    ASSERT_TRUE(fresh.Build(path));
    EXPECT_DOUBLE_EQ(t.Current().makespan_s, fresh.Current().makespan_s);
    EXPECT_DOUBLE_EQ(t.Current().lower_bound_s, fresh.Current().lower_bound_s);
    for (std::size_t k = 0; k < path.size(); ++k)
      EXPECT_DOUBLE_EQ(t.EventTime(k), fresh.EventTime(k)) << k;
    for (task::FactId f = 0; f < snap_->num_facts(); ++f) {
      EXPECT_DOUBLE_EQ(t.FactWrittenAt(f), fresh.FactWrittenAt(f)) << f;
      EXPECT_DOUBLE_EQ(t.FactReadUntil(f), fresh.FactReadUntil(f)) << f;
    }
    for (task::ActionId x = 0; x < snap_->num_actions(); ++x)
      EXPECT_DOUBLE_EQ(t.StartedAt(x), fresh.StartedAt(x)) << x;
  };
  Timeline t(*snap_, 0.001);
  ASSERT_TRUE(t.Build(first));
  expect_same(t, first);
  ASSERT_TRUE(t.Build(second));
  expect_same(t, second);
  // A prefix, then a path that shares nothing but grows from it again.
  ASSERT_TRUE(t.Build(std::span<const Event>(first).first(3)));
  expect_same(t, std::span<const Event>(first).first(3));
  Timeline::Outcome out, fresh_out;
  ASSERT_TRUE(t.TryAdd(first[3], &out));
  t.Keep(first[3]);
  Timeline fresh(*snap_, 0.001);
  ASSERT_TRUE(fresh.Build(std::span<const Event>(first).first(3)));
  ASSERT_TRUE(fresh.TryAdd(first[3], &fresh_out));
  EXPECT_DOUBLE_EQ(out.makespan_s, fresh_out.makespan_s);
  EXPECT_DOUBLE_EQ(out.lower_bound_s, fresh_out.lower_bound_s);
  fresh.Undo();
  expect_same(t, std::span<const Event>(first).first(4));
  ASSERT_TRUE(t.Build(std::span<const Event>()));
  EXPECT_DOUBLE_EQ(t.Current().makespan_s, 0.0);
  ASSERT_TRUE(t.Build(first));
  expect_same(t, first);
  // A tentative event left without Undo() does not survive a Build.
  ASSERT_TRUE(t.Build(std::span<const Event>(second).first(2)));
  ASSERT_TRUE(t.TryAdd(second[2], &out));
  ASSERT_TRUE(t.Build(second));
  expect_same(t, second);
  // Told the shared prefix (as the search is, from its tree): the same.
  ASSERT_TRUE(t.Build(2, std::span<const Event>(first).subspan(2)));
  expect_same(t, first);
  ASSERT_TRUE(t.Build(0, second));
  expect_same(t, second);
  ASSERT_TRUE(t.Build(6, std::span<const Event>()));
  expect_same(t, second);
  // The makespan a successor is scheduled against is the rebuilt path's.
  ASSERT_TRUE(t.Build(2, std::span<const Event>(first).subspan(2, 1)));
  ASSERT_TRUE(t.TryAdd(first[3], &out));
  t.Undo();
  EXPECT_DOUBLE_EQ(out.makespan_s, fresh_out.makespan_s);
  EXPECT_DOUBLE_EQ(out.lower_bound_s, fresh_out.lower_bound_s);
}

}  // namespace
}  // namespace seaplan::search
