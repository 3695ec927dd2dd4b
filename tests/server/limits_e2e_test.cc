// Limits that protect the server, end to end over both transports: the
// per-caller rate limit, the planning wait queue and its bound, the request
// size cap, and HTTP connections of clients that stall.
#include <arpa/inet.h>
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <future>
#include <vector>

#include "seaplan/testing/shared_data.h"
#include "server/auth/authenticator.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

TEST(LimitsE2eTest, RateLimitPerCallerOverBothTransportsWithRetryAfter) {
  InProcessServer s(nullptr, 1, [](ServerOptions& options) {
    // One call per 100 s after a burst of 3: no refill during the test.
    options.core.rate_limit = {/*calls_per_s=*/0.01, /*burst=*/3.0};
  });
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  // A second caller: a viewer token of its own (calls without a credential
  // present the fixtures' admin token).
  auto viewer =
      auth::Authenticator(s.store().tokens()).Issue(auth::Role::kViewer, "", "viewer", 0, "");
  ASSERT_TRUE(viewer.ok()) << viewer.status();
  const std::string another_caller = "Bearer " + viewer->bearer;
  auto missions = v1::MissionService::NewStub(s.channel());
  auto list = [&](const std::string& authorization, ClientContext* ctx) {
    if (!authorization.empty()) ctx->AddMetadata("authorization", authorization);
    v1::ListMissionsRequest req;
    v1::ListMissionsResponse resp;
    return missions->ListMissions(ctx, req, &resp);
  };
  for (int i = 0; i < 3; ++i) {
    ClientContext ctx;
    EXPECT_TRUE(list("", &ctx).ok()) << i;
  }
  {
    ClientContext ctx;
    const grpc::Status refused = list("", &ctx);
    EXPECT_EQ(refused.error_code(), StatusCode::RESOURCE_EXHAUSTED);
    EXPECT_NE(refused.error_message().find("rate limit"), std::string::npos);
    const auto& trailers = ctx.GetServerTrailingMetadata();
    auto it = trailers.find("retry-after-ms");
    ASSERT_NE(it, trailers.end());
    EXPECT_GT(std::stoll(std::string(it->second.data(), it->second.size())), 1000);
  }
  // HTTP with the same credentials shares the bucket.
  auto res = s.http().Post("/v1/MissionService/ListMissions", "{}", "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 429) << res->body;
  ASSERT_TRUE(res->has_header("Retry-After"));
  EXPECT_GE(std::stoi(res->get_header_value("Retry-After")), 1);
  // A caller with its own credentials has its own bucket, on both transports.
  {
    ClientContext ctx;
    EXPECT_TRUE(list(another_caller, &ctx).ok());
  }
  httplib::Headers headers{{"Authorization", another_caller}};
  auto other = s.http().Post("/v1/MissionService/ListMissions", headers, "{}", "application/json");
  ASSERT_TRUE(other);
  EXPECT_EQ(other->status, 200) << other->body;
  // Health checks are never limited.
  auto health = s.http().Get("/healthz");
  ASSERT_TRUE(health);
  EXPECT_EQ(health->status, 200);
}

TEST(LimitsE2eTest, BusyPoolQueuesCallsAndRefusesBeyondTheQueueBound) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->block_until_stopped = true;
  constexpr int kQueue = 6;
  InProcessServer s(engine, 1, [](ServerOptions& options) {
    options.core.planning_queue = kQueue;
    options.worker_threads = 16;  // queued HTTP calls hold a handler thread each
  });
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  // The only worker is held by a mission plan until that call's deadline.
  auto missions = v1::MissionService::NewStub(s.channel());
  auto blocker = std::async(std::launch::async, [&] {
    ClientContext ctx;
    SetDeadline(&ctx, 4000);
    v1::CreateMissionRequest req;
    *req.mutable_spec() = SampleSpec("blocker");
    v1::Mission resp;
    return missions->CreateMission(&ctx, req, &resp).error_code();
  });
  while (s.server().core().pool().busy() == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  // Validate runs on the pool too (grounding) and is quick once it runs.
  const std::string body =
      "{\"domain\":\"(define (domain d) (:requirements :strips) (:predicates (p)) (:action a "
      ":parameters () :precondition () :effect (p)))\",\"problem\":\"(define (problem q) "
      "(:domain d) (:init) (:goal (p)))\",\"plan\":\"0: (a)\"}";
  std::vector<std::future<int>> queued;
  queued.reserve(kQueue);
  for (int i = 0; i < kQueue; ++i) {
    queued.push_back(std::async(std::launch::async, [&] {
      auto res = s.http().Post("/v1/PlanningService/Validate", body, "application/json");
      return res ? res->status : -1;
    }));
  }
  while (s.server().core().pool().waiting() < kQueue)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  // The queue is full: refused at once on both transports.
  auto refused = s.http().Post("/v1/PlanningService/Validate", body, "application/json");
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 429) << refused->body;
  EXPECT_TRUE(refused->has_header("Retry-After"));
  {
    auto planning = v1::PlanningService::NewStub(s.channel());
    ClientContext ctx;
    v1::ValidateRequest req;
    ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(body, &req).ok());
    v1::ValidateResponse resp;
    EXPECT_EQ(planning->Validate(&ctx, req, &resp).error_code(), StatusCode::RESOURCE_EXHAUSTED);
  }
  // The blocker ends at its deadline; every queued call then runs.
  EXPECT_EQ(blocker.get(), StatusCode::DEADLINE_EXCEEDED);
  for (auto& q : queued) EXPECT_EQ(q.get(), 200);
  EXPECT_EQ(s.server().core().pool().waiting(), 0);
}

TEST(LimitsE2eTest, TwelveConcurrentCaseAPlansOverHttpQueueAndAllSucceed) {
  const auto fjord = seaplan::testing::SourceDir() / "examples" / "fjord";
  const std::string domain = seaplan::testing::ReadFile(fjord / "domain.pddl");
  const std::string problem = seaplan::testing::ReadFile(fjord / "case-a.pddl");
  InProcessServer s(nullptr, 2, [](ServerOptions& options) { options.worker_threads = 16; });
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  v1::PlanRequest req;
  req.set_domain(domain);
  req.set_problem(problem);
  req.mutable_options()->mutable_time_limit()->set_seconds(60);
  std::string body;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(req, &body).ok());
  std::atomic<int> most_waiting{0};
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    while (!done) {
      most_waiting = std::max(most_waiting.load(), s.server().core().pool().waiting());
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  constexpr int kCallers = 12;
  std::vector<std::future<std::pair<int, std::string>>> plans;
  plans.reserve(kCallers);
  for (int i = 0; i < kCallers; ++i) {
    plans.push_back(std::async(std::launch::async, [&] {
      auto res = s.http().Post("/v1/PlanningService/Plan", body, "application/json");
      return res ? std::make_pair(res->status, res->body) : std::make_pair(-1, std::string());
    }));
  }
  for (auto& p : plans) {
    auto [status, response] = p.get();
    EXPECT_EQ(status, 200) << response.substr(0, 300);
    EXPECT_NE(response.find("SOLVED"), std::string::npos) << response.substr(0, 300);
  }
  done = true;
  watcher.join();
  // Twelve at once on two workers: most of them waited their turn.
  EXPECT_GT(most_waiting.load(), 0);
}

TEST(LimitsE2eTest, RequestsAskingForMoreThanTheServersBudgetsAreRefused) {
  InProcessServer s(nullptr, 1,
                    [](ServerOptions& options) { options.core.budgets.max_plan_time_s = 60; });
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  auto planning = v1::PlanningService::NewStub(s.channel());
  v1::PlanRequest req;
  req.set_domain("(define (domain d))");
  req.set_problem("(define (problem p) (:domain d))");
  req.mutable_options()->mutable_time_limit()->set_seconds(3600);
  {
    ClientContext ctx;
    v1::PlanResponse resp;
    const grpc::Status st = planning->Plan(&ctx, req, &resp);
    EXPECT_EQ(st.error_code(), StatusCode::INVALID_ARGUMENT);
    EXPECT_NE(st.error_message().find("more than this server allows (60 s)"), std::string::npos)
        << st.error_message();
  }
  req.mutable_options()->mutable_time_limit()->set_seconds(10);
  req.mutable_options()->set_memory_limit_mb(1 << 20);
  {
    ClientContext ctx;
    v1::PlanResponse resp;
    EXPECT_EQ(planning->Plan(&ctx, req, &resp).error_code(), StatusCode::INVALID_ARGUMENT);
  }
  // A route optimizer run of a billion evaluations, over HTTP.
  auto res =
      s.http().Post("/v1/RouteService/PlanRoute",
                    "{\"chartId\":\"any\",\"start\":{\"latitudeDeg\":63.44,\"longitudeDeg\":10.33},"
                    "\"goal\":{\"latitudeDeg\":63.45,\"longitudeDeg\":10.35},"
                    "\"options\":{\"particles\":1000,\"iterations\":1000}}",
                    "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 400) << res->body;
  EXPECT_NE(res->body.find("particles x iterations"), std::string::npos) << res->body;
}

// One message above --max-request-bytes: RESOURCE_EXHAUSTED / 413 before any
// handler runs, nothing stored; the same chart under the cap is stored.
TEST(LimitsE2eTest, ARequestAboveTheSizeCapIsRefusedOverBothTransports) {
  constexpr std::size_t kCap = 64 * 1024;
  InProcessServer s(nullptr, 1, [](ServerOptions& options) { options.max_request_bytes = kCap; });
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  auto charts = v1::ChartService::NewStub(s.channel());
  {
    ClientContext ctx;
    v1::UploadChartResponse resp;
    const grpc::Status st = charts->UploadChart(&ctx, HarbourChartUpload(kCap), &resp);
    EXPECT_EQ(st.error_code(), StatusCode::RESOURCE_EXHAUSTED) << st.error_message();
  }
  // HTTP allows 4/3 of the cap (base64) plus 1 MiB of JSON: a 1 MiB file's
  // base64 is beyond it.
  std::string body;
  ASSERT_TRUE(
      google::protobuf::util::MessageToJsonString(HarbourChartUpload(1u << 20), &body).ok());
  auto res = s.http().Post("/v1/ChartService/UploadChart", body, "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 413);
  EXPECT_NE(res->body.find("RESOURCE_EXHAUSTED"), std::string::npos) << res->body;
  {
    ClientContext ctx;
    v1::ListChartsResponse list;
    ASSERT_TRUE(charts->ListCharts(&ctx, v1::ListChartsRequest(), &list).ok());
    EXPECT_EQ(list.charts_size(), 0);
  }
  // The same chart within the cap, on each transport.
  {
    ClientContext ctx;
    v1::UploadChartResponse resp;
    const grpc::Status st = charts->UploadChart(&ctx, HarbourChartUpload(kCap / 2), &resp);
    EXPECT_TRUE(st.ok()) << st.error_message();
  }
  std::string within_cap;
  ASSERT_TRUE(
      google::protobuf::util::MessageToJsonString(HarbourChartUpload(kCap / 2), &within_cap).ok());
  res = s.http().Post("/v1/ChartService/UploadChart", within_cap, "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200) << res->body;
}

// A raw connection to the HTTP port; the server's answer and whether it
// closed the connection within `limit`.
struct RawResult {
  bool closed = false;
  std::string received;
};
RawResult SendAndStall(int port, const std::string& bytes, std::chrono::seconds limit) {
  RawResult result;
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    ::close(fd);
    return result;
  }
  if (!bytes.empty()) (void)::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL);
  const auto until = std::chrono::steady_clock::now() + limit;
  char buffer[4096];
  while (std::chrono::steady_clock::now() < until) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, 100) <= 0) continue;
    const ssize_t n = ::recv(fd, buffer, sizeof(buffer), 0);
    if (n <= 0) {
      result.closed = true;
      break;
    }
    result.received.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fd);
  return result;
}

TEST(LimitsE2eTest, HttpConnectionsThatStallAreDropped) {
  InProcessServer s(nullptr, 1, [](ServerOptions& options) {
    options.http_read_timeout = std::chrono::milliseconds(300);
  });
  ASSERT_TRUE(s.start_status().ok()) << s.start_status();
  // Headers announce a body that never comes.
  RawResult stalled_body =
      SendAndStall(s.http_port(),
                   "POST /v1/MissionService/ListMissions HTTP/1.1\r\nHost: x\r\n"
                   "Content-Length: 1000\r\n\r\n{",
                   std::chrono::seconds(60));
  EXPECT_TRUE(stalled_body.closed) << stalled_body.received;
  EXPECT_EQ(stalled_body.received.find("200 OK"), std::string::npos) << stalled_body.received;
  // Half a request line, then nothing.
  RawResult stalled_headers =
      SendAndStall(s.http_port(), "POST /v1/MissionService/List", std::chrono::seconds(60));
  EXPECT_TRUE(stalled_headers.closed);
  // The server still answers others.
  auto res = s.http().Get("/healthz");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 200);
}

}  // namespace
}  // namespace seaplan::server::testing
