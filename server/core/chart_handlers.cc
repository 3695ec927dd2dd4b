#include "server/core/chart_handlers.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "seaplan/chart/geojson.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/mission/mission_state.h"
#include "seaplan/v1/mission.pb.h"
#include "server/core/audit_entry.h"
#include "server/core/convert.h"
#include "server/core/mission_engine_adapter.h"

namespace seaplan::server {
namespace {

// Defaults documented in chart.proto.
constexpr double kDefaultMinimumDepthM = 10.0;
constexpr double kDefaultSafetyBufferM = 10.0;

absl::StatusOr<chart::ChartOptions> MakeChartOptions(double min_depth_m, double safety_buffer_m) {
  chart::ChartOptions options;
  options.min_depth_m = min_depth_m;
  options.safety_buffer_m = safety_buffer_m;
  // Keep the simplification inside the buffer (ChartOptions' invariant).
  options.simplify_tolerance_m =
      std::min(options.simplify_tolerance_m, options.safety_buffer_m / 2);
  if (absl::Status valid = options.Validate(); !valid.ok()) {
    return absl::InvalidArgumentError(absl::StrCat("chart options: ", valid.message()));
  }
  return options;
}

// Loads uploaded files on the pool; `serialized` (optional) receives the
// stored form of the map.
absl::StatusOr<chart::ObstacleMap> LoadOnPool(
    WorkPool& pool, const StopToken& root,
    const google::protobuf::RepeatedPtrField<v1::ChartFile>& uploaded,
    const chart::ChartOptions& options, const CallContext& ctx, const std::string& what,
    std::string* serialized) {
  std::vector<chart::ChartFile> files;
  files.reserve(static_cast<std::size_t>(uploaded.size()));
  for (const auto& f : uploaded) files.push_back({f.name(), f.content()});
  absl::StatusOr<chart::ObstacleMap> map = absl::UnknownError("chart loader did not run");
  SEAPLAN_RETURN_IF_ERROR(pool.Run(
      [&] {
        map = chart::LoadChartBytes(files, options);
        if (map.ok() && serialized != nullptr) *serialized = chart::SerializeObstacleMap(*map);
      },
      ctx.stop, [&] { ctx.ForwardCancellation(); }));
  if (ctx.stop.StopRequested()) return StopStatus(ctx.stop, root.StopRequested(), what);
  return map;
}

v1::ObstacleSummary ToProto(const chart::ObstacleSummary& s) {
  v1::ObstacleSummary out;
  out.set_obstacle_count(s.polygon_count);
  for (const auto& [layer, count] : s.features_per_layer)
    (*out.mutable_count_by_layer())[layer] = count;
  out.set_total_area_m2(s.total_area_m2);
  out.mutable_south_west()->set_latitude_deg(s.bbox_min.lat_deg);
  out.mutable_south_west()->set_longitude_deg(s.bbox_min.lon_deg);
  out.mutable_north_east()->set_latitude_deg(s.bbox_max.lat_deg);
  out.mutable_north_east()->set_longitude_deg(s.bbox_max.lon_deg);
  out.set_frame(absl::StrCat("EPSG:", s.frame_epsg));
  return out;
}

}  // namespace

v1::Chart ChartFromRecord(const storage::ChartRecord& record) {
  v1::Chart chart;
  chart.set_chart_id(record.id);
  chart.set_name(record.name);
  chart.set_format(static_cast<v1::ChartFormat>(record.format));
  v1::UploadChartRequest options;  // stored without the files
  if (options.ParseFromString(record.options)) {
    chart.set_minimum_depth_m(options.minimum_depth_m());
    chart.set_safety_buffer_m(options.safety_buffer_m());
  }
  chart.mutable_summary()->ParseFromString(record.summary);
  *chart.mutable_created_at() = ToTimestamp(record.created_at_ms);
  return chart;
}

absl::StatusOr<v1::UploadChartResponse> ChartHandlers::UploadChart(
    const v1::UploadChartRequest& request, const CallContext& ctx) {
  if (request.name().empty()) return absl::InvalidArgumentError("name: a chart needs a name");
  if (request.files_size() == 0) return absl::InvalidArgumentError("files: no chart file uploaded");
  for (int i = 0; i < request.files_size(); ++i) {
    if (request.files(i).name().empty())
      return absl::InvalidArgumentError(absl::StrCat("files[", i, "].name is empty"));
  }
  if (request.minimum_depth_m() < 0 || request.safety_buffer_m() < 0) {
    return absl::InvalidArgumentError("minimum_depth_m and safety_buffer_m must not be negative");
  }
  SEAPLAN_ASSIGN_OR_RETURN(
      chart::ChartOptions options,
      MakeChartOptions(
          request.minimum_depth_m() > 0 ? request.minimum_depth_m() : kDefaultMinimumDepthM,
          request.safety_buffer_m() > 0 ? request.safety_buffer_m() : kDefaultSafetyBufferM));
  std::string serialized;
  SEAPLAN_ASSIGN_OR_RETURN(
      chart::ObstacleMap map,
      LoadOnPool(pool_, root_, request.files(), options, ctx, "chart upload", &serialized));

  v1::UploadChartRequest stored_options = request;
  stored_options.clear_files();
  stored_options.set_minimum_depth_m(options.min_depth_m);
  stored_options.set_safety_buffer_m(options.safety_buffer_m);
  v1::UploadChartRequest stored_files;
  *stored_files.mutable_files() = request.files();

  storage::ChartRecord record;
  record.id = NewId("c-");
  record.name = request.name();
  record.format = request.format();
  record.options = stored_options.SerializeAsString();
  record.summary = ToProto(map.summary()).SerializeAsString();
  record.obstacles = std::move(serialized);
  record.source_files = stored_files.SerializeAsString();
  record.created_at_ms = NowMs();
  const auto audit = AuditEntry(ctx, record.id);
  SEAPLAN_ASSIGN_OR_RETURN(storage::ChartRecord stored,
                           charts_.Insert(std::move(record), AuditPointer(audit)));
  v1::UploadChartResponse response;
  *response.mutable_chart() = ChartFromRecord(stored);
  for (const auto& w : map.summary().warnings) response.add_warnings(w);
  return response;
}

absl::StatusOr<v1::GetChartResponse> ChartHandlers::GetChart(const v1::GetChartRequest& request,
                                                             const CallContext& ctx) {
  (void)ctx;
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  SEAPLAN_ASSIGN_OR_RETURN(storage::ChartRecord record,
                           charts_.Get(request.chart_id(), request.include_obstacles_geojson()));
  v1::GetChartResponse response;
  *response.mutable_chart() = ChartFromRecord(record);
  if (request.include_obstacles_geojson()) {
    SEAPLAN_ASSIGN_OR_RETURN(chart::ObstacleMap map,
                             chart::DeserializeObstacleMap(record.obstacles));
    response.set_obstacles_geojson(chart::ToGeoJson(map));
  }
  return response;
}

absl::StatusOr<v1::GetObstaclesResponse> ChartHandlers::GetObstacles(
    const v1::GetObstaclesRequest& request, const CallContext& ctx) {
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  if (request.minimum_depth_m() < 0)
    return absl::InvalidArgumentError("minimum_depth_m must not be negative");
  SEAPLAN_ASSIGN_OR_RETURN(storage::ChartRecord record, charts_.Get(request.chart_id(), true));
  const v1::Chart stored = ChartFromRecord(record);
  v1::GetObstaclesResponse response;
  response.set_chart_id(stored.chart_id());
  response.set_safety_buffer_m(stored.safety_buffer_m());
  const bool same_depth = request.minimum_depth_m() == 0 ||
                          std::abs(request.minimum_depth_m() - stored.minimum_depth_m()) < 1e-9;
  absl::StatusOr<chart::ObstacleMap> map = absl::UnknownError("no obstacles");
  if (same_depth) {
    response.set_minimum_depth_m(stored.minimum_depth_m());
    map = chart::DeserializeObstacleMap(record.obstacles);
  } else {
    response.set_minimum_depth_m(request.minimum_depth_m());
    v1::UploadChartRequest files;
    if (!files.ParseFromString(record.source_files) || files.files_size() == 0) {
      return absl::FailedPreconditionError(absl::StrCat(
          "chart ", request.chart_id(), " has no stored source files to load at another depth"));
    }
    SEAPLAN_ASSIGN_OR_RETURN(chart::ChartOptions options,
                             MakeChartOptions(request.minimum_depth_m(), stored.safety_buffer_m()));
    map = LoadOnPool(pool_, root_, files.files(), options, ctx, "obstacles", nullptr);
  }
  if (!map.ok()) return map.status();
  response.set_obstacle_count(map->summary().polygon_count);
  response.set_geojson(chart::ToGeoJson(*map));
  return response;
}

absl::StatusOr<v1::DeleteChartResponse> ChartHandlers::DeleteChart(
    const v1::DeleteChartRequest& request, const CallContext& ctx) {
  if (request.chart_id().empty()) return absl::InvalidArgumentError("chart_id is empty");
  // A finished mission never loads its chart again; an unfinished one
  // replans with it. Which states are final is the mission engine's to say.
  storage::ChartUse use;
  for (int state = v1::MissionState_MIN; state <= v1::MissionState_MAX; ++state) {
    if (state != v1::MISSION_STATE_UNSPECIFIED && v1::MissionState_IsValid(state) &&
        !mission::IsFinal(MissionStateFromProto(state))) {
      use.active_states.push_back(state);
    }
  }
  use.spec_uses_chart = [](const std::string& spec, const std::string& chart_id) {
    v1::MissionSpec parsed;
    // An unreadable spec counts as a user: deleting must not lose a chart
    // a mission might need.
    return !parsed.ParseFromString(spec) || parsed.chart_id() == chart_id;
  };
  const auto audit = AuditEntry(ctx, request.chart_id());
  SEAPLAN_RETURN_IF_ERROR(charts_.Delete(request.chart_id(), use, AuditPointer(audit)));
  if (on_deleted_) on_deleted_(request.chart_id());
  v1::DeleteChartResponse response;
  response.set_chart_id(request.chart_id());
  return response;
}

absl::StatusOr<v1::ListChartsResponse> ChartHandlers::ListCharts(
    const v1::ListChartsRequest& request, const CallContext& ctx) {
  (void)ctx;
  SEAPLAN_ASSIGN_OR_RETURN(int page_size, PageSize(request.page_size()));
  SEAPLAN_ASSIGN_OR_RETURN(std::int64_t after, ParsePageToken(request.page_token()));
  SEAPLAN_ASSIGN_OR_RETURN(auto page, charts_.List(page_size, after));
  v1::ListChartsResponse response;
  for (const auto& record : page.items) *response.add_charts() = ChartFromRecord(record);
  response.set_next_page_token(MakePageToken(page.next_after));
  return response;
}

}  // namespace seaplan::server
