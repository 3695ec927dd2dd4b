#include "in_process.h"

#include <atomic>
#include <csignal>

namespace seaplan::cli {
namespace {

std::atomic<bool> g_interrupted{false};
void OnInterrupt(int) {
  g_interrupted.store(true);
}

absl::Status NeedsServer(const char* what) {
  return absl::FailedPreconditionError(std::string(what) +
                                       " needs a running server: give --server HOST:PORT");
}

}  // namespace

InProcessBackend::InProcessBackend() {
  std::signal(SIGINT, OnInterrupt);
}

bool InProcessBackend::Interrupted() {
  return g_interrupted.load();
}

server::CallContext InProcessBackend::NewCall(const StopToken& root) {
  return server::CallContext{"local", root.Child(StopToken::Clock::time_point::max()),
                             &InProcessBackend::Interrupted};
}

absl::Status InProcessBackend::Plan(const v1::PlanRequest&, v1::PlanResponse*) {
  return Refuse("plan");
}
absl::Status InProcessBackend::PlanStream(const v1::PlanRequest&,
                                          const std::function<void(const v1::PlanStreamEvent&)>&) {
  return Refuse("plan");
}
absl::Status InProcessBackend::Validate(const v1::ValidateRequest&, v1::ValidateResponse*) {
  return Refuse("validate");
}
absl::Status InProcessBackend::UploadChart(const v1::UploadChartRequest&,
                                           v1::UploadChartResponse*) {
  return Refuse("chart upload");
}
absl::Status InProcessBackend::GetChart(const v1::GetChartRequest&, v1::GetChartResponse*) {
  return Refuse("chart get");
}
absl::Status InProcessBackend::ListCharts(const v1::ListChartsRequest&, v1::ListChartsResponse*) {
  return Refuse("chart list");
}
absl::Status InProcessBackend::DeleteChart(const v1::DeleteChartRequest&,
                                           v1::DeleteChartResponse*) {
  return Refuse("chart delete");
}
absl::Status InProcessBackend::PlanRoute(const v1::PlanRouteRequest&, v1::PlanRouteResponse*) {
  return Refuse("route");
}
absl::Status InProcessBackend::EstimateRisk(const v1::EstimateRiskRequest&,
                                            v1::EstimateRiskResponse*) {
  return Refuse("risk");
}
absl::Status InProcessBackend::CreateMission(const v1::CreateMissionRequest&, v1::Mission*) {
  return NeedsServer("mission create");
}
absl::Status InProcessBackend::GetMission(const v1::GetMissionRequest&, v1::Mission*) {
  return NeedsServer("mission get");
}
absl::Status InProcessBackend::ListMissions(const v1::ListMissionsRequest&,
                                            v1::ListMissionsResponse*) {
  return NeedsServer("mission list");
}
absl::Status InProcessBackend::WatchMission(const v1::WatchMissionRequest&,
                                            const std::function<bool(const v1::MissionEvent&)>&) {
  return NeedsServer("mission watch");
}
absl::Status InProcessBackend::RequestReplan(const v1::RequestReplanRequest&,
                                             v1::RequestReplanResponse*) {
  return NeedsServer("mission replan");
}
absl::Status InProcessBackend::CancelMission(const v1::CancelMissionRequest&, v1::Mission*) {
  return NeedsServer("mission cancel");
}
absl::Status InProcessBackend::ListFeedback(const v1::ListFeedbackRequest&,
                                            v1::ListFeedbackResponse*) {
  return NeedsServer("mission feedback");
}

}  // namespace seaplan::cli
