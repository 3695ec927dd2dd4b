#include "seaplan/convert/mission_convert.h"

#include <gtest/gtest.h>

namespace seaplan::convert {
namespace {

const chart::LocalFrame kFrame = chart::LocalFrame::ForCentre({63.44, 10.40});

// A version as a ship receives it: a port operation (no route) and a move
// whose route's waypoints are WGS84 positions.
TEST(MissionConvertTest, VersionFromTheWireHasLocalRoutesAndKeepsEverything) {
  v1::PlanVersion p;
  p.set_version(2);
  p.set_reason("machinery fault");
  p.set_mission_time_origin_s(50);
  p.set_makespan_s(900);
  p.set_planner_status(v1::SOLVED_SATISFICING);
  v1::TimedAction* load = p.add_plan();
  load->set_start_s(50);
  load->set_duration_s(120);
  load->set_name("load");
  load->add_arguments("ship0");
  v1::Task* port = p.add_tasks();
  port->set_task_id("v2-t1");
  port->set_kind(v1::Task::KIND_LOAD);
  *port->mutable_action() = *load;
  v1::Task* move = p.add_tasks();
  move->set_task_id("v2-t2");
  move->set_kind(v1::Task::KIND_MOVE);
  move->set_from_location("port-a");
  move->set_to_location("port-b");
  v1::RouteAlternative* r = move->mutable_route();
  r->set_length_m(2000);
  r->set_sailing_time_s(400);
  for (double east_m : {0.0, 2000.0}) {
    const chart::LatLon ll = kFrame.ToLatLon({east_m, 100.0});
    v1::RouteWaypoint* w = r->add_waypoints();
    w->mutable_position()->set_latitude_deg(ll.lat_deg);
    w->mutable_position()->set_longitude_deg(ll.lon_deg);
    w->set_mode(v1::MSO_MODE_MEC);
    w->set_eta_s(east_m / 5);
    w->set_grounding_probability(east_m > 0 ? 0.25 : 0);
  }

  const mission::PlanVersion v = PlanVersionFromProto(p, kFrame);
  EXPECT_EQ(v.version, 2);
  EXPECT_EQ(v.quality, mission::PlanQuality::kSatisficing);
  ASSERT_EQ(v.plan.steps.size(), 1u);
  EXPECT_EQ(v.plan.steps[0].name, "load");
  EXPECT_EQ(v.plan.steps[0].args, std::vector<std::string>{"ship0"});
  ASSERT_EQ(v.tasks.size(), 2u);
  EXPECT_EQ(v.tasks[0].kind, mission::TaskKind::kLoad);
  EXPECT_FALSE(v.tasks[0].route.has_value());
  ASSERT_TRUE(v.tasks[1].route.has_value());
  const mission::Route& route = *v.tasks[1].route;
  EXPECT_DOUBLE_EQ(route.length_m, 2000);
  ASSERT_EQ(route.waypoints.size(), 2u);
  EXPECT_NEAR(route.waypoints[1].position.east_m, 2000, 1e-3);
  EXPECT_NEAR(route.waypoints[1].position.north_m, 100, 1e-3);
  EXPECT_EQ(route.waypoints[1].mode, mission::MsoMode::kMec);
  EXPECT_DOUBLE_EQ(route.waypoints[1].grounding_probability, 0.25);

  // Back on the wire: the same messages, plus the mode schedule the
  // engine derives (one MEC run over the single segment).
  const v1::PlanVersion again = PlanVersionToProto(v, kFrame);
  ASSERT_EQ(again.tasks_size(), 2);
  EXPECT_EQ(again.tasks(0).mode_schedule_size(), 0);
  ASSERT_EQ(again.tasks(1).mode_schedule_size(), 1);
  EXPECT_EQ(again.tasks(1).mode_schedule(0).mode(), v1::MSO_MODE_MEC);
  EXPECT_EQ(again.tasks(1).route().waypoints(1).eta_s(), 400);
  EXPECT_NEAR(again.tasks(1).route().waypoints(1).position().latitude_deg(),
              p.tasks(1).route().waypoints(1).position().latitude_deg(), 1e-9);
}

TEST(MissionConvertTest, EnumsRoundTripAndUnknownValuesFallBack) {
  for (mission::MsoMode m : {mission::MsoMode::kUnspecified, mission::MsoMode::kPto,
                             mission::MsoMode::kMec, mission::MsoMode::kPti})
    EXPECT_EQ(MsoModeFromProto(MsoModeToProto(m)), m);
  for (mission::TaskKind k :
       {mission::TaskKind::kMove, mission::TaskKind::kLoad, mission::TaskKind::kUnload,
        mission::TaskKind::kRepair, mission::TaskKind::kRefuel, mission::TaskKind::kOther})
    EXPECT_EQ(TaskKindFromProto(TaskKindToProto(k)), k);
  for (mission::FeedbackKind k :
       {mission::FeedbackKind::kTaskStarted, mission::FeedbackKind::kTaskCompleted,
        mission::FeedbackKind::kTaskFailed, mission::FeedbackKind::kPosition,
        mission::FeedbackKind::kGnssFault, mission::FeedbackKind::kMachineryFault,
        mission::FeedbackKind::kOperatorChange, mission::FeedbackKind::kCollisionAvoidance})
    EXPECT_EQ(FeedbackKindFromProto(FeedbackKindToProto(k)), k);
  EXPECT_EQ(MsoModeFromProto(static_cast<v1::MsoMode>(99)), mission::MsoMode::kUnspecified);
  EXPECT_EQ(TaskKindFromProto(v1::Task::KIND_UNSPECIFIED), mission::TaskKind::kOther);
  EXPECT_EQ(FeedbackKindFromProto(v1::Feedback::KIND_UNSPECIFIED),
            mission::FeedbackKind::kPosition);
}

}  // namespace
}  // namespace seaplan::convert
