#include "seaplan/mission/replan_policy.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace seaplan::mission {
namespace {

PlanVersion TwoTaskVersion(TaskKind second_kind) {
  PlanVersion v;
  v.version = 2;
  Task move;
  move.id = "v2-t1";
  move.kind = TaskKind::kMove;
  move.start_s = 0;
  move.duration_s = 100;
  move.action.name = "move-ship";
  Route r;
  RouteWaypoint a, b;
  a.position = {0, 0};
  b.position = {1000, 0};
  r.waypoints = {a, b};
  move.route = r;
  Task second;
  second.id = "v2-t2";
  second.kind = second_kind;
  second.start_s = 100.001;
  second.duration_s = 80;
  Task third = move;
  third.id = "v2-t3";
  third.start_s = 200;
  v.tasks = {move, second, third};
  return v;
}

TEST(ReplanPolicyTest, FailedTaskTriggers) {
  PlanVersion v = TwoTaskVersion(TaskKind::kLoad);
  Feedback f{FeedbackKind::kTaskFailed, "v2-t1", 2, 50, EastNorth{500, 0}, 0.8, "gnss jump"};
  auto reason = DecideReplan(f, v, &v.tasks[0], ReplanPolicy{});
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->find("v2-t1 move-ship failed"), std::string::npos) << *reason;
}

TEST(ReplanPolicyTest, DeviationBeyondThresholdTriggers) {
  PlanVersion v = TwoTaskVersion(TaskKind::kLoad);
  Feedback near{FeedbackKind::kPosition, "v2-t1", 2, 50, EastNorth{500, 150}, std::nullopt, ""};
  EXPECT_FALSE(DecideReplan(near, v, &v.tasks[0], ReplanPolicy{}));
  Feedback far{FeedbackKind::kPosition, "v2-t1", 2, 50, EastNorth{500, 250}, std::nullopt, ""};
  auto reason = DecideReplan(far, v, &v.tasks[0], ReplanPolicy{});
  ASSERT_TRUE(reason);
  EXPECT_NE(reason->find("250 m off the route"), std::string::npos) << *reason;
}

// A give-way manoeuvre takes the ship 466 m off a route with a 350 m limit
// while it sails on at full speed: replanning from there gave it a route
// starting behind it, and its turning circle back to that route crossed an
// islet. While its collision avoidance is active the ship is brought back by
// its own path follower; only a deviation beyond 3 x the limit replans.
TEST(ReplanPolicyTest, DeviationDuringCollisionAvoidanceWaitsForTheShipToRejoin) {
  PlanVersion v = TwoTaskVersion(TaskKind::kLoad);
  ReplanPolicy policy;
  policy.position_deviation_m = 350;
  Feedback avoiding{FeedbackKind::kPosition, "v2-t1", 2, 50, EastNorth{500, 466}, std::nullopt, ""};
  avoiding.collision_avoidance_active = true;
  EXPECT_FALSE(DecideReplan(avoiding, v, &v.tasks[0], policy));
  // The same position without a manoeuvre is a deviation.
  Feedback drifting = avoiding;
  drifting.collision_avoidance_active = false;
  auto drift = DecideReplan(drifting, v, &v.tasks[0], policy);
  ASSERT_TRUE(drift);
  EXPECT_NE(drift->find("466 m off the route of v2-t1 (limit 350 m)"), std::string::npos) << *drift;
  // Far beyond what an avoidance manoeuvre takes: replanned all the same.
  avoiding.position = EastNorth{500, 1100};
  auto far = DecideReplan(avoiding, v, &v.tasks[0], policy);
  ASSERT_TRUE(far);
  EXPECT_NE(far->find("1100 m off the route of v2-t1 (limit 1050 m during collision avoidance)"),
            std::string::npos)
      << *far;
  policy.avoidance_deviation_factor = 0.5;
  EXPECT_FALSE(policy.Validate().ok());
}

TEST(ReplanPolicyTest, LowFuelTriggersOnlyWithoutRefuelAhead) {
  Feedback f{FeedbackKind::kTaskCompleted, "v2-t1", 2, 100, EastNorth{1000, 0}, 0.28, ""};
  PlanVersion with_refuel = TwoTaskVersion(TaskKind::kRefuel);
  EXPECT_FALSE(DecideReplan(f, with_refuel, &with_refuel.tasks[0], ReplanPolicy{}));
  PlanVersion without = TwoTaskVersion(TaskKind::kLoad);
  auto reason = DecideReplan(f, without, &without.tasks[0], ReplanPolicy{});
  ASSERT_TRUE(reason);
  EXPECT_EQ(*reason, "fuel 28% <= 30%");
  f.fuel_fraction = 0.31;
  EXPECT_FALSE(DecideReplan(f, without, &without.tasks[0], ReplanPolicy{}));
  // Fuel planned by the planner: only an empty tank means the plan failed.
  ReplanPolicy planned;
  planned.fuel_planned = true;
  f.fuel_fraction = 0.28;
  EXPECT_FALSE(DecideReplan(f, without, &without.tasks[0], planned));
  f.fuel_fraction = 0.0;
  EXPECT_TRUE(DecideReplan(f, without, &without.tasks[0], planned));
}

// The numeric domain lets an action take the last of the fuel, so a plan
// may empty the tank on purpose and refuel next (case C numeric: S -> A -> B
// from 30 %, then the refuel at B). That plan holds; one whose next task
// needs fuel before a refuelling ends does not.
TEST(ReplanPolicyTest, PlannedFuelEmptiedJustBeforeARefuelHolds) {
  ReplanPolicy planned;
  planned.fuel_planned = true;
  // Move (0-100 s), refuel (100.001-180.001 s), move (from 200 s).
  PlanVersion refuel_next = TwoTaskVersion(TaskKind::kRefuel);
  Feedback arrived{FeedbackKind::kTaskCompleted, "v2-t1", 2, 100, EastNorth{1000, 0}, 0.0, ""};
  EXPECT_FALSE(DecideReplan(arrived, refuel_next, &refuel_next.tasks[0], planned));
  Feedback refuelling{FeedbackKind::kTaskStarted, "v2-t2", 2, 100.001, EastNorth{1000, 0}, 0.0, ""};
  EXPECT_FALSE(DecideReplan(refuelling, refuel_next, &refuel_next.tasks[1], planned));
  const std::set<std::string> moved = {"v2-t1"};
  EXPECT_FALSE(DecideReplan(refuelling, refuel_next, &refuel_next.tasks[1], planned, &moved));
  // Still empty once the refuel is done: the next move has nothing to burn.
  const std::set<std::string> refuelled = {"v2-t1", "v2-t2"};
  Feedback done{FeedbackKind::kTaskCompleted, "v2-t2", 2, 180.001, EastNorth{1000, 0}, 0.0, ""};
  auto after = DecideReplan(done, refuel_next, &refuel_next.tasks[1], planned, &refuelled);
  ASSERT_TRUE(after);
  EXPECT_EQ(*after, "fuel tank empty although fuel was planned");

  // Move, load (100.001-180.001 s), move, and a refuel only after them.
  PlanVersion load_next = TwoTaskVersion(TaskKind::kLoad);
  Task late_refuel = load_next.tasks[1];
  late_refuel.id = "v2-t4";
  late_refuel.kind = TaskKind::kRefuel;
  late_refuel.start_s = 300;
  load_next.tasks.push_back(late_refuel);
  auto empty = DecideReplan(arrived, load_next, &load_next.tasks[0], planned);
  ASSERT_TRUE(empty);
  EXPECT_EQ(*empty, "fuel tank empty although fuel was planned");
  // Case C numeric: an unload takes the last 10 % as a refuel starts beside
  // it; neither's start is a reason to replan, whichever is reported first.
  PlanVersion beside = TwoTaskVersion(TaskKind::kUnload);  // unload 100.001-180.001
  Task refuel = beside.tasks[1];
  refuel.id = "v2-t4";
  refuel.kind = TaskKind::kRefuel;
  beside.tasks.push_back(refuel);  // 100.001-180.001, before the move at 200
  for (const Task* started : {&beside.tasks[1], &beside.tasks[3]}) {
    Feedback f{FeedbackKind::kTaskStarted, started->id, 2, 400, EastNorth{1000, 0}, 0.0, ""};
    EXPECT_FALSE(DecideReplan(f, beside, started, planned, &moved)) << started->id;
  }
  // Empty while a move is under way: it cannot arrive as planned.
  Feedback sailing{FeedbackKind::kPosition, "v2-t3", 2, 250, EastNorth{500, 0}, 0.0, ""};
  EXPECT_TRUE(DecideReplan(sailing, refuel_next, &refuel_next.tasks[2], planned, &refuelled));
  // Nothing left that needs fuel: nothing to replan.
  PlanVersion last_move = TwoTaskVersion(TaskKind::kOther);
  last_move.tasks.pop_back();
  EXPECT_FALSE(DecideReplan(arrived, last_move, &last_move.tasks[0], planned));
}

TEST(ReplanPolicyTest, LateCompletionAndStaleVersion) {
  PlanVersion v = TwoTaskVersion(TaskKind::kLoad);
  Feedback late{FeedbackKind::kTaskCompleted, "v2-t1", 2, 300, EastNorth{1000, 0}, 0.9, ""};
  EXPECT_TRUE(DecideReplan(late, v, &v.tasks[0], ReplanPolicy{}));
  late.plan_version = 1;  // about an older version: ignored
  EXPECT_FALSE(DecideReplan(late, v, &v.tasks[0], ReplanPolicy{}));
  EXPECT_FALSE((ReplanPolicy{-1, 1, 1}.Validate().ok()));
}

// A ship running late: the refuel (v2-t2, planned to end at 180 s) has not
// happened at 400 s. With the completed list it still counts as ahead; the
// planned-time guess alone would call it done and replan (fjord case C once
// replanned away a plan that was about to refuel).
TEST(ReplanPolicyTest, LateRefuelStillCountsAsAheadWithTheCompletedList) {
  PlanVersion v = TwoTaskVersion(TaskKind::kRefuel);
  Feedback f{FeedbackKind::kPosition, "v2-t1", 2, 400, EastNorth{900, 0}, 0.15, ""};
  const std::set<std::string> done;  // nothing completed yet
  EXPECT_FALSE(DecideReplan(f, v, &v.tasks[0], ReplanPolicy{}, &done));
  const std::set<std::string> refuelled = {"v2-t1", "v2-t2"};
  Feedback later{FeedbackKind::kTaskCompleted, "v2-t2", 2, 500, EastNorth{1000, 0}, 0.15, ""};
  EXPECT_TRUE(DecideReplan(later, v, &v.tasks[1], ReplanPolicy{}, &refuelled));
}

// 1.0 - 0.1 - 0.15 - 0.1 - 0.1 - 0.15 - 0.1 is 0.30000000000000004 in
// binary floating point: that is 30 %, at the threshold.
TEST(ReplanPolicyTest, FuelAtTheThresholdCountsDespiteRoundingError) {
  double fuel = 1.0;
  for (double step : {0.1, 0.15, 0.1, 0.1, 0.15, 0.1}) fuel -= step;
  ASSERT_GT(fuel, 0.3);  // the rounding error this guards against
  EXPECT_TRUE(FuelAtOrBelow(fuel, 0.3));
  EXPECT_FALSE(FuelAtOrBelow(0.305, 0.3));
  PlanVersion v = TwoTaskVersion(TaskKind::kLoad);
  Feedback f{FeedbackKind::kTaskCompleted, "v2-t1", 2, 100, EastNorth{1000, 0}, fuel, ""};
  auto reason = DecideReplan(f, v, &v.tasks[0], ReplanPolicy{});
  ASSERT_TRUE(reason);
  EXPECT_EQ(*reason, "fuel 30% <= 30%");
}

}  // namespace
}  // namespace seaplan::mission
