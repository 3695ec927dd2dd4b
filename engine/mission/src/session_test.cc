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
  ReplanPolicy def;
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

TEST(SessionTest, AReportWithoutATaskIdCompletesNothing) {
  PlanVersion v = Version();
  std::vector<std::string> all_but_last;
  for (size_t i = 0; i + 1 < v.tasks.size(); ++i) all_but_last.push_back(v.tasks[i].id);
  Feedback no_id{
      FeedbackKind::kTaskCompleted, "", 1, v.tasks.back().end_s(), std::nullopt, 0.9, ""};
  FeedbackOutcome o = OnFeedback(ReplanPolicy{}, v, all_but_last, no_id);
  EXPECT_FALSE(o.completed_changed);
  EXPECT_EQ(o.completed_task_ids, all_but_last);
  EXPECT_FALSE(o.mission_completed);
}

TEST(SessionTest, CompletingTheLastTaskLateCompletesTheMissionWithoutAReplan) {
  PlanVersion v = Version();
  std::vector<std::string> all_but_last;
  for (size_t i = 0; i + 1 < v.tasks.size(); ++i) all_but_last.push_back(v.tasks[i].id);
  ReplanPolicy policy;
  policy.delay_tolerance_s = 60;
  Feedback late{FeedbackKind::kTaskCompleted,
                v.tasks.back().id,
                1,
                v.tasks.back().end_s() + 600,
                std::nullopt,
                0.9,
                ""};
  FeedbackOutcome o = OnFeedback(policy, v, all_but_last, late);
  EXPECT_TRUE(o.mission_completed);
  EXPECT_FALSE(o.replan_reason);
  EXPECT_EQ(o.log_messages.back(), "mission completed");
  // An earlier task completing as late is a replan.
  Feedback early_late{FeedbackKind::kTaskCompleted,
                      v.tasks[0].id,
                      1,
                      v.tasks[0].end_s() + 600,
                      std::nullopt,
                      0.9,
                      ""};
  FeedbackOutcome e = OnFeedback(policy, v, {}, early_late);
  EXPECT_FALSE(e.mission_completed);
  ASSERT_TRUE(e.replan_reason);
  EXPECT_NE(e.replan_reason->find("late"), std::string::npos) << *e.replan_reason;
}

TEST(SessionTest, PositionReportsAreCheckedAgainstTheMoveUnderWay) {
  PlanVersion v = Version();
  const Task* move = nullptr;
  for (const Task& t : v.tasks) {
    if (t.kind == TaskKind::kMove && t.route) {
      move = &t;
      break;
    }
  }
  ASSERT_NE(move, nullptr);
  ReplanPolicy policy;
  policy.position_deviation_m = 200;
  const EastNorth start = move->route->waypoints.front().position;
  // No task id: the move that started by then and is not completed.
  Feedback off{FeedbackKind::kPosition,
               "",
               1,
               move->start_s + 1,
               EastNorth{start.east_m, start.north_m - 500},
               0.9,
               ""};
  std::vector<std::string> before;
  for (const Task& t : v.tasks) {
    if (t.end_s() <= move->start_s + 1e-6 && t.id != move->id) before.push_back(t.id);
  }
  FeedbackOutcome o = OnFeedback(policy, v, before, off);
  ASSERT_TRUE(o.replan_reason);
  EXPECT_NE(o.replan_reason->find("off the route of " + move->id), std::string::npos)
      << *o.replan_reason;
  Feedback on = off;
  on.position = start;
  EXPECT_FALSE(OnFeedback(policy, v, before, on).replan_reason);
}

TEST(SessionTest, CollisionAvoidanceLogsThePapersWording) {
  Feedback f{FeedbackKind::kCollisionAvoidance, "", 1, 10, std::nullopt, 0.9, "give way to ferry"};
  FeedbackOutcome o = OnFeedback(ReplanPolicy{}, Version(), {}, f);
  ASSERT_EQ(o.log_messages.size(), 1u);
  EXPECT_EQ(o.log_messages[0], "potential collision situation");
}

TEST(SessionTest, EngineStateRoundTrip) {
  EngineState t{{{"port-a", {0.1, 2.0 / 3.0}}, {"port-s", {-5, 1e6}}}, "fuel-level"};
  auto back = DecodeEngineState(EncodeEngineState(t));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, t);
  t.fuel_function = "";
  back = DecodeEngineState(EncodeEngineState(t));
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(*back, t);
  // Stored before the fuel line existed: undecided.
  back = DecodeEngineState("port-a 1 2\n");
  ASSERT_TRUE(back.ok());
  EXPECT_FALSE(back->fuel_function.has_value());
  EXPECT_FALSE(DecodeEngineState("port-a 1\n").ok());
}

}  // namespace
}  // namespace seaplan::mission
