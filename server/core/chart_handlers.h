// ChartService handlers: UploadChart loads the chart with engine/chart on
// the WorkPool and stores it (summary, serialized obstacles, the uploaded
// files) in the ChartRepository; GetChart / ListCharts read storage only;
// GetObstacles reads storage or, at another minimum depth, reloads the files;
// DeleteChart removes a chart no unfinished mission uses (and has the mission
// engine drop its routings over it; the handlers themselves cache nothing).
#pragma once

#include <functional>
#include <string>

#include "seaplan/common/stop_token.h"
#include "seaplan/storage/repositories.h"
#include "seaplan/v1/chart.pb.h"
#include "server/core/call_context.h"
#include "server/core/work_pool.h"

namespace seaplan::server {

class ChartHandlers {
 public:
  // `on_deleted` (optional) runs after a chart was deleted, so that whoever
  // keeps it in memory drops it.
  ChartHandlers(storage::ChartRepository& charts, WorkPool& pool, StopToken root,
                std::function<void(const std::string& chart_id)> on_deleted = {})
      : charts_(charts), pool_(pool), root_(std::move(root)), on_deleted_(std::move(on_deleted)) {}

  absl::StatusOr<v1::UploadChartResponse> UploadChart(const v1::UploadChartRequest& request,
                                                      const CallContext& ctx);
  absl::StatusOr<v1::GetChartResponse> GetChart(const v1::GetChartRequest& request,
                                                const CallContext& ctx);
  absl::StatusOr<v1::ListChartsResponse> ListCharts(const v1::ListChartsRequest& request,
                                                    const CallContext& ctx);
  // The stored obstacles at the chart's own depth; at another depth the
  // uploaded files are loaded again on the WorkPool (same buffer).
  absl::StatusOr<v1::GetObstaclesResponse> GetObstacles(const v1::GetObstaclesRequest& request,
                                                        const CallContext& ctx);
  // NotFound for an unknown chart; FailedPrecondition naming the missions
  // (planning, active or replanning) whose spec uses it.
  absl::StatusOr<v1::DeleteChartResponse> DeleteChart(const v1::DeleteChartRequest& request,
                                                      const CallContext& ctx);

 private:
  storage::ChartRepository& charts_;
  WorkPool& pool_;
  StopToken root_;
  std::function<void(const std::string& chart_id)> on_deleted_;
};

// The stored chart as the API shows it (summary decoded from the record).
v1::Chart ChartFromRecord(const storage::ChartRecord& record);

}  // namespace seaplan::server
