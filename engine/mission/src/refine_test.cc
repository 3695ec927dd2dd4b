#include "seaplan/mission/refine.h"

#include <gtest/gtest.h>

#include <cmath>

#include "seaplan/mission/tasks.h"
#include "test_util.h"

namespace seaplan::mission {
namespace {

using testing::CaseALocations;
using testing::CaseAPlan;
using testing::ReadTestData;

class RefineTest : public ::testing::Test {
 protected:
  std::string domain_ = ReadTestData("domain.pddl");
  std::string problem_ = ReadTestData("case-a.pddl");
  validate::Plan plan_ = CaseAPlan();
};

TEST_F(RefineTest, CaseAWithStraightLinesGivesHandComputedTimes) {
  ASSERT_EQ(plan_.steps.size(), 13u);
  auto refined = RefinePlan(domain_, problem_, plan_, CaseALocations(), StraightLineRouter(5.0));
  ASSERT_TRUE(refined.ok()) << refined.status();
  const auto& s = refined->plan.steps;
  ASSERT_EQ(s.size(), 13u);
  // Every action waits for the previous one (+1 ms) except the final two,
  // which stay concurrent. Moves: 1000/5, 1500/5, 500/5, 2000/5 seconds.
  const double e = 0.001;
  std::vector<double> durations = {60, 200, 50, 60, 300, 50, 60, 100, 50, 60, 400};
  double t = 0.0;
  for (size_t i = 0; i < durations.size(); ++i) {
    EXPECT_NEAR(s[i].start_s, t, 1e-9) << "step " << i << " " << s[i].DisplayName();
    EXPECT_NEAR(s[i].duration_s, durations[i], 1e-9) << "step " << i;
    t += durations[i] + e;
  }
  EXPECT_NEAR(s[11].start_s, t, 1e-9);
  EXPECT_NEAR(s[12].start_s, t, 1e-9);
  EXPECT_NEAR(refined->makespan_s, t + 80, 1e-9);
  EXPECT_EQ(s[1].name, "move-ship");
  ASSERT_TRUE(refined->routes[1].has_value());
  EXPECT_NEAR(refined->routes[1]->length_m, 1000, 1e-9);
  EXPECT_FALSE(refined->routes[0].has_value());
  // Routes do not depend on time: the second pass confirms the first.
  EXPECT_EQ(refined->iterations, 2);
}

TEST_F(RefineTest, RescheduleKeepsOrderAndConcurrency) {
  std::vector<double> d;
  for (const auto& st : plan_.steps) d.push_back(st.duration_s);
  d[1] = 10.0;    // the first move much shorter
  d[11] = 120.0;  // repair longer than refuel
  auto r = Reschedule(domain_, problem_, plan_, d);
  ASSERT_TRUE(r.ok()) << r.status();
  const auto& s = r->steps;
  // Chain kept with epsilon: each of the first 11 starts after the previous ends.
  for (size_t i = 1; i < 11; ++i) {
    EXPECT_GE(s[i].start_s, s[i - 1].end_s() + 0.001 - 1e-9) << i;
    EXPECT_LT(s[i].start_s, s[i - 1].end_s() + 0.0011) << i;  // and no later than needed
  }
  // The concurrent pair stays concurrent.
  EXPECT_DOUBLE_EQ(s[11].start_s, s[12].start_s);
  EXPECT_DOUBLE_EQ(s[11].duration_s, 120.0);
  // The move got shorter, so everything after it is earlier than in the input.
  EXPECT_LT(s[2].start_s, plan_.steps[2].start_s - 270);
}

TEST_F(RefineTest, TimeDependentRoutesIterateUntilSettled) {
  // Sailing slows down for departures after t = 500 s.
  RoutePlanner router = [](const RouteRequest& r) -> StatusOr<Route> {
    double speed = r.depart_s > 500 ? 2.5 : 5.0;
    return StraightLineRouter(speed)(r);
  };
  auto refined = RefinePlan(domain_, problem_, plan_, CaseALocations(), router);
  ASSERT_TRUE(refined.ok()) << refined.status();
  for (size_t i = 0; i < refined->plan.steps.size(); ++i) {
    const auto& st = refined->plan.steps[i];
    if (st.name != "move-ship") continue;
    double dist = refined->routes[i]->length_m;
    double expected = dist / (st.start_s > 500 ? 2.5 : 5.0);
    EXPECT_NEAR(st.duration_s, expected, 1e-9) << st.DisplayName() << " at " << st.start_s;
  }
  EXPECT_GE(refined->iterations, 2);
}

TEST_F(RefineTest, NoSafeRouteNamesTheLeg) {
  RoutePlanner router = [](const RouteRequest& r) -> StatusOr<Route> {
    if (r.from == "port-b" && r.to == "port-c") return absl::NotFoundError("island in the way");
    return StraightLineRouter(5.0)(r);
  };
  auto refined = RefinePlan(domain_, problem_, plan_, CaseALocations(), router);
  ASSERT_FALSE(refined.ok());
  EXPECT_TRUE(absl::IsFailedPrecondition(refined.status()));
  EXPECT_NE(refined.status().message().find("port-b -> port-c"), std::string::npos)
      << refined.status();
}

TEST_F(RefineTest, UnknownActionIsInvalidArgument) {
  validate::Plan bad = plan_;
  bad.steps[3].name = "fly";
  auto refined = RefinePlan(domain_, problem_, bad, CaseALocations(), StraightLineRouter(5.0));
  EXPECT_TRUE(absl::IsInvalidArgument(refined.status())) << refined.status();
}

// A ship that burns one fuel unit per metre of route: whether the refined
// plan is valid depends on the routes' lengths, which only the validation of
// the problem with the routes' durations (route-length scaled) can see.
constexpr char kFuelDomain[] = R"(
(define (domain fuel-legs)
  (:requirements :typing :durative-actions :fluents)
  (:types ship port route)
  (:predicates (at ?v - ship ?p - port) (connects ?r - route ?a ?b - port))
  (:functions (route-length ?r - route) (speed ?v - ship) (fuel-level ?v - ship))
  (:durative-action move-ship
    :parameters (?v - ship ?a - port ?b - port ?r - route)
    :duration (= ?duration (/ (route-length ?r) (speed ?v)))
    :condition (and (at start (at ?v ?a)) (at start (connects ?r ?a ?b))
                    (at start (>= (fuel-level ?v) (route-length ?r))))
    :effect (and (at start (not (at ?v ?a))) (at end (at ?v ?b))
                 (at start (decrease (fuel-level ?v) (route-length ?r)))))
  (:durative-action unload
    :parameters (?v - ship ?p - port)
    :duration (= ?duration 60)
    :condition (at start (at ?v ?p))
    :effect (at end (at ?v ?p))))
)";
constexpr char kFuelProblem[] = R"(
(define (problem two-legs) (:domain fuel-legs)
  (:objects ship0 - ship port-a port-b port-c - port r-ab r-bc - route)
  (:init (at ship0 port-a) (connects r-ab port-a port-b) (connects r-bc port-b port-c)
         (= (route-length r-ab) 1000) (= (route-length r-bc) 1000)
         (= (speed ship0) 5) (= (fuel-level ship0) 2500))
  (:goal (at ship0 port-c)))
)";

class RefineValidationTest : public ::testing::Test {
 protected:
  RefineValidationTest() {
    plan_.steps = {{0.0, "move-ship", {"ship0", "port-a", "port-b", "r-ab"}, 200.0},
                   {200.001, "unload", {"ship0", "port-b"}, 60.0},
                   {260.002, "move-ship", {"ship0", "port-b", "port-c", "r-bc"}, 200.0}};
  }
  // Straight lines, but every route `detour` times the distance.
  static RoutePlanner Detour(double detour) {
    return [detour](const RouteRequest& r) -> StatusOr<Route> {
      auto route = StraightLineRouter(5.0)(r);
      if (route.ok()) {
        route->length_m *= detour;
        route->sailing_time_s *= detour;
      }
      return route;
    };
  }
  LocationTable locations_ = {{"port-a", {0, 0}}, {"port-b", {1000, 0}}, {"port-c", {1000, 1000}}};
  validate::Plan plan_;
};

TEST_F(RefineValidationTest, RoutesWithinTheFuelGiveAValidPlan) {
  // 2 x 1200 m of route against 2500 units of fuel.
  auto refined = RefinePlan(kFuelDomain, kFuelProblem, plan_, locations_, Detour(1.2));
  ASSERT_TRUE(refined.ok()) << refined.status();
  EXPECT_NEAR(refined->plan.steps[0].duration_s, 240.0, 1e-9);
  EXPECT_NEAR(refined->plan.steps[2].duration_s, 240.0, 1e-9);
}

TEST_F(RefineValidationTest, RoutesBeyondTheFuelAreAMissionError) {
  // 2 x 1500 m of route: the second leg's fuel condition fails, although the
  // plan as planned (2 x 1000 m) was valid and the schedule is consistent.
  auto refined = RefinePlan(kFuelDomain, kFuelProblem, plan_, locations_, Detour(1.5));
  ASSERT_FALSE(refined.ok());
  EXPECT_TRUE(absl::IsFailedPrecondition(refined.status())) << refined.status();
  const std::string message(refined.status().message());
  EXPECT_NE(message.find("not valid"), std::string::npos) << message;
  EXPECT_NE(message.find("fuel-level"), std::string::npos) << message;
}

TEST_F(RefineValidationTest, MeasuredPortDurationsAreAccepted) {
  RefineOptions options;
  options.port_operation_durations_s["unload"] = 95.0;  // the domain says 60
  auto refined = RefinePlan(kFuelDomain, kFuelProblem, plan_, locations_, Detour(1.0), options);
  ASSERT_TRUE(refined.ok()) << refined.status();
  EXPECT_NEAR(refined->plan.steps[1].duration_s, 95.0, 1e-9);
}

TEST_F(RefineValidationTest, AGoalTheRefinedPlanMissesIsAMissionError) {
  // Dropping the last move (a route planner cannot, but a broken input plan
  // can) leaves the goal unreached: the refined plan is not sent.
  plan_.steps.pop_back();
  auto refined = RefinePlan(kFuelDomain, kFuelProblem, plan_, locations_, Detour(1.0));
  ASSERT_FALSE(refined.ok());
  EXPECT_TRUE(absl::IsFailedPrecondition(refined.status())) << refined.status();
  EXPECT_NE(refined.status().message().find("goal"), std::string::npos) << refined.status();
}

TEST(RecognizeMoveTest, ByNameAndByArguments) {
  LocationTable loc = {{"a", {0, 0}}, {"b", {1, 0}}};
  MoveRecognition rec;
  validate::PlanStep named{0, "move-ship", {"ship0", "a", "a", "b", "b", "r"}, 1};
  auto leg = RecognizeMove(named, loc, rec);
  ASSERT_TRUE(leg);
  EXPECT_EQ(leg->from, "a");
  EXPECT_EQ(leg->to, "b");
  validate::PlanStep sail{0, "sail", {"ship0", "b", "a"}, 1};
  leg = RecognizeMove(sail, loc, rec);
  ASSERT_TRUE(leg);
  EXPECT_EQ(leg->from, "b");
  EXPECT_EQ(leg->to, "a");
  rec.by_arguments = false;
  EXPECT_FALSE(RecognizeMove(sail, loc, rec));
  validate::PlanStep load{0, "load-cont", {"ship0", "a", "x"}, 60};
  EXPECT_FALSE(RecognizeMove(load, loc, MoveRecognition{}));
}

TEST_F(RefineTest, ParseTasksKindsLocationsAndIds) {
  auto refined = RefinePlan(domain_, problem_, plan_, CaseALocations(), StraightLineRouter(5.0));
  ASSERT_TRUE(refined.ok());
  auto tasks = ParseTasks(*refined, CaseALocations(), MoveRecognition{}, 3);
  ASSERT_EQ(tasks.size(), 13u);
  EXPECT_EQ(tasks[0].id, "v3-t1");
  EXPECT_EQ(tasks[0].kind, TaskKind::kLoad);
  EXPECT_EQ(tasks[0].to_location, "port-a");
  EXPECT_EQ(tasks[1].kind, TaskKind::kMove);
  EXPECT_EQ(tasks[1].from_location, "port-a");
  EXPECT_EQ(tasks[1].to_location, "port-b");
  ASSERT_TRUE(tasks[1].route);
  EXPECT_EQ(tasks[2].kind, TaskKind::kUnload);
  EXPECT_EQ(tasks[11].kind, TaskKind::kRepair);
  EXPECT_EQ(tasks[12].kind, TaskKind::kRefuel);
  EXPECT_EQ(TaskKindOfAction("move-fueling-ship"), TaskKind::kMove);
  EXPECT_NEAR(CrossTrackDistance(*tasks[1].route, {500, 30}), 30, 1e-9);
  EXPECT_NEAR(CrossTrackDistance(*tasks[1].route, {1300, 400}), 500, 1e-9);
}

}  // namespace
}  // namespace seaplan::mission
