// The in-process backend of seaplan-charts: the server's own
// transport-agnostic core over a private in-memory SQLite store, so
// `seaplan route|risk|chart` without --server runs exactly the code the
// server runs. Missions need a running server (they outlive one command).
#include "backend.h"
#include "in_process.h"
#include "seaplan/storage/sqlite_store.h"
#include "server/core/service_core.h"

namespace seaplan::cli {
namespace {

class LocalBackend final : public InProcessBackend {
 public:
  LocalBackend(std::unique_ptr<storage::SqliteStore> store)
      : store_(std::move(store)), core_(*store_, server::CoreOptions{}, nullptr) {}
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
  absl::Status DeleteChart(const v1::DeleteChartRequest& request,
                           v1::DeleteChartResponse* response) override {
    return Assign(core_.charts().DeleteChart(request, Call()), response);
  }
  absl::Status PlanRoute(const v1::PlanRouteRequest& request,
                         v1::PlanRouteResponse* response) override {
    return Assign(core_.routes().PlanRoute(request, Call()), response);
  }
  absl::Status EstimateRisk(const v1::EstimateRiskRequest& request,
                            v1::EstimateRiskResponse* response) override {
    return Assign(core_.routes().EstimateRisk(request, Call()), response);
  }

 protected:
  // Every call but the missions' is served above.
  absl::Status Refuse(const char* method) const override {
    return absl::InternalError(std::string(method) + " is not served in-process");
  }

 private:
  server::CallContext Call() const {
    return core_.NewCall("local", StopToken::Clock::time_point::max(), &Interrupted);
  }

  std::unique_ptr<storage::SqliteStore> store_;
  server::ServiceCore core_;
};

}  // namespace

std::unique_ptr<Backend> MakeLocalBackend() {
  auto store = storage::SqliteStore::Open(":memory:");
  if (!store.ok()) return std::make_unique<BrokenBackend>(store.status());
  return std::make_unique<LocalBackend>(*std::move(store));
}

}  // namespace seaplan::cli
