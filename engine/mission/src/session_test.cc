#include "seaplan/mission/session.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace seaplan::mission {
namespace {

PlanVersion Version() {
  MissionDefinition def{testing::ReadTestData("domain.pddl"), testing::ReadTestData("case-a.pddl"),
                        testing::CaseALocations()};
  auto refined = RefinePlan(def.domain, def.problem, testing::CaseAPlan(), def.locations,
                            StraightLineRouter(5));
  PlanVersion v;
  v.version = 1;
  v.tasks = ParseTasks(*refined, def.locations, MoveRecognition{}, 1);
  return v;
}

TEST(SessionTest, CompletionFailureAndLog) {
  MissionDefinition def;
  PlanVersion v = Version();
  std::vector<std::string> done;
  for (size_t i = 0; i + 1 < v.tasks.size(); ++i) {
    Feedback f{
        FeedbackKind::kTaskCompleted, v.tasks[i].id, 1, v.tasks[i].end_s(), std::nullopt, 0.9, ""};
    FeedbackOutcome o = OnFeedback(def, v, done, f);
    EXPECT_FALSE(o.mission_completed);
    EXPECT_TRUE(o.completed_changed);
    done = o.completed_task_ids;
  }
  Feedback again{FeedbackKind::kTaskCompleted, v.tasks[0].id, 1, 10, std::nullopt, 0.9, ""};
  EXPECT_FALSE(OnFeedback(def, v, done, again).completed_changed);
  Feedback last{FeedbackKind::kTaskCompleted,
                v.tasks.back().id,
                1,
                v.tasks.back().end_s(),
                std::nullopt,
                0.9,
                ""};
  FeedbackOutcome o = OnFeedback(def, v, done, last);
  EXPECT_TRUE(o.mission_completed);
  EXPECT_EQ(o.log_messages.front(), "refuel task completed");

  Feedback failed{FeedbackKind::kTaskFailed, v.tasks[1].id, 1,     100,
                  EastNorth{400, 600},       0.9,           "gnss"};
  FeedbackOutcome f = OnFeedback(def, v, {v.tasks[0].id}, failed);
  ASSERT_TRUE(f.replan_reason);
  EXPECT_EQ(f.log_messages.front(), "task move failed, need re-planning");
}

TEST(SessionTest, ReplanInputLetsPortOperationsFinish) {
  PlanVersion v = Version();
  std::vector<Feedback> recent = {{FeedbackKind::kTaskStarted, v.tasks[1].id, 1, 60, {}, {}, ""},
                                  {FeedbackKind::kTaskFailed, v.tasks[1].id, 1, 100, {}, {}, ""}};
  ReplanInput in = MakeReplanInput(v, {v.tasks[0].id}, recent, "r", {{400, 600}, 0.9}, 100);
  EXPECT_EQ(in.completed_task_ids, std::vector<std::string>{v.tasks[0].id});
  EXPECT_EQ(in.interrupted_task_ids, std::vector<std::string>{v.tasks[1].id});
  EXPECT_EQ(in.mission_time_s, 100);
  // A load under way at the replan: completed, new version after its end.
  std::vector<Feedback> loading = {{FeedbackKind::kTaskStarted, v.tasks[0].id, 1, 0, {}, {}, ""}};
  ReplanInput l = MakeReplanInput(v, {}, loading, "r", {{0, 0}, 0.2}, 30);
  EXPECT_EQ(l.completed_task_ids, std::vector<std::string>{v.tasks[0].id});
  EXPECT_DOUBLE_EQ(l.mission_time_s, v.tasks[0].end_s());
}

TEST(SessionTest, EngineStateRoundTrip) {
  LocationTable t = {{"port-a", {0.1, 2.0 / 3.0}}, {"port-s", {-5, 1e6}}};
  auto back = DecodeEngineState(EncodeEngineState(t));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, t);
  EXPECT_FALSE(DecodeEngineState("port-a 1\n").ok());
}

}  // namespace
}  // namespace seaplan::mission
