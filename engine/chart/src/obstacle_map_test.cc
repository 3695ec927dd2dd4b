#include "seaplan/chart/obstacle_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>
#include <vector>

#include "seaplan/chart/geojson.h"

namespace seaplan::chart {
namespace {

// A 100 m square island centred on (cx, cy), in WGS84 UTM 33N coordinates.
constexpr double kCx = 500000.0, kCy = 6900000.0;
Polygon Square(double cx, double cy, double half) {
  return {{{cx - half, cy - half},
           {cx + half, cy - half},
           {cx + half, cy + half},
           {cx - half, cy + half}},
          {}};
}
LocalFrame Utm33() {
  return *LocalFrame::FromEpsg(32633);
}

ChartOptions Buffer10NoSimplify() {
  ChartOptions o;
  o.safety_buffer_m = 10.0;
  o.simplify_tolerance_m = 0.0;
  return o;
}

TEST(ObstacleMap, SquareIslandBufferedArea) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok()) << map.status();
  ASSERT_EQ(map->polygons().size(), 1u);
  // 100x100 square + four 100 x g strips + four quarter discs of radius g,
  // g = the growth (10 m over cos(pi/32): the 8 chords per quarter circle
  // keep the 10 m), so the area is slightly below pi g^2.
  const double g = ObstacleGrowthM(Buffer10NoSimplify());
  EXPECT_NEAR(g, 10.0484, 1e-4);
  const double exact = 100.0 * 100.0 + 4 * 100.0 * g + M_PI * g * g;
  EXPECT_NEAR(map->summary().total_area_m2, exact, 0.005 * exact);
  EXPECT_LT(map->summary().total_area_m2, exact);
  EXPECT_EQ(map->summary().features_per_layer.at("polygons"), 1);
  EXPECT_EQ(map->summary().frame_epsg, 32633);
  EXPECT_NEAR(map->bounds().min.east_m, kCx - 50 - g, 1e-6);
  EXPECT_NEAR(map->bounds().max.north_m, kCy + 50 + g, 1e-6);
  // Bounding box in lat/lon contains the island's centre.
  const LatLon c = map->frame().ToLatLon({kCx, kCy});
  EXPECT_LT(map->summary().bbox_min.lat_deg, c.lat_deg);
  EXPECT_GT(map->summary().bbox_max.lon_deg, c.lon_deg);
}

TEST(ObstacleMap, DistanceQueriesByHand) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  ObstacleQuery q(*map);
  const double g = ObstacleGrowthM(Buffer10NoSimplify());
  // East of the island: the buffered edge is at x = cx + 50 + g.
  EXPECT_NEAR(q.DistanceM({kCx + 150, kCy}), 100.0 - g, 1e-6);
  const NearestObstacle n = q.Nearest({kCx + 150, kCy + 10});
  EXPECT_NEAR(n.distance_m, 100.0 - g, 1e-6);
  EXPECT_NEAR(n.nearest.east_m, kCx + 50 + g, 1e-6);
  EXPECT_NEAR(n.nearest.north_m, kCy + 10, 1e-6);
  EXPECT_EQ(n.polygon_index, 0);
  // Diagonal from the corner: |(100,100)| - 10 (45 degrees is a chord vertex).
  EXPECT_NEAR(q.DistanceM({kCx + 150, kCy + 150}), std::sqrt(2.0) * 100.0 - g, 1e-6);
  // Inside: 0, and the signed distance is minus the distance to the edge.
  EXPECT_TRUE(q.Inside({kCx, kCy}));
  EXPECT_DOUBLE_EQ(q.DistanceM({kCx, kCy}), 0.0);
  EXPECT_NEAR(q.SignedDistanceM({kCx, kCy}), -50.0 - g, 1e-6);
  EXPECT_NEAR(q.SignedDistanceM({kCx + 150, kCy}), 100.0 - g, 1e-6);
  EXPECT_FALSE(q.Inside({kCx + 61, kCy}));
}

TEST(ObstacleMap, SegmentAndPolygonIntersection) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  ObstacleQuery q(*map);
  EXPECT_TRUE(q.SegmentHits({kCx - 200, kCy}, {kCx + 200, kCy}));
  EXPECT_FALSE(q.SegmentHits({kCx - 200, kCy + 61}, {kCx + 200, kCy + 61}));
  EXPECT_TRUE(q.SegmentHits({kCx - 200, kCy + 59}, {kCx + 200, kCy + 59}));
  const std::vector<EastNorth> route = {
      {kCx - 200, kCy}, {kCx - 200, kCy + 100}, {kCx + 200, kCy + 100}};
  EXPECT_FALSE(q.PolylineHits(route));
  const std::vector<EastNorth> touching = {
      {kCx + 55, kCy - 5}, {kCx + 65, kCy - 5}, {kCx + 65, kCy + 5}, {kCx + 55, kCy + 5}};
  EXPECT_TRUE(q.PolygonHits(touching));
  EXPECT_DOUBLE_EQ(q.PolygonDistanceM(touching), 0.0);
  const std::vector<EastNorth> away = {
      {kCx + 100, kCy - 5}, {kCx + 110, kCy - 5}, {kCx + 110, kCy + 5}, {kCx + 100, kCy + 5}};
  EXPECT_FALSE(q.PolygonHits(away));
  EXPECT_NEAR(q.PolygonDistanceM(away), 50.0 - ObstacleGrowthM(Buffer10NoSimplify()), 1e-6);
}

TEST(ObstacleMap, NearestPicksTheCloserIsland) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50), Square(kCx + 1000, kCy, 50)}, Utm33(),
                                       Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  ASSERT_EQ(map->polygons().size(), 2u);
  ObstacleQuery q(*map);
  const double g = ObstacleGrowthM(Buffer10NoSimplify());
  EXPECT_NEAR(q.DistanceM({kCx + 800, kCy}), 150.0 - g, 1e-6);
  EXPECT_NEAR(q.DistanceM({kCx + 300, kCy}), 250.0 - g, 1e-6);
  const NearestObstacle n = q.Nearest({kCx + 800, kCy});
  EXPECT_NEAR(map->polygons()[n.polygon_index].outer[0].east_m, kCx + 1000, 70.0);
}

TEST(ObstacleMap, UnbufferedClearanceIsTheDistanceToTheChartedObstacle) {
  ChartOptions o = Buffer10NoSimplify();
  o.simplify_tolerance_m = 4.0;  // grows the buffer by 4 m more
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), o);
  ASSERT_TRUE(map.ok());
  ASSERT_TRUE(map->has_unbuffered_obstacles());
  ObstacleQuery q(*map);
  // A route along y = cy + 80 passes 30 m north of the charted square.
  const std::vector<EastNorth> north = {{kCx - 200, kCy + 80}, {kCx + 200, kCy + 80}};
  auto c = q.UnbufferedClearance(north);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->distance_m, 30.0, 1e-9);
  EXPECT_NEAR(c->route_point.north_m, kCy + 80, 1e-9);
  EXPECT_NEAR(c->obstacle_point.north_m, kCy + 50, 1e-9);
  EXPECT_GE(c->obstacle_point.east_m, kCx - 50 - 1e-9);
  EXPECT_LE(c->obstacle_point.east_m, kCx + 50 + 1e-9);
  // Grazing the buffered outline keeps at least the 10 m buffer from the
  // square, at the straight edges and at the corners (chords) alike.
  const double edge = 50.0 + ObstacleGrowthM(o);
  for (const std::vector<EastNorth>& graze :
       {std::vector<EastNorth>{{kCx - 200, kCy + edge + 1e-6}, {kCx + 200, kCy + edge + 1e-6}},
        std::vector<EastNorth>{{kCx + 50 + edge, kCy + 50 - edge},
                               {kCx + 50 - edge, kCy + 50 + edge}}}) {
    if (q.PolylineHits(graze)) continue;  // inside the polygonised corner: no claim
    auto g = q.UnbufferedClearance(graze);
    ASSERT_TRUE(g.has_value());
    EXPECT_GE(g->distance_m, o.safety_buffer_m);
  }
  // Through the island: 0.
  const std::vector<EastNorth> through = {{kCx - 200, kCy}, {kCx + 200, kCy}};
  EXPECT_DOUBLE_EQ(q.UnbufferedClearance(through)->distance_m, 0.0);
  // Kept through serialization.
  auto back = DeserializeObstacleMap(SerializeObstacleMap(*map));
  ASSERT_TRUE(back.ok());
  ObstacleQuery qb(*back);
  EXPECT_NEAR(qb.UnbufferedClearance(north)->distance_m, 30.0, 1e-9);
}

TEST(ObstacleMap, NearestNavigableLeavesTheObstacleTheShortestWay) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  ObstacleQuery q(*map);
  const double g = ObstacleGrowthM(Buffer10NoSimplify());
  // 20 m west of the east edge of the buffered island: out eastwards.
  const EastNorth inside{kCx + 50 + g - 20, kCy + 3};
  ASSERT_TRUE(q.Inside(inside));
  auto out = q.NearestNavigable(inside, 5.0);
  ASSERT_TRUE(out.has_value());
  EXPECT_FALSE(q.Inside(*out));
  EXPECT_NEAR(out->east_m, kCx + 50 + g + 5, 1e-6);
  EXPECT_NEAR(out->north_m, kCy + 3, 1e-6);
  // Navigable points are their own answer.
  const EastNorth free{kCx + 300, kCy};
  EXPECT_EQ(q.NearestNavigable(free), free);
  // Outside the coverage box: brought inside it.
  const LocalBox box = map->summary().coverage;
  auto in_box = q.NearestNavigable({box.max.east_m + 500, kCy + 300});
  ASSERT_TRUE(in_box.has_value());
  EXPECT_TRUE(map->Covers(*in_box));
  EXPECT_FALSE(q.Inside(*in_box));
}

TEST(ObstacleMap, OverlappingObstaclesAreUnioned) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50), Square(kCx + 80, kCy, 50)}, Utm33(),
                                       Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  EXPECT_EQ(map->polygons().size(), 1u);
  EXPECT_EQ(map->summary().polygon_count, 1);
}

TEST(ObstacleMap, EmptyMapHasInfiniteDistance) {
  const LocalBox box{{kCx - 1000, kCy - 1000}, {kCx + 1000, kCy + 1000}};
  auto map = ObstacleMap::FromPolygons({}, Utm33(), Buffer10NoSimplify(), "none", box);
  ASSERT_TRUE(map.ok()) << map.status();
  ObstacleQuery q(*map);
  EXPECT_TRUE(std::isinf(q.DistanceM({kCx, kCy})));
  EXPECT_FALSE(q.Inside({kCx, kCy}));
  EXPECT_FALSE(q.SegmentHits({kCx - 10, kCy}, {kCx + 10, kCy}));
  EXPECT_TRUE(map->Covers({kCx, kCy}));
  EXPECT_FALSE(map->Covers({kCx + 2000, kCy}));
}

TEST(ObstacleMap, SelfIntersectingPolygonIsRepairedWithWarning) {
  // A bow tie: two triangles meeting at the centre.
  Polygon bowtie{{{kCx, kCy}, {kCx + 100, kCy + 100}, {kCx + 100, kCy}, {kCx, kCy + 100}}, {}};
  auto map = ObstacleMap::FromPolygons({bowtie}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok()) << map.status();
  ASSERT_FALSE(map->summary().warnings.empty());
  EXPECT_NE(map->summary().warnings[0].find("repaired"), std::string::npos);
  ObstacleQuery q(*map);
  EXPECT_TRUE(q.Inside({kCx + 10, kCy + 50}));  // left triangle
  EXPECT_TRUE(q.Inside({kCx + 90, kCy + 50}));  // right triangle
}

TEST(ObstacleMap, BadInputIsAnError) {
  ChartOptions bad;
  bad.safety_buffer_m = -1;
  EXPECT_EQ(ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), bad).status().code(),
            absl::StatusCode::kInvalidArgument);
  ChartOptions nan_depth;
  nan_depth.min_depth_m = std::nan("");
  EXPECT_FALSE(nan_depth.Validate().ok());
  Polygon degenerate{{{kCx, kCy}, {kCx + 1, kCy}}, {}};
  EXPECT_EQ(ObstacleMap::FromPolygons({degenerate}, Utm33(), ChartOptions{}).status().code(),
            absl::StatusCode::kInvalidArgument);
  Polygon inf{{{kCx, kCy}, {HUGE_VAL, kCy}, {kCx, kCy + 1}}, {}};
  EXPECT_FALSE(ObstacleMap::FromPolygons({inf}, Utm33(), ChartOptions{}).ok());
}

TEST(ObstacleMap, SerializationRoundTrip) {
  Polygon with_hole = Square(kCx + 3000, kCy, 500);
  with_hole.holes.push_back(Square(kCx + 3000, kCy, 300).outer);
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50), with_hole}, Utm33(),
                                       Buffer10NoSimplify(), "test");
  ASSERT_TRUE(map.ok());
  const std::string blob = SerializeObstacleMap(*map);
  auto back = DeserializeObstacleMap(blob);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_EQ(back->frame().epsg(), 32633);
  EXPECT_EQ(back->polygons().size(), map->polygons().size());
  EXPECT_DOUBLE_EQ(back->summary().total_area_m2, map->summary().total_area_m2);
  EXPECT_EQ(back->summary().features_per_layer, map->summary().features_per_layer);
  EXPECT_EQ(back->summary().source_format, "polygons");
  EXPECT_DOUBLE_EQ(back->summary().options.safety_buffer_m, 10.0);
  EXPECT_DOUBLE_EQ(back->summary().coverage.max.east_m, map->summary().coverage.max.east_m);
  ObstacleQuery q1(*map), q2(*back);
  for (const EastNorth p :
       {EastNorth{kCx + 150, kCy}, EastNorth{kCx + 3000, kCy}, EastNorth{kCx + 3000, kCy + 400}}) {
    EXPECT_DOUBLE_EQ(q1.SignedDistanceM(p), q2.SignedDistanceM(p));
  }
  EXPECT_FALSE(q2.Inside({kCx + 3000, kCy}));  // in the hole
  EXPECT_EQ(SerializeObstacleMap(*back), blob);
}

TEST(ObstacleMap, CorruptBlobsAreRejected) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  const std::string blob = SerializeObstacleMap(*map);
  EXPECT_EQ(DeserializeObstacleMap("").status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(DeserializeObstacleMap("garbage bytes, not a chart").status().code(),
            absl::StatusCode::kInvalidArgument);
  EXPECT_FALSE(DeserializeObstacleMap(blob.substr(0, blob.size() / 2)).ok());
  for (size_t i = 0; i < blob.size(); i += 7) {
    std::string bad = blob;
    bad[i] = static_cast<char>(bad[i] ^ 0x5a);
    EXPECT_FALSE(DeserializeObstacleMap(bad).ok()) << "byte " << i;
  }
}

TEST(ObstacleMap, QueriesFromSeveralThreadsAgree) {
  std::vector<Polygon> islands;
  islands.reserve(20);
  for (int i = 0; i < 20; ++i)
    islands.push_back(Square(kCx + 300.0 * i, kCy + 100.0 * (i % 3), 40));
  auto map = ObstacleMap::FromPolygons(islands, Utm33(), ChartOptions{});
  ASSERT_TRUE(map.ok());
  std::vector<EastNorth> points;
  points.reserve(400);
  for (int i = 0; i < 400; ++i) points.push_back({kCx - 500 + 17.3 * i, kCy - 300 + 1.7 * i});
  std::vector<double> expected;
  {
    ObstacleQuery q(*map);
    for (const EastNorth& p : points) expected.push_back(q.SignedDistanceM(p));
  }
  std::vector<std::vector<double>> got(4);
  std::vector<std::thread> threads;
  threads.reserve(4);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      ObstacleQuery q(*map);  // one query object per thread
      for (int rep = 0; rep < 5; ++rep) {
        got[t].clear();
        for (const EastNorth& p : points) got[t].push_back(q.SignedDistanceM(p));
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(got[t], expected);
}

TEST(GeoJson, ObstaclesAndRoutes) {
  auto map = ObstacleMap::FromPolygons({Square(kCx, kCy, 50)}, Utm33(), Buffer10NoSimplify());
  ASSERT_TRUE(map.ok());
  const std::string json =
      ToGeoJson(*map, {{"alt \"0\"", {{kCx - 200, kCy}, {kCx + 200, kCy + 100}}}});
  EXPECT_EQ(json.rfind("{\"type\":\"FeatureCollection\"", 0), 0u);
  EXPECT_NE(json.find("\"kind\":\"obstacle\""), std::string::npos);
  EXPECT_NE(json.find("\"name\":\"alt \\\"0\\\"\""), std::string::npos);
  // Coordinates are lon,lat: the island is at 15 E (central meridian), ~62.2 N.
  const LatLon c = Utm33().ToLatLon({kCx, kCy});
  char expect[32];
  std::snprintf(expect, sizeof(expect), "[15.00");
  EXPECT_NE(json.find(expect), std::string::npos);
  EXPECT_NEAR(c.lon_deg, 15.0, 1e-9);
  // Read back as a chart: the obstacle (already buffered) has the same area.
  ChartOptions o;
  o.safety_buffer_m = 0;
  o.simplify_tolerance_m = 0;
  o.frame_epsg = 32633;
  auto back = LoadChartBytes({{"export.geojson", ToGeoJson(*map)}}, o);
  ASSERT_TRUE(back.ok()) << back.status();
  EXPECT_NEAR(back->summary().total_area_m2, map->summary().total_area_m2, 1.0);
}

}  // namespace
}  // namespace seaplan::chart
