// What the operator console needs from the server, in the API for every
// client: JSON bodies whatever their Content-Type, the console's files at
// "/", the chart's obstacles as GeoJSON at a chosen depth, the vessel's
// live picture on WatchMission, the stored feedback history (ListFeedback),
// and every RPC on the HTTP gateway.
#include <google/protobuf/descriptor.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <fstream>
#include <future>

#include "absl/strings/escaping.h"
#include "seaplan/testing/shared_data.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::StatusCode;

std::vector<v1::MissionEvent> ParseNdjson(const std::string& body) {
  std::vector<v1::MissionEvent> events;
  std::size_t start = 0;
  while (start < body.size()) {
    const std::size_t end = body.find('\n', start);
    if (end == std::string::npos) break;
    v1::MissionEvent ev;
    EXPECT_TRUE(
        google::protobuf::util::JsonStringToMessage(body.substr(start, end - start), &ev).ok())
        << body.substr(start, end - start);
    events.push_back(ev);
    start = end + 1;
  }
  return events;
}

void CreateSampleMission(v1::MissionService::Stub& missions, v1::Mission* mission) {
  grpc::ClientContext ctx;
  v1::CreateMissionRequest req;
  *req.mutable_spec() = SampleSpec();
  ASSERT_TRUE(missions.CreateMission(&ctx, req, mission).ok());
}

TEST(ConsoleApiE2eTest, JsonBodyIsReadWhateverTheContentTypeAndBeyondEightKiB) {
  InProcessServer s;
  auto http = s.http();
  // curl -d sends application/x-www-form-urlencoded; cpp-httplib used to
  // take such a body as a form and refuse it beyond 8 KiB.
  const std::string padding(20000, ' ');
  const std::string body = "{\"pageSize\":5" + padding + "}";
  for (const char* type : {"application/x-www-form-urlencoded", "text/plain", "application/json"}) {
    auto res = http.Post("/v1/MissionService/ListMissions", body, type);
    ASSERT_TRUE(res);
    EXPECT_EQ(res->status, 200) << type << ": " << res->body;
  }
  // The body still has to be the request message.
  auto bad = http.Post("/v1/MissionService/ListMissions", "pageSize=5",
                       "application/x-www-form-urlencoded");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400);
  EXPECT_NE(bad->body.find("INVALID_ARGUMENT"), std::string::npos) << bad->body;
  // Multipart forms are refused with a message saying what to send.
  httplib::MultipartFormDataItems items = {{"request", "{}", "", "application/json"}};
  auto multipart = http.Post("/v1/MissionService/ListMissions", items);
  ASSERT_TRUE(multipart);
  EXPECT_EQ(multipart->status, 400);
  EXPECT_NE(multipart->body.find("multipart/form-data is not accepted"), std::string::npos)
      << multipart->body;
  // A POST without a body is still the empty message.
  auto empty = http.Post("/v1/MissionService/ListMissions");
  ASSERT_TRUE(empty);
  EXPECT_EQ(empty->status, 200) << empty->body;
}

TEST(ConsoleApiE2eTest, ServesTheConsoleFromItsFolderWithASameOriginPolicy) {
  TempDir dir;
  const auto console = dir.path() / "console";
  std::filesystem::create_directories(console);
  std::ofstream(console / "index.html") << "<!doctype html><title>console</title>";
  std::ofstream(console / "app.js") << "console.log('seaplan');";
  auto store = storage::SqliteStore::Open((dir.path() / "seaplan.db").string());
  ASSERT_TRUE(store.ok()) << store.status();
  ServerOptions options;
  options.grpc_address = "127.0.0.1:0";
  options.http_address = "127.0.0.1:0";
  options.console_dir = console.string();
  options.shutdown_grace = std::chrono::milliseconds(200);
  auto server = Server::Start(options, **store);
  ASSERT_TRUE(server.ok()) << server.status();
  httplib::Client http("127.0.0.1", (*server)->http_port());
  auto index = http.Get("/");
  ASSERT_TRUE(index);
  EXPECT_EQ(index->status, 200);
  EXPECT_EQ(index->body, "<!doctype html><title>console</title>");
  EXPECT_NE(index->get_header_value("Content-Type").find("text/html"), std::string::npos);
  EXPECT_NE(index->get_header_value("Content-Security-Policy").find("default-src 'self'"),
            std::string::npos);
  auto js = http.Get("/app.js");
  ASSERT_TRUE(js);
  EXPECT_EQ(js->status, 200);
  EXPECT_NE(js->get_header_value("Content-Type").find("javascript"), std::string::npos);
  auto missing = http.Get("/nothing.js");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  // The API and health are unchanged beside the files.
  auto health = http.Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
  (*server)->Shutdown();
  EXPECT_TRUE((*store)->Close().ok());
}

TEST(ConsoleApiE2eTest, WithoutAConsoleTheRootSaysSo) {
  InProcessServer s;
  auto res = s.http().Get("/");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  EXPECT_NE(res->body.find("operator console not installed"), std::string::npos) << res->body;
}

TEST(ConsoleApiE2eTest, ObstaclesAsGeoJsonAtTheStoredOrAnotherDepth) {
  const std::string geojson = seaplan::testing::ReadFile(seaplan::testing::SourceDir() /
                                                         "engine/chart/testdata/harbour.geojson");
  ASSERT_FALSE(geojson.empty());
  InProcessServer s;
  auto charts = v1::ChartService::NewStub(s.channel());
  // Uploaded over HTTP as the console sends it (file bytes in base64).
  auto res = s.http().Post("/v1/ChartService/UploadChart",
                           "{\"name\":\"harbour\",\"format\":\"CHART_FORMAT_GEOJSON\","
                           "\"minimumDepthM\":10,\"files\":[{\"name\":\"harbour.geojson\","
                           "\"content\":\"" +
                               absl::Base64Escape(geojson) + "\"}]}",
                           "text/plain");
  ASSERT_TRUE(res);
  if (res->status == 501) GTEST_SKIP() << res->body;
  ASSERT_EQ(res->status, 200) << res->body;
  v1::UploadChartResponse uploaded;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(res->body, &uploaded).ok()) << res->body;
  const std::string id = uploaded.chart().chart_id();
  auto get = [&](double depth, v1::GetObstaclesResponse* out) {
    grpc::ClientContext ctx;
    v1::GetObstaclesRequest req;
    req.set_chart_id(id);
    req.set_minimum_depth_m(depth);
    return charts->GetObstacles(&ctx, req, out);
  };
  v1::GetObstaclesResponse stored, shallower, again;
  ASSERT_TRUE(get(0, &stored).ok());
  EXPECT_DOUBLE_EQ(stored.minimum_depth_m(), 10);
  EXPECT_GT(stored.obstacle_count(), 0);
  EXPECT_NE(stored.geojson().find("FeatureCollection"), std::string::npos);
  {  // The stored depth is the chart's own obstacles, as GetChart gives them.
    grpc::ClientContext ctx;
    v1::GetChartRequest req;
    req.set_chart_id(id);
    req.set_include_obstacles_geojson(true);
    v1::GetChartResponse chart;
    ASSERT_TRUE(charts->GetChart(&ctx, req, &chart).ok());
    EXPECT_EQ(stored.geojson(), chart.obstacles_geojson());
  }
  // At 1 m the 2 m shallows are water: the chart is loaded again and the
  // obstacles differ; asking for 10 m explicitly gives the stored ones.
  ASSERT_TRUE(get(1, &shallower).ok());
  EXPECT_DOUBLE_EQ(shallower.minimum_depth_m(), 1);
  EXPECT_NE(shallower.geojson(), stored.geojson());
  ASSERT_TRUE(get(10, &again).ok());
  EXPECT_EQ(again.geojson(), stored.geojson());

  v1::GetObstaclesResponse none;
  EXPECT_EQ(get(-1, &none).error_code(), StatusCode::INVALID_ARGUMENT);
  grpc::ClientContext ctx;
  v1::GetObstaclesRequest unknown;
  unknown.set_chart_id("c-nope");
  EXPECT_EQ(charts->GetObstacles(&ctx, unknown, &none).error_code(), StatusCode::NOT_FOUND);
  // Over HTTP too.
  res = s.http().Post("/v1/ChartService/GetObstacles",
                      "{\"chartId\":\"" + id + "\",\"minimumDepthM\":1}", "text/plain");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_NE(res->body.find("\"obstacleCount\""), std::string::npos);
}

TEST(ConsoleApiE2eTest, VesselStateReachesWatchersWithTheTraffic) {
  auto engine = std::make_shared<FakeMissionEngine>();
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::Mission mission;
  ASSERT_NO_FATAL_FAILURE(CreateSampleMission(*missions, &mission));
  auto report = [&](double lat, const std::string& vessel, v1::ReportVesselStateResponse* out) {
    grpc::ClientContext ctx;
    v1::ReportVesselStateRequest req;
    req.set_mission_id(mission.mission_id());
    req.set_vessel_id(vessel);
    req.set_mission_time_s(12.5);
    req.mutable_state()->mutable_position()->set_latitude_deg(lat);
    req.mutable_state()->mutable_position()->set_longitude_deg(10.4);
    req.mutable_state()->set_heading_deg(65);
    auto* target = req.add_targets();
    target->set_target_id("ferry");
    target->set_kind("ferry");
    target->mutable_position()->set_latitude_deg(63.441);
    target->mutable_position()->set_longitude_deg(10.36);
    target->set_course_deg(0);
    target->set_speed_mps(4);
    return missions->ReportVesselState(&ctx, req, out);
  };
  v1::ReportVesselStateResponse first;
  ASSERT_TRUE(report(63.44, "ship0", &first).ok());
  EXPECT_TRUE(first.published());
  // Bad input and another vessel are refused.
  v1::ReportVesselStateResponse refused;
  EXPECT_EQ(report(95, "ship0", &refused).error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_EQ(report(63.44, "intruder", &refused).error_code(), StatusCode::PERMISSION_DENIED);
  {
    grpc::ClientContext ctx;
    v1::ReportVesselStateRequest req;
    req.set_mission_id("m-nope");
    req.mutable_state()->mutable_position()->set_latitude_deg(63.44);
    EXPECT_EQ(missions->ReportVesselState(&ctx, req, &refused).error_code(), StatusCode::NOT_FOUND);
  }

  // An NDJSON watcher gets the vessel update among the mission's events.
  auto canceller = std::async(std::launch::async, [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(600));
    return s.http().Post("/v1/MissionService/CancelMission",
                         "{\"missionId\":\"" + mission.mission_id() + "\"}", "application/json");
  });
  auto watch =
      s.http().Post("/v1/MissionService/WatchMission",
                    "{\"missionId\":\"" + mission.mission_id() + "\"}", "application/json");
  ASSERT_TRUE(watch);
  ASSERT_EQ(watch->status, 200);
  ASSERT_TRUE(canceller.get());
  int vessel_events = 0;
  bool ended_cancelled = false;
  for (const auto& ev : ParseNdjson(watch->body)) {
    if (ev.has_vessel()) {
      ++vessel_events;
      EXPECT_EQ(ev.vessel().vessel_id(), "ship0");
      EXPECT_DOUBLE_EQ(ev.vessel().mission_time_s(), 12.5);
      EXPECT_DOUBLE_EQ(ev.vessel().state().position().latitude_deg(), 63.44);
      ASSERT_EQ(ev.vessel().targets_size(), 1);
      EXPECT_EQ(ev.vessel().targets(0).target_id(), "ferry");
      EXPECT_DOUBLE_EQ(ev.vessel().targets(0).speed_mps(), 4);
    }
    if (ev.has_mission()) ended_cancelled = ev.mission().state() == v1::MISSION_STATE_CANCELLED;
  }
  EXPECT_EQ(vessel_events, 1) << watch->body;  // one report, one update
  EXPECT_TRUE(ended_cancelled);
}

TEST(ConsoleApiE2eTest, FeedbackHistoryIsPagedInArrivalOrderOnBothTransports) {
  auto engine = std::make_shared<FakeMissionEngine>();
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::Mission mission;
  ASSERT_NO_FATAL_FAILURE(CreateSampleMission(*missions, &mission));
  const std::string& id = mission.mission_id();
  // Position reports along a track, fuel falling; sequence numbers sent out
  // of order (a journal resent after an outage) and one retry.
  auto report = [&](std::int64_t sequence, int step) {
    grpc::ClientContext ctx;
    v1::ReportFeedbackRequest req;
    req.set_mission_id(id);
    req.set_vessel_id("ship0");
    req.set_sequence_number(sequence);
    v1::Feedback* f = req.mutable_feedback();
    f->set_kind(v1::Feedback::KIND_POSITION);
    f->set_plan_version(1);
    f->set_mission_time_s(30.0 * step);
    f->mutable_state()->mutable_position()->set_latitude_deg(63.44 + 0.001 * step);
    f->mutable_state()->mutable_position()->set_longitude_deg(10.40);
    f->mutable_state()->set_fuel_fraction(0.9 - 0.01 * step);
    v1::ReportFeedbackResponse resp;
    return missions->ReportFeedback(&ctx, req, &resp);
  };
  for (int step = 0; step < 5; ++step) {
    ASSERT_TRUE(report(10 - step, step).ok());
  }
  ASSERT_TRUE(report(8, 2).ok());  // a retry: stored once

  // gRPC, two per page: every report once, in arrival order, with its state.
  std::vector<v1::StoredFeedback> history;
  std::int64_t after = 0;
  int pages = 0;
  do {
    grpc::ClientContext ctx;
    v1::ListFeedbackRequest req;
    req.set_mission_id(id);
    req.set_after_sequence(after);
    req.set_page_size(2);
    v1::ListFeedbackResponse resp;
    ASSERT_TRUE(missions->ListFeedback(&ctx, req, &resp).ok());
    ++pages;
    history.insert(history.end(), resp.feedback().begin(), resp.feedback().end());
    after = resp.next_after_sequence();
  } while (after != 0 && pages < 10);
  EXPECT_EQ(pages, 3);
  ASSERT_EQ(history.size(), 5u);
  for (int step = 0; step < 5; ++step) {
    const v1::StoredFeedback& h = history[step];
    if (step > 0) {
      EXPECT_GT(h.sequence(), history[step - 1].sequence());
    }
    EXPECT_EQ(h.vessel_id(), "ship0");
    EXPECT_EQ(h.sequence_number(), 10 - step);
    EXPECT_GT(h.received_at().seconds(), 0);
    EXPECT_EQ(h.feedback().kind(), v1::Feedback::KIND_POSITION);
    EXPECT_DOUBLE_EQ(h.feedback().mission_time_s(), 30.0 * step);
    EXPECT_DOUBLE_EQ(h.feedback().state().position().latitude_deg(), 63.44 + 0.001 * step);
    EXPECT_DOUBLE_EQ(h.feedback().state().fuel_fraction(), 0.9 - 0.01 * step);
  }

  // HTTP/JSON: the same reports; after the last sequence, only what came since.
  auto http = s.http();
  auto all = http.Post("/v1/MissionService/ListFeedback",
                       "{\"missionId\":\"" + id + "\",\"pageSize\":100}", "application/json");
  ASSERT_TRUE(all);
  ASSERT_EQ(all->status, 200) << all->body;
  v1::ListFeedbackResponse json;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(all->body, &json).ok()) << all->body;
  ASSERT_EQ(json.feedback_size(), 5);
  EXPECT_EQ(json.next_after_sequence(), 0);
  EXPECT_EQ(json.feedback(4).sequence(), history.back().sequence());
  ASSERT_TRUE(report(42, 5).ok());
  const std::string since_body = "{\"missionId\":\"" + id + "\",\"afterSequence\":\"" +
                                 std::to_string(history.back().sequence()) + "\"}";
  auto since = http.Post("/v1/MissionService/ListFeedback", since_body, "application/json");
  ASSERT_TRUE(since);
  ASSERT_EQ(since->status, 200) << since->body;
  v1::ListFeedbackResponse newer;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(since->body, &newer).ok());
  ASSERT_EQ(newer.feedback_size(), 1);
  EXPECT_EQ(newer.feedback(0).sequence_number(), 42);

  // Bad requests: what is wrong, with the right status on each transport.
  auto unknown = http.Post("/v1/MissionService/ListFeedback", "{\"missionId\":\"m-nope\"}",
                           "application/json");
  ASSERT_TRUE(unknown);
  EXPECT_EQ(unknown->status, 404) << unknown->body;
  EXPECT_NE(unknown->body.find("m-nope"), std::string::npos) << unknown->body;
  auto negative =
      http.Post("/v1/MissionService/ListFeedback",
                "{\"missionId\":\"" + id + "\",\"afterSequence\":\"-1\"}", "application/json");
  ASSERT_TRUE(negative);
  EXPECT_EQ(negative->status, 400) << negative->body;
  EXPECT_NE(negative->body.find("after_sequence"), std::string::npos) << negative->body;
  grpc::ClientContext ctx;
  v1::ListFeedbackRequest empty;
  v1::ListFeedbackResponse resp;
  EXPECT_EQ(missions->ListFeedback(&ctx, empty, &resp).error_code(), StatusCode::INVALID_ARGUMENT);
}

// Each RPC must be reachable over HTTP too: a method left out of the
// gateway would answer "no route". Empty requests are refused or answered
// cheaply, never routed nowhere.
TEST(ConsoleApiE2eTest, EveryRpcOfEveryServiceIsMappedOnTheHttpGateway) {
  InProcessServer s(std::make_shared<FakeMissionEngine>());
  auto http = s.http();
  http.set_read_timeout(std::chrono::seconds(20));
  const auto* pool = google::protobuf::DescriptorPool::generated_pool();
  int methods = 0;
  for (const char* name : {"seaplan.v1.PlanningService", "seaplan.v1.ChartService",
                           "seaplan.v1.RouteService", "seaplan.v1.MissionService"}) {
    const google::protobuf::ServiceDescriptor* service = pool->FindServiceByName(name);
    ASSERT_NE(service, nullptr) << name;
    for (int i = 0; i < service->method_count(); ++i) {
      const std::string path = "/v1/" + service->name() + "/" + service->method(i)->name();
      auto res = http.Post(path, "{}", "application/json");
      ASSERT_TRUE(res) << path;
      EXPECT_EQ(res->body.find("no route"), std::string::npos) << path << ": " << res->body;
      ++methods;
    }
  }
  EXPECT_GE(methods, 17);
}

}  // namespace
}  // namespace seaplan::server::testing
