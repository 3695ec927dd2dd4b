// Helpers of the server end-to-end tests: a temporary data folder, a server
// started in-process on ephemeral loopback ports, gRPC stubs, an HTTP client
// and a fake mission engine whose timing the tests control.
#pragma once

// The mission engine before httplib: httplib includes <resolv.h>, whose
// `_res` macro breaks Eigen (reached through the route planner), which names
// parameters `_res`.
// clang-format off
#include "seaplan/mission/mission_engine.h"
// clang-format on

#include <grpcpp/grpcpp.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <thread>

#include "seaplan/storage/sqlite_store.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"
#include "seaplan/v1/planning.grpc.pb.h"
#include "seaplan/v1/route.grpc.pb.h"
#include "server/server.h"

namespace seaplan::server::testing {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// A mission engine for tests. Version N has tasks "vN-t0" (a move) and
// "vN-t1" (a load). TASK_COMPLETED of the last task of the current version
// completes the mission; TASK_FAILED asks for a replan.
class FakeMissionEngine final : public mission::MissionEngine {
 public:
  // When set, PlanInitial and Replan wait until their StopToken stops (at
  // most 20 s) and report what stopped them.
  std::atomic<bool> block_until_stopped{false};
  std::atomic<int> last_stop_reason{static_cast<int>(StopReason::kNone)};
  std::atomic<int> plan_calls{0};
  std::atomic<bool> stopped_work_finished{false};
  // Replan takes at least this long (stops early with its StopToken).
  std::atomic<int> replan_delay_ms{0};
  std::atomic<int> replan_calls{0};
  // Replans running now, and the most at once.
  std::atomic<int> replans_running{0};
  std::atomic<int> most_replans_at_once{0};

  Status CheckSpec(const mission::MissionSpec& spec,
                   std::vector<pddl::Diagnostic>* diagnostics) override;
  StatusOr<chart::LocalFrame> Frame(const mission::MissionSpec& spec) override;
  StatusOr<mission::PlannedVersion> PlanInitial(const mission::MissionSpec& spec,
                                                const StopToken& stop) override;
  StatusOr<std::optional<mission::PlannedVersion>> Replan(const mission::MissionSpec& spec,
                                                          const mission::MissionRuntime& runtime,
                                                          std::string_view reason,
                                                          const StopToken& stop) override;
  mission::FeedbackOutcome OnFeedback(const mission::MissionSpec& spec,
                                      const mission::MissionRuntime& runtime,
                                      const mission::Feedback& feedback) override;

 private:
  absl::Status MaybeBlock(const StopToken& stop);
  static mission::PlannedVersion MakeVersion(int version, double origin_s);
};

// The server in-process on 127.0.0.1:0 (both transports), over a fresh
// database in a temporary folder. The database holds the fixtures' admin
// token (seaplan/testing/test_token.h); with `default_admin_token`, every
// gRPC call of this process without its own `authorization` metadata and
// every request of http() present it, so tests need not handle tokens.
class InProcessServer {
 public:
  // Whether this process's calls present the fixtures' admin token when
  // they carry no credential of their own.
  enum class AdminTokenUse { kPresentByDefault, kNone };
  // Without `engine`, the server's own (engine/mission over its store's charts).
  explicit InProcessServer(std::shared_ptr<mission::MissionEngine> engine = nullptr,
                           int planning_threads = 2,
                           AdminTokenUse admin_token = AdminTokenUse::kPresentByDefault);
  // `configure` changes the test's options (TLS, limits) before the start;
  // Start's status is in start_status() (the server is null when it failed).
  InProcessServer(std::shared_ptr<mission::MissionEngine> engine, int planning_threads,
                  const std::function<void(ServerOptions&)>& configure);
  // Over the PostgreSQL database at `database_url` (a fresh one) instead.
  InProcessServer(const std::string& database_url, std::shared_ptr<mission::MissionEngine> engine);
  ~InProcessServer();

  Server& server() { return *server_; }
  storage::Store& store() { return *store_; }
  // The SQLite store (not with a `database_url`).
  storage::SqliteStore& sqlite_store() { return *sqlite_; }
  std::string grpc_target() const { return "127.0.0.1:" + std::to_string(server_->grpc_port()); }
  int http_port() const { return server_->http_port(); }
  std::shared_ptr<grpc::Channel> channel() { return channel_; }
  // With the admin token's Authorization header when `default_admin_token`.
  httplib::Client http() const;
  const absl::Status& start_status() const { return start_status_; }

 private:
  // Opens the database (empty url: SQLite in the temporary folder) and
  // imports the fixtures' admin token.
  void OpenStore(const std::string& database_url = "");
  void Start(std::shared_ptr<mission::MissionEngine> engine, int planning_threads,
             const std::function<void(ServerOptions&)>& configure);

  TempDir dir_;
  std::unique_ptr<storage::Store> store_;
  storage::SqliteStore* sqlite_ = nullptr;  // store_ on SQLite
  std::unique_ptr<Server> server_;
  std::shared_ptr<grpc::Channel> channel_;
  bool default_admin_token_ = true;
  absl::Status start_status_;
};

// A minimal valid mission spec (the fake engine does not read the PDDL).
v1::MissionSpec SampleSpec(const std::string& name = "case-a");

// An upload of engine/chart's harbour test chart (GeoJSON, minimum depth
// 5 m) followed by `padding` spaces, which keep the GeoJSON valid at any size.
v1::UploadChartRequest HarbourChartUpload(std::size_t padding = 0);

// A position in WGS84 degrees.
v1::LatLon LatLon(double latitude_deg, double longitude_deg);

// Runs `fn` with a deadline of `ms` on `ctx`.
inline void SetDeadline(grpc::ClientContext* ctx, int ms) {
  ctx->set_deadline(std::chrono::system_clock::now() + std::chrono::milliseconds(ms));
}

}  // namespace seaplan::server::testing
