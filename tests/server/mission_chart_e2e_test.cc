// MissionService over a chart: a mission whose spec names a stored chart
// gets its moves routed by engine/route (duration = the route's sailing
// time, waypoints with MSO modes); a leg with no safe route fails
// CreateMission naming the leg; CreateMission racing DeleteChart of its
// chart never leaves a mission on a deleted chart (SQLite and PostgreSQL).
// And the coordinator replans once for one situation reported twice.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <set>
#include <thread>
#include <vector>

#include "seaplan/storage/testing/postgres_cluster.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

// Open water (deep, 50 m) from 6.08 to 6.14 E, 62.46 to 62.48 N with an
// island in the middle and, in the north-east, an atoll whose lagoon no
// route can reach. Features without a depth are obstacles.
constexpr char kIslandChart[] = R"({
  "type": "FeatureCollection",
  "features": [
    { "type": "Feature", "properties": { "name": "water", "DRVAL1": 50.0 },
      "geometry": { "type": "Polygon", "coordinates": [[[6.080, 62.460], [6.140, 62.460], [6.140, 62.480], [6.080, 62.480], [6.080, 62.460]]] } },
    { "type": "Feature", "properties": { "name": "island" },
      "geometry": { "type": "Polygon", "coordinates": [[[6.105, 62.464], [6.115, 62.464], [6.115, 62.474], [6.105, 62.474], [6.105, 62.464]]] } },
    { "type": "Feature", "properties": { "name": "atoll" },
      "geometry": { "type": "Polygon", "coordinates": [
        [[6.124, 62.4755], [6.138, 62.4755], [6.138, 62.4795], [6.124, 62.4795], [6.124, 62.4755]],
        [[6.128, 62.4765], [6.134, 62.4765], [6.134, 62.4785], [6.128, 62.4785], [6.128, 62.4765]]] } }
  ]
})";

constexpr char kDomain[] = R"((define (domain ferry)
  (:requirements :typing :durative-actions)
  (:types ship location)
  (:predicates (at ?s - ship ?l - location))
  (:durative-action move-ship
    :parameters (?s - ship ?from ?to - location)
    :duration (= ?duration 100)
    :condition (at start (at ?s ?from))
    :effect (and (at start (not (at ?s ?from))) (at end (at ?s ?to))))))";

std::string Problem(const std::string& goal) {
  return "(define (problem p) (:domain ferry) (:objects ship0 - ship port-w port-e port-lagoon - "
         "location) "
         "(:init (at ship0 port-w)) (:goal (at ship0 " +
         goal + ")))";
}

std::string UploadIslandChart(InProcessServer& s) {
  auto charts = v1::ChartService::NewStub(s.channel());
  v1::UploadChartRequest upload;
  upload.set_name("island");
  upload.set_format(v1::CHART_FORMAT_GEOJSON);
  upload.set_minimum_depth_m(5);
  upload.set_safety_buffer_m(10);
  v1::ChartFile* file = upload.add_files();
  file->set_name("island.geojson");
  file->set_content(kIslandChart);
  v1::UploadChartResponse uploaded;
  ClientContext ctx;
  grpc::Status st = charts->UploadChart(&ctx, upload, &uploaded);
  if (!st.ok()) ADD_FAILURE() << st.error_message();
  return uploaded.chart().chart_id();
}

v1::MissionSpec ChartSpec(const std::string& chart_id, const std::string& goal) {
  v1::MissionSpec spec;
  spec.set_name("island crossing");
  spec.set_domain(kDomain);
  spec.set_problem(Problem(goal));
  spec.set_chart_id(chart_id);
  spec.set_vessel_id("ship0");
  struct {
    const char* name;
    double lat, lon;
  } const ports[] = {
      {"port-w", 62.469, 6.090}, {"port-e", 62.469, 6.130}, {"port-lagoon", 62.4775, 6.131}};
  for (const auto& p : ports) {
    v1::NamedLocation* l = spec.add_locations();
    l->set_name(p.name);
    l->mutable_position()->set_latitude_deg(p.lat);
    l->mutable_position()->set_longitude_deg(p.lon);
  }
  *spec.mutable_initial_state()->mutable_position() = spec.locations(0).position();
  spec.mutable_initial_state()->set_fuel_fraction(0.9);
  spec.mutable_planner_options()->mutable_time_limit()->set_seconds(20);
  return spec;
}

TEST(MissionChartE2eTest, MovesAreRoutedAroundTheIslandWithModes) {
  InProcessServer s;  // with the server's own mission engine
  const std::string chart_id = UploadIslandChart(s);
  ASSERT_FALSE(chart_id.empty());
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest req;
  *req.mutable_spec() = ChartSpec(chart_id, "port-e");
  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::Mission mission;
  const auto t0 = std::chrono::steady_clock::now();
  grpc::Status st = missions->CreateMission(&ctx, req, &mission);
  ASSERT_TRUE(st.ok()) << st.error_message();
  RecordProperty("create_ms",
                 static_cast<int>(std::chrono::duration_cast<std::chrono::milliseconds>(
                                      std::chrono::steady_clock::now() - t0)
                                      .count()));
  EXPECT_EQ(mission.state(), v1::MISSION_STATE_ACTIVE);

  auto record = s.store().missions().GetVersion(mission.mission_id(), 1);
  ASSERT_TRUE(record.ok()) << record.status();
  v1::PlanVersion version;
  ASSERT_TRUE(version.ParseFromString(record->content));
  ASSERT_EQ(version.tasks_size(), 1);
  const v1::Task& move = version.tasks(0);
  EXPECT_EQ(move.kind(), v1::Task::KIND_MOVE);
  EXPECT_EQ(move.from_location(), "port-w");
  EXPECT_EQ(move.to_location(), "port-e");
  // The PDDL says 100 s; the route's sailing time replaces it.
  EXPECT_GT(move.route().sailing_time_s(), 0);
  EXPECT_NE(move.duration_s(), 100.0);
  EXPECT_NEAR(move.duration_s(), move.route().sailing_time_s(), 1e-6);
  // The straight line (2.0 km at 62.469 N) crosses the island: the route is longer.
  ASSERT_GT(move.route().waypoints_size(), 2);
  EXPECT_GT(move.route().length_m(), 2050.0);
  // Ends at the ports, and no waypoint on the island.
  const auto& first = move.route().waypoints(0).position();
  const auto& last = move.route().waypoints(move.route().waypoints_size() - 1).position();
  EXPECT_NEAR(first.longitude_deg(), 6.090, 1e-4);
  EXPECT_NEAR(last.longitude_deg(), 6.130, 1e-4);
  for (const auto& w : move.route().waypoints()) {
    const bool on_island =
        w.position().longitude_deg() > 6.105 && w.position().longitude_deg() < 6.115 &&
        w.position().latitude_deg() > 62.464 && w.position().latitude_deg() < 62.474;
    EXPECT_FALSE(on_island) << w.position().latitude_deg() << " " << w.position().longitude_deg();
    EXPECT_NE(w.mode(), v1::MSO_MODE_UNSPECIFIED);
  }
  EXPECT_GT(move.route().fuel_kg(), 0);
  ASSERT_GE(move.mode_schedule_size(), 1);
  double scheduled = 0;
  for (const auto& e : move.mode_schedule()) scheduled += e.duration_s();
  EXPECT_NEAR(scheduled, move.route().sailing_time_s(), 1e-3);

  // A replan from a position beside the island routes from there (the
  // RoutePlanner and the routes are cached per mission chart).
  v1::ReportFeedbackRequest fb;
  fb.set_mission_id(mission.mission_id());
  fb.set_vessel_id("ship0");
  fb.set_sequence_number(1);
  fb.mutable_feedback()->set_kind(v1::Feedback::KIND_TASK_FAILED);
  fb.mutable_feedback()->set_task_id(move.task_id());
  fb.mutable_feedback()->set_plan_version(1);
  fb.mutable_feedback()->set_mission_time_s(200);
  fb.mutable_feedback()->mutable_state()->mutable_position()->set_latitude_deg(62.476);
  fb.mutable_feedback()->mutable_state()->mutable_position()->set_longitude_deg(6.100);
  fb.mutable_feedback()->mutable_state()->set_fuel_fraction(0.8);
  {
    ClientContext fctx;
    v1::ReportFeedbackResponse resp;
    ASSERT_TRUE(missions->ReportFeedback(&fctx, fb, &resp).ok());
    ASSERT_TRUE(resp.replan_triggered());
  }
  absl::StatusOr<storage::PlanVersionRecord> v2 = absl::NotFoundError("not yet");
  for (int i = 0; i < 1000 && !v2.ok(); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    v2 = s.store().missions().GetVersion(mission.mission_id(), 2);
  }
  ASSERT_TRUE(v2.ok()) << v2.status();
  v1::PlanVersion second;
  ASSERT_TRUE(second.ParseFromString(v2->content));
  ASSERT_EQ(second.tasks_size(), 1);
  EXPECT_EQ(second.tasks(0).to_location(), "port-e");
  EXPECT_NEAR(second.tasks(0).duration_s(), second.tasks(0).route().sailing_time_s(), 1e-6);
  EXPECT_NEAR(second.tasks(0).route().waypoints(0).position().latitude_deg(), 62.476, 1e-4);
}

TEST(MissionChartE2eTest, LegWithoutSafeRouteIsFailedPreconditionNamingTheLeg) {
  InProcessServer s;  // with the server's own mission engine
  const std::string chart_id = UploadIslandChart(s);
  ASSERT_FALSE(chart_id.empty());
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest req;
  *req.mutable_spec() = ChartSpec(chart_id, "port-lagoon");
  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::Mission mission;
  grpc::Status st = missions->CreateMission(&ctx, req, &mission);
  EXPECT_EQ(st.error_code(), StatusCode::FAILED_PRECONDITION) << st.error_message();
  EXPECT_NE(st.error_message().find("port-w -> port-lagoon"), std::string::npos)
      << st.error_message();

  // An unknown chart is a precondition too, not an internal error.
  *req.mutable_spec() = ChartSpec("no-such-chart", "port-e");
  ClientContext ctx2;
  st = missions->CreateMission(&ctx2, req, &mission);
  EXPECT_EQ(st.error_code(), StatusCode::FAILED_PRECONDITION) << st.error_message();
}

// DeleteChart: NOT_FOUND for an unknown chart; FAILED_PRECONDITION naming
// the mission while an active mission uses it (the chart stays); once the
// mission is cancelled the chart goes with its audit row, and the mission
// engine's routings over it go too: a new mission on it is refused.
TEST(MissionChartE2eTest, ChartInUseIsNotDeletedAndADeletedChartIsGoneEverywhere) {
  InProcessServer s;  // with the server's own mission engine (its routing cache)
  const std::string chart_id = UploadIslandChart(s);
  ASSERT_FALSE(chart_id.empty());
  auto charts = v1::ChartService::NewStub(s.channel());
  auto missions = v1::MissionService::NewStub(s.channel());
  const auto delete_chart = [&](const std::string& id) {
    v1::DeleteChartRequest req;
    req.set_chart_id(id);
    v1::DeleteChartResponse resp;
    ClientContext ctx;
    grpc::Status st = charts->DeleteChart(&ctx, req, &resp);
    if (st.ok()) {
      EXPECT_EQ(resp.chart_id(), id);
    }
    return st;
  };
  const auto create = [&](v1::Mission* mission) {
    v1::CreateMissionRequest req;
    *req.mutable_spec() = ChartSpec(chart_id, "port-e");
    ClientContext ctx;
    SetDeadline(&ctx, 60000);
    return missions->CreateMission(&ctx, req, mission);
  };
  EXPECT_EQ(delete_chart("c-no-such-chart").error_code(), StatusCode::NOT_FOUND);
  EXPECT_EQ(delete_chart("").error_code(), StatusCode::INVALID_ARGUMENT);

  v1::Mission mission;
  grpc::Status st = create(&mission);
  ASSERT_TRUE(st.ok()) << st.error_message();
  st = delete_chart(chart_id);
  EXPECT_EQ(st.error_code(), StatusCode::FAILED_PRECONDITION) << st.error_message();
  EXPECT_NE(st.error_message().find(mission.mission_id()), std::string::npos) << st.error_message();
  ASSERT_TRUE(s.store().charts().Get(chart_id, false).ok());

  {
    v1::CancelMissionRequest cancel;
    cancel.set_mission_id(mission.mission_id());
    v1::Mission cancelled;
    ClientContext ctx;
    ASSERT_TRUE(missions->CancelMission(&ctx, cancel, &cancelled).ok());
  }
  st = delete_chart(chart_id);
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_EQ(s.store().charts().Get(chart_id, false).status().code(), absl::StatusCode::kNotFound);
  auto audit = s.store().audit().ListAudit(1000, 0);
  ASSERT_TRUE(audit.ok());
  int delete_rows = 0;
  for (const auto& row : audit->items) {
    if (row.action == "ChartService/DeleteChart") {
      ++delete_rows;
      EXPECT_EQ(row.target, chart_id);
      EXPECT_EQ(row.role, "admin");
    }
  }
  EXPECT_EQ(delete_rows, 1);  // the refused attempt left none

  // The same spec as the first mission: without the dropped routing it
  // would still plan over the deleted chart.
  v1::Mission again;
  st = create(&again);
  EXPECT_EQ(st.error_code(), StatusCode::FAILED_PRECONDITION) << st.error_message();
  EXPECT_NE(st.error_message().find(chart_id), std::string::npos) << st.error_message();
  EXPECT_EQ(delete_chart(chart_id).error_code(), StatusCode::NOT_FOUND);
}

// CreateMission on a chart racing DeleteChart of that chart, through the
// server (its own mission engine, which loads the chart to plan), round
// after round with the delete sent at another point of the creations: before
// planning starts, while they plan, after they committed. A creation either
// succeeds, and then the delete is refused naming a created mission (an
// unfinished mission uses the chart), or it is FAILED_PRECONDITION; never a
// stored mission whose chart is gone.
void CreateRacesDelete(InProcessServer& s, int rounds) {
  using std::chrono::steady_clock;
  auto charts = v1::ChartService::NewStub(s.channel());
  auto missions = v1::MissionService::NewStub(s.channel());
  const auto create = [&](const std::string& chart_id, v1::Mission* mission) {
    v1::CreateMissionRequest req;
    *req.mutable_spec() = ChartSpec(chart_id, "port-e");
    ClientContext ctx;
    SetDeadline(&ctx, 120000);
    return missions->CreateMission(&ctx, req, mission);
  };
  const auto delete_chart = [&](const std::string& chart_id) {
    v1::DeleteChartRequest req;
    req.set_chart_id(chart_id);
    v1::DeleteChartResponse resp;
    ClientContext ctx;
    SetDeadline(&ctx, 60000);
    return charts->DeleteChart(&ctx, req, &resp);
  };
  const auto cancel = [&](const std::string& mission_id) {
    v1::CancelMissionRequest req;
    req.set_mission_id(mission_id);
    v1::Mission cancelled;
    ClientContext ctx;
    return missions->CancelMission(&ctx, req, &cancelled);
  };
  // The stored missions whose spec names `chart_id`.
  const auto stored_on = [&](const std::string& chart_id) {
    std::set<std::string> ids;
    std::int64_t after = 0;
    while (true) {
      auto page = s.store().missions().List(0, 1000, after);
      EXPECT_TRUE(page.ok()) << page.status();
      if (!page.ok()) break;
      for (const storage::MissionRecord& m : page->items) {
        v1::MissionSpec spec;
        EXPECT_TRUE(spec.ParseFromString(m.spec));
        if (spec.chart_id() == chart_id) ids.insert(m.id);
      }
      if (page->next_after == 0) break;
      after = page->next_after;
    }
    return ids;
  };

  // One creation's time here (the chart loaded, the move routed): the
  // deletes are sent from 0 to 2.5 times it after the creations.
  steady_clock::duration create_time{};
  {
    const std::string chart_id = UploadIslandChart(s);
    v1::Mission mission;
    const auto t0 = steady_clock::now();
    const grpc::Status st = create(chart_id, &mission);
    create_time = steady_clock::now() - t0;
    ASSERT_TRUE(st.ok()) << st.error_message();
  }
  constexpr int kCreators = 2;
  int deletes_first = 0, creates_first = 0, refused_after_planning = 0;
  for (int round = 0; round < rounds; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const std::string chart_id = UploadIslandChart(s);
    ASSERT_FALSE(chart_id.empty());
    const auto delay = create_time * (round % 6) / 2;
    std::atomic<int> ready{0};
    const auto start_together = [&] {
      ++ready;
      while (ready.load() < kCreators + 1) {
      }
    };
    std::vector<grpc::Status> created(kCreators);
    std::vector<v1::Mission> mission(kCreators);
    grpc::Status deleted;
    std::vector<std::thread> threads;
    threads.reserve(kCreators + 1);  // the creators and the deleter
    for (int i = 0; i < kCreators; ++i) {
      threads.emplace_back([&, i] {
        start_together();
        created[i] = create(chart_id, &mission[i]);
      });
    }
    threads.emplace_back([&] {
      start_together();
      std::this_thread::sleep_for(delay);
      deleted = delete_chart(chart_id);
    });
    for (std::thread& t : threads) t.join();

    std::set<std::string> created_ids;
    for (int i = 0; i < kCreators; ++i) {
      if (created[i].ok()) {
        created_ids.insert(mission[i].mission_id());
        EXPECT_EQ(mission[i].state(), v1::MISSION_STATE_ACTIVE);
        continue;
      }
      EXPECT_EQ(created[i].error_code(), StatusCode::FAILED_PRECONDITION)
          << created[i].error_message();
      EXPECT_NE(created[i].error_message().find(chart_id), std::string::npos)
          << created[i].error_message();
      if (created[i].error_message().find("deleted while the mission was planned") !=
          std::string::npos) {
        ++refused_after_planning;
      }
    }
    // Storage holds exactly the missions the server said it created.
    EXPECT_EQ(stored_on(chart_id), created_ids);
    const bool chart_stored = s.store().charts().Get(chart_id, false).ok();
    if (deleted.ok()) {
      ++deletes_first;
      EXPECT_TRUE(created_ids.empty()) << "a mission was created on a deleted chart";
      EXPECT_FALSE(chart_stored);
    } else {
      ++creates_first;
      EXPECT_EQ(deleted.error_code(), StatusCode::FAILED_PRECONDITION) << deleted.error_message();
      ASSERT_FALSE(created_ids.empty())
          << "the delete was refused but no mission was created: " << deleted.error_message();
      EXPECT_TRUE(chart_stored);
      bool names_a_created_mission = false;
      for (const std::string& id : created_ids) {
        names_a_created_mission |= deleted.error_message().find(id) != std::string::npos;
      }
      EXPECT_TRUE(names_a_created_mission) << deleted.error_message();
      // Once its missions are cancelled the chart goes.
      for (const std::string& id : created_ids) {
        const grpc::Status st = cancel(id);
        EXPECT_TRUE(st.ok()) << st.error_message();
      }
      const grpc::Status st = delete_chart(chart_id);
      EXPECT_TRUE(st.ok()) << st.error_message();
    }
  }
  std::cout << rounds << " rounds: the delete first in " << deletes_first
            << ", a creation first in " << creates_first << "; " << refused_after_planning
            << " creations refused after planning (the chart deleted meanwhile); one creation "
            << std::chrono::duration_cast<std::chrono::milliseconds>(create_time).count()
            << " ms\n";
}

TEST(MissionChartE2eTest, CreatingOnAChartWhileItIsDeletedNeverLeavesAMissionWithoutItsChart) {
  InProcessServer s;  // SQLite, the server's own mission engine
  CreateRacesDelete(s, 24);
}

TEST(MissionChartE2eTest, CreatingOnAChartWhileItIsDeletedOnPostgresql) {
  auto cluster = storage::testing::ProcessCluster();
  if (absl::IsNotFound(cluster.status())) {
    if (std::getenv("CI") != nullptr) FAIL() << cluster.status();
    GTEST_SKIP() << "PostgreSQL not available: " << cluster.status().message();
  }
  ASSERT_TRUE(cluster.ok()) << cluster.status();
  auto url = (*cluster)->CreateDatabase();
  ASSERT_TRUE(url.ok()) << url.status();
  InProcessServer s(*url, nullptr);
  CreateRacesDelete(s, 12);
}

TEST(MissionChartE2eTest, TwoTriggeringFeedbacksInARowReplanOnce) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->replan_delay_ms = 300;  // the second report arrives while the first replan runs
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest req;
  req.mutable_spec()->set_name("twice");
  req.mutable_spec()->set_domain("d");
  req.mutable_spec()->set_problem("p");
  v1::Mission mission;
  {
    ClientContext ctx;
    ASSERT_TRUE(missions->CreateMission(&ctx, req, &mission).ok());
  }
  for (int seq = 1; seq <= 3; ++seq) {
    v1::ReportFeedbackRequest fb;
    fb.set_mission_id(mission.mission_id());
    fb.set_vessel_id("v");
    fb.set_sequence_number(seq);
    fb.mutable_feedback()->set_kind(v1::Feedback::KIND_TASK_FAILED);
    fb.mutable_feedback()->set_task_id("v1-t0");
    fb.mutable_feedback()->set_plan_version(1);
    fb.mutable_feedback()->set_mission_time_s(10.0 * seq);
    ClientContext ctx;
    v1::ReportFeedbackResponse resp;
    ASSERT_TRUE(missions->ReportFeedback(&ctx, fb, &resp).ok());
    EXPECT_TRUE(resp.replan_triggered());  // a new version follows: the one already under way
  }
  // Wait for the replan, then a while longer for a (wrong) second one.
  absl::StatusOr<storage::MissionRecord> record = s.store().missions().Get(mission.mission_id());
  for (int i = 0; i < 300 && record.ok() && record->current_version < 2; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    record = s.store().missions().Get(mission.mission_id());
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  record = s.store().missions().Get(mission.mission_id());
  ASSERT_TRUE(record.ok());
  EXPECT_EQ(record->current_version, 2);
  EXPECT_EQ(record->state, v1::MISSION_STATE_ACTIVE);
  EXPECT_EQ(engine->replan_calls.load(), 1);
}

}  // namespace
}  // namespace seaplan::server::testing
