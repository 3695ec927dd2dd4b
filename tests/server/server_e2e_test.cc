// The server on loopback, in-process: health, error mapping,
// the bounded pool, deadlines and cancellation, the mission flow and the
// HTTP/JSON gateway, over both transports.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <future>
#include <set>

#include "grpc/health/v1/health.grpc.pb.h"
#include "seaplan/testing/shared_data.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

std::string ReadExample(const std::string& name) {
  return seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "examples" / "fjord" / name);
}

TEST(ServerE2eTest, HealthIsServingForEveryServiceOverBothTransports) {
  InProcessServer s;
  auto health = grpc::health::v1::Health::NewStub(s.channel());
  for (const std::string service : {"", "seaplan.v1.PlanningService", "seaplan.v1.ChartService",
                                    "seaplan.v1.RouteService", "seaplan.v1.MissionService"}) {
    ClientContext ctx;
    grpc::health::v1::HealthCheckRequest req;
    req.set_service(service);
    grpc::health::v1::HealthCheckResponse resp;
    grpc::Status st = health->Check(&ctx, req, &resp);
    ASSERT_TRUE(st.ok()) << service << ": " << st.error_message();
    EXPECT_EQ(resp.status(), grpc::health::v1::HealthCheckResponse::SERVING) << service;
  }
  {
    ClientContext ctx;
    grpc::health::v1::HealthCheckRequest req;
    req.set_service("seaplan.v1.NoSuchService");
    grpc::health::v1::HealthCheckResponse resp;
    EXPECT_EQ(health->Check(&ctx, req, &resp).error_code(), StatusCode::NOT_FOUND);
  }
  auto res = s.http().Get("/healthz");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
  EXPECT_EQ(res->body, "{\"status\":\"SERVING\"}");
}

TEST(ServerE2eTest, UnknownIdsAreNotFoundOverBothTransports) {
  InProcessServer s;
  auto missions = v1::MissionService::NewStub(s.channel());
  auto charts = v1::ChartService::NewStub(s.channel());
  {
    ClientContext ctx;
    v1::GetMissionRequest req;
    req.set_mission_id("m-does-not-exist");
    v1::Mission resp;
    grpc::Status st = missions->GetMission(&ctx, req, &resp);
    EXPECT_EQ(st.error_code(), StatusCode::NOT_FOUND);
    EXPECT_NE(st.error_message().find("m-does-not-exist"), std::string::npos);
  }
  {
    ClientContext ctx;
    v1::GetChartRequest req;
    req.set_chart_id("c-nope");
    v1::GetChartResponse resp;
    EXPECT_EQ(charts->GetChart(&ctx, req, &resp).error_code(), StatusCode::NOT_FOUND);
  }
  {
    ClientContext ctx;
    v1::ReportFeedbackRequest req;
    req.set_mission_id("m-nope");
    req.set_vessel_id("ship0");
    req.set_sequence_number(1);
    v1::ReportFeedbackResponse resp;
    EXPECT_EQ(missions->ReportFeedback(&ctx, req, &resp).error_code(), StatusCode::NOT_FOUND);
  }
  auto http = s.http();
  auto res =
      http.Post("/v1/MissionService/GetMission", "{\"missionId\":\"m-nope\"}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  EXPECT_NE(res->body.find("\"code\":\"NOT_FOUND\""), std::string::npos) << res->body;
  res = http.Post("/v1/ChartService/GetChart", "{\"chartId\":\"c-nope\"}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  // Bad JSON and unknown routes are errors with a JSON body too.
  res = http.Post("/v1/MissionService/GetMission", "{\"noSuchField\":1}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_NE(res->body.find("INVALID_ARGUMENT"), std::string::npos);
  res = http.Post("/v1/NoService/NoMethod", "{}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 404);
  EXPECT_NE(res->body.find("NOT_FOUND"), std::string::npos);
}

TEST(ServerE2eTest, MalformedMissionSpecIsInvalidArgumentAndStoresNothing) {
  InProcessServer s;  // the server's own mission engine
  auto missions = v1::MissionService::NewStub(s.channel());
  ClientContext ctx;
  v1::CreateMissionRequest req;
  *req.mutable_spec() = SampleSpec();
  req.mutable_spec()->set_domain("(define (domain d)\n (:predicates (p)\n");
  v1::Mission resp;
  grpc::Status st = missions->CreateMission(&ctx, req, &resp);
  EXPECT_EQ(st.error_code(), StatusCode::INVALID_ARGUMENT);
  EXPECT_NE(st.error_message().find("malformed PDDL"), std::string::npos) << st.error_message();
  v1::DiagnosticList diagnostics;
  ASSERT_TRUE(diagnostics.ParseFromString(st.error_details()));
  ASSERT_GE(diagnostics.diagnostics_size(), 1);
  EXPECT_EQ(diagnostics.diagnostics(0).file(), "domain");
  auto listed = s.store().missions().List(0, 10, 0);
  ASSERT_TRUE(listed.ok());
  EXPECT_TRUE(listed->items.empty());
  auto res = s.http().Post("/v1/MissionService/CreateMission",
                           "{\"spec\":{\"name\":\"x\",\"domain\":\"(define\",\"problem\":\"p\"}}",
                           "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400);
  EXPECT_NE(res->body.find("INVALID_ARGUMENT"), std::string::npos);
}

TEST(ServerE2eTest, RouteRpcsCheckTheChartFirst) {
  InProcessServer s;
  auto routes = v1::RouteService::NewStub(s.channel());
  ClientContext ctx;
  v1::PlanRouteRequest req;
  req.set_chart_id("c-nope");
  req.mutable_start()->set_latitude_deg(62.5);
  req.mutable_goal()->set_latitude_deg(62.6);
  v1::PlanRouteResponse resp;
  EXPECT_EQ(routes->PlanRoute(&ctx, req, &resp).error_code(), StatusCode::NOT_FOUND);
  ClientContext ctx2;
  req.mutable_start()->set_latitude_deg(123);  // not a latitude
  EXPECT_EQ(routes->PlanRoute(&ctx2, req, &resp).error_code(), StatusCode::INVALID_ARGUMENT);
}

TEST(ServerE2eTest, MalformedPddlIsInvalidArgumentWithLocation) {
  InProcessServer s;
  auto planning = v1::PlanningService::NewStub(s.channel());
  v1::ValidateRequest req;
  // Line 3 uses an undeclared predicate.
  req.set_domain(
      "(define (domain d)\n (:predicates (p))\n (:action a :parameters () :precondition (q) "
      ":effect (p)))\n");
  req.set_problem("(define (problem x) (:domain d) (:init) (:goal (p)))");
  req.set_plan("0: (a)\n");
  ClientContext ctx;
  v1::ValidateResponse resp;
  grpc::Status st = planning->Validate(&ctx, req, &resp);
  ASSERT_EQ(st.error_code(), StatusCode::INVALID_ARGUMENT) << st.error_message();
  v1::DiagnosticList diagnostics;
  ASSERT_TRUE(diagnostics.ParseFromString(st.error_details()));
  ASSERT_GE(diagnostics.diagnostics_size(), 1);
  const v1::Diagnostic& d = diagnostics.diagnostics(0);
  EXPECT_EQ(d.file(), "domain");
  EXPECT_EQ(d.line(), 3);
  EXPECT_GT(d.column(), 0);
  EXPECT_EQ(d.symbol(), "q");
  // Same over HTTP: 400 with the diagnostics in "details".
  auto res = s.http().Post("/v1/PlanningService/Validate",
                           "{\"domain\":\"(define (domain d)\\n (:predicates (p))\\n (:action a "
                           ":parameters () :precondition (q) :effect "
                           "(p)))\",\"problem\":\"(define (problem x) (:domain d) (:init) (:goal "
                           "(p)))\",\"plan\":\"0: (a)\"}",
                           "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400) << res->body;
  EXPECT_NE(res->body.find("seaplan.v1.DiagnosticList"), std::string::npos) << res->body;
  EXPECT_NE(res->body.find("\"line\":3"), std::string::npos) << res->body;
}

TEST(ServerE2eTest, ValidateJsonRoundTripOnTheFjordExample) {
  const std::string domain = ReadExample("domain.pddl");
  const std::string problem = ReadExample("case-a.pddl");
  const std::string good = ReadExample("case-a-repaired.plan");
  const std::string paper = ReadExample("case-a-paper.plan");
  if (domain.empty() || problem.empty() || good.empty() || paper.empty())
    GTEST_SKIP() << "examples/fjord missing";
  InProcessServer s;
  auto planning = v1::PlanningService::NewStub(s.channel());
  v1::ValidateRequest req;
  req.set_domain(domain);
  req.set_problem(problem);
  req.set_plan(good);
  ClientContext ctx;
  v1::ValidateResponse resp;
  grpc::Status st = planning->Validate(&ctx, req, &resp);
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_TRUE(resp.valid()) << resp.first_failure().reason();
  EXPECT_EQ(resp.action_count(), 13);
  EXPECT_GT(resp.makespan_s(), 2403.0);
  // The paper's printed plan is rejected, over HTTP/JSON this time.
  req.set_plan(paper);
  std::string body;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(req, &body).ok());
  auto res = s.http().Post("/v1/PlanningService/Validate", body, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  v1::ValidateResponse http_resp;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(res->body, &http_resp).ok()) << res->body;
  EXPECT_FALSE(http_resp.valid());
  EXPECT_FALSE(http_resp.first_failure().reason().empty());
  EXPECT_NE(res->body.find("\"valid\":false"), std::string::npos)
      << res->body;  // defaults are printed
}

// ---- the bounded pool, deadlines and cancellation (fake mission engine) ----

TEST(ServerE2eTest, FullPoolWithoutQueueIsResourceExhaustedAtOnceOverBothTransports) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->block_until_stopped = true;
  InProcessServer s(engine, /*planning_threads=*/1,
                    [](ServerOptions& options) { options.core.planning_queue = 0; });
  auto missions = v1::MissionService::NewStub(s.channel());
  // The first create occupies the only planning worker until its deadline.
  auto first = std::async(std::launch::async, [&] {
    ClientContext ctx;
    SetDeadline(&ctx, 3000);
    v1::CreateMissionRequest req;
    *req.mutable_spec() = SampleSpec();
    v1::Mission resp;
    return missions->CreateMission(&ctx, req, &resp).error_code();
  });
  while (s.server().core().pool().busy() == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const auto t0 = std::chrono::steady_clock::now();
  ClientContext ctx;
  v1::CreateMissionRequest req;
  *req.mutable_spec() = SampleSpec("second");
  v1::Mission resp;
  grpc::Status st = missions->CreateMission(&ctx, req, &resp);
  EXPECT_EQ(st.error_code(), StatusCode::RESOURCE_EXHAUSTED) << st.error_message();
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(1));  // not queued
  auto res = s.http().Post("/v1/MissionService/CreateMission",
                           "{\"spec\":{\"name\":\"third\",\"domain\":\"d\",\"problem\":\"p\"}}",
                           "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 429) << res->body;
  EXPECT_NE(res->body.find("RESOURCE_EXHAUSTED"), std::string::npos);
  EXPECT_EQ(first.get(), StatusCode::DEADLINE_EXCEEDED);
  EXPECT_EQ(engine->plan_calls.load(), 1);
}

TEST(ServerE2eTest, ClientDeadlineReachesTheWorkAndIsDeadlineExceeded) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->block_until_stopped = true;
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  ClientContext ctx;
  SetDeadline(&ctx, 300);
  v1::CreateMissionRequest req;
  *req.mutable_spec() = SampleSpec();
  v1::Mission resp;
  const auto t0 = std::chrono::steady_clock::now();
  grpc::Status st = missions->CreateMission(&ctx, req, &resp);
  EXPECT_EQ(st.error_code(), StatusCode::DEADLINE_EXCEEDED);
  // The work itself stopped (not just the client): the engine saw the deadline.
  const auto wait_until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!engine->stopped_work_finished && std::chrono::steady_clock::now() < wait_until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_TRUE(engine->stopped_work_finished);
  EXPECT_EQ(engine->last_stop_reason.load(), static_cast<int>(StopReason::kDeadline));
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(3));
  EXPECT_TRUE(s.store().missions().List(0, 10, 0)->items.empty());  // nothing stored
  // HTTP: the deadline header gives 504.
  engine->stopped_work_finished = false;
  httplib::Headers headers{{"X-Seaplan-Timeout-Ms", "200"}};
  auto res = s.http().Post("/v1/MissionService/CreateMission", headers,
                           "{\"spec\":{\"name\":\"h\",\"domain\":\"d\",\"problem\":\"p\"}}",
                           "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 504) << res->body;
  EXPECT_NE(res->body.find("DEADLINE_EXCEEDED"), std::string::npos);
}

TEST(ServerE2eTest, ClientCancellationReachesTheWork) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->block_until_stopped = true;
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  ClientContext ctx;
  v1::CreateMissionRequest req;
  *req.mutable_spec() = SampleSpec();
  v1::Mission resp;
  auto call = std::async(std::launch::async,
                         [&] { return missions->CreateMission(&ctx, req, &resp).error_code(); });
  while (s.server().core().pool().busy() == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ctx.TryCancel();
  EXPECT_EQ(call.get(), StatusCode::CANCELLED);
  const auto wait_until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (!engine->stopped_work_finished && std::chrono::steady_clock::now() < wait_until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(engine->last_stop_reason.load(), static_cast<int>(StopReason::kCancelled));
  // The worker is free again.
  const auto free_until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (s.server().core().pool().busy() != 0 && std::chrono::steady_clock::now() < free_until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(s.server().core().pool().busy(), 0);
}

// ---- the mission flow ----

std::vector<v1::MissionEvent> ReadAll(grpc::ClientReader<v1::MissionEvent>* reader) {
  std::vector<v1::MissionEvent> events;
  v1::MissionEvent e;
  while (reader->Read(&e)) events.push_back(e);
  return events;
}

TEST(ServerE2eTest, MissionFlowFeedbackIdempotentReplanAndResumableWatch) {
  auto engine = std::make_shared<FakeMissionEngine>();
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());

  v1::Mission mission;
  {
    ClientContext ctx;
    v1::CreateMissionRequest req;
    *req.mutable_spec() = SampleSpec();
    req.set_request_id("create-1");
    ASSERT_TRUE(missions->CreateMission(&ctx, req, &mission).ok());
    EXPECT_EQ(mission.state(), v1::MISSION_STATE_ACTIVE);
    EXPECT_EQ(mission.current_version(), 1);
    EXPECT_EQ(mission.spec().name(), "case-a");
    // A retry with the same request id returns the same mission, no new plan.
    ClientContext ctx2;
    v1::Mission again;
    ASSERT_TRUE(missions->CreateMission(&ctx2, req, &again).ok());
    EXPECT_EQ(again.mission_id(), mission.mission_id());
    EXPECT_EQ(engine->plan_calls.load(), 1);
  }
  const std::string id = mission.mission_id();

  // A live watcher from the start.
  ClientContext watch_ctx;
  SetDeadline(&watch_ctx, 20000);
  v1::WatchMissionRequest watch_req;
  watch_req.set_mission_id(id);
  auto watcher = missions->WatchMission(&watch_ctx, watch_req);

  auto report = [&](std::int64_t seq, v1::Feedback::Kind kind, const std::string& task) {
    ClientContext ctx;
    v1::ReportFeedbackRequest req;
    req.set_mission_id(id);
    req.set_vessel_id("ship0");
    req.set_sequence_number(seq);
    req.mutable_feedback()->set_kind(kind);
    req.mutable_feedback()->set_task_id(task);
    req.mutable_feedback()->set_mission_time_s(150.0);
    v1::ReportFeedbackResponse resp;
    grpc::Status st = missions->ReportFeedback(&ctx, req, &resp);
    EXPECT_TRUE(st.ok()) << st.error_message();
    return resp;
  };
  auto r1 = report(1, v1::Feedback::KIND_TASK_COMPLETED, "v1-t0");
  EXPECT_FALSE(r1.duplicate());
  auto r1_retry = report(1, v1::Feedback::KIND_TASK_COMPLETED, "v1-t0");
  EXPECT_TRUE(r1_retry.duplicate());
  EXPECT_EQ(s.store().missions().ListFeedback(id, 100)->size(), 1u);  // stored once

  // A failed task triggers a replan whose version 2 reaches the watcher.
  auto r2 = report(2, v1::Feedback::KIND_TASK_FAILED, "v1-t1");
  EXPECT_TRUE(r2.replan_triggered());
  EXPECT_EQ(r2.replan_reason(), "task v1-t1 failed");
  int version = 0;
  std::vector<v1::MissionEvent> live;
  v1::MissionEvent e;
  while (version < 2 && watcher->Read(&e)) {
    live.push_back(e);
    if (e.has_plan_version()) version = e.plan_version().version();
  }
  ASSERT_EQ(version, 2);

  // RequestReplan: synchronous version 3.
  {
    ClientContext ctx;
    v1::RequestReplanRequest req;
    req.set_mission_id(id);
    req.set_reason("operator: port-c closed");
    v1::RequestReplanResponse resp;
    ASSERT_TRUE(missions->RequestReplan(&ctx, req, &resp).ok());
    EXPECT_EQ(resp.version().version(), 3);
    EXPECT_EQ(resp.version().reason(), "operator: port-c closed");
    EXPECT_EQ(resp.version().mission_id(), id);
  }
  // Completing the last task of version 3 completes the mission; the watch ends OK.
  report(3, v1::Feedback::KIND_TASK_COMPLETED, "v3-t1");
  while (watcher->Read(&e)) live.push_back(e);
  EXPECT_TRUE(watcher->Finish().ok());

  // Versions 1..3 once each in order; event ids strictly increasing from 1
  // with no gap; the last mission state is COMPLETED.
  std::vector<int> versions;
  std::vector<std::int64_t> event_ids;
  v1::MissionState last_state = v1::MISSION_STATE_UNSPECIFIED;
  for (const auto& ev : live) {
    if (ev.has_plan_version()) versions.push_back(ev.plan_version().version());
    if (ev.has_log()) event_ids.push_back(ev.log().event_id());
    if (ev.has_mission()) last_state = ev.mission().state();
  }
  EXPECT_EQ(versions, (std::vector<int>{1, 2, 3}));
  ASSERT_FALSE(event_ids.empty());
  for (std::size_t i = 0; i < event_ids.size(); ++i)
    EXPECT_EQ(event_ids[i], static_cast<std::int64_t>(i + 1));
  EXPECT_EQ(last_state, v1::MISSION_STATE_COMPLETED);
  const auto stored_events = s.store().missions().ListEvents(id, 0, 1000);
  EXPECT_EQ(event_ids.size(), stored_events->size());

  // Resume after version 2 and event 4: exactly the rest, nothing twice.
  ClientContext resume_ctx;
  SetDeadline(&resume_ctx, 5000);
  watch_req.set_after_version(2);
  watch_req.set_after_event_id(4);
  auto resumed = ReadAll(missions->WatchMission(&resume_ctx, watch_req).get());
  std::vector<int> resumed_versions;
  std::vector<std::int64_t> resumed_ids;
  for (const auto& ev : resumed) {
    if (ev.has_plan_version()) resumed_versions.push_back(ev.plan_version().version());
    if (ev.has_log()) resumed_ids.push_back(ev.log().event_id());
  }
  EXPECT_EQ(resumed_versions, (std::vector<int>{3}));
  ASSERT_EQ(resumed_ids.size(), event_ids.size() - 4);
  EXPECT_EQ(resumed_ids.front(), 5);

  // Feedback after completion is refused; cancelling a completed mission too.
  {
    ClientContext ctx;
    v1::ReportFeedbackRequest req;
    req.set_mission_id(id);
    req.set_vessel_id("ship0");
    req.set_sequence_number(99);
    v1::ReportFeedbackResponse resp;
    EXPECT_EQ(missions->ReportFeedback(&ctx, req, &resp).error_code(),
              StatusCode::FAILED_PRECONDITION);
    ClientContext ctx2;
    v1::CancelMissionRequest cancel;
    cancel.set_mission_id(id);
    v1::Mission m;
    EXPECT_EQ(missions->CancelMission(&ctx2, cancel, &m).error_code(),
              StatusCode::FAILED_PRECONDITION);
  }
}

TEST(ServerE2eTest, HttpJsonMissionRoundTripAndNdjsonWatch) {
  auto engine = std::make_shared<FakeMissionEngine>();
  InProcessServer s(engine);
  auto http = s.http();
  auto res =
      http.Post("/v1/MissionService/CreateMission",
                "{\"spec\":{\"name\":\"json\",\"domain\":\"(define (domain d))\",\"problem\":\"p\","
                "\"initialState\":{\"fuelFraction\":0.3}}}",
                "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/json");
  v1::Mission mission;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(res->body, &mission).ok()) << res->body;
  EXPECT_EQ(mission.spec().name(), "json");
  EXPECT_DOUBLE_EQ(mission.spec().initial_state().fuel_fraction(), 0.3);
  EXPECT_NE(res->body.find("\"state\":\"MISSION_STATE_ACTIVE\""), std::string::npos) << res->body;
  EXPECT_NE(res->body.find("\"currentVersion\":1"), std::string::npos);

  res = http.Post("/v1/MissionService/ListMissions", "{\"pageSize\":10}", "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200);
  v1::ListMissionsResponse list;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(res->body, &list).ok());
  ASSERT_EQ(list.missions_size(), 1);
  EXPECT_EQ(list.missions(0).mission_id(), mission.mission_id());

  // NDJSON watch: cancel the mission from another thread; the stream ends.
  auto canceller = std::async(std::launch::async, [&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    auto c = s.http();
    return c.Post("/v1/MissionService/CancelMission",
                  "{\"missionId\":\"" + mission.mission_id() + "\",\"reason\":\"test over\"}",
                  "application/json");
  });
  auto watch = http.Post("/v1/MissionService/WatchMission",
                         "{\"missionId\":\"" + mission.mission_id() + "\"}", "application/json");
  ASSERT_TRUE(watch);
  EXPECT_EQ(watch->status, 200);
  EXPECT_EQ(watch->get_header_value("Content-Type"), "application/x-ndjson");
  auto cancelled = canceller.get();
  ASSERT_TRUE(cancelled);
  EXPECT_EQ(cancelled->status, 200) << cancelled->body;
  std::vector<v1::MissionEvent> events;
  std::size_t start = 0;
  while (start < watch->body.size()) {
    const std::size_t end = watch->body.find('\n', start);
    ASSERT_NE(end, std::string::npos) << "every line ends with \\n";
    v1::MissionEvent ev;
    ASSERT_TRUE(
        google::protobuf::util::JsonStringToMessage(watch->body.substr(start, end - start), &ev)
            .ok())
        << watch->body.substr(start, end - start);
    events.push_back(ev);
    start = end + 1;
  }
  ASSERT_GE(events.size(), 3u);
  EXPECT_TRUE(events.front().has_plan_version());
  EXPECT_TRUE(events.back().has_mission());
  EXPECT_EQ(events.back().mission().state(), v1::MISSION_STATE_CANCELLED);
  bool saw_cancel_log = false;
  for (const auto& ev : events)
    saw_cancel_log |= ev.has_log() && ev.log().message() == "mission cancelled: test over";
  EXPECT_TRUE(saw_cancel_log);

  // Streams that fail before the first message are plain HTTP errors.
  auto missing = http.Post("/v1/MissionService/WatchMission", "{\"missionId\":\"m-nope\"}",
                           "application/json");
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
}

TEST(ServerE2eTest, ShutdownEndsWatchesAndReportsNotServing) {
  auto engine = std::make_shared<FakeMissionEngine>();
  InProcessServer s(engine);
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::Mission mission;
  {
    ClientContext ctx;
    v1::CreateMissionRequest req;
    *req.mutable_spec() = SampleSpec();
    ASSERT_TRUE(missions->CreateMission(&ctx, req, &mission).ok());
  }
  ClientContext watch_ctx;
  SetDeadline(&watch_ctx, 20000);
  v1::WatchMissionRequest watch_req;
  watch_req.set_mission_id(mission.mission_id());
  auto watcher = missions->WatchMission(&watch_ctx, watch_req);
  v1::MissionEvent e;
  ASSERT_TRUE(watcher->Read(&e));  // the stream is live
  auto health = grpc::health::v1::Health::NewStub(s.channel());
  ClientContext health_ctx;
  SetDeadline(&health_ctx, 20000);
  grpc::health::v1::HealthCheckRequest health_req;
  health_req.set_service("seaplan.v1.MissionService");
  auto health_watch = health->Watch(&health_ctx, health_req);
  grpc::health::v1::HealthCheckResponse health_resp;
  ASSERT_TRUE(health_watch->Read(&health_resp));
  EXPECT_EQ(health_resp.status(), grpc::health::v1::HealthCheckResponse::SERVING);
  std::thread stopper([&] { s.server().Shutdown(); });
  // Draining: the health watch reports NOT_SERVING.
  ASSERT_TRUE(health_watch->Read(&health_resp));
  EXPECT_EQ(health_resp.status(), grpc::health::v1::HealthCheckResponse::NOT_SERVING);
  while (watcher->Read(&e)) {
  }
  grpc::Status st = watcher->Finish();
  health_ctx.TryCancel();
  while (health_watch->Read(&health_resp)) {
  }
  stopper.join();
  EXPECT_EQ(st.error_code(), StatusCode::UNAVAILABLE) << st.error_message();
  // The database is intact and holds the mission.
  EXPECT_TRUE(s.sqlite_store().CheckIntegrity().ok());
  EXPECT_TRUE(s.store().missions().Get(mission.mission_id()).ok());
}

}  // namespace
}  // namespace seaplan::server::testing
