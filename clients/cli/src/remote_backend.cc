#include <chrono>
#include <cstdlib>
#include <iostream>

#include "absl/strings/cord.h"
#include "backend.h"
#include "grpcpp/grpcpp.h"
#include "output.h"
#include "seaplan/v1/access.grpc.pb.h"
#include "seaplan/v1/chart.grpc.pb.h"
#include "seaplan/v1/mission.grpc.pb.h"
#include "seaplan/v1/planning.grpc.pb.h"
#include "seaplan/v1/route.grpc.pb.h"
#include "token_channel.h"

namespace seaplan::cli {
namespace {

absl::Status FromGrpc(const grpc::Status& status) {
  if (status.ok()) return absl::OkStatus();
  // gRPC and absl share the canonical code numbering.
  absl::Status result(static_cast<absl::StatusCode>(status.error_code()), status.error_message());
  // The server puts a serialized DiagnosticList into error_details.
  if (!status.error_details().empty()) {
    result.SetPayload(kDiagnosticsPayloadUrl, absl::Cord(status.error_details()));
  }
  return result;
}

class RemoteBackend final : public Backend {
 public:
  RemoteBackend(const std::string& address, double timeout_s,
                const std::shared_ptr<grpc::ChannelCredentials>& credentials,
                const std::string& token)
      : channel_(
            client::CreateChannelWithToken(address, credentials, grpc::ChannelArguments(), token)),
        planning_(v1::PlanningService::NewStub(channel_)),
        charts_(v1::ChartService::NewStub(channel_)),
        routes_(v1::RouteService::NewStub(channel_)),
        missions_(v1::MissionService::NewStub(channel_)),
        access_(v1::AccessService::NewStub(channel_)),
        timeout_s_(timeout_s) {}

  absl::Status Plan(const v1::PlanRequest& request, v1::PlanResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(planning_->Plan(context.get(), request, response));
  }
  absl::Status PlanStream(
      const v1::PlanRequest& request,
      const std::function<void(const v1::PlanStreamEvent&)>& on_event) override {
    auto context = MakeContext();
    auto reader = planning_->PlanStream(context.get(), request);
    v1::PlanStreamEvent event;
    while (reader->Read(&event)) on_event(event);
    return FromGrpc(reader->Finish());
  }
  absl::Status Validate(const v1::ValidateRequest& request,
                        v1::ValidateResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(planning_->Validate(context.get(), request, response));
  }
  absl::Status UploadChart(const v1::UploadChartRequest& request,
                           v1::UploadChartResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(charts_->UploadChart(context.get(), request, response));
  }
  absl::Status GetChart(const v1::GetChartRequest& request,
                        v1::GetChartResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(charts_->GetChart(context.get(), request, response));
  }
  absl::Status ListCharts(const v1::ListChartsRequest& request,
                          v1::ListChartsResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(charts_->ListCharts(context.get(), request, response));
  }
  absl::Status DeleteChart(const v1::DeleteChartRequest& request,
                           v1::DeleteChartResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(charts_->DeleteChart(context.get(), request, response));
  }
  absl::Status PlanRoute(const v1::PlanRouteRequest& request,
                         v1::PlanRouteResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(routes_->PlanRoute(context.get(), request, response));
  }
  absl::Status EstimateRisk(const v1::EstimateRiskRequest& request,
                            v1::EstimateRiskResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(routes_->EstimateRisk(context.get(), request, response));
  }
  absl::Status CreateMission(const v1::CreateMissionRequest& request,
                             v1::Mission* response) override {
    auto context = MakeContext();
    return FromGrpc(missions_->CreateMission(context.get(), request, response));
  }
  absl::Status GetMission(const v1::GetMissionRequest& request, v1::Mission* response) override {
    auto context = MakeContext();
    return FromGrpc(missions_->GetMission(context.get(), request, response));
  }
  absl::Status ListMissions(const v1::ListMissionsRequest& request,
                            v1::ListMissionsResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(missions_->ListMissions(context.get(), request, response));
  }
  absl::Status WatchMission(const v1::WatchMissionRequest& request,
                            const std::function<bool(const v1::MissionEvent&)>& on_event) override {
    grpc::ClientContext context;  // a watch has no deadline: it follows the mission
    auto reader = missions_->WatchMission(&context, request);
    v1::MissionEvent event;
    while (reader->Read(&event)) {
      if (!on_event(event)) {
        context.TryCancel();
        reader->Finish();
        return absl::OkStatus();
      }
    }
    return FromGrpc(reader->Finish());
  }
  absl::Status RequestReplan(const v1::RequestReplanRequest& request,
                             v1::RequestReplanResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(missions_->RequestReplan(context.get(), request, response));
  }
  absl::Status CancelMission(const v1::CancelMissionRequest& request,
                             v1::Mission* response) override {
    auto context = MakeContext();
    return FromGrpc(missions_->CancelMission(context.get(), request, response));
  }
  absl::Status ListFeedback(const v1::ListFeedbackRequest& request,
                            v1::ListFeedbackResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(missions_->ListFeedback(context.get(), request, response));
  }
  absl::Status CreateToken(const v1::CreateTokenRequest& request,
                           v1::CreateTokenResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(access_->CreateToken(context.get(), request, response));
  }
  absl::Status ListTokens(const v1::ListTokensRequest& request,
                          v1::ListTokensResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(access_->ListTokens(context.get(), request, response));
  }
  absl::Status RevokeToken(const v1::RevokeTokenRequest& request,
                           v1::RevokeTokenResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(access_->RevokeToken(context.get(), request, response));
  }
  absl::Status ListAuditEvents(const v1::ListAuditEventsRequest& request,
                               v1::ListAuditEventsResponse* response) override {
    auto context = MakeContext();
    return FromGrpc(access_->ListAuditEvents(context.get(), request, response));
  }

 private:
  std::unique_ptr<grpc::ClientContext> MakeContext() const {
    auto context = std::make_unique<grpc::ClientContext>();
    if (timeout_s_ > 0) {
      context->set_deadline(std::chrono::system_clock::now() +
                            std::chrono::milliseconds(static_cast<long long>(timeout_s_ * 1000)));
    }
    return context;
  }

  std::shared_ptr<grpc::Channel> channel_;
  std::unique_ptr<v1::PlanningService::Stub> planning_;
  std::unique_ptr<v1::ChartService::Stub> charts_;
  std::unique_ptr<v1::RouteService::Stub> routes_;
  std::unique_ptr<v1::MissionService::Stub> missions_;
  std::unique_ptr<v1::AccessService::Stub> access_;
  double timeout_s_;
};

}  // namespace

std::unique_ptr<Backend> MakeRemoteBackend(const std::string& address, double timeout_s,
                                           const std::string& token,
                                           const client::TlsFiles& tls) {
  auto credentials = client::ChannelCredentials(tls);
  if (!credentials.ok()) {
    // RunCli checked the files before any command ran: only a file changed
    // in between gets here.
    std::cerr << "error: " << credentials.status().message() << "\n";
    std::exit(kExitBadInput);
  }
  return std::make_unique<RemoteBackend>(address, timeout_s, *credentials, token);
}

}  // namespace seaplan::cli
