// The mission engine end to end over engine values: straight-line missions
// planned by the real temporal planner.
#include "seaplan/mission/mission_engine.h"

#include <gtest/gtest.h>

#include "test_util.h"

namespace seaplan::mission {
namespace {

using testing::ReadTestData;

// Two legs, port-a -> port-b -> port-c, 1 km each (east, then north).
constexpr char kTwoLegs[] = R"((define (problem two-legs)
  (:domain fjord)
  (:objects ship0 - ship port-a port-b port-c - port r-ab r-bc - route)
  (:init (at ship0 port-a) (available ship0)
         (in_port port-a port-a) (in_port port-b port-b) (in_port port-c port-c)
         (connects r-ab port-a port-b) (connects r-bc port-b port-c)
         (route_available r-ab) (route_available r-bc)
         (= (route-length r-ab) 1000) (= (route-length r-bc) 1000) (= (speed ship0) 5))
  (:goal (at ship0 port-c))))";

MissionSpec Spec() {
  MissionSpec spec;
  spec.domain = ReadTestData("domain.pddl");
  spec.problem = kTwoLegs;
  const chart::LocalFrame frame = chart::LocalFrame::ForCentre({63.44, 10.40});
  const EastNorth a = frame.ToLocal({63.44, 10.40});
  spec.locations = {{"port-a", frame.ToLatLon(a)},
                    {"port-b", frame.ToLatLon({a.east_m + 1000, a.north_m})},
                    {"port-c", frame.ToLatLon({a.east_m + 1000, a.north_m + 1000})}};
  spec.initial_position = spec.locations[0].position;
  spec.service_speed_mps = 5.0;
  spec.planner.time_limit_s = 20;
  spec.planner.anytime = false;
  return spec;
}

MissionRuntime Runtime(const PlannedVersion& v) {
  MissionRuntime runtime;
  runtime.current = v.version;
  runtime.current.version = 1;
  runtime.engine_state = v.engine_state;
  return runtime;
}

const Task& FirstMove(const PlanVersion& v) {
  for (const Task& t : v.tasks) {
    if (t.kind == TaskKind::kMove) return t;
  }
  ADD_FAILURE() << "no move";
  return v.tasks.front();
}

TEST(MissionEngineTest, PlansStraightLegsAndCarriesTheEngineState) {
  auto engine = MakeMissionEngine(nullptr);
  MissionSpec spec = Spec();
  ASSERT_TRUE(engine->CheckSpec(spec, nullptr).ok());
  auto planned = engine->PlanInitial(spec, StopToken());
  ASSERT_TRUE(planned.ok()) << planned.status();
  ASSERT_EQ(planned->version.tasks.size(), 2u);
  const Task& move = FirstMove(planned->version);
  ASSERT_TRUE(move.route.has_value());
  EXPECT_NEAR(move.route->length_m, 1000.0, 1.0);
  EXPECT_NEAR(move.duration_s, 200.0, 0.5);  // 1 km at 5 m/s
  auto state = DecodeEngineState(planned->engine_state);
  ASSERT_TRUE(state.ok()) << state.status();
  EXPECT_EQ(state->locations.size(), 3u);
  ASSERT_TRUE(state->fuel_function.has_value());
  EXPECT_EQ(*state->fuel_function, "");  // this domain does not plan fuel
  EXPECT_FALSE(planned->log_messages.empty());
}

TEST(MissionEngineTest, CheckSpecSaysWhatAndWhere) {
  auto engine = MakeMissionEngine(nullptr);
  MissionSpec spec = Spec();
  spec.problem = "(define (problem p) (:domain fjord) (:objects";
  std::vector<pddl::Diagnostic> diagnostics;
  Status st = engine->CheckSpec(spec, &diagnostics);
  EXPECT_TRUE(absl::IsInvalidArgument(st)) << st;
  EXPECT_FALSE(diagnostics.empty());
  spec = Spec();
  spec.locations[1].name = "";
  st = engine->CheckSpec(spec, nullptr);
  EXPECT_NE(st.message().find("spec.locations[1].name"), std::string::npos) << st;
}

TEST(MissionEngineTest, PositionOffTheRouteOfTheMoveUnderWayTriggersAReplan) {
  auto engine = MakeMissionEngine(nullptr);
  MissionSpec spec = Spec();
  spec.policy.position_deviation_m = 200;
  auto planned = engine->PlanInitial(spec, StopToken());
  ASSERT_TRUE(planned.ok()) << planned.status();
  MissionRuntime runtime = Runtime(*planned);
  const Task& move = FirstMove(runtime.current);
  const EastNorth start = move.route->waypoints.front().position;
  Feedback near{FeedbackKind::kPosition,
                "",
                1,
                move.start_s + 50,
                EastNorth{start.east_m + 250, start.north_m + 150},
                0.9,
                ""};
  EXPECT_FALSE(engine->OnFeedback(spec, runtime, near).replan_reason);
  Feedback off = near;
  off.position = EastNorth{start.east_m + 250, start.north_m + 450};
  FeedbackOutcome o = engine->OnFeedback(spec, runtime, off);
  ASSERT_TRUE(o.replan_reason);
  EXPECT_NE(o.replan_reason->find("off the route of " + move.id), std::string::npos)
      << *o.replan_reason;
}

TEST(MissionEngineTest, FuelPlannedIsReadFromTheEngineStateNotTheDomain) {
  auto engine = MakeMissionEngine(nullptr);
  MissionSpec spec = Spec();
  auto planned = engine->PlanInitial(spec, StopToken());
  ASSERT_TRUE(planned.ok()) << planned.status();
  MissionRuntime runtime = Runtime(*planned);
  const Task& move = FirstMove(runtime.current);
  Feedback low{FeedbackKind::kPosition, move.id, 1, move.start_s + 10, std::nullopt, 0.1, ""};
  // Recorded at creation: no fuel planned, so 10 % with moves left replans.
  ASSERT_TRUE(engine->OnFeedback(spec, runtime, low).replan_reason);
  // A state that records a planned tank: the plan already handles fuel.
  auto state = DecodeEngineState(runtime.engine_state);
  ASSERT_TRUE(state.ok());
  state->fuel_function = "charge";
  runtime.engine_state = EncodeEngineState(*state);
  EXPECT_FALSE(engine->OnFeedback(spec, runtime, low).replan_reason);
}

TEST(MissionEngineTest, ReplanAfterAFailedMoveStartsWhereTheShipIs) {
  auto engine = MakeMissionEngine(nullptr);
  MissionSpec spec = Spec();
  auto planned = engine->PlanInitial(spec, StopToken());
  ASSERT_TRUE(planned.ok()) << planned.status();
  MissionRuntime runtime = Runtime(*planned);
  const Task& move = FirstMove(runtime.current);
  const EastNorth start = move.route->waypoints.front().position;
  runtime.recent_feedback = {
      {FeedbackKind::kTaskStarted, move.id, 1, move.start_s, std::nullopt, 0.9, ""},
      {FeedbackKind::kTaskFailed, move.id, 1, move.start_s + 60, std::nullopt, 0.9, ""}};
  runtime.last_report = ShipReport{EastNorth{start.east_m + 500, start.north_m + 400}, 0.9};
  auto next = engine->Replan(spec, runtime, "task failed", StopToken());
  ASSERT_TRUE(next.ok()) << next.status();
  ASSERT_TRUE(next->has_value());
  const PlanVersion& v = (*next)->version;
  EXPECT_EQ(v.version, 2);
  EXPECT_EQ(v.reason, "task failed");
  EXPECT_DOUBLE_EQ(v.mission_time_origin_s, move.start_s + 60);
  const Task& first = FirstMove(v);
  ASSERT_TRUE(first.route.has_value());
  EXPECT_NEAR(first.route->waypoints.front().position.east_m, start.east_m + 500, 1e-6);
  EXPECT_NEAR(first.route->waypoints.front().position.north_m, start.north_m + 400, 1e-6);
  // The new location the replan added is carried in the engine state.
  auto state = DecodeEngineState((*next)->engine_state);
  ASSERT_TRUE(state.ok());
  EXPECT_TRUE(state->locations.contains("port-s"));
}

TEST(MissionEngineTest, UnknownChartIsAFailedPrecondition) {
  auto engine = MakeMissionEngine(
      [](const std::string& id) -> StatusOr<std::shared_ptr<const chart::ObstacleMap>> {
        return absl::NotFoundError("chart '" + id + "' not found");
      });
  MissionSpec spec = Spec();
  spec.chart_id = "c-missing";
  auto planned = engine->PlanInitial(spec, StopToken());
  EXPECT_TRUE(absl::IsFailedPrecondition(planned.status())) << planned.status();
  EXPECT_NE(planned.status().message().find("spec.chart_id"), std::string::npos);
}

}  // namespace
}  // namespace seaplan::mission
