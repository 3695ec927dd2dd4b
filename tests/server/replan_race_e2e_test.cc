// Replans of one mission asked for at once, through one server on SQLite
// (the embedded setup): RequestReplan calls from two operators (one over
// gRPC, one over HTTP), and a call racing a report that triggers a replan.
// Replans run under the mission's work lease on SQLite too, so they run one
// at a time: each operator's call answers with a version of its own, planned
// from the version before it, numbered without gap; a report's trigger gives
// at most one version.
#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <iostream>
#include <string>
#include <thread>
#include <vector>

#include "absl/strings/str_cat.h"
#include "server/http/json_codec.h"
#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;

v1::Mission CreateFakeMission(InProcessServer& s) {
  auto missions = v1::MissionService::NewStub(s.channel());
  v1::CreateMissionRequest req;
  *req.mutable_spec() = SampleSpec("replan race");
  v1::Mission mission;
  ClientContext ctx;
  const grpc::Status st = missions->CreateMission(&ctx, req, &mission);
  EXPECT_TRUE(st.ok()) << st.error_message();
  return mission;
}

// Waits (at most 20 s) until the mission is ACTIVE with no replan pending or
// running; returns it.
storage::MissionRecord AwaitSettled(InProcessServer& s, const std::string& id) {
  absl::StatusOr<storage::MissionRecord> record = s.store().missions().Get(id);
  for (int i = 0; i < 2000; ++i) {
    record = s.store().missions().Get(id);
    auto work = s.store().work().Get(id);
    const bool idle =
        work.ok() && (!work->has_value() || (!(*work)->pending() && (*work)->holder.empty()));
    if (record.ok() && record->state == v1::MISSION_STATE_ACTIVE && idle) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_TRUE(record.ok()) << record.status();
  return record.ok() ? *record : storage::MissionRecord();
}

// Every stored version after the first was planned from the one before it
// (the fake engine names version N's tasks "vN-..." from the version it was
// handed + 1), and the log has one "ready" line per version. With
// `log_in_order` (only operators' replans), each replan's start is followed
// by its version before the next replan starts (a report logs its trigger
// when it arrives, also while a replan runs).
void ExpectReplansOneAfterAnother(InProcessServer& s, const std::string& id, int last_version,
                                  bool log_in_order) {
  for (int v = 1; v <= last_version; ++v) {
    auto stored = s.store().missions().GetVersion(id, v);
    ASSERT_TRUE(stored.ok()) << "version " << v << ": " << stored.status();
    v1::PlanVersion version;
    ASSERT_TRUE(version.ParseFromString(stored->content));
    ASSERT_GT(version.tasks_size(), 0);
    EXPECT_EQ(version.tasks(0).task_id(), absl::StrCat("v", v, "-t0"))
        << "version " << v << " was not planned from version " << v - 1;
  }
  EXPECT_EQ(s.store().missions().GetVersion(id, last_version + 1).status().code(),
            absl::StatusCode::kNotFound);
  auto events = s.store().missions().ListEvents(id, 0, 10000);
  ASSERT_TRUE(events.ok());
  int started = 0, ready = 0;
  for (const storage::LogEventRecord& e : *events) {
    if (e.message.rfind("replanning: ", 0) == 0 && log_in_order) {
      EXPECT_EQ(started, ready) << "a replan started before the previous one ended: " << e.message;
      started = ready + 1;
    } else if (e.message.rfind("plan version ", 0) == 0 &&
               e.message.find(" ready (") != std::string::npos &&
               e.message.rfind("plan version 1 ready", 0) != 0) {
      ++ready;
    }
  }
  EXPECT_EQ(ready, last_version - 1);
}

// An operator's RequestReplan over gRPC (deadline 30 s), sent once
// `start_together` returns.
grpc::Status RequestReplanOverGrpc(v1::MissionService::Stub& missions, const std::string& id,
                                   const std::string& reason,
                                   const std::function<void()>& start_together,
                                   v1::RequestReplanResponse* answer) {
  v1::RequestReplanRequest req;
  req.set_mission_id(id);
  req.set_reason(reason);
  ClientContext ctx;
  SetDeadline(&ctx, 30000);
  start_together();
  return missions.RequestReplan(&ctx, req, answer);
}

TEST(ReplanRaceE2eTest, TwoOperatorsAtOnceGetAVersionEachPlannedOneAfterTheOther) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->replan_delay_ms = 200;  // the two calls overlap
  InProcessServer s(engine);
  const v1::Mission mission = CreateFakeMission(s);
  const std::string& id = mission.mission_id();
  auto missions = v1::MissionService::NewStub(s.channel());
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const std::string by_grpc = absl::StrCat("operator A, round ", round);
    const std::string by_http = absl::StrCat("operator B, round ", round);
    std::atomic<int> ready{0};
    const auto start_together = [&] {
      ++ready;
      while (ready.load() < 2) {
      }
    };
    grpc::Status grpc_status;
    v1::RequestReplanResponse grpc_answer;
    int http_code = 0;
    std::string http_body;
    std::thread a([&] {
      grpc_status = RequestReplanOverGrpc(*missions, id, by_grpc, start_together, &grpc_answer);
    });
    std::thread b([&] {
      httplib::Client http = s.http();
      const std::string body =
          absl::StrCat(R"({"missionId":")", id, R"(","reason":")", by_http, R"("})");
      start_together();
      auto res = http.Post("/v1/MissionService/RequestReplan", body, "application/json");
      if (res) {
        http_code = res->status;
        http_body = res->body;
      }
    });
    a.join();
    b.join();
    ASSERT_TRUE(grpc_status.ok()) << grpc_status.error_message();
    ASSERT_EQ(http_code, 200) << http_body;
    v1::RequestReplanResponse http_answer;
    ASSERT_TRUE(MessageFromJson(http_body, &http_answer).ok()) << http_body;
    // A version each, with the caller's reason, the two next numbers.
    EXPECT_EQ(grpc_answer.version().reason(), by_grpc);
    EXPECT_EQ(http_answer.version().reason(), by_http);
    const int first = 2 + 2 * round;
    EXPECT_EQ(std::min(grpc_answer.version().version(), http_answer.version().version()), first);
    EXPECT_EQ(std::max(grpc_answer.version().version(), http_answer.version().version()),
              first + 1);
  }
  const storage::MissionRecord settled = AwaitSettled(s, id);
  EXPECT_EQ(settled.current_version, 1 + 2 * kRounds);
  EXPECT_EQ(engine->replan_calls.load(), 2 * kRounds);  // none planned twice
  EXPECT_EQ(engine->most_replans_at_once.load(), 1);
  ExpectReplansOneAfterAnother(s, id, 1 + 2 * kRounds, true);
}

// A report that triggers a replan, and an operator's call at the same
// moment (even rounds) or while the operator's replan runs (odd rounds):
// the call answers with a version of its own; the report's trigger gives at
// most one more (none when the operator's replan took the report's pending
// request with its claim, or was already under way from the same version);
// versions stay gapless, planned one after the other.
TEST(ReplanRaceE2eTest, AnOperatorRacingATriggeringReportGetsOneVersionPerReplan) {
  auto engine = std::make_shared<FakeMissionEngine>();
  engine->replan_delay_ms = 150;
  InProcessServer s(engine);
  const v1::Mission mission = CreateFakeMission(s);
  const std::string& id = mission.mission_id();
  auto missions = v1::MissionService::NewStub(s.channel());
  constexpr int kRounds = 6;
  int version = 1, covered = 0, one_each = 0;
  for (int round = 0; round < kRounds; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    const std::string operator_reason = absl::StrCat("operator, round ", round);
    std::atomic<int> ready{0};
    const auto start_together = [&] {
      ++ready;
      while (ready.load() < 2) {
      }
    };
    grpc::Status report_status, replan_status;
    v1::ReportFeedbackResponse report;
    v1::RequestReplanResponse replan;
    std::thread reporter([&] {
      v1::ReportFeedbackRequest req;
      req.set_mission_id(id);
      req.set_vessel_id("ship0");
      req.set_sequence_number(round + 1);
      req.mutable_feedback()->set_kind(v1::Feedback::KIND_TASK_FAILED);
      req.mutable_feedback()->set_task_id(absl::StrCat("v", version, "-t0"));
      req.mutable_feedback()->set_plan_version(version);
      req.mutable_feedback()->set_mission_time_s(10.0 * (round + 1));
      ClientContext ctx;
      SetDeadline(&ctx, 30000);
      start_together();
      if (round % 2 == 1) std::this_thread::sleep_for(std::chrono::milliseconds(60));
      report_status = missions->ReportFeedback(&ctx, req, &report);
    });
    std::thread requester([&] {
      replan_status =
          RequestReplanOverGrpc(*missions, id, operator_reason, start_together, &replan);
    });
    reporter.join();
    requester.join();
    ASSERT_TRUE(replan_status.ok()) << replan_status.error_message();
    EXPECT_EQ(replan.version().reason(), operator_reason);
    // The report is stored whatever the state it met (REPLANNING included).
    ASSERT_TRUE(report_status.ok()) << report_status.error_message();
    const storage::MissionRecord settled = AwaitSettled(s, id);
    // One or two new versions: the operator's, and the report's unless the
    // operator's replan covered it.
    const int added = settled.current_version - version;
    EXPECT_GE(added, 1);
    EXPECT_LE(added, 2);
    const std::string report_reason = absl::StrCat("task v", version, "-t0 failed");
    int operator_versions = 0, report_versions = 0;
    for (int v = version + 1; v <= settled.current_version; ++v) {
      auto stored = s.store().missions().GetVersion(id, v);
      ASSERT_TRUE(stored.ok()) << stored.status();
      operator_versions += stored->reason == operator_reason ? 1 : 0;
      report_versions += stored->reason == report_reason ? 1 : 0;
    }
    EXPECT_EQ(operator_versions, 1);
    EXPECT_EQ(operator_versions + report_versions, added);
    (added == 1 ? covered : one_each) += 1;
    version = settled.current_version;
  }
  std::cout << kRounds << " rounds: the report's trigger gave no version of its own in " << covered
            << ", one in " << one_each << "\n";
  ExpectReplansOneAfterAnother(s, id, version, false);
  EXPECT_EQ(engine->most_replans_at_once.load(), 1);
  EXPECT_EQ(engine->replan_calls.load(), version - 1);
}

}  // namespace
}  // namespace seaplan::server::testing
