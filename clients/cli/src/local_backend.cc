// The in-process backend: the server's own transport-agnostic core over a
// private in-memory SQLite store, so `seaplan plan|validate|route|risk`
// without --server runs exactly the code the server runs. Missions need a
// running server (they outlive one command) and answer FAILED_PRECONDITION.
#include <csignal>

#include "backend.h"
#include "seaplan/storage/sqlite_store.h"
#include "server/core/service_core.h"

namespace seaplan::cli {
namespace {

absl::Status NeedsServer(const char* what) {
  return absl::FailedPreconditionError(std::string(what) +
                                       " needs a running server: give --server HOST:PORT");
}

// Ctrl-C cancels the in-process call (as a client going away does remotely).
std::atomic<bool> g_interrupted{false};
void OnInterrupt(int) {
  g_interrupted.store(true);
}

class LocalBackend final : public Backend {
 public:
  LocalBackend(std::unique_ptr<storage::SqliteStore> store)
      : store_(std::move(store)), core_(*store_, server::CoreOptions{}, nullptr) {
    std::signal(SIGINT, OnInterrupt);
  }
  ~LocalBackend() override { core_.Stop(); }

  absl::Status Plan(const v1::PlanRequest& request, v1::PlanResponse* response) override {
    return Assign(core_.planning().Plan(request, Call()), response);
  }
  absl::Status PlanStream(
      const v1::PlanRequest& request,
      const std::function<void(const v1::PlanStreamEvent&)>& on_event) override {
    return core_.planning().PlanStream(request, Call(), [&](const v1::PlanStreamEvent& event) {
      on_event(event);
      return true;
    });
  }
  absl::Status Validate(const v1::ValidateRequest& request,
                        v1::ValidateResponse* response) override {
    return Assign(core_.planning().Validate(request, Call()), response);
  }
  absl::Status UploadChart(const v1::UploadChartRequest& request,
                           v1::UploadChartResponse* response) override {
    return Assign(core_.charts().UploadChart(request, Call()), response);
  }
  absl::Status GetChart(const v1::GetChartRequest& request,
                        v1::GetChartResponse* response) override {
    return Assign(core_.charts().GetChart(request, Call()), response);
  }
  absl::Status ListCharts(const v1::ListChartsRequest& request,
                          v1::ListChartsResponse* response) override {
    return Assign(core_.charts().ListCharts(request, Call()), response);
  }
  absl::Status PlanRoute(const v1::PlanRouteRequest& request,
                         v1::PlanRouteResponse* response) override {
    return Assign(core_.routes().PlanRoute(request, Call()), response);
  }
  absl::Status EstimateRisk(const v1::EstimateRiskRequest& request,
                            v1::EstimateRiskResponse* response) override {
    return Assign(core_.routes().EstimateRisk(request, Call()), response);
  }
  absl::Status CreateMission(const v1::CreateMissionRequest&, v1::Mission*) override {
    return NeedsServer("mission create");
  }
  absl::Status GetMission(const v1::GetMissionRequest&, v1::Mission*) override {
    return NeedsServer("mission get");
  }
  absl::Status ListMissions(const v1::ListMissionsRequest&, v1::ListMissionsResponse*) override {
    return NeedsServer("mission list");
  }
  absl::Status WatchMission(const v1::WatchMissionRequest&,
                            const std::function<bool(const v1::MissionEvent&)>&) override {
    return NeedsServer("mission watch");
  }
  absl::Status RequestReplan(const v1::RequestReplanRequest&, v1::RequestReplanResponse*) override {
    return NeedsServer("mission replan");
  }
  absl::Status CancelMission(const v1::CancelMissionRequest&, v1::Mission*) override {
    return NeedsServer("mission cancel");
  }

 private:
  server::CallContext Call() const {
    return core_.NewCall("local", StopToken::Clock::time_point::max(),
                         [] { return g_interrupted.load(); });
  }

  template <typename T>
  static absl::Status Assign(absl::StatusOr<T> result, T* response) {
    if (!result.ok()) return result.status();
    *response = *std::move(result);
    return absl::OkStatus();
  }

  std::unique_ptr<storage::SqliteStore> store_;
  server::ServiceCore core_;
};

// Used when the in-memory store cannot be opened (should not happen): every
// call reports why instead of crashing.
class BrokenBackend final : public Backend {
 public:
  explicit BrokenBackend(absl::Status status) : status_(std::move(status)) {}
  absl::Status Plan(const v1::PlanRequest&, v1::PlanResponse*) override { return status_; }
  absl::Status PlanStream(const v1::PlanRequest&,
                          const std::function<void(const v1::PlanStreamEvent&)>&) override {
    return status_;
  }
  absl::Status Validate(const v1::ValidateRequest&, v1::ValidateResponse*) override {
    return status_;
  }
  absl::Status UploadChart(const v1::UploadChartRequest&, v1::UploadChartResponse*) override {
    return status_;
  }
  absl::Status GetChart(const v1::GetChartRequest&, v1::GetChartResponse*) override {
    return status_;
  }
  absl::Status ListCharts(const v1::ListChartsRequest&, v1::ListChartsResponse*) override {
    return status_;
  }
  absl::Status PlanRoute(const v1::PlanRouteRequest&, v1::PlanRouteResponse*) override {
    return status_;
  }
  absl::Status EstimateRisk(const v1::EstimateRiskRequest&, v1::EstimateRiskResponse*) override {
    return status_;
  }
  absl::Status CreateMission(const v1::CreateMissionRequest&, v1::Mission*) override {
    return status_;
  }
  absl::Status GetMission(const v1::GetMissionRequest&, v1::Mission*) override { return status_; }
  absl::Status ListMissions(const v1::ListMissionsRequest&, v1::ListMissionsResponse*) override {
    return status_;
  }
  absl::Status WatchMission(const v1::WatchMissionRequest&,
                            const std::function<bool(const v1::MissionEvent&)>&) override {
    return status_;
  }
  absl::Status RequestReplan(const v1::RequestReplanRequest&, v1::RequestReplanResponse*) override {
    return status_;
  }
  absl::Status CancelMission(const v1::CancelMissionRequest&, v1::Mission*) override {
    return status_;
  }

 private:
  absl::Status status_;
};

}  // namespace

std::unique_ptr<Backend> MakeLocalBackend() {
  auto store = storage::SqliteStore::Open(":memory:");
  if (!store.ok()) return std::make_unique<BrokenBackend>(store.status());
  return std::make_unique<LocalBackend>(*std::move(store));
}

}  // namespace seaplan::cli
