#include "test_support.h"

#include <unistd.h>

#include "absl/strings/str_cat.h"
#include "seaplan/common/wall_clock.h"
#include "seaplan/storage/open_store.h"
#include "seaplan/testing/grpc_test_token.h"
#include "seaplan/testing/shared_data.h"
#include "server/auth/authenticator.h"
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

Status FakeMissionEngine::CheckSpec(const mission::MissionSpec&, std::vector<pddl::Diagnostic>*) {
  return absl::OkStatus();
}

StatusOr<chart::LocalFrame> FakeMissionEngine::Frame(const mission::MissionSpec&) {
  return chart::LocalFrame();
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

mission::PlannedVersion FakeMissionEngine::MakeVersion(int version, double origin_s) {
  mission::PlannedVersion planned;
  mission::PlanVersion& v = planned.version;
  v.version = version;
  v.mission_time_origin_s = origin_s;
  for (int i = 0; i < 2; ++i) {
    mission::Task t;
    t.id = absl::StrCat("v", version, "-t", i);
    t.kind = i == 0 ? mission::TaskKind::kMove : mission::TaskKind::kLoad;
    t.start_s = origin_s + 100.0 * i;
    t.duration_s = 100.0;
    t.action.start_s = t.start_s;
    t.action.name = i == 0 ? "move-ship" : "load-cont";
    t.action.duration_s = t.duration_s;
    v.plan.steps.push_back(t.action);
    v.tasks.push_back(std::move(t));
  }
  v.makespan_s = origin_s + 200.0;
  planned.engine_state = absl::StrCat("state-of-v", version);
  planned.log_messages = {"computing the temporal plan", "replan and refined done"};
  return planned;
}

StatusOr<mission::PlannedVersion> FakeMissionEngine::PlanInitial(const mission::MissionSpec&,
                                                                 const StopToken& stop) {
  ++plan_calls;
  SEAPLAN_RETURN_IF_ERROR(MaybeBlock(stop));
  return MakeVersion(1, 0.0);
}

StatusOr<std::optional<mission::PlannedVersion>> FakeMissionEngine::Replan(
    const mission::MissionSpec&, const mission::MissionRuntime& runtime, std::string_view reason,
    const StopToken& stop) {
  ++plan_calls;
  ++replan_calls;
  const int running = ++replans_running;
  int most = most_replans_at_once.load();
  while (running > most && !most_replans_at_once.compare_exchange_weak(most, running)) {
  }
  struct Leave {
    std::atomic<int>& n;
    ~Leave() { --n; }
  } leave{replans_running};
  SEAPLAN_RETURN_IF_ERROR(MaybeBlock(stop));
  const auto until =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(replan_delay_ms.load());
  while (!stop.StopRequested() && std::chrono::steady_clock::now() < until) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  if (runtime.engine_state != absl::StrCat("state-of-v", runtime.current.version)) {
    return absl::InternalError("engine state of the current version was not handed back");
  }
  mission::PlannedVersion planned = MakeVersion(
      runtime.current.version + 1,
      runtime.recent_feedback.empty() ? 0.0 : runtime.recent_feedback.back().mission_time_s);
  planned.version.reason = std::string(reason);
  return std::optional<mission::PlannedVersion>(std::move(planned));
}

mission::FeedbackOutcome FakeMissionEngine::OnFeedback(const mission::MissionSpec&,
                                                       const mission::MissionRuntime& runtime,
                                                       const mission::Feedback& feedback) {
  mission::FeedbackOutcome d;
  d.completed_task_ids = runtime.completed_task_ids;
  if (feedback.kind == mission::FeedbackKind::kTaskCompleted) {
    d.completed_task_ids.push_back(feedback.task_id);
    d.completed_changed = true;
    const auto& tasks = runtime.current.tasks;
    if (!tasks.empty() && feedback.task_id == tasks.back().id) {
      d.mission_completed = true;
      d.log_messages.push_back("mission completed");
    }
  } else if (feedback.kind == mission::FeedbackKind::kTaskFailed) {
    d.replan_reason = absl::StrCat("task ", feedback.task_id, " failed");
    d.log_messages.push_back(absl::StrCat("task ", feedback.task_id, " failed, need re-planning"));
  }
  return d;
}

InProcessServer::InProcessServer(std::shared_ptr<mission::MissionEngine> engine,
                                 int planning_threads, AdminTokenUse admin_token)
    : default_admin_token_(admin_token == AdminTokenUse::kPresentByDefault) {
  OpenStore();
  Start(std::move(engine), planning_threads, {});
}

InProcessServer::InProcessServer(std::shared_ptr<mission::MissionEngine> engine,
                                 int planning_threads,
                                 const std::function<void(ServerOptions&)>& configure) {
  OpenStore();
  Start(std::move(engine), planning_threads, configure);
}

InProcessServer::InProcessServer(const std::string& database_url,
                                 std::shared_ptr<mission::MissionEngine> engine) {
  OpenStore(database_url);
  Start(std::move(engine), 2, {});
}

void InProcessServer::OpenStore(const std::string& database_url) {
  if (database_url.empty()) {
    auto store = storage::SqliteStore::Open((dir_.path() / "seaplan.db").string());
    EXPECT_TRUE(store.ok()) << store.status();
    sqlite_ = store->get();
    store_ = std::move(*store);
  } else {
    auto opened = storage::OpenStore(database_url, dir_.path().string());
    EXPECT_TRUE(opened.ok()) << opened.status();
    store_ = std::move(opened->store);
  }
  const absl::Status imported = auth::Authenticator(store_->tokens())
                                    .ImportAdmin(seaplan::testing::TestAdminToken(), "tests");
  EXPECT_TRUE(imported.ok()) << imported;
  if (default_admin_token_) seaplan::testing::UseTestAdminTokenByDefault();
}

void InProcessServer::Start(std::shared_ptr<mission::MissionEngine> engine, int planning_threads,
                            const std::function<void(ServerOptions&)>& configure) {
  ServerOptions options;
  options.grpc_address = "127.0.0.1:0";
  options.http_address = "127.0.0.1:0";
  options.worker_threads = 8;
  options.core.planning_threads = planning_threads;
  options.core.missions.watch_poll = std::chrono::milliseconds(20);
  options.shutdown_grace = std::chrono::milliseconds(500);
  if (configure) {
    configure(options);
  }
  auto server = Server::Start(options, *store_, std::move(engine));
  start_status_ = server.status();
  if (!configure) {
    EXPECT_TRUE(server.ok()) << server.status();
  }
  if (!server.ok()) return;
  server_ = std::move(*server);
  channel_ = grpc::CreateChannel(grpc_target(), grpc::InsecureChannelCredentials());
}

InProcessServer::~InProcessServer() {
  if (server_) server_->Shutdown();
  server_.reset();
  EXPECT_TRUE(store_->Close().ok());
}

httplib::Client InProcessServer::http() const {
  httplib::Client client("127.0.0.1", server_->http_port());
  // Stretched in slower builds (a sanitizer's): the same calls take longer.
  client.set_read_timeout(ScaledWallClock(std::chrono::milliseconds(30'000)));
  if (default_admin_token_) {
    client.set_default_headers({{"Authorization", seaplan::testing::TestAdminAuthorization()}});
  }
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

v1::UploadChartRequest HarbourChartUpload(std::size_t padding) {
  v1::UploadChartRequest upload;
  upload.set_name("harbour");
  upload.set_format(v1::CHART_FORMAT_GEOJSON);
  upload.set_minimum_depth_m(5);
  v1::ChartFile* file = upload.add_files();
  file->set_name("harbour.geojson");
  std::string content = seaplan::testing::ReadFile(seaplan::testing::SourceDir() /
                                                   "engine/chart/testdata/harbour.geojson");
  EXPECT_FALSE(content.empty()) << "engine/chart/testdata/harbour.geojson is missing";
  content.append(padding, ' ');
  file->set_content(std::move(content));
  return upload;
}

v1::LatLon LatLon(double latitude_deg, double longitude_deg) {
  v1::LatLon p;
  p.set_latitude_deg(latitude_deg);
  p.set_longitude_deg(longitude_deg);
  return p;
}

}  // namespace seaplan::server::testing
