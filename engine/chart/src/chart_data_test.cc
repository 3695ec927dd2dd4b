// Tests on the real charts in the shared folder (LABEL data; skipped with a
// reason when the folder is absent). Licences: NOAA ENC User Agreement,
// Kartverket CC BY 4.0 ("© Kartverket"); see ../shared/enc/README.md.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cpl_vsi.h"
#include "gdal_priv.h"
#include "ogrsf_frmts.h"
#include "seaplan/chart/alternatives.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::chart {
namespace {

// Independent count with plain OGR: features of `layer` whose `field` is
// below `limit` (or null, when count_null), optionally areas only.
int CountBelow(const std::string& path, const char* layer, const char* field, double limit,
               bool count_null, bool areas_only, const char* const* open_options = nullptr) {
  GDALAllRegister();
  std::unique_ptr<GDALDataset> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY,
                                                    nullptr, open_options, nullptr));
  if (!ds) return -1;
  OGRLayer* l = ds->GetLayerByName(layer);
  if (l == nullptr) return -1;
  const int idx = field == nullptr ? -1 : l->GetLayerDefn()->GetFieldIndex(field);
  int n = 0;
  for (auto& f : *l) {
    const OGRGeometry* g = f->GetGeometryRef();
    if (g == nullptr) continue;
    const auto t = wkbFlatten(g->getGeometryType());
    if (areas_only && t != wkbPolygon && t != wkbMultiPolygon) continue;
    if (idx >= 0 && !f->IsFieldSetAndNotNull(idx)) {
      n += count_null ? 1 : 0;
    } else if (idx < 0 || f->GetFieldAsDouble(idx) < limit) {
      ++n;
    }
  }
  return n;
}

void ExpectRouteAvoidsEverything(const ObstacleMap& map, const AlternativesResult& result) {
  ObstacleQuery q(map);
  ASSERT_FALSE(result.alternatives.empty());
  for (const Alternative& alt : result.alternatives) {
    EXPECT_FALSE(q.PolylineHits(alt.waypoints));
    for (const EastNorth& p : alt.waypoints) EXPECT_TRUE(map.Covers(p));
    // Sample the route densely too (independent of GEOS' segment test).
    for (size_t i = 1; i < alt.waypoints.size(); ++i) {
      const EastNorth a = alt.waypoints[i - 1], b = alt.waypoints[i];
      for (int s = 0; s <= 200; ++s) {
        const EastNorth p{a.east_m + (b.east_m - a.east_m) * s / 200,
                          a.north_m + (b.north_m - a.north_m) * s / 200};
        ASSERT_GT(q.DistanceM(p), 0.0)
            << "route touches an obstacle at " << p.east_m << ", " << p.north_m;
      }
    }
  }
}

TEST(NoaaUS4MD81M, ObstacleCountsPerLayer) {
  SEAPLAN_REQUIRE_SHARED(cell, "enc/noaa-US4MD81M/US4MD81M.000");
  ChartOptions o;
  o.min_depth_m = 5.0;
  auto map = LoadChartFile(cell.string(), o);
  ASSERT_TRUE(map.ok()) << map.status();
  const auto& layers = map->summary().features_per_layer;
  static const char* const kOpen[] = {"UPDATES=APPLY", nullptr};
  const std::string p = cell.string();
  EXPECT_EQ(layers.at("LNDARE"), CountBelow(p, "LNDARE", nullptr, 0, true, false, kOpen));
  EXPECT_EQ(layers.at("LNDARE"), 183);  // README: 183 (polygons and points)
  EXPECT_EQ(layers.at("DEPARE"), CountBelow(p, "DEPARE", "DRVAL1", 5.0, true, true, kOpen));
  EXPECT_EQ(layers.at("OBSTRN"), CountBelow(p, "OBSTRN", "VALSOU", 5.0, true, false, kOpen));
  EXPECT_EQ(layers.at("WRECKS"), CountBelow(p, "WRECKS", "VALSOU", 5.0, true, false, kOpen));
  EXPECT_EQ(layers.at("UWTROC"), CountBelow(p, "UWTROC", "VALSOU", 5.0, true, false, kOpen));
  EXPECT_GT(layers.at("DEPARE"), 100);
  EXPECT_LT(layers.at("DEPARE"), 525);
  EXPECT_EQ(map->frame().epsg(), 32618);
  EXPECT_EQ(map->summary().source_format, "S57");
  // Obstacles inside the cell's extent (README: lon -76.622..-75.998, lat 38.347..39.053).
  EXPECT_GT(map->summary().bbox_min.lon_deg, -76.63);
  EXPECT_LT(map->summary().bbox_max.lon_deg, -75.99);
  EXPECT_GT(map->summary().bbox_min.lat_deg, 38.34);
  EXPECT_LT(map->summary().bbox_max.lat_deg, 39.06);
  EXPECT_GT(map->summary().total_area_m2, 1e8);

  // A deeper minimum depth can only add obstacles.
  o.min_depth_m = 10.0;
  auto deeper = LoadChartFile(cell.string(), o);
  ASSERT_TRUE(deeper.ok());
  EXPECT_GT(deeper->summary().features_per_layer.at("DEPARE"), layers.at("DEPARE"));
  EXPECT_GT(deeper->summary().total_area_m2, map->summary().total_area_m2);
}

TEST(NoaaUS4MD81M, UploadedBytesWithUpdatesMatchTheFile) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/noaa-US4MD81M");
  std::vector<ChartFile> files;
  for (const char* ext : {"000", "001", "002", "003"}) {
    const std::string name = std::string("US4MD81M.") + ext;
    files.push_back({name, testing::ReadFile(dir / name)});
  }
  auto from_bytes = LoadChartBytes(files, ChartOptions{});
  auto from_file = LoadChartFile((dir / "US4MD81M.000").string(), ChartOptions{});
  ASSERT_TRUE(from_bytes.ok()) << from_bytes.status();
  ASSERT_TRUE(from_file.ok()) << from_file.status();
  EXPECT_EQ(from_bytes->summary().features_per_layer, from_file->summary().features_per_layer);
  EXPECT_DOUBLE_EQ(from_bytes->summary().total_area_m2, from_file->summary().total_area_m2);
  // And the stored blob reloads to the same map.
  auto reloaded = DeserializeObstacleMap(SerializeObstacleMap(*from_file));
  ASSERT_TRUE(reloaded.ok()) << reloaded.status();
  EXPECT_EQ(reloaded->polygons().size(), from_file->polygons().size());
  EXPECT_DOUBLE_EQ(reloaded->summary().total_area_m2, from_file->summary().total_area_m2);
}

TEST(NoaaUS4MD81M, RouteDownTheBayAvoidsEveryObstacle) {
  SEAPLAN_REQUIRE_SHARED(cell, "enc/noaa-US4MD81M/US4MD81M.000");
  auto map = LoadChartFile(cell.string(), ChartOptions{});
  ASSERT_TRUE(map.ok()) << map.status();
  // Chesapeake Bay south of the Bay Bridge, off Annapolis -> east of Cove Point.
  const EastNorth annapolis = map->frame().ToLocal({38.950, -76.405});
  const EastNorth cove_point = map->frame().ToLocal({38.400, -76.330});
  auto result = PlanAlternatives(*map, annapolis, cove_point);
  ASSERT_TRUE(result.ok()) << result.status();
  ExpectRouteAvoidsEverything(*map, *result);
  const double straight =
      std::hypot(cove_point.east_m - annapolis.east_m, cove_point.north_m - annapolis.north_m);
  EXPECT_LT(result->alternatives[0].length_m, 1.5 * straight);
  // A point on land (Kent Island) is refused with a clear message.
  auto on_land = PlanAlternatives(*map, map->frame().ToLocal({38.93, -76.25}), cove_point);
  EXPECT_EQ(on_land.status().code(), absl::StatusCode::kInvalidArgument) << on_land.status();
}

TEST(TrondheimGdb, ObstacleCountsAndRoute) {
  SEAPLAN_REQUIRE_SHARED(gdb, "enc/trondheim/Trondheim.gdb");
  ChartOptions o;
  o.min_depth_m = 5.0;
  auto map = LoadChartFile(gdb.string(), o);
  ASSERT_TRUE(map.ok()) << map.status();
  const auto& layers = map->summary().features_per_layer;
  EXPECT_EQ(layers.at("landareal"), 98);
  EXPECT_EQ(layers.at("torrfall"), 126);
  EXPECT_EQ(layers.at("skjer"), 12);
  EXPECT_EQ(layers.at("ikkekartlagtsjomaltomr"), 7);
  EXPECT_EQ(layers.at("dybdeareal"),
            CountBelow(gdb.string(), "dybdeareal", "minimumsdybde", 5.0, true, true));
  EXPECT_EQ(layers.at("grunne"), CountBelow(gdb.string(), "grunne", "dybde", 5.0, true, false));
  EXPECT_EQ(map->frame().epsg(), 32632);
  // Off Trondheim harbour (Ila) -> the fjord off Stjordal: around Lade.
  const EastNorth harbour = map->frame().ToLocal({63.4417, 10.3794});
  const EastNorth stjordal = map->frame().ToLocal({63.4837, 10.6114});
  const EastNorth fjord_west = map->frame().ToLocal({63.5011, 10.1243});
  for (const auto& [from, to] : {std::pair{harbour, stjordal}, std::pair{fjord_west, harbour}}) {
    auto result = PlanAlternatives(*map, from, to);
    ASSERT_TRUE(result.ok()) << result.status();
    ExpectRouteAvoidsEverything(*map, *result);
  }
}

// Zips a folder of the shared data in memory (GDAL's /vsizip/ writer), as the
// server receives an uploaded FileGDB folder or shapefile set.
std::string ZipFolder(const std::filesystem::path& dir, const std::string& prefix) {
  static int n = 0;
  const std::string zip = "/vsimem/chart_data_test_" + std::to_string(++n) + ".zip";
  const std::string entry_prefix = "/vsizip/" + zip + "/" + prefix;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file()) continue;
    const std::string rel = std::filesystem::relative(entry.path(), dir).string();
    const std::string bytes = testing::ReadFile(entry.path());
    VSILFILE* f = VSIFOpenL((entry_prefix + rel).c_str(), "wb");
    if (f == nullptr) return "";
    VSIFWriteL(bytes.data(), 1, bytes.size(), f);
    VSIFCloseL(f);
  }
  vsi_l_offset size = 0;
  GByte* data = VSIGetMemFileBuffer(zip.c_str(), &size, FALSE);
  std::string out(reinterpret_cast<const char*>(data), size);
  VSIUnlink(zip.c_str());
  return out;
}

TEST(TrondheimGdb, ZippedUploadMatchesTheFolder) {
  SEAPLAN_REQUIRE_SHARED(gdb, "enc/trondheim/Trondheim.gdb");
  const std::string zip = ZipFolder(gdb, "Trondheim.gdb/");
  ASSERT_FALSE(zip.empty());
  auto from_zip = LoadChartBytes({{"trondheim.zip", zip}}, ChartOptions{});
  auto from_dir = LoadChartFile(gdb.string(), ChartOptions{});
  ASSERT_TRUE(from_zip.ok()) << from_zip.status();
  ASSERT_TRUE(from_dir.ok()) << from_dir.status();
  EXPECT_EQ(from_zip->summary().features_per_layer, from_dir->summary().features_per_layer);
  EXPECT_DOUBLE_EQ(from_zip->summary().total_area_m2, from_dir->summary().total_area_m2);
}

TEST(AlesundShapefiles, ZippedUploadMatchesTheFolder) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/alesund/shapefiles");
  ChartOptions o;
  o.frame_epsg = 25833;
  auto from_zip = LoadChartBytes({{"alesund.zip", ZipFolder(dir, "")}}, o);
  auto from_dir = LoadChartFile(dir.string(), o);
  ASSERT_TRUE(from_zip.ok()) << from_zip.status();
  ASSERT_TRUE(from_dir.ok()) << from_dir.status();
  EXPECT_EQ(from_zip->summary().features_per_layer, from_dir->summary().features_per_layer);
  EXPECT_DOUBLE_EQ(from_zip->summary().total_area_m2, from_dir->summary().total_area_m2);
}

TEST(AlesundShapefiles, TwoAlternativesAroundTheIsland) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/alesund/shapefiles");
  SEAPLAN_REQUIRE_SHARED(route_csv, "enc/alesund/config/routes/route1.csv");
  ChartOptions o;
  o.min_depth_m = 5.0;
  o.frame_epsg = 25833;  // the set's own UTM33 coordinates, as route1.csv
  auto map = LoadChartFile(dir.string(), o);
  ASSERT_TRUE(map.ok()) << map.status();
  const auto& layers = map->summary().features_per_layer;
  EXPECT_EQ(layers.at("land"), 1);
  EXPECT_EQ(layers.at("shore"), 1);
  EXPECT_EQ(layers.count("chart_box-minus-seabed5m"), 1u);
  // Chart box: centre (39600, 6960500), 5040 x 2835 m.
  EXPECT_NEAR(map->summary().coverage.min.east_m, 39600 - 2520, 1.0);
  EXPECT_NEAR(map->summary().coverage.max.north_m, 6960500 + 1417.5, 1.0);

  std::ifstream in(route_csv);
  std::vector<EastNorth> route;
  double e = 0, n = 0;
  char comma = 0;
  while (in >> e >> comma >> n) route.push_back({e, n});
  ASSERT_EQ(route.size(), 4u);
  // route1.csv starts and ends outside the 5 x 3 km chart box: refused.
  auto outside = PlanAlternatives(*map, route.front(), route.back());
  EXPECT_EQ(outside.status().code(), absl::StatusCode::kInvalidArgument);
  // Its inner waypoints are in the box, on either side of the island.
  auto result = PlanAlternatives(*map, route[1], route[2]);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_FALSE(result->used_fallback) << result->note;
  ASSERT_GE(result->alternatives.size(), 2u);
  ExpectRouteAvoidsEverything(*map, *result);
  // The two shortest pass on opposite sides of the straight line.
  auto side = [&](const Alternative& alt) {
    double s = 0;
    const EastNorth a = route[1], b = route[2];
    for (const EastNorth& p : alt.waypoints) {
      s += (b.east_m - a.east_m) * (p.north_m - a.north_m) -
           (b.north_m - a.north_m) * (p.east_m - a.east_m);
    }
    return s;
  };
  EXPECT_LT(side(result->alternatives[0]) * side(result->alternatives[1]), 0.0);
}

TEST(AlesundShapefiles, DraftBetweenLayersUsesTheDeeperLayer) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/alesund/shapefiles");
  ChartOptions o;
  o.frame_epsg = 25833;
  o.min_depth_m = 5.0;
  auto at_5m = LoadChartFile(dir.string(), o);
  o.min_depth_m = 8.0;  // between seabed5m and seabed10m
  auto at_8m = LoadChartFile(dir.string(), o);
  ASSERT_TRUE(at_5m.ok()) << at_5m.status();
  ASSERT_TRUE(at_8m.ok()) << at_8m.status();
  EXPECT_EQ(at_8m->summary().features_per_layer.count("chart_box-minus-seabed10m"), 1u);
  // The 5-10 m water is an obstacle at 8 m.
  EXPECT_GT(at_8m->summary().total_area_m2, at_5m->summary().total_area_m2);
  o.min_depth_m = 150.0;  // deeper than seabed100m: no layer shows it
  auto too_deep = LoadChartFile(dir.string(), o);
  ASSERT_EQ(too_deep.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(too_deep.status().message().find("seabed100m"), absl::string_view::npos)
      << too_deep.status();
}

}  // namespace
}  // namespace seaplan::chart
