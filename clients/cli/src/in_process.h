// What the in-process backends share: a Backend that answers every call it
// does not serve with Refuse(method), and mission calls with
// FAILED_PRECONDITION (a mission outlives one command: it needs a server);
// Ctrl-C cancelling the running call, as a client going away does remotely.
#pragma once

#include <string>

#include "absl/status/statusor.h"
#include "backend.h"
#include "seaplan/common/stop_token.h"
#include "server/core/call_context.h"

namespace seaplan::cli {

class InProcessBackend : public Backend {
 public:
  // Installs the SIGINT handler that cancels calls made through NewCall().
  InProcessBackend();

  absl::Status Plan(const v1::PlanRequest&, v1::PlanResponse*) override;
  absl::Status PlanStream(const v1::PlanRequest&,
                          const std::function<void(const v1::PlanStreamEvent&)>&) override;
  absl::Status Validate(const v1::ValidateRequest&, v1::ValidateResponse*) override;
  absl::Status UploadChart(const v1::UploadChartRequest&, v1::UploadChartResponse*) override;
  absl::Status GetChart(const v1::GetChartRequest&, v1::GetChartResponse*) override;
  absl::Status ListCharts(const v1::ListChartsRequest&, v1::ListChartsResponse*) override;
  absl::Status DeleteChart(const v1::DeleteChartRequest&, v1::DeleteChartResponse*) override;
  absl::Status PlanRoute(const v1::PlanRouteRequest&, v1::PlanRouteResponse*) override;
  absl::Status EstimateRisk(const v1::EstimateRiskRequest&, v1::EstimateRiskResponse*) override;
  absl::Status CreateMission(const v1::CreateMissionRequest&, v1::Mission*) override;
  absl::Status GetMission(const v1::GetMissionRequest&, v1::Mission*) override;
  absl::Status ListMissions(const v1::ListMissionsRequest&, v1::ListMissionsResponse*) override;
  absl::Status WatchMission(const v1::WatchMissionRequest&,
                            const std::function<bool(const v1::MissionEvent&)>&) override;
  absl::Status RequestReplan(const v1::RequestReplanRequest&, v1::RequestReplanResponse*) override;
  absl::Status CancelMission(const v1::CancelMissionRequest&, v1::Mission*) override;
  absl::Status ListFeedback(const v1::ListFeedbackRequest&, v1::ListFeedbackResponse*) override;

 protected:
  // The answer to `method` ("chart upload", ...) when this backend does not serve it.
  virtual absl::Status Refuse(const char* method) const = 0;

  // A call under `root` with no deadline, cancelled by Ctrl-C.
  static server::CallContext NewCall(const StopToken& root);
  // True once Ctrl-C was pressed.
  static bool Interrupted();

  template <typename T>
  static absl::Status Assign(absl::StatusOr<T> result, T* response) {
    if (!result.ok()) return result.status();
    *response = *std::move(result);
    return absl::OkStatus();
  }
};

// Answers every call with `status` (used when a backend cannot be built).
class BrokenBackend final : public InProcessBackend {
 public:
  explicit BrokenBackend(absl::Status status) : status_(std::move(status)) {}

 protected:
  absl::Status Refuse(const char*) const override { return status_; }

 private:
  absl::Status status_;
};

}  // namespace seaplan::cli
