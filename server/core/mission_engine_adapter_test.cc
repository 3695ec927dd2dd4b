#include "server/core/mission_engine_adapter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

const chart::LocalFrame kFrame = chart::LocalFrame::ForCentre({63.44, 10.40});

mission::PlanVersion VersionWithRoute() {
  mission::PlanVersion v;
  v.version = 3;
  v.reason = "fuel 28% <= 30%";
  v.mission_time_origin_s = 100;
  v.makespan_s = 400;
  v.problem = "(define (problem p))";
  v.quality = mission::PlanQuality::kOptimal;
  mission::Task move;
  move.id = "v3-t1";
  move.kind = mission::TaskKind::kMove;
  move.start_s = 100;
  move.duration_s = 300;
  move.action = {100, "move-ship", {"ship0", "port-a", "port-b"}, 300, 0};
  move.from_location = "port-a";
  move.to_location = "port-b";
  const EastNorth a = kFrame.ToLocal({63.44, 10.40});
  mission::Route route;
  route.length_m = 1500;
  route.sailing_time_s = 300;
  route.waypoints = {{{a.east_m, a.north_m}, mission::MsoMode::kPti, 0, 0, 50, 0.01, 1, 2},
                     {{a.east_m + 500, a.north_m}, mission::MsoMode::kPti, 100, 500, 0, 0, 0, 2},
                     {{a.east_m + 1500, a.north_m}, mission::MsoMode::kMec, 300, 1500, 0, 0, 0, 0}};
  move.route = route;
  v.plan.steps.push_back(move.action);
  v.tasks.push_back(move);
  return v;
}

TEST(MissionAdapterTest, PlanVersionsKeepTheirRoutesBothWays) {
  const mission::PlanVersion v = VersionWithRoute();
  const v1::PlanVersion p = PlanVersionToProto(v, kFrame);
  EXPECT_EQ(p.planner_status(), v1::SOLVED_OPTIMALLY);
  ASSERT_EQ(p.tasks_size(), 1);
  EXPECT_EQ(p.tasks(0).kind(), v1::Task::KIND_MOVE);
  ASSERT_EQ(p.tasks(0).route().waypoints_size(), 3);
  EXPECT_NEAR(p.tasks(0).route().waypoints(0).position().latitude_deg(), 63.44, 1e-9);
  // Both segments start at a PTI waypoint (the last waypoint starts none):
  // one run, PTI from waypoint 0 to 2.
  ASSERT_EQ(p.tasks(0).mode_schedule_size(), 1);
  EXPECT_EQ(p.tasks(0).mode_schedule(0).mode(), v1::MSO_MODE_PTI);
  EXPECT_DOUBLE_EQ(p.tasks(0).mode_schedule(0).duration_s(), 300);

  const mission::PlanVersion back = PlanVersionFromProto(p, kFrame);
  EXPECT_EQ(back.version, 3);
  EXPECT_EQ(back.reason, v.reason);
  EXPECT_EQ(back.quality, mission::PlanQuality::kOptimal);
  EXPECT_EQ(back.plan, v.plan);
  ASSERT_EQ(back.tasks.size(), 1u);
  ASSERT_TRUE(back.tasks[0].route.has_value());
  const auto& w = back.tasks[0].route->waypoints;
  ASSERT_EQ(w.size(), 3u);
  for (size_t i = 0; i < w.size(); ++i) {
    const auto& want = v.tasks[0].route->waypoints[i];
    EXPECT_NEAR(w[i].position.east_m, want.position.east_m, 1e-3);
    EXPECT_NEAR(w[i].position.north_m, want.position.north_m, 1e-3);
    EXPECT_EQ(w[i].mode, want.mode);
    EXPECT_DOUBLE_EQ(w[i].eta_s, want.eta_s);
  }
  EXPECT_DOUBLE_EQ(back.tasks[0].route->length_m, 1500);
}

TEST(MissionAdapterTest, SpecDefaultsAndErrors) {
  v1::MissionSpec spec;
  spec.set_domain("d");
  spec.add_locations()->set_name("port-a");
  auto s = SpecFromProto(spec);
  ASSERT_TRUE(s.ok()) << s.status();
  const mission::MissionSpec defaults;
  EXPECT_EQ(s->planner.time_limit_s, defaults.planner.time_limit_s);
  EXPECT_EQ(s->planner.max_expansions, 0u);
  EXPECT_EQ(s->policy.position_deviation_m, defaults.policy.position_deviation_m);
  EXPECT_EQ(s->service_speed_mps, 0.0);
  spec.mutable_replan_policy()->set_position_deviation_m(75);
  spec.mutable_planner_options()->set_anytime(false);
  spec.mutable_planner_options()->mutable_time_limit()->set_seconds(7);
  spec.mutable_planner_options()->set_max_expansions(20000);
  spec.mutable_planner_options()->set_landmarks(false);
  spec.mutable_planner_options()->set_type_based_exploration(false);
  spec.mutable_planner_options()->set_symmetry_reduction(false);
  spec.mutable_planner_options()->set_eager_ends(false);
  spec.mutable_planner_options()->set_second_greedy_after_share(0.125);
  spec.mutable_planner_options()->set_seed_rounds_share(2.5);
  spec.mutable_planner_options()->set_suffix_search_share(0.5);
  spec.mutable_planner_options()->mutable_cpu_time_limit()->set_seconds(5);
  spec.mutable_ship()->set_service_speed_mps(9);
  auto given = SpecFromProto(spec);
  ASSERT_TRUE(given.ok());
  EXPECT_EQ(given->policy.position_deviation_m, 75);
  EXPECT_FALSE(given->planner.anytime);
  EXPECT_NE(given->planner.landmarks, defaults.planner.landmarks);
  EXPECT_FALSE(given->planner.landmarks);
  EXPECT_FALSE(given->planner.type_based_exploration);
  EXPECT_TRUE(defaults.planner.symmetry_reduction);
  EXPECT_FALSE(given->planner.symmetry_reduction);
  EXPECT_TRUE(defaults.planner.eager_ends);
  EXPECT_FALSE(given->planner.eager_ends);
  EXPECT_EQ(defaults.planner.second_greedy_after_share, 0.25);
  EXPECT_EQ(given->planner.second_greedy_after_share, 0.125);
  EXPECT_EQ(defaults.planner.seed_rounds_share, 1);
  EXPECT_EQ(given->planner.seed_rounds_share, 2.5);
  EXPECT_EQ(defaults.planner.suffix_search_share, 1);
  EXPECT_EQ(given->planner.suffix_search_share, 0.5);
  EXPECT_EQ(given->planner.cpu_time_limit_s, 5);
  EXPECT_EQ(given->planner.time_limit_s, 7);
  EXPECT_EQ(given->planner.max_expansions, 20000u);
  EXPECT_EQ(given->service_speed_mps, 9);
  EXPECT_NE(given->routing_key, s->routing_key);  // the ship differs
  spec.mutable_planner_options()->set_second_greedy_after_share(1.5);
  const absl::Status share = SpecFromProto(spec).status();
  EXPECT_TRUE(absl::IsInvalidArgument(share)) << share;
  EXPECT_NE(share.message().find("second_greedy_after_share must be in [0, 1], got 1.5"),
            std::string::npos)
      << share;
  spec.mutable_planner_options()->set_second_greedy_after_share(0.125);
  spec.mutable_planner_options()->set_seed_rounds_share(-1);
  const absl::Status rounds = SpecFromProto(spec).status();
  EXPECT_TRUE(absl::IsInvalidArgument(rounds)) << rounds;
  EXPECT_NE(rounds.message().find("seed_rounds_share must be a finite number >= 0"),
            std::string::npos)
      << rounds;
  spec.mutable_planner_options()->set_seed_rounds_share(2.5);
  spec.mutable_planner_options()->set_suffix_search_share(-1);
  const absl::Status suffix = SpecFromProto(spec).status();
  EXPECT_TRUE(absl::IsInvalidArgument(suffix)) << suffix;
  EXPECT_NE(suffix.message().find("suffix_search_share must be a finite number >= 0"),
            std::string::npos)
      << suffix;
  spec.mutable_planner_options()->set_suffix_search_share(0.5);
  spec.mutable_planner_options()->mutable_time_limit()->set_seconds(-1);
  EXPECT_TRUE(absl::IsInvalidArgument(SpecFromProto(spec).status()));
  spec.mutable_planner_options()->mutable_time_limit()->set_seconds(7);
  spec.mutable_planner_options()->set_max_concurrent_actions(-2);
  const absl::Status negative = SpecFromProto(spec).status();
  EXPECT_TRUE(absl::IsInvalidArgument(negative)) << negative;
  EXPECT_NE(negative.message().find("spec.planner_options.max_concurrent_actions"),
            std::string::npos)
      << negative;
}

TEST(MissionAdapterTest, FeedbackStateIsAFullState) {
  v1::Feedback f;
  f.set_kind(v1::Feedback::KIND_POSITION);
  f.set_plan_version(2);
  EXPECT_FALSE(FeedbackFromProto(f, &kFrame).fuel_fraction.has_value());
  f.mutable_state()->set_fuel_fraction(0.0);  // an empty tank
  mission::Feedback e = FeedbackFromProto(f, &kFrame);
  ASSERT_TRUE(e.fuel_fraction.has_value());
  EXPECT_EQ(*e.fuel_fraction, 0.0);
  EXPECT_FALSE(e.position.has_value());
  f.mutable_state()->mutable_position()->set_latitude_deg(63.44);
  f.mutable_state()->mutable_position()->set_longitude_deg(10.40);
  e = FeedbackFromProto(f, &kFrame);
  ASSERT_TRUE(e.position.has_value());
  const EastNorth want = kFrame.ToLocal({63.44, 10.40});
  EXPECT_NEAR(e.position->east_m, want.east_m, 1e-6);
  EXPECT_EQ(e.plan_version, 2);
  EXPECT_EQ(e.kind, mission::FeedbackKind::kPosition);
  EXPECT_FALSE(FeedbackFromProto(f, nullptr).position.has_value());
}

TEST(MissionAdapterTest, MissionStatesMapOneToOne) {
  for (auto s : {mission::MissionState::kActive, mission::MissionState::kReplanning,
                 mission::MissionState::kCompleted, mission::MissionState::kFailed,
                 mission::MissionState::kCancelled}) {
    EXPECT_EQ(MissionStateFromProto(MissionStateToProto(s)), s);
  }
}

// Records what the adapter hands the engine.
class RecordingEngine final : public mission::MissionEngine {
 public:
  mission::MissionRuntime runtime;
  mission::Feedback feedback;
  Status CheckSpec(const mission::MissionSpec&, std::vector<pddl::Diagnostic>* d) override {
    d->push_back({});
    return absl::InvalidArgumentError("spec: malformed PDDL: x");
  }
  StatusOr<chart::LocalFrame> Frame(const mission::MissionSpec&) override { return kFrame; }
  StatusOr<mission::PlannedVersion> PlanInitial(const mission::MissionSpec&,
                                                const StopToken&) override {
    return mission::PlannedVersion{VersionWithRoute(), "state", {"line"}};
  }
  StatusOr<std::optional<mission::PlannedVersion>> Replan(const mission::MissionSpec&,
                                                          const mission::MissionRuntime&,
                                                          std::string_view,
                                                          const StopToken&) override {
    return std::optional<mission::PlannedVersion>();
  }
  mission::FeedbackOutcome OnFeedback(const mission::MissionSpec&, const mission::MissionRuntime& r,
                                      const mission::Feedback& f) override {
    runtime = r;
    feedback = f;
    return {};
  }
};

TEST(MissionAdapterTest, TheEngineSeesTheStoredRoutesAndTheReportedPosition) {
  auto engine = std::make_shared<RecordingEngine>();
  MissionAdapter adapter(engine);
  v1::MissionSpec spec;
  auto planned = adapter.PlanInitial(spec, StopToken());
  ASSERT_TRUE(planned.ok());
  EXPECT_EQ(planned->engine_state, "state");
  MissionRuntimeState state;
  state.current_version = planned->version;
  state.engine_state = planned->engine_state;
  state.mission.add_completed_tasks("v2-t9");
  v1::ShipState* last = state.mission.mutable_last_state();
  last->mutable_position()->set_latitude_deg(63.44);
  last->mutable_position()->set_longitude_deg(10.40);
  last->set_heading_deg(90);
  last->set_speed_mps(8.5);
  v1::Feedback f;
  f.set_task_id("v3-t1");
  f.mutable_state()->mutable_position()->set_latitude_deg(63.45);
  f.mutable_state()->mutable_position()->set_longitude_deg(10.40);
  f.mutable_state()->set_collision_avoidance_active(true);
  adapter.OnFeedback(spec, state, f);
  EXPECT_TRUE(engine->feedback.collision_avoidance_active);
  // The ship's last state with its motion (a replan of a ship under way).
  ASSERT_TRUE(engine->runtime.last_report.has_value());
  ASSERT_TRUE(engine->runtime.last_report->motion.has_value());
  EXPECT_NEAR(engine->runtime.last_report->motion->course_rad, M_PI / 2, 1e-12);
  EXPECT_DOUBLE_EQ(engine->runtime.last_report->motion->speed_mps, 8.5);
  ASSERT_EQ(engine->runtime.current.tasks.size(), 1u);
  EXPECT_TRUE(engine->runtime.current.tasks[0].route.has_value());
  EXPECT_EQ(engine->runtime.completed_task_ids, std::vector<std::string>{"v2-t9"});
  ASSERT_TRUE(engine->feedback.position.has_value());
  EXPECT_GT(engine->feedback.position->north_m, kFrame.ToLocal({63.44, 10.40}).north_m + 1000);
  // Diagnostics ride in the status details.
  absl::Status st = adapter.CheckSpec(spec);
  EXPECT_TRUE(absl::IsInvalidArgument(st));
  EXPECT_TRUE(GetDiagnostics(st).has_value()) << st;
}

}  // namespace
}  // namespace seaplan::server
