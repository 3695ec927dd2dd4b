#include "server/grpc/services.h"

#include <grpcpp/security/auth_context.h>

#include <string>
#include <string_view>

#include "server/core/caller_limits.h"
#include "server/core/status_details.h"
#include "server/grpc/status_mapping.h"

namespace seaplan::server {
namespace {

// The client's deadline on the steady clock (max() when there is none).
StopToken::Clock::time_point Deadline(const grpc::ServerContext* ctx) {
  const auto deadline = ctx->deadline();
  const auto now = std::chrono::system_clock::now();
  // No deadline is "infinite future"; treat anything beyond a year as none.
  if (deadline - now > std::chrono::hours(24 * 365)) return StopToken::Clock::time_point::max();
  return StopToken::Clock::now() +
         std::chrono::duration_cast<StopToken::Clock::duration>(deadline - now);
}

// The call's context with its caller, or the status that ends the call
// before any handler runs: over the caller's rate limit, or no, bad or
// insufficient credentials. The credential is the `authorization`
// metadata, "Bearer <token>"; the rate limit is counted before the token is
// looked up, so guessing tokens is limited too.
absl::StatusOr<CallContext> MakeCall(ServiceCore& core, const char* method,
                                     grpc::ServerContext* ctx) {
  CallContext call = core.NewCall("grpc", Deadline(ctx), [ctx] { return ctx->IsCancelled(); });
  call.method = method;
  std::string authorization;
  const auto& metadata = ctx->client_metadata();
  if (auto it = metadata.find("authorization"); it != metadata.end()) {
    authorization.assign(it->second.data(), it->second.size());
  }
  call.caller_key = CallerKey(authorization, ctx->peer());
  // Set only for a certificate the server verified against its client CA.
  if (auto auth = ctx->auth_context(); auth && auth->IsPeerAuthenticated()) {
    for (const auto& cn : auth->FindPropertyValues(GRPC_X509_CN_PROPERTY_NAME)) {
      call.client_cert_subject.assign(cn.data(), cn.size());
      break;
    }
  }
  SEAPLAN_RETURN_IF_ERROR(core.Admit(call));
  SEAPLAN_ASSIGN_OR_RETURN(call.caller, core.Authorize(method, authorization));
  return call;
}

// The status to return; a refusal says when to retry (trailing metadata).
grpc::Status Finish(grpc::ServerContext* ctx, const absl::Status& status) {
  if (auto retry_after = GetRetryAfter(status))
    ctx->AddTrailingMetadata("retry-after-ms", std::to_string(retry_after->count()));
  return ToGrpcStatus(status);
}

template <typename Response, typename Fn>
grpc::Status Unary(ServiceCore& core, const char* method, grpc::ServerContext* ctx, Response* out,
                   Fn&& fn) {
  const auto started = StopToken::Clock::now();
  absl::StatusOr<CallContext> call = MakeCall(core, method, ctx);
  absl::Status status = call.status();
  if (call.ok()) {
    absl::StatusOr<Response> result = fn(*call);
    status = result.status();
    if (result.ok()) *out = std::move(*result);
  }
  LogCall("grpc", method, status, started);
  return Finish(ctx, status);
}

template <typename Event, typename Fn>
grpc::Status Stream(ServiceCore& core, const char* method, grpc::ServerContext* ctx,
                    grpc::ServerWriter<Event>* writer, Fn&& fn) {
  const auto started = StopToken::Clock::now();
  absl::StatusOr<CallContext> call = MakeCall(core, method, ctx);
  absl::Status status = call.status();
  if (call.ok()) {
    StreamSink<Event> sink = [writer](const Event& event) { return writer->Write(event); };
    status = fn(*call, sink);
  }
  LogCall("grpc", method, status, started);
  return Finish(ctx, status);
}

}  // namespace

class GrpcServices::Planning final : public v1::PlanningService::Service {
 public:
  explicit Planning(ServiceCore& core) : core_(core) {}
  grpc::Status Plan(grpc::ServerContext* ctx, const v1::PlanRequest* req,
                    v1::PlanResponse* resp) override {
    return Unary(core_, "PlanningService/Plan", ctx, resp,
                 [&](const CallContext& c) { return core_.planning().Plan(*req, c); });
  }
  grpc::Status PlanStream(grpc::ServerContext* ctx, const v1::PlanRequest* req,
                          grpc::ServerWriter<v1::PlanStreamEvent>* writer) override {
    return Stream(core_, "PlanningService/PlanStream", ctx, writer,
                  [&](const CallContext& c, const StreamSink<v1::PlanStreamEvent>& sink) {
                    return core_.planning().PlanStream(*req, c, sink);
                  });
  }
  grpc::Status Validate(grpc::ServerContext* ctx, const v1::ValidateRequest* req,
                        v1::ValidateResponse* resp) override {
    return Unary(core_, "PlanningService/Validate", ctx, resp,
                 [&](const CallContext& c) { return core_.planning().Validate(*req, c); });
  }

 private:
  ServiceCore& core_;
};

class GrpcServices::Charts final : public v1::ChartService::Service {
 public:
  explicit Charts(ServiceCore& core) : core_(core) {}
  grpc::Status UploadChart(grpc::ServerContext* ctx, const v1::UploadChartRequest* req,
                           v1::UploadChartResponse* resp) override {
    return Unary(core_, "ChartService/UploadChart", ctx, resp,
                 [&](const CallContext& c) { return core_.charts().UploadChart(*req, c); });
  }
  grpc::Status GetChart(grpc::ServerContext* ctx, const v1::GetChartRequest* req,
                        v1::GetChartResponse* resp) override {
    return Unary(core_, "ChartService/GetChart", ctx, resp,
                 [&](const CallContext& c) { return core_.charts().GetChart(*req, c); });
  }
  grpc::Status GetObstacles(grpc::ServerContext* ctx, const v1::GetObstaclesRequest* req,
                            v1::GetObstaclesResponse* resp) override {
    return Unary(core_, "ChartService/GetObstacles", ctx, resp,
                 [&](const CallContext& c) { return core_.charts().GetObstacles(*req, c); });
  }
  grpc::Status DeleteChart(grpc::ServerContext* ctx, const v1::DeleteChartRequest* req,
                           v1::DeleteChartResponse* resp) override {
    return Unary(core_, "ChartService/DeleteChart", ctx, resp,
                 [&](const CallContext& c) { return core_.charts().DeleteChart(*req, c); });
  }
  grpc::Status ListCharts(grpc::ServerContext* ctx, const v1::ListChartsRequest* req,
                          v1::ListChartsResponse* resp) override {
    return Unary(core_, "ChartService/ListCharts", ctx, resp,
                 [&](const CallContext& c) { return core_.charts().ListCharts(*req, c); });
  }

 private:
  ServiceCore& core_;
};

class GrpcServices::Routes final : public v1::RouteService::Service {
 public:
  explicit Routes(ServiceCore& core) : core_(core) {}
  grpc::Status PlanRoute(grpc::ServerContext* ctx, const v1::PlanRouteRequest* req,
                         v1::PlanRouteResponse* resp) override {
    return Unary(core_, "RouteService/PlanRoute", ctx, resp,
                 [&](const CallContext& c) { return core_.routes().PlanRoute(*req, c); });
  }
  grpc::Status EstimateRisk(grpc::ServerContext* ctx, const v1::EstimateRiskRequest* req,
                            v1::EstimateRiskResponse* resp) override {
    return Unary(core_, "RouteService/EstimateRisk", ctx, resp,
                 [&](const CallContext& c) { return core_.routes().EstimateRisk(*req, c); });
  }

 private:
  ServiceCore& core_;
};

class GrpcServices::Missions final : public v1::MissionService::Service {
 public:
  explicit Missions(ServiceCore& core) : core_(core) {}
  grpc::Status CreateMission(grpc::ServerContext* ctx, const v1::CreateMissionRequest* req,
                             v1::Mission* resp) override {
    return Unary(core_, "MissionService/CreateMission", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().CreateMission(*req, c); });
  }
  grpc::Status GetMission(grpc::ServerContext* ctx, const v1::GetMissionRequest* req,
                          v1::Mission* resp) override {
    return Unary(core_, "MissionService/GetMission", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().GetMission(*req, c); });
  }
  grpc::Status ListMissions(grpc::ServerContext* ctx, const v1::ListMissionsRequest* req,
                            v1::ListMissionsResponse* resp) override {
    return Unary(core_, "MissionService/ListMissions", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().ListMissions(*req, c); });
  }
  grpc::Status WatchMission(grpc::ServerContext* ctx, const v1::WatchMissionRequest* req,
                            grpc::ServerWriter<v1::MissionEvent>* writer) override {
    return Stream(core_, "MissionService/WatchMission", ctx, writer,
                  [&](const CallContext& c, const StreamSink<v1::MissionEvent>& sink) {
                    return core_.vessels().WatchMission(core_.missions(), *req, c, sink);
                  });
  }
  grpc::Status ReportFeedback(grpc::ServerContext* ctx, const v1::ReportFeedbackRequest* req,
                              v1::ReportFeedbackResponse* resp) override {
    return Unary(core_, "MissionService/ReportFeedback", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().ReportFeedback(*req, c); });
  }
  grpc::Status RequestReplan(grpc::ServerContext* ctx, const v1::RequestReplanRequest* req,
                             v1::RequestReplanResponse* resp) override {
    return Unary(core_, "MissionService/RequestReplan", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().RequestReplan(*req, c); });
  }
  grpc::Status CancelMission(grpc::ServerContext* ctx, const v1::CancelMissionRequest* req,
                             v1::Mission* resp) override {
    return Unary(core_, "MissionService/CancelMission", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().CancelMission(*req, c); });
  }
  grpc::Status ReportVesselState(grpc::ServerContext* ctx, const v1::ReportVesselStateRequest* req,
                                 v1::ReportVesselStateResponse* resp) override {
    return Unary(core_, "MissionService/ReportVesselState", ctx, resp,
                 [&](const CallContext& c) { return core_.vessels().ReportVesselState(*req, c); });
  }
  grpc::Status ListFeedback(grpc::ServerContext* ctx, const v1::ListFeedbackRequest* req,
                            v1::ListFeedbackResponse* resp) override {
    return Unary(core_, "MissionService/ListFeedback", ctx, resp,
                 [&](const CallContext& c) { return core_.missions().ListFeedback(*req, c); });
  }

 private:
  ServiceCore& core_;
};

class GrpcServices::Access final : public v1::AccessService::Service {
 public:
  explicit Access(ServiceCore& core) : core_(core) {}
  grpc::Status WhoAmI(grpc::ServerContext* ctx, const v1::WhoAmIRequest* req,
                      v1::WhoAmIResponse* resp) override {
    return Unary(core_, "AccessService/WhoAmI", ctx, resp,
                 [&](const CallContext& c) { return core_.access().WhoAmI(*req, c); });
  }
  grpc::Status CreateToken(grpc::ServerContext* ctx, const v1::CreateTokenRequest* req,
                           v1::CreateTokenResponse* resp) override {
    return Unary(core_, "AccessService/CreateToken", ctx, resp,
                 [&](const CallContext& c) { return core_.access().CreateToken(*req, c); });
  }
  grpc::Status ListTokens(grpc::ServerContext* ctx, const v1::ListTokensRequest* req,
                          v1::ListTokensResponse* resp) override {
    return Unary(core_, "AccessService/ListTokens", ctx, resp,
                 [&](const CallContext& c) { return core_.access().ListTokens(*req, c); });
  }
  grpc::Status RevokeToken(grpc::ServerContext* ctx, const v1::RevokeTokenRequest* req,
                           v1::RevokeTokenResponse* resp) override {
    return Unary(core_, "AccessService/RevokeToken", ctx, resp,
                 [&](const CallContext& c) { return core_.access().RevokeToken(*req, c); });
  }
  grpc::Status ListAuditEvents(grpc::ServerContext* ctx, const v1::ListAuditEventsRequest* req,
                               v1::ListAuditEventsResponse* resp) override {
    return Unary(core_, "AccessService/ListAuditEvents", ctx, resp,
                 [&](const CallContext& c) { return core_.access().ListAuditEvents(*req, c); });
  }

 private:
  ServiceCore& core_;
};

GrpcServices::GrpcServices(ServiceCore& core)
    : planning_(std::make_unique<Planning>(core)),
      charts_(std::make_unique<Charts>(core)),
      routes_(std::make_unique<Routes>(core)),
      missions_(std::make_unique<Missions>(core)),
      access_(std::make_unique<Access>(core)) {}

GrpcServices::~GrpcServices() = default;

std::vector<std::string> GrpcServices::ServiceNames() {
  return {v1::PlanningService::service_full_name(), v1::ChartService::service_full_name(),
          v1::RouteService::service_full_name(), v1::MissionService::service_full_name(),
          v1::AccessService::service_full_name()};
}

std::vector<grpc::Service*> GrpcServices::services() {
  return {planning_.get(), charts_.get(), routes_.get(), missions_.get(), access_.get()};
}

}  // namespace seaplan::server
