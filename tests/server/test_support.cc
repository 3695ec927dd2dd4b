#include "test_support.h"

#include <unistd.h>

#include "absl/strings/str_cat.h"
#include "server/core/convert.h"

namespace seaplan::server::testing {

TempDir::TempDir() {
  static std::atomic<int> counter{0};
  path_ = std::filesystem::temp_directory_path() /
          absl::StrCat("seaplan-server-test-", ::getpid(), "-", counter++);
  std::filesystem::remove_all(path_);
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

absl::Status FakeMissionEngine::CheckSpec(const v1::MissionSpec& spec) {
  if (spec.name() == "bad")
    return absl::InvalidArgumentError("spec.name: 'bad' is refused by the fake engine");
  return absl::OkStatus();
}

absl::Status FakeMissionEngine::MaybeBlock(const StopToken& stop) {
  if (!block_until_stopped) return absl::OkStatus();
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!stop.StopRequested() && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  last_stop_reason = static_cast<int>(stop.Reason());
  stopped_work_finished = true;
  return absl::CancelledError("stopped");
}

PlannedVersion FakeMissionEngine::MakeVersion(int version, double origin_s) {
  PlannedVersion planned;
  v1::PlanVersion& v = planned.version;
  v.set_mission_time_origin_s(origin_s);
  v.set_planner_status(v1::SOLVED_SATISFICING);
  for (int i = 0; i < 2; ++i) {
    v1::Task* t = v.add_tasks();
    t->set_task_id(absl::StrCat("v", version, "-t", i));
    t->set_kind(i == 0 ? v1::Task::KIND_MOVE : v1::Task::KIND_LOAD);
    t->set_start_s(origin_s + 100.0 * i);
    t->set_duration_s(100.0);
    v1::TimedAction* a = v.add_plan();
    a->set_start_s(origin_s + 100.0 * i);
    a->set_duration_s(100.0);
    a->set_name(i == 0 ? "move-ship" : "load-cont");
  }
  v.set_makespan_s(origin_s + 200.0);
  planned.engine_state = absl::StrCat("state-of-v", version);
  planned.log_messages = {"computing the temporal plan", "replan and refined done"};
  return planned;
}

absl::StatusOr<PlannedVersion> FakeMissionEngine::PlanInitial(const v1::MissionSpec&,
                                                              const StopToken& stop) {
  ++plan_calls;
  SEAPLAN_RETURN_IF_ERROR(MaybeBlock(stop));
  return MakeVersion(1, 0.0);
}

absl::StatusOr<std::optional<PlannedVersion>> FakeMissionEngine::Replan(
    const v1::MissionSpec&, const MissionRuntimeState& state, std::string_view reason,
    const StopToken& stop) {
  ++plan_calls;
  ++replan_calls;
  SEAPLAN_RETURN_IF_ERROR(MaybeBlock(stop));
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(replan_delay_ms.load());
  while (!stop.StopRequested() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (state.engine_state != absl::StrCat("state-of-v", state.mission.current_version())) {
    return absl::InternalError("engine state of the current version was not handed back");
  }
  PlannedVersion planned = MakeVersion(
      state.mission.current_version() + 1,
      state.recent_feedback.empty() ? 0.0 : state.recent_feedback.back().mission_time_s());
  planned.version.set_reason(std::string(reason));
  return std::optional<PlannedVersion>(std::move(planned));
}

FeedbackDecision FakeMissionEngine::OnFeedback(const v1::MissionSpec&,
                                               const MissionRuntimeState& state,
                                               const v1::Feedback& feedback) {
  FeedbackDecision d;
  if (feedback.kind() == v1::Feedback::KIND_TASK_COMPLETED) {
    std::vector<std::string> done(state.mission.completed_tasks().begin(),
                                  state.mission.completed_tasks().end());
    done.push_back(feedback.task_id());
    d.completed_tasks = done;
    const auto& tasks = state.current_version.tasks();
    if (!tasks.empty() && feedback.task_id() == tasks[tasks.size() - 1].task_id()) {
      d.new_state = v1::MISSION_STATE_COMPLETED;
      d.log_messages.push_back("mission completed");
    }
  } else if (feedback.kind() == v1::Feedback::KIND_TASK_FAILED) {
    d.replan = true;
    d.replan_reason = absl::StrCat("task ", feedback.task_id(), " failed");
    d.log_messages.push_back(
        absl::StrCat("task ", feedback.task_id(), " failed, need re-planning"));
  }
  return d;
}

InProcessServer::InProcessServer(std::shared_ptr<MissionEngine> engine, int planning_threads) {
  auto store = storage::SqliteStore::Open((dir_.path() / "seaplan.db").string());
  EXPECT_TRUE(store.ok()) << store.status();
  store_ = std::move(*store);
  Start(std::move(engine), planning_threads);
}

InProcessServer::InProcessServer(const EngineFactory& make_engine, int planning_threads) {
  auto store = storage::SqliteStore::Open((dir_.path() / "seaplan.db").string());
  EXPECT_TRUE(store.ok()) << store.status();
  store_ = std::move(*store);
  Start(make_engine(*store_), planning_threads);
}

void InProcessServer::Start(std::shared_ptr<MissionEngine> engine, int planning_threads) {
  ServerOptions options;
  options.grpc_address = "127.0.0.1:0";
  options.http_address = "127.0.0.1:0";
  options.worker_threads = 8;
  options.core.planning_threads = planning_threads;
  options.core.missions.watch_poll = std::chrono::milliseconds(20);
  options.shutdown_grace = std::chrono::milliseconds(500);
  auto server = Server::Start(options, *store_, std::move(engine));
  EXPECT_TRUE(server.ok()) << server.status();
  server_ = std::move(*server);
  channel_ = grpc::CreateChannel(grpc_target(), grpc::InsecureChannelCredentials());
}

InProcessServer::~InProcessServer() {
  server_->Shutdown();
  server_.reset();
  EXPECT_TRUE(store_->Close().ok());
}

httplib::Client InProcessServer::http() const {
  httplib::Client client("127.0.0.1", server_->http_port());
  client.set_read_timeout(30, 0);
  return client;
}

v1::MissionSpec SampleSpec(const std::string& name) {
  v1::MissionSpec spec;
  spec.set_name(name);
  spec.set_domain("(define (domain d))");
  spec.set_problem("(define (problem p) (:domain d))");
  spec.set_vessel_id("ship0");
  spec.mutable_initial_state()->set_fuel_fraction(0.3);
  return spec;
}

}  // namespace seaplan::server::testing
