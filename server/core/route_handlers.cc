#include "server/core/route_handlers.h"

#include <cmath>

#include "absl/strings/str_cat.h"

namespace seaplan::server {
namespace {

absl::Status CheckLatLon(const v1::LatLon& p, const char* field) {
  if (!std::isfinite(p.latitude_deg()) || !std::isfinite(p.longitude_deg()) || std::abs(p.latitude_deg()) > 90 ||
      std::abs(p.longitude_deg()) > 180) {
    return absl::InvalidArgumentError(absl::StrCat(field, ": not a WGS84 position (", p.latitude_deg(), ", ",
                                                   p.longitude_deg(), ")"));
  }
  return absl::OkStatus();
}

}  // namespace

absl::StatusOr<v1::PlanRouteResponse> RouteHandlers::PlanRoute(const v1::PlanRouteRequest& request,
                                                               const CallContext& ctx) {
  (void)ctx;
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  SEAPLAN_RETURN_IF_ERROR(CheckLatLon(request.start(), "start"));
  SEAPLAN_RETURN_IF_ERROR(CheckLatLon(request.goal(), "goal"));
  SEAPLAN_RETURN_IF_ERROR(charts_.Get(request.chart_id(), /*with_blobs=*/false).status());
  // TODO(#2): wire engine/route once its PlanRoute facade (Level 1 + Level 2
  // over an ObstacleMap) is public.
  return absl::UnimplementedError(
      "RouteService.PlanRoute: the route planner (engine/route PlanRoute facade) is not wired into this server yet");
}

absl::StatusOr<v1::EstimateRiskResponse> RouteHandlers::EstimateRisk(const v1::EstimateRiskRequest& request,
                                                                     const CallContext& ctx) {
  (void)ctx;
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  if (request.track_size() == 0) return absl::InvalidArgumentError("track: no track point");
  for (int i = 0; i < request.track_size(); ++i) {
    SEAPLAN_RETURN_IF_ERROR(CheckLatLon(request.track(i).position(), "track[].position"));
  }
  SEAPLAN_RETURN_IF_ERROR(charts_.Get(request.chart_id(), /*with_blobs=*/false).status());
  return absl::UnimplementedError(
      "RouteService.EstimateRisk: the grounding-risk estimator (engine/route) is not wired into this server yet");
}

}  // namespace seaplan::server
