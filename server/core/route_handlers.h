// RouteService handlers: PlanRoute and EstimateRisk over a stored chart.
#pragma once

#include "seaplan/common/stop_token.h"
#include "seaplan/storage/repositories.h"
#include "seaplan/v1/route.pb.h"
#include "server/core/call_context.h"
#include "server/core/caller_limits.h"
#include "server/core/work_pool.h"

namespace seaplan::server {

class RouteHandlers {
 public:
  RouteHandlers(storage::ChartRepository& charts, WorkPool& pool, StopToken root,
                const RequestBudgets& budgets = {})
      : charts_(charts), pool_(pool), root_(std::move(root)), budgets_(budgets) {}

  absl::StatusOr<v1::PlanRouteResponse> PlanRoute(const v1::PlanRouteRequest& request,
                                                  const CallContext& ctx);
  absl::StatusOr<v1::EstimateRiskResponse> EstimateRisk(const v1::EstimateRiskRequest& request,
                                                        const CallContext& ctx);

 private:
  storage::ChartRepository& charts_;
  WorkPool& pool_;
  StopToken root_;
  RequestBudgets budgets_;
};

}  // namespace seaplan::server
