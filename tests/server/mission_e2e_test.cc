// MissionService with the real mission engine (engine/mission + search):
// the fjord case A planned, refined on straight-line legs and parsed into
// tasks; an operator replan gives version 2; the mission is cancelled.
#include <gtest/gtest.h>

#include "seaplan/testing/case_a_mission.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

v1::CreateMissionRequest CaseARequest(const std::string& name) {
  return seaplan::testing::CaseAMissionRequest(name);
}

TEST(MissionE2eTest, CaseAPlannedRefinedAndReplannedWithTheRealEngine) {
  InProcessServer s;  // with the server's own mission engine
  auto missions = v1::MissionService::NewStub(s.channel());
  const v1::CreateMissionRequest req = CaseARequest("case A");

  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::Mission mission;
  grpc::Status st = missions->CreateMission(&ctx, req, &mission);
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

// A ship reported farther than position_deviation_m from the route of the
// move it sails gets a new plan with that reason, over gRPC, through the
// stored version (its routes included) and the background replan.
TEST(MissionE2eTest, AShipOffItsRouteIsReplannedWithThatReason) {
  InProcessServer s;  // with the server's own mission engine
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest req = CaseARequest("deviation");
  v1::MissionSpec* spec = req.mutable_spec();
  spec->mutable_replan_policy()->set_position_deviation_m(300);
  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::Mission mission;
  ASSERT_TRUE(missions->CreateMission(&ctx, req, &mission).ok());
  auto stored = s.store().missions().GetVersion(mission.mission_id(), 1);
  ASSERT_TRUE(stored.ok());
  v1::PlanVersion version;
  ASSERT_TRUE(version.ParseFromString(stored->content));
  const v1::Task* move = nullptr;
  for (const auto& t : version.tasks()) {
    if (t.kind() == v1::Task::KIND_MOVE) {
      move = &t;
      break;
    }
  }
  ASSERT_NE(move, nullptr);
  ASSERT_GE(move->route().waypoints_size(), 2);

  // Watch from the start: version 2 must arrive on the stream.
  ClientContext wctx;
  SetDeadline(&wctx, 60000);
  v1::WatchMissionRequest wreq;
  wreq.set_mission_id(mission.mission_id());
  wreq.set_after_version(1);
  auto watch = missions->WatchMission(&wctx, wreq);

  auto report = [&](int seq, double lat_offset_deg, v1::ReportFeedbackResponse* resp) {
    ClientContext fctx;
    v1::ReportFeedbackRequest f;
    f.set_mission_id(mission.mission_id());
    f.set_vessel_id("ship0");
    f.set_sequence_number(seq);
    v1::Feedback* fb = f.mutable_feedback();
    fb->set_kind(v1::Feedback::KIND_POSITION);
    fb->set_task_id(move->task_id());
    fb->set_plan_version(1);
    fb->set_mission_time_s(move->start_s() + 60);
    // Half way along the leg (the legs run east along 63.45 N), shifted north.
    const auto& a = move->route().waypoints(0).position();
    const auto& b = move->route().waypoints(move->route().waypoints_size() - 1).position();
    fb->mutable_state()->mutable_position()->set_latitude_deg(
        (a.latitude_deg() + b.latitude_deg()) / 2 + lat_offset_deg);
    fb->mutable_state()->mutable_position()->set_longitude_deg(
        (a.longitude_deg() + b.longitude_deg()) / 2);
    fb->mutable_state()->set_fuel_fraction(0.9);
    return missions->ReportFeedback(&fctx, f, resp);
  };
  // 0.001 deg of latitude is about 111 m: within the 300 m limit.
  v1::ReportFeedbackResponse near;
  ASSERT_TRUE(report(1, 0.001, &near).ok());
  EXPECT_FALSE(near.replan_triggered());
  // 0.005 deg is about 556 m off the route.
  v1::ReportFeedbackResponse off;
  ASSERT_TRUE(report(2, 0.005, &off).ok());
  ASSERT_TRUE(off.replan_triggered());
  EXPECT_NE(off.replan_reason().find("off the route of " + move->task_id()), std::string::npos)
      << off.replan_reason();
  EXPECT_NE(off.replan_reason().find("limit 300 m"), std::string::npos) << off.replan_reason();

  v1::MissionEvent event;
  bool got_version = false;
  while (watch->Read(&event)) {
    if (!event.has_plan_version()) continue;
    EXPECT_EQ(event.plan_version().version(), 2);
    EXPECT_EQ(event.plan_version().reason(), off.replan_reason());
    // The new plan starts where the ship was reported.
    ASSERT_GT(event.plan_version().tasks_size(), 0);
    got_version = true;
    break;
  }
  EXPECT_TRUE(got_version);
  wctx.TryCancel();
}

}  // namespace
}  // namespace seaplan::server::testing
