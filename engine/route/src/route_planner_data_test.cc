// The Alesund case of paper 002 on the real chart (CC BY 4.0, (c) Kartverket):
// ../shared/enc/alesund, obstacles = chart box minus seabed5m (minimum
// depth 5 m), route1.csv's in-chart leg (rows 2 and 3: E 41200 N 6959900 ->
// E 38000 N 6961100; rows 1 and 4 lie outside the chart box, and the public
// code also plans between rows 2 and 3), wind 10 m/s from -110 deg and a
// 1 m/s current set toward -110 deg (the public code's reading of "-110").
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>

#include "seaplan/route/route_planner.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::route {
namespace {

std::vector<EastNorth> ReadRoute(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::vector<EastNorth> pts;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream s(line);
    double e, n;
    char comma;
    if (s >> e >> comma >> n) pts.push_back({e, n});
  }
  return pts;
}

Environment AlesundWeather() {
  Environment env;
  env.wind_speed_mps = 10.0;
  env.wind_from_deg = -110.0;
  env.current_speed_mps = 1.0;
  env.current_toward_deg = -110.0;
  return env;
}

TEST(RoutePlannerDataTest, AlesundTwoAlternativesRiskAndModes) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/alesund/shapefiles");
  const auto route = ReadRoute(dir.parent_path() / "config/routes/route1.csv");
  ASSERT_EQ(route.size(), 4u);
  chart::ChartOptions co;
  co.min_depth_m = 5.0;
  co.frame_epsg = 25833;
  auto map = chart::LoadChartFile(dir.string(), co);
  ASSERT_TRUE(map.ok()) << map.status();
  auto shared = std::make_shared<const chart::ObstacleMap>(std::move(map).value());
  RouteOptions options;
  options.min_depth_m = 5.0;
  auto planner = RoutePlanner::Create(shared, ShipParticulars{}, options);
  ASSERT_TRUE(planner.ok()) << planner.status();

  // The true route1 start is outside the chart box: a clear error.
  auto outside = planner->Plan(route[0], route[2], AlesundWeather());
  EXPECT_EQ(outside.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(outside.status().message().find("start"), std::string_view::npos);

  auto r = planner->Plan(route[1], route[2], AlesundWeather());
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_EQ(r->alternatives.size(), 2u);
  ASSERT_GE(r->chosen, 0);
  // The chosen one has the lowest expected cost among the safe ones.
  for (const auto& alt : r->alternatives) {
    EXPECT_TRUE(alt.safe);
    EXPECT_LE(r->alternatives[r->chosen].expected_cost, alt.expected_cost);
    // 20 segments: 21 waypoints, unless the repair inserted Level-1 vertices
    // or fillets replaced corners (their vertices count as inserted).
    if (alt.inserted_waypoints == 0) {
      EXPECT_EQ(alt.waypoints.size(), 21u);
    }
    for (const std::string& w : alt.warnings) ADD_FAILURE() << w;
    EXPECT_GT(alt.length_m, 3000.0);
    EXPECT_GT(alt.sailing_time_s, alt.length_m / 10.0);
    EXPECT_GT(alt.fuel_kg, 0.0);
  }
  // Somewhere the drift runs onto a near shore: higher P(G) and a robust
  // mode there; the economical PTO elsewhere (most segments).
  int robust = 0, pto = 0;
  double p_robust_ttg = 1e9, p_pto_ttg_max = 0;
  for (const auto& alt : r->alternatives) {
    for (size_t k = 0; k + 1 < alt.waypoints.size(); ++k) {
      const auto& w = alt.waypoints[k];
      if (w.mode == MsoMode::kPto) {
        ++pto;
        p_pto_ttg_max = std::max(p_pto_ttg_max, w.ttg_s);
      } else {
        ++robust;
        p_robust_ttg = std::min(p_robust_ttg, w.ttg_s);
        EXPECT_LT(w.ttg_s, 630.0) << "robust mode where the drift never grounds, waypoint " << k;
      }
    }
  }
  EXPECT_GE(robust, 1);
  EXPECT_GT(pto, robust);
  double min_ttg = 1e9;
  for (const auto& alt : r->alternatives) {
    for (const auto& w : alt.waypoints) min_ttg = std::min(min_ttg, w.ttg_s);
  }
  EXPECT_LT(min_ttg, 300.0);

  // EstimateRisk along the chosen route agrees with the planner's TTG.
  std::vector<TrackPoint> track;
  const auto& chosen = r->alternatives[r->chosen];
  for (const auto& w : chosen.waypoints)
    track.push_back({w.latlon, std::nullopt, std::nullopt, w.mode});
  auto risk = planner->EstimateRisk(track, AlesundWeather());
  ASSERT_TRUE(risk.ok()) << risk.status();
  ASSERT_EQ(risk->size(), track.size());
  for (const auto& p : *risk) EXPECT_GE(p.ttg_s, 30.0);
}

TEST(RoutePlannerDataTest, StartInsideAnObstacleIsInvalidArgument) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/alesund/shapefiles");
  chart::ChartOptions co;
  co.frame_epsg = 25833;
  auto map = chart::LoadChartFile(dir.string(), co);
  ASSERT_TRUE(map.ok()) << map.status();
  // A point on the island's land (shapefile land layer covers it).
  const auto& poly = map->polygons().front().outer;
  EastNorth inside{0, 0};
  for (const auto& p : poly)
    inside = {inside.east_m + p.east_m / poly.size(), inside.north_m + p.north_m / poly.size()};
  auto planner =
      RoutePlanner::Create(std::shared_ptr<const chart::ObstacleMap>(&*map, [](auto*) {}),
                           ShipParticulars{}, RouteOptions{});
  ASSERT_TRUE(planner.ok());
  if (!planner->field().Inside({inside.east_m, inside.north_m}))
    GTEST_SKIP() << "centroid not inside";
  auto r = planner->Plan(inside, {38000, 6961100}, AlesundWeather());
  EXPECT_EQ(r.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("inside"), std::string_view::npos);
}

}  // namespace
}  // namespace seaplan::route
