#include "seaplan/mission/mission_planner.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace seaplan::mission {
namespace {

using testing::CaseALocations;
using testing::CaseAPlan;
using testing::ReadTestData;

// A planner stand-in that returns a fixed plan and records what it was asked.
struct FixedPlanner {
  validate::Plan plan;
  std::string* last_problem;
  StatusOr<PlannerOutcome> operator()(std::string_view, std::string_view problem,
                                      const StopToken&) const {
    *last_problem = std::string(problem);
    return PlannerOutcome{true, plan, "SOLVED_SATISFICING"};
  }
};

TEST(MissionPlannerTest, InitialVersionPlansRefinesParsesAndLogs) {
  MissionDefinition def{ReadTestData("domain.pddl"), ReadTestData("case-a.pddl"), CaseALocations()};
  std::string asked;
  NavigationLog log;
  auto v = PlanInitialVersion(def, FixedPlanner{CaseAPlan(), &asked}, StraightLineRouter(5.0),
                              StopToken(), &log);
  ASSERT_TRUE(v.ok()) << v.status();
  EXPECT_EQ(v->version, 1);
  EXPECT_EQ(v->reason, "initial plan");
  EXPECT_EQ(v->tasks.size(), 13u);
  EXPECT_NEAR(v->makespan_s, 1390.011 + 80, 1e-6);
  EXPECT_EQ(asked, def.problem);
  int a = log.Find(messages::kComputingPlan), b = log.Find(messages::kRefiningPlan),
      c = log.Find(messages::kParsingPlan);
  EXPECT_TRUE(a >= 0 && a < b && b < c) << a << " " << b << " " << c;
}

TEST(MissionPlannerTest, ReplanShiftsToMissionTimeAndNumbersTheVersion) {
  MissionDefinition def{ReadTestData("domain.pddl"), ReadTestData("case-a.pddl"), CaseALocations()};
  std::string asked;
  auto v1 = PlanInitialVersion(def, FixedPlanner{CaseAPlan(), &asked}, StraightLineRouter(5.0),
                               StopToken(), nullptr);
  ASSERT_TRUE(v1.ok());
  // A hand-made replan: from port-s straight to port-b, unload, then the rest
  // of case A (a refined plan is validated, so it must reach the goal).
  validate::Plan rest;
  rest.steps.push_back(
      {0, "move-ship", {"ship0", "port-s", "port-s", "port-b", "port-b", "r-port-s-port-b"}, 10});
  rest.steps.push_back({10.001, "unload-cont", {"cont-x", "port-b", "ship0"}, 50});
  const validate::Plan case_a = CaseAPlan();
  for (size_t i = 3; i < case_a.steps.size(); ++i) {
    validate::PlanStep step = case_a.steps[i];
    step.start_s += 60.002 - case_a.steps[3].start_s;
    rest.steps.push_back(step);
  }
  NavigationLog log;
  ReplanInput in{"task v1-t2 move-ship failed", 120.0, {"v1-t1"}, {"v1-t2"}, {{400, 600}, 0.8}};
  auto r = Replan(def, *v1, def.locations, in, FixedPlanner{rest, &asked}, StraightLineRouter(5.0),
                  StopToken(), &log);
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_TRUE(r->version);
  EXPECT_EQ(r->version->version, 2);
  EXPECT_EQ(r->version->reason, "task v1-t2 move-ship failed");
  EXPECT_TRUE(r->locations.contains("port-s"));
  EXPECT_NE(asked.find("(at ship0 port-s)"), std::string::npos);
  ASSERT_EQ(r->version->tasks.size(), 12u);
  const Task& move = r->version->tasks[0];
  EXPECT_EQ(move.kind, TaskKind::kMove);
  EXPECT_EQ(move.from_location, "port-s");
  EXPECT_DOUBLE_EQ(move.start_s, 120.0);
  EXPECT_NEAR(move.duration_s, std::hypot(600, 600) / 5.0, 1e-9);
  EXPECT_NEAR(r->version->tasks[1].start_s, move.end_s() + 0.001, 1e-9);
  EXPECT_GE(log.Find(messages::kReplanDone), 0);
  // A ship under way: the move from where it is (and only that one) is
  // routed from its course and speed; nearly stopped, from rest.
  std::vector<RouteRequest> asked_routes;
  const RoutePlanner straight = StraightLineRouter(5.0);
  auto recording = [&](const RouteRequest& req) {
    asked_routes.push_back(req);
    return straight(req);
  };
  in.ship.motion = ShipMotion{1.2, 8.0};
  ASSERT_TRUE(Replan(def, *v1, def.locations, in, FixedPlanner{rest, &asked}, recording,
                     StopToken(), nullptr)
                  .ok());
  int with_motion = 0;
  for (const RouteRequest& req : asked_routes) {
    if (!req.start_motion) continue;
    ++with_motion;
    EXPECT_EQ(req.from, "port-s");
    EXPECT_DOUBLE_EQ(req.start_motion->course_rad, 1.2);
    EXPECT_DOUBLE_EQ(req.start_motion->speed_mps, 8.0);
  }
  EXPECT_GT(with_motion, 0);
  EXPECT_LT(with_motion, static_cast<int>(asked_routes.size()));
  asked_routes.clear();
  in.ship.motion = ShipMotion{1.2, 0.5};
  ASSERT_TRUE(Replan(def, *v1, def.locations, in, FixedPlanner{rest, &asked}, recording,
                     StopToken(), nullptr)
                  .ok());
  for (const RouteRequest& req : asked_routes) EXPECT_FALSE(req.start_motion.has_value());
  // Unknown task ids are rejected.
  in.completed_task_ids = {"v9-t1"};
  EXPECT_TRUE(
      absl::IsInvalidArgument(Replan(def, *v1, def.locations, in, FixedPlanner{rest, &asked},
                                     StraightLineRouter(5.0), StopToken(), nullptr)
                                  .status()));
}

}  // namespace
}  // namespace seaplan::mission
