// MissionService with the real mission engine (engine/mission + search):
// the fjord case A planned, refined on straight-line legs and parsed into
// tasks; an operator replan gives version 2; the mission is cancelled.
#include <gtest/gtest.h>

#include "seaplan/testing/shared_data.h"
#include "server/core/mission_engine_adapter.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

std::string Example(const std::string& name) {
  return seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "examples" / "fjord" / name);
}

TEST(MissionE2eTest, CaseAPlannedRefinedAndReplannedWithTheRealEngine) {
  InProcessServer s(InProcessServer::EngineFactory(
      [](storage::Store& store) { return MakeMissionEngine(store.charts()); }));
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest req;
  v1::MissionSpec* spec = req.mutable_spec();
  spec->set_name("case A");
  spec->set_domain(Example("domain.pddl"));
  spec->set_problem(Example("case-a.pddl"));
  spec->set_vessel_id("ship0");
  spec->mutable_ship()->set_service_speed_mps(5.0);
  // Five ports about 1 km apart along a line of latitude.
  const char* ports[] = {"port-a", "port-b", "port-c", "port-d", "port-e"};
  for (int i = 0; i < 5; ++i) {
    v1::NamedLocation* l = spec->add_locations();
    l->set_name(ports[i]);
    l->mutable_position()->set_latitude_deg(63.45);
    l->mutable_position()->set_longitude_deg(10.30 + 0.02 * i);
  }
  *spec->mutable_initial_state()->mutable_position() = spec->locations(0).position();
  spec->mutable_initial_state()->set_fuel_fraction(0.9);
  spec->mutable_planner_options()->mutable_time_limit()->set_seconds(20);

  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::Mission mission;
  grpc::Status st = missions->CreateMission(&ctx, req, &mission);
  if (st.error_code() == StatusCode::UNIMPLEMENTED) GTEST_SKIP() << st.error_message();
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_EQ(mission.state(), v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(mission.current_version(), 1);

  auto v1_record = s.store().missions().GetVersion(mission.mission_id(), 1);
  ASSERT_TRUE(v1_record.ok());
  v1::PlanVersion version;
  ASSERT_TRUE(version.ParseFromString(v1_record->content));
  EXPECT_EQ(version.tasks_size(), 13);
  int moves = 0;
  for (const auto& t : version.tasks()) {
    if (t.kind() != v1::Task::KIND_MOVE) continue;
    ++moves;
    // Refined: ~1 km (0.02 deg of longitude at 63.45 N) at 5 m/s, not the PDDL duration.
    ASSERT_GE(t.route().waypoints_size(), 2) << t.task_id();
    EXPECT_NEAR(t.duration_s(), t.route().sailing_time_s(), 1e-6);
    EXPECT_NEAR(t.route().length_m(), 995.0, 30.0);
  }
  EXPECT_EQ(moves, 4);
  EXPECT_GT(s.store().missions().ListEvents(mission.mission_id(), 0, 100)->size(), 1u);

  // Malformed PDDL: INVALID_ARGUMENT with the diagnostics, nothing stored.
  {
    ClientContext bad_ctx;
    v1::CreateMissionRequest bad = req;
    bad.mutable_spec()->set_domain(
        "(define (domain d) (:predicates (p)) (:action a :parameters () :precondition (q)))");
    v1::Mission m;
    grpc::Status bad_st = missions->CreateMission(&bad_ctx, bad, &m);
    EXPECT_EQ(bad_st.error_code(), StatusCode::INVALID_ARGUMENT) << bad_st.error_message();
    v1::DiagnosticList diagnostics;
    EXPECT_TRUE(diagnostics.ParseFromString(bad_st.error_details()) &&
                diagnostics.diagnostics_size() > 0);
    EXPECT_EQ(s.store().missions().List(0, 10, 0)->items.size(), 1u);
  }

  // Operator replan from the ship's position (still at port-a): version 2.
  {
    ClientContext rctx;
    SetDeadline(&rctx, 60000);
    v1::RequestReplanRequest rreq;
    rreq.set_mission_id(mission.mission_id());
    rreq.set_reason("operator request");
    v1::RequestReplanResponse rresp;
    grpc::Status rst = missions->RequestReplan(&rctx, rreq, &rresp);
    ASSERT_TRUE(rst.ok()) << rst.error_message();
    EXPECT_EQ(rresp.version().version(), 2);
    EXPECT_EQ(rresp.version().tasks_size(), 13);
    EXPECT_EQ(rresp.version().tasks(0).task_id().rfind("v2-", 0), 0u)
        << rresp.version().tasks(0).task_id();
  }
  {
    ClientContext cctx;
    v1::CancelMissionRequest creq;
    creq.set_mission_id(mission.mission_id());
    v1::Mission cancelled;
    ASSERT_TRUE(missions->CancelMission(&cctx, creq, &cancelled).ok());
    EXPECT_EQ(cancelled.state(), v1::MISSION_STATE_CANCELLED);
    EXPECT_EQ(cancelled.current_version(), 2);
  }
}

}  // namespace
}  // namespace seaplan::server::testing
