// PlanningService end to end with the real planner (engine/search): plans
// on the fjord example checked by the server's own validator, NDJSON
// streaming, and deadlines / the bounded pool on a search that runs until
// its time limit (depots-time p05 from the shared benchmark set).
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include <future>

#include "seaplan/testing/large_pddl.h"
#include "seaplan/testing/shared_data.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

std::string Example(const std::string& name) {
  return seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "examples" / "fjord" / name);
}

TEST(PlanningE2eTest, PlanCaseAReturnsAPlanTheValidatorAccepts) {
  const std::string domain = Example("domain.pddl");
  const std::string problem = Example("case-a.pddl");
  ASSERT_FALSE(domain.empty() || problem.empty());
  InProcessServer s;
  auto planning = v1::PlanningService::NewStub(s.channel());
  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::PlanRequest req;
  req.set_domain(domain);
  req.set_problem(problem);
  req.mutable_options()->mutable_time_limit()->set_seconds(30);
  v1::PlanResponse resp;
  grpc::Status st = planning->Plan(&ctx, req, &resp);
  ASSERT_TRUE(st.ok()) << st.error_message();
  ASSERT_TRUE(resp.status() == v1::SOLVED_SATISFICING || resp.status() == v1::SOLVED_OPTIMALLY)
      << resp.message();
  EXPECT_EQ(resp.plan_size(), 13);
  EXPECT_GE(resp.makespan_s(), 2403.33);
  EXPECT_GT(resp.statistics().ground_actions(), 0u);
  EXPECT_FALSE(resp.plan_text().empty());
  // The printed plan is valid as printed.
  ClientContext vctx;
  v1::ValidateRequest vreq;
  vreq.set_domain(domain);
  vreq.set_problem(problem);
  vreq.set_plan(resp.plan_text());
  v1::ValidateResponse vresp;
  ASSERT_TRUE(planning->Validate(&vctx, vreq, &vresp).ok());
  EXPECT_TRUE(vresp.valid()) << vresp.first_failure().reason();
  EXPECT_DOUBLE_EQ(vresp.makespan_s(), resp.makespan_s());
}

TEST(PlanningE2eTest, PlanStreamOverHttpIsNdjsonEndingWithTheFinalResult) {
  const std::string domain = Example("domain.pddl");
  const std::string problem = Example("case-a.pddl");
  InProcessServer s;
  auto planning = v1::PlanningService::NewStub(s.channel());
  v1::PlanRequest req;
  req.set_domain(domain);
  req.set_problem(problem);
  req.mutable_options()->mutable_time_limit()->set_seconds(30);
  std::string body;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(req, &body).ok());
  auto res = s.http().Post("/v1/PlanningService/PlanStream", body, "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  EXPECT_EQ(res->get_header_value("Content-Type"), "application/x-ndjson");
  std::vector<v1::PlanStreamEvent> events;
  std::size_t start = 0;
  while (start < res->body.size()) {
    const std::size_t end = res->body.find('\n', start);
    ASSERT_NE(end, std::string::npos);
    v1::PlanStreamEvent ev;
    ASSERT_TRUE(
        google::protobuf::util::JsonStringToMessage(res->body.substr(start, end - start), &ev)
            .ok());
    events.push_back(ev);
    start = end + 1;
  }
  ASSERT_GE(events.size(), 2u);  // at least one improved plan and the final result
  EXPECT_TRUE(events.back().has_final_result());
  int improved = 0;
  for (std::size_t i = 0; i + 1 < events.size(); ++i) {
    EXPECT_FALSE(events[i].has_final_result());
    improved += events[i].has_improved_plan();
  }
  EXPECT_GE(improved, 1);
  EXPECT_EQ(events.back().final_result().plan_size(), 13);
  // Malformed PDDL before the stream starts: a plain 400 with diagnostics.
  auto bad =
      s.http().Post("/v1/PlanningService/PlanStream",
                    "{\"domain\":\"(define (domain d\",\"problem\":\"(define (problem p))\"}",
                    "application/json");
  ASSERT_TRUE(bad);
  EXPECT_EQ(bad->status, 400) << bad->body;
  EXPECT_NE(bad->body.find("DiagnosticList"), std::string::npos) << bad->body;
}

TEST(PlanningE2eTest, TheTimeLimitBoundsGroundingToo) {
  // 100^3 action instances: grounding alone would take seconds and hundreds
  // of MB; under a 200 ms limit the response says the limit ended grounding.
  const auto task = seaplan::testing::CubicGroundingTask(100);
  InProcessServer s;
  auto planning = v1::PlanningService::NewStub(s.channel());
  ClientContext ctx;
  SetDeadline(&ctx, 60000);
  v1::PlanRequest req;
  req.set_domain(task.domain);
  req.set_problem(task.problem);
  req.mutable_options()->mutable_time_limit()->set_nanos(200'000'000);
  v1::PlanResponse resp;
  grpc::Status st = planning->Plan(&ctx, req, &resp);
  ASSERT_TRUE(st.ok()) << st.error_message();
  EXPECT_EQ(resp.status(), v1::TIMEOUT);
  EXPECT_EQ(resp.message(), "time limit reached while grounding");
  EXPECT_EQ(resp.statistics().ground_actions(), 0u);
  EXPECT_EQ(resp.statistics().first_plan_time_s(), -1.0);  // none
  EXPECT_GT(resp.statistics().grounding().parse_s(), 0.0);
}

TEST(PlanningE2eTest, ClientDeadlineStopsALongSearch) {
  SEAPLAN_REQUIRE_SHARED(problem_path, "bench/depots-time/p05.pddl");
  const std::string domain = seaplan::testing::ReadFile(problem_path.parent_path() / "domain.pddl");
  const std::string problem = seaplan::testing::ReadFile(problem_path);
  // No wait queue: a second call is refused while the first runs.
  InProcessServer s(nullptr, /*planning_threads=*/1,
                    [](ServerOptions& options) { options.core.planning_queue = 0; });
  auto planning = v1::PlanningService::NewStub(s.channel());
  v1::PlanRequest req;
  req.set_domain(domain);
  req.set_problem(problem);
  req.mutable_options()->mutable_time_limit()->set_seconds(
      120);  // the search alone would run for minutes

  // While one long search holds the only worker, another is refused at once.
  auto first = std::async(std::launch::async, [&] {
    ClientContext ctx;
    SetDeadline(&ctx, 1500);
    v1::PlanResponse resp;
    const auto t0 = std::chrono::steady_clock::now();
    const StatusCode code = planning->Plan(&ctx, req, &resp).error_code();
    return std::make_pair(code, std::chrono::steady_clock::now() - t0);
  });
  while (s.server().core().pool().busy() == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  {
    ClientContext ctx;
    v1::PlanResponse resp;
    EXPECT_EQ(planning->Plan(&ctx, req, &resp).error_code(), StatusCode::RESOURCE_EXHAUSTED);
  }
  auto [code, took] = first.get();
  EXPECT_EQ(code, StatusCode::DEADLINE_EXCEEDED);
  EXPECT_LT(took, std::chrono::seconds(5));
  // The search itself stopped: the worker is free within a moment.
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (s.server().core().pool().busy() != 0 && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  EXPECT_EQ(s.server().core().pool().busy(), 0);
  // Over HTTP the deadline header gives 504.
  std::string body;
  ASSERT_TRUE(google::protobuf::util::MessageToJsonString(req, &body).ok());
  httplib::Headers headers{{"X-Seaplan-Timeout-Ms", "500"}};
  auto res = s.http().Post("/v1/PlanningService/Plan", headers, body, "application/json");
  ASSERT_TRUE(res);
  EXPECT_EQ(res->status, 504) << res->body;
}

}  // namespace
}  // namespace seaplan::server::testing
