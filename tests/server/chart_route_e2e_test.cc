// ChartService and RouteService end to end: upload a small GeoJSON chart
// (engine/chart/testdata/harbour.geojson), read it back from storage over
// both transports, and ask for a route and a risk estimate on it.
#include <google/protobuf/util/json_util.h>
#include <gtest/gtest.h>

#include "test_support.h"

namespace seaplan::server::testing {
namespace {

using grpc::ClientContext;
using grpc::StatusCode;

TEST(ChartRouteE2eTest, UploadGetListAndRouteOnAStoredChart) {
  InProcessServer s;
  auto charts = v1::ChartService::NewStub(s.channel());
  v1::UploadChartRequest upload = HarbourChartUpload();
  upload.set_safety_buffer_m(10);
  v1::UploadChartResponse uploaded;
  {
    ClientContext ctx;
    grpc::Status st = charts->UploadChart(&ctx, upload, &uploaded);
    ASSERT_TRUE(st.ok()) << st.error_message();
  }
  const v1::Chart& chart = uploaded.chart();
  EXPECT_FALSE(chart.chart_id().empty());
  EXPECT_EQ(chart.name(), "harbour");
  EXPECT_DOUBLE_EQ(chart.minimum_depth_m(), 5);
  EXPECT_GE(chart.summary().obstacle_count(), 1);
  EXPECT_GT(chart.summary().total_area_m2(), 0);
  EXPECT_NEAR(chart.summary().south_west().latitude_deg(), 62.47, 0.01);
  EXPECT_EQ(chart.summary().frame().rfind("EPSG:", 0), 0u);

  // A chart that is not one: INVALID_ARGUMENT, nothing stored.
  {
    v1::UploadChartRequest bad = upload;
    bad.mutable_files(0)->set_content("{ not json");
    ClientContext ctx;
    v1::UploadChartResponse resp;
    EXPECT_EQ(charts->UploadChart(&ctx, bad, &resp).error_code(), StatusCode::INVALID_ARGUMENT);
  }

  // Read back over HTTP/JSON, with the obstacles as GeoJSON.
  auto res =
      s.http().Post("/v1/ChartService/GetChart",
                    "{\"chartId\":\"" + chart.chart_id() + "\",\"includeObstaclesGeojson\":true}",
                    "application/json");
  ASSERT_TRUE(res);
  ASSERT_EQ(res->status, 200) << res->body;
  v1::GetChartResponse got;
  ASSERT_TRUE(google::protobuf::util::JsonStringToMessage(res->body, &got).ok());
  EXPECT_EQ(got.chart().chart_id(), chart.chart_id());
  EXPECT_EQ(got.chart().summary().obstacle_count(), chart.summary().obstacle_count());
  EXPECT_NE(got.obstacles_geojson().find("FeatureCollection"), std::string::npos);
  {
    ClientContext ctx;
    v1::ListChartsRequest list_req;
    v1::ListChartsResponse list;
    ASSERT_TRUE(charts->ListCharts(&ctx, list_req, &list).ok());
    ASSERT_EQ(list.charts_size(), 1);
    EXPECT_EQ(list.charts(0).chart_id(), chart.chart_id());
    EXPECT_TRUE(list.next_page_token().empty());
    ClientContext ctx2;
    list_req.set_page_token("garbage");
    EXPECT_EQ(charts->ListCharts(&ctx2, list_req, &list).error_code(),
              StatusCode::INVALID_ARGUMENT);
  }

  // Risk along a short track in the deep water east of the shallows.
  auto routes = v1::RouteService::NewStub(s.channel());
  {
    ClientContext ctx;
    v1::EstimateRiskRequest req;
    req.set_chart_id(chart.chart_id());
    *req.add_track()->mutable_position() = LatLon(62.4705, 6.1085);
    *req.add_track()->mutable_position() = LatLon(62.4712, 6.1090);
    v1::EstimateRiskResponse resp;
    grpc::Status st = routes->EstimateRisk(&ctx, req, &resp);
    ASSERT_TRUE(st.ok()) << st.error_message();
    ASSERT_EQ(resp.points_size(), 2);
    for (const auto& p : resp.points()) {
      EXPECT_GE(p.grounding_probability(), 0.0);
      EXPECT_LE(p.grounding_probability(), 1.0);
      EXPECT_GE(p.time_to_grounding_s(), 0.0);
    }
    EXPECT_LE(resp.max_grounding_probability(), 1.0);
  }
  // A route between two points in the deep water; start on land is refused.
  {
    ClientContext ctx;
    SetDeadline(&ctx, 60000);
    v1::PlanRouteRequest req;
    req.set_chart_id(chart.chart_id());
    *req.mutable_start() = LatLon(62.4703, 6.1080);
    *req.mutable_goal() = LatLon(62.4718, 6.1117);
    req.mutable_options()->set_particles(8);
    req.mutable_options()->set_iterations(10);
    req.mutable_options()->set_segments(6);
    req.mutable_options()->set_safety_distance_m(5);
    v1::PlanRouteResponse resp;
    grpc::Status st = routes->PlanRoute(&ctx, req, &resp);
    ASSERT_TRUE(st.ok()) << st.error_message();
    ASSERT_GE(resp.alternatives_size(), 1);
    ASSERT_GE(resp.chosen_alternative(), 0);
    const v1::RouteAlternative& route = resp.chosen_route();
    ASSERT_GE(route.waypoints_size(), 2);
    EXPECT_NEAR(route.waypoints(0).position().latitude_deg(), 62.4703, 1e-5);
    EXPECT_NEAR(route.waypoints(route.waypoints_size() - 1).position().longitude_deg(), 6.1117,
                1e-5);
    EXPECT_GT(route.length_m(), 0);
    EXPECT_GT(route.sailing_time_s(), 0);
    ASSERT_GE(resp.mode_schedule_size(), 1);
    EXPECT_EQ(resp.mode_schedule(0).from_waypoint(), 0);
    EXPECT_EQ(resp.mode_schedule(resp.mode_schedule_size() - 1).to_waypoint(),
              route.waypoints_size() - 1);

    ClientContext ctx2;
    *req.mutable_start() = LatLon(62.471, 6.102);  // on the land square
    EXPECT_EQ(routes->PlanRoute(&ctx2, req, &resp).error_code(), StatusCode::INVALID_ARGUMENT);
  }
}

}  // namespace
}  // namespace seaplan::server::testing
