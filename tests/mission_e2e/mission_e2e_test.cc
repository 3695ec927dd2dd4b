// Missions end to end: seaplan-server (real binary, loopback, ephemeral
// port, fresh database) + seaplan-sim (real binary) on the example
// scenarios, checked through the sim's report and the server's API.
#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "e2e_support.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/wall_clock.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"

namespace seaplan {
namespace {

namespace fs = std::filesystem;
using seaplan::testing::BinDir;
using seaplan::testing::ReadFile;
using seaplan::testing::SourceDir;

using e2e::Flag;
using e2e::Numbers;
using e2e::ReadWholeFile;
using e2e::Strings;

struct SimRun {
  int exit_code = -1;
  std::string report;  // report.json text
  fs::path dir;
};

// The fjord's five ports (case A) with the given positions, speed 3.6 m/s.
v1::CreateMissionRequest FjordMission(const std::string& name, const std::string& vessel_id,
                                      const double (&lat)[5], const double (&lon)[5]) {
  v1::CreateMissionRequest create;
  auto* spec = create.mutable_spec();
  spec->set_name(name);
  spec->set_domain(ReadFile(SourceDir() / "examples/fjord/domain.pddl"));
  spec->set_problem(ReadFile(SourceDir() / "examples/fjord/case-a.pddl"));
  const char* names[] = {"port-a", "port-b", "port-c", "port-d", "port-e"};
  for (int i = 0; i < 5; ++i) {
    auto* l = spec->add_locations();
    l->set_name(names[i]);
    l->mutable_position()->set_latitude_deg(lat[i]);
    l->mutable_position()->set_longitude_deg(lon[i]);
  }
  spec->mutable_ship()->set_service_speed_mps(3.6);
  spec->set_vessel_id(vessel_id);
  return create;
}

// The fjord chart's land as drawn (no safety buffer, no simplification).
StatusOr<chart::ObstacleMap> FjordLand() {
  chart::ChartOptions o;
  o.safety_buffer_m = 0;
  o.simplify_tolerance_m = 0;
  return chart::LoadChartFile((SourceDir() / "examples/scenarios/fjord-entrance.geojson").string(),
                              o);
}

class MissionE2eTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(BinDir() / "seaplan-server") || !fs::exists(BinDir() / "seaplan-sim")) {
      GTEST_SKIP() << "seaplan-server or seaplan-sim not built in " << BinDir();
    }
    dir_ = fs::temp_directory_path() /
           ("seaplan-mission-e2e-" + std::to_string(getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    ASSERT_TRUE(server_.Start(BinDir() / "seaplan-server", dir_ / "server"))
        << "seaplan-server did not start";
    channel_ = grpc::CreateChannel(server_.address(), grpc::InsecureChannelCredentials());
    stub_ = v1::MissionService::NewStub(channel_);
  }
  void TearDown() override {
    std::error_code ec;
    if (!HasFailure()) fs::remove_all(dir_, ec);
  }

  // The sim waits for each plan version at most 120 s, stretched in the
  // slower builds: the scenarios' planner time limits (60 s in case C) are
  // safety nets that an expansion limit ends the search before.
  SimRun RunSim(const std::string& scenario, const std::string& extra = "") {
    SimRun r;
    const std::string replan_timeout_s = std::to_string(static_cast<int>(120 * kWallClockScale));
    r.dir = dir_ / scenario;
    std::string cmd =
        (BinDir() / "seaplan-sim").string() + " --server " + server_.address() + " --scenario " +
        (SourceDir() / "examples/scenarios" / (scenario + ".scenario")).string() +
        " --report-dir " + r.dir.string() + " --replan-timeout-s " + replan_timeout_s + " " +
        extra + " > " + (dir_ / (scenario + ".out")).string() + " 2>&1";
    int status = std::system(cmd.c_str());
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.report = ReadWholeFile(r.dir / "report.json");
    return r;
  }
  std::string SimOutput(const std::string& scenario) {
    return ReadWholeFile(dir_ / (scenario + ".out"));
  }

  fs::path dir_;
  e2e::ServerProcess server_;
  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::MissionService::Stub> stub_;
};

TEST_F(MissionE2eTest, CaseAOneVersionGoalsReachedNoGroundingSafeCpa) {
  SimRun r = RunSim("case-a");
  ASSERT_EQ(r.exit_code, 0) << SimOutput("case-a");
  EXPECT_TRUE(Flag(r.report, "completed"));
  EXPECT_EQ(Numbers(r.report, "version").size(), 1u) << r.report.substr(0, 2000);
  double safety = Numbers(r.report, "safety_distance_m").at(0);
  auto cpas = Numbers(r.report, "min_distance_m");
  EXPECT_EQ(cpas.size(), 3u);
  for (double d : cpas) EXPECT_GT(d, safety);
  // No grounding: every trajectory point is outside the land polygons.
  auto map = FjordLand();
  ASSERT_TRUE(map.ok()) << map.status();
  chart::ObstacleQuery q(*map);
  int points = 0;
  for (const e2e::TrackPoint& p : e2e::Trajectory(r.report)) {
    ++points;
    EXPECT_FALSE(q.Inside({p.east_m, p.north_m})) << "aground at t=" << p.time_s;
  }
  EXPECT_GT(points, 10);
  // The sim's own check, every 2 s of the track against the same land.
  EXPECT_GT(Numbers(r.report, "min_land_clearance_m").at(0), 0.0);
  EXPECT_EQ(Numbers(r.report, "aground_s").at(0), 0.0);
  // The refined routes themselves never touch the land (they are planned
  // against the buffered obstacles): every move's polyline, sampled every 5 m.
  int routes = 0;
  for (const e2e::RoutedMove& move : e2e::RoutedMoves(r.report)) {
    ++routes;
    const std::string& id = move.id;
    std::vector<EastNorth> line;
    for (const auto& [x, y] : move.waypoints) line.push_back({x, y});
    ASSERT_GE(line.size(), 2u) << id;
    for (size_t i = 0; i + 1 < line.size(); ++i) {
      const double len =
          std::hypot(line[i + 1].east_m - line[i].east_m, line[i + 1].north_m - line[i].north_m);
      const int n = std::max(1, static_cast<int>(len / 5.0));
      for (int k = 0; k <= n; ++k) {
        const EastNorth on{line[i].east_m + (line[i + 1].east_m - line[i].east_m) * k / n,
                           line[i].north_m + (line[i + 1].north_m - line[i].north_m) * k / n};
        EXPECT_FALSE(q.Inside(on))
            << id << " crosses land at (" << on.east_m << ", " << on.north_m << ")";
      }
    }
  }
  EXPECT_EQ(routes, 4) << "case A has four moves";
}

TEST_F(MissionE2eTest, CaseBExactlyOneReplanFromTheGnssJump) {
  SimRun r = RunSim("case-b");
  ASSERT_EQ(r.exit_code, 0) << SimOutput("case-b");
  EXPECT_TRUE(Flag(r.report, "completed"));
  auto reasons = Strings(r.report, "reason");
  ASSERT_EQ(reasons.size(), 2u) << r.report.substr(0, 3000);
  EXPECT_EQ(reasons[0], "initial plan");
  EXPECT_NE(reasons[1].find("failed"), std::string::npos) << reasons[1];
  EXPECT_NE(r.report.find("GNSS fault"), std::string::npos);
}

// Both scenarios plan under an expansion limit, so their plans, and the
// comparison of their end times, do not depend on the machine's speed.
TEST_F(MissionE2eTest, CaseCExecutorFuelReplansAndNumericFuelDoesBetter) {
  SimRun c = RunSim("case-c");
  ASSERT_EQ(c.exit_code, 0) << SimOutput("case-c");
  EXPECT_TRUE(Flag(c.report, "completed"));
  EXPECT_GE(Numbers(c.report, "fuel_triggered_replans").at(0), 1);
  for (const std::string& reason : Strings(c.report, "reason")) {
    EXPECT_TRUE(reason == "initial plan" || reason.rfind("fuel", 0) == 0) << reason;
  }
  EXPECT_FALSE(Flag(c.report, "tank_ran_dry"));
  EXPECT_GT(Numbers(c.report, "min_fuel_fraction").at(0), 0.0);
  EXPECT_EQ(Numbers(c.report, "aground_s").at(0), 0.0) << "the simulated ship ran aground";
  const double safety = Numbers(c.report, "safety_distance_m").at(0);
  for (double d : Numbers(c.report, "min_distance_m")) EXPECT_GE(d, safety) << "case C CPA";

  SimRun n = RunSim("case-c-numeric");
  ASSERT_EQ(n.exit_code, 0) << SimOutput("case-c-numeric");
  EXPECT_TRUE(Flag(n.report, "completed"));
  EXPECT_EQ(Numbers(n.report, "fuel_triggered_replans").at(0), 0);
  EXPECT_FALSE(Flag(n.report, "tank_ran_dry"));
  EXPECT_LT(Numbers(n.report, "end_time_s").at(0), Numbers(c.report, "end_time_s").at(0));
  EXPECT_EQ(Numbers(n.report, "aground_s").at(0), 0.0) << "the simulated ship ran aground";
  for (double d : Numbers(n.report, "min_distance_m")) EXPECT_GE(d, safety) << "numeric CPA";
}

std::vector<v1::MissionEvent> Watch(v1::MissionService::Stub* stub, const std::string& id,
                                    int after_version, int64_t after_event) {
  v1::WatchMissionRequest req;
  req.set_mission_id(id);
  req.set_after_version(after_version);
  req.set_after_event_id(after_event);
  grpc::ClientContext ctx;
  ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(3));
  auto reader = stub->WatchMission(&ctx, req);
  std::vector<v1::MissionEvent> out;
  v1::MissionEvent ev;
  while (reader->Read(&ev)) out.push_back(ev);
  reader->Finish();  // ends at the deadline or after the terminal state
  return out;
}

TEST_F(MissionE2eTest, ReconnectingWatcherMissesNothingAndFeedbackIsIdempotent) {
  SimRun r = RunSim("case-b");
  ASSERT_EQ(r.exit_code, 0) << SimOutput("case-b");
  std::smatch m;
  std::string out = SimOutput("case-b");
  // The line the sim prints first on stdout: "mission <id>".
  ASSERT_TRUE(std::regex_search(out, m, std::regex("(^|\\n)mission ([^ \\n:]+)\\n")));
  const std::string id = m[2];

  auto all = Watch(stub_.get(), id, 0, 0);
  std::vector<int64_t> events;
  std::vector<int> versions;
  for (const auto& e : all) {
    if (e.has_log()) events.push_back(e.log().event_id());
    if (e.has_plan_version()) versions.push_back(e.plan_version().version());
  }
  ASSERT_GE(events.size(), 4u);
  ASSERT_EQ(versions, (std::vector<int>{1, 2}));
  // Reconnect in the middle: exactly the rest, no gap, no duplicate.
  int64_t cut = events[events.size() / 2];
  auto rest = Watch(stub_.get(), id, 1, cut);
  std::vector<int64_t> rest_events;
  std::vector<int> rest_versions;
  for (const auto& e : rest) {
    if (e.has_log()) rest_events.push_back(e.log().event_id());
    if (e.has_plan_version()) rest_versions.push_back(e.plan_version().version());
  }
  std::vector<int64_t> expected(events.begin() + events.size() / 2 + 1, events.end());
  EXPECT_EQ(rest_events, expected);
  EXPECT_EQ(rest_versions, std::vector<int>{2});

  // A repeated report (same vessel, same sequence number) is stored once;
  // on a fresh, active mission (the one above is completed).
  const double lat[] = {63.4418, 63.4458, 63.4422, 63.4458, 63.4427};
  const double lon[] = {10.3271, 10.3462, 10.3864, 10.4286, 10.4627};
  const v1::CreateMissionRequest create = FjordMission("idempotency", "e2e-vessel", lat, lon);
  v1::Mission live;
  {
    grpc::ClientContext ctx;
    grpc::Status st = stub_->CreateMission(&ctx, create, &live);
    ASSERT_TRUE(st.ok()) << st.error_message();
  }
  v1::ReportFeedbackRequest fb;
  fb.set_mission_id(live.mission_id());
  fb.set_vessel_id("e2e-vessel");
  fb.set_sequence_number(7);
  fb.mutable_feedback()->set_kind(v1::Feedback::KIND_POSITION);
  fb.mutable_feedback()->set_detail("duplicate check");
  v1::ReportFeedbackResponse first, second;
  {
    grpc::ClientContext ctx;
    ASSERT_TRUE(stub_->ReportFeedback(&ctx, fb, &first).ok());
  }
  {
    grpc::ClientContext ctx;
    ASSERT_TRUE(stub_->ReportFeedback(&ctx, fb, &second).ok());
  }
  EXPECT_FALSE(first.duplicate());
  EXPECT_TRUE(second.duplicate());
  auto after = Watch(stub_.get(), live.mission_id(), 1, 0);
  int duplicates_logged = 0;
  for (const auto& e : after) {
    if (e.has_log() && e.log().message().find("duplicate check") != std::string::npos)
      ++duplicates_logged;
  }
  EXPECT_LE(duplicates_logged, 1);
}

// A move that starts inside the buffered obstacles (port-a 5 m off the
// shore, inside the chart's 10 m safety buffer; a replan from where a ship
// was pushed is the same situation): the server routes it out of the buffer
// the shortest way instead of refusing the start ("lies inside a grounding
// obstacle"; fjord case C).
TEST_F(MissionE2eTest, MoveStartingInsideTheBufferLeavesItInsteadOfFailing) {
  auto charts = v1::ChartService::NewStub(channel_);
  v1::UploadChartRequest upload;
  upload.set_name("fjord");
  upload.set_format(v1::CHART_FORMAT_GEOJSON);
  auto* file = upload.add_files();
  file->set_name("fjord-entrance.geojson");
  file->set_content(ReadFile(SourceDir() / "examples/scenarios/fjord-entrance.geojson"));
  v1::UploadChartResponse chart;
  {
    grpc::ClientContext ctx;
    ctx.set_deadline(std::chrono::system_clock::now() + std::chrono::seconds(60));
    grpc::Status st = charts->UploadChart(&ctx, upload, &chart);
    ASSERT_TRUE(st.ok()) << st.error_message();
  }
  // The south shore runs through (63.44 N, 10.327122 E): port-a 5 m north of it.
  const double lat[] = {63.440045, 63.445835, 63.442244, 63.445835, 63.442693};
  const double lon[] = {10.327122, 10.346208, 10.386389, 10.428579, 10.462732};
  v1::CreateMissionRequest create = FjordMission("start-in-buffer", "e2e-buffer", lat, lon);
  create.mutable_spec()->set_chart_id(chart.chart().chart_id());
  v1::Mission m;
  {
    grpc::ClientContext ctx;
    grpc::Status st = stub_->CreateMission(&ctx, create, &m);
    ASSERT_TRUE(st.ok()) << st.error_message();
  }
  // Planning runs in the background: wait for version 1 (or a failure).
  for (int i = 0; i < 600 && m.current_version() < 1 && m.state() != v1::MISSION_STATE_FAILED;
       ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    v1::GetMissionRequest get;
    get.set_mission_id(m.mission_id());
    grpc::ClientContext ctx;
    ASSERT_TRUE(stub_->GetMission(&ctx, get, &m).ok());
  }
  ASSERT_NE(m.state(), v1::MISSION_STATE_FAILED) << m.failure_reason();
  ASSERT_GE(m.current_version(), 1);
  const v1::PlanVersion* first = nullptr;
  auto events = Watch(stub_.get(), m.mission_id(), 0, 0);
  for (const auto& e : events) {
    if (e.has_plan_version() && e.plan_version().version() == 1) first = &e.plan_version();
  }
  ASSERT_NE(first, nullptr);
  auto map = FjordLand();
  ASSERT_TRUE(map.ok()) << map.status();
  chart::ObstacleQuery q(*map);
  int from_a = 0;
  for (const v1::Task& t : first->tasks()) {
    if (t.kind() != v1::Task::KIND_MOVE || t.from_location() != "port-a") continue;
    ++from_a;
    ASSERT_GE(t.route().waypoints_size(), 3) << t.task_id();
    const auto& w0 = t.route().waypoints(0).position();
    EXPECT_NEAR(w0.latitude_deg(), lat[0], 1e-6);  // the route starts where the ship is
    EXPECT_NEAR(w0.longitude_deg(), lon[0], 1e-6);
    // ... and its way out is short (the shore is 5 m away, the buffer 10 m).
    const EastNorth a = map->frame().ToLocal({w0.latitude_deg(), w0.longitude_deg()});
    const auto& w1 = t.route().waypoints(1).position();
    const EastNorth b = map->frame().ToLocal({w1.latitude_deg(), w1.longitude_deg()});
    EXPECT_LT(std::hypot(b.east_m - a.east_m, b.north_m - a.north_m), 40.0);
    for (const auto& w : t.route().waypoints()) {
      EXPECT_FALSE(q.Inside(
          map->frame().ToLocal({w.position().latitude_deg(), w.position().longitude_deg()})));
    }
  }
  EXPECT_GE(from_a, 1);
}

}  // namespace
}  // namespace seaplan
