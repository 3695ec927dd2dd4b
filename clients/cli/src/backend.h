// The operator CLI talks to seaplan through a Backend: a server over gRPC
// (RemoteBackend, in seaplan-remote), the server's planning handlers linked
// in-process (PlanningBackend, in seaplan: plan and validate), or the
// server's whole transport-agnostic core in-process (LocalBackend, in
// seaplan-charts: charts, route, risk). All speak the seaplan.v1 messages,
// so the CLI's output code is shared.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "absl/status/status.h"
#include "seaplan/v1/access.pb.h"
#include "seaplan/v1/chart.pb.h"
#include "seaplan/v1/mission.pb.h"
#include "seaplan/v1/planning.pb.h"
#include "seaplan/v1/route.pb.h"
#include "tls_channel.h"

namespace seaplan::cli {

namespace v1 = ::seaplan::v1;

class Backend {
 public:
  virtual ~Backend() = default;

  virtual absl::Status Plan(const v1::PlanRequest& request, v1::PlanResponse* response) = 0;
  virtual absl::Status PlanStream(
      const v1::PlanRequest& request,
      const std::function<void(const v1::PlanStreamEvent&)>& on_event) = 0;
  virtual absl::Status Validate(const v1::ValidateRequest& request,
                                v1::ValidateResponse* response) = 0;
  virtual absl::Status UploadChart(const v1::UploadChartRequest& request,
                                   v1::UploadChartResponse* response) = 0;
  virtual absl::Status GetChart(const v1::GetChartRequest& request,
                                v1::GetChartResponse* response) = 0;
  virtual absl::Status ListCharts(const v1::ListChartsRequest& request,
                                  v1::ListChartsResponse* response) = 0;
  virtual absl::Status DeleteChart(const v1::DeleteChartRequest& request,
                                   v1::DeleteChartResponse* response) = 0;
  virtual absl::Status PlanRoute(const v1::PlanRouteRequest& request,
                                 v1::PlanRouteResponse* response) = 0;
  virtual absl::Status EstimateRisk(const v1::EstimateRiskRequest& request,
                                    v1::EstimateRiskResponse* response) = 0;
  virtual absl::Status CreateMission(const v1::CreateMissionRequest& request,
                                     v1::Mission* response) = 0;
  virtual absl::Status GetMission(const v1::GetMissionRequest& request, v1::Mission* response) = 0;
  virtual absl::Status ListMissions(const v1::ListMissionsRequest& request,
                                    v1::ListMissionsResponse* response) = 0;
  // Calls `on_event` for each event; stops when it returns false or the stream ends.
  virtual absl::Status WatchMission(
      const v1::WatchMissionRequest& request,
      const std::function<bool(const v1::MissionEvent&)>& on_event) = 0;
  virtual absl::Status RequestReplan(const v1::RequestReplanRequest& request,
                                     v1::RequestReplanResponse* response) = 0;
  virtual absl::Status CancelMission(const v1::CancelMissionRequest& request,
                                     v1::Mission* response) = 0;
  virtual absl::Status ListFeedback(const v1::ListFeedbackRequest& request,
                                    v1::ListFeedbackResponse* response) = 0;

  // Tokens and the audit log live on a server: in-process backends answer
  // FailedPrecondition.
  virtual absl::Status CreateToken(const v1::CreateTokenRequest&, v1::CreateTokenResponse*) {
    return TokensNeedAServer();
  }
  virtual absl::Status ListTokens(const v1::ListTokensRequest&, v1::ListTokensResponse*) {
    return TokensNeedAServer();
  }
  virtual absl::Status RevokeToken(const v1::RevokeTokenRequest&, v1::RevokeTokenResponse*) {
    return TokensNeedAServer();
  }
  virtual absl::Status ListAuditEvents(const v1::ListAuditEventsRequest&,
                                       v1::ListAuditEventsResponse*) {
    return TokensNeedAServer();
  }

 private:
  static absl::Status TokensNeedAServer() {
    return absl::FailedPreconditionError(
        "tokens and the audit log are a server's: give --server HOST:PORT");
  }
};

// A server at `address` (host:port), presenting `token` (empty: none).
// `timeout_s` <= 0 means no deadline. `tls`: plaintext or TLS to the server
// (clients/common/tls_channel.h).
std::unique_ptr<Backend> MakeRemoteBackend(const std::string& address, double timeout_s,
                                           const std::string& token,
                                           const client::TlsFiles& tls);

// The server core in-process, with charts kept in memory for the call.
std::unique_ptr<Backend> MakeLocalBackend();

// The server's planning handlers in-process: Plan, PlanStream and Validate
// only (mission calls need a server, the rest answer UNIMPLEMENTED).
std::unique_ptr<Backend> MakePlanningBackend();

}  // namespace seaplan::cli
