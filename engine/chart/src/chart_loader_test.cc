#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cpl_vsi.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::chart {
namespace {

std::string HarbourPath() {
  return (testing::SourceDir() / "engine/chart/testdata/harbour.geojson").string();
}

// Shoelace area of a lon/lat rectangle projected into `frame`.
double RectArea(const LocalFrame& f, double lon0, double lat0, double lon1, double lat1,
                double* perimeter) {
  const EastNorth a = f.ToLocal({lat0, lon0}), b = f.ToLocal({lat0, lon1}),
                  c = f.ToLocal({lat1, lon1}), d = f.ToLocal({lat1, lon0});
  const EastNorth pts[4] = {a, b, c, d};
  double area = 0, per = 0;
  for (int i = 0; i < 4; ++i) {
    const EastNorth& p = pts[i];
    const EastNorth& q = pts[(i + 1) % 4];
    area += (p.east_m - a.east_m) * (q.north_m - a.north_m) -
            (q.east_m - a.east_m) * (p.north_m - a.north_m);
    per += std::hypot(q.east_m - p.east_m, q.north_m - p.north_m);
  }
  *perimeter = per;
  return std::abs(area) / 2;
}

// Builds a zip in memory through GDAL's /vsizip/ writer.
std::string MakeZip(const std::vector<std::pair<std::string, std::string>>& files) {
  static int n = 0;
  const std::string zip = "/vsimem/chart_loader_test_" + std::to_string(++n) + ".zip";
  for (const auto& [name, bytes] : files) {
    VSILFILE* f = VSIFOpenL(("/vsizip/" + zip + "/" + name).c_str(), "wb");
    EXPECT_NE(f, nullptr);
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

TEST(ChartLoader, HandWrittenGeoJson) {
  ChartOptions o;
  o.min_depth_m = 5;
  o.safety_buffer_m = 10;
  o.point_hazard_radius_m = 20;
  o.simplify_tolerance_m = 0;
  auto map = LoadChartFile(HarbourPath(), o);
  ASSERT_TRUE(map.ok()) << map.status();
  EXPECT_EQ(map->frame().epsg(), 32632);  // 6.1 E is UTM zone 32
  EXPECT_EQ(map->summary().source_format, "GeoJSON");
  EXPECT_EQ(map->summary().features_per_layer.at("harbour"), 3);  // land, shallow, rock
  ASSERT_EQ(map->polygons().size(), 2u);                          // land+shallow merged, rock
  double per = 0;
  const double box = RectArea(map->frame(), 6.100, 62.470, 6.106, 62.472, &per);
  const double expected = box + per * 10 + M_PI * 100 + M_PI * 30 * 30;
  EXPECT_NEAR(map->summary().total_area_m2, expected, 0.01 * expected);
  ObstacleQuery q(*map);
  EXPECT_TRUE(q.Inside(map->frame().ToLocal({62.471, 6.105})));    // shallow
  EXPECT_FALSE(q.Inside(map->frame().ToLocal({62.4705, 6.108})));  // deep
  EXPECT_TRUE(q.Inside(map->frame().ToLocal({62.4715, 6.1102})));  // rock disc
  EXPECT_TRUE(map->Covers(map->frame().ToLocal({62.471, 6.108})));
  EXPECT_FALSE(map->Covers(map->frame().ToLocal({62.60, 6.108})));

  o.min_depth_m = 1;  // the 2 m area is deep enough now
  auto shallow_ok = LoadChartFile(HarbourPath(), o);
  ASSERT_TRUE(shallow_ok.ok());
  EXPECT_EQ(shallow_ok->summary().features_per_layer.at("harbour"), 2);
  ObstacleQuery q2(*shallow_ok);
  EXPECT_FALSE(q2.Inside(shallow_ok->frame().ToLocal({62.471, 6.1052})));

  o.unknown_depth_is_obstacle = false;  // the rock (and the depth-less land) go
  auto no_unknown = LoadChartFile(HarbourPath(), o);
  ASSERT_TRUE(no_unknown.ok());
  EXPECT_EQ(no_unknown->summary().features_per_layer.at("harbour"), 0);
}

TEST(ChartLoader, BytesAndZipGiveTheSameChart) {
  const std::string bytes = testing::ReadFile(HarbourPath());
  ASSERT_FALSE(bytes.empty());
  auto from_file = LoadChartFile(HarbourPath(), ChartOptions{});
  auto from_bytes = LoadChartBytes({{"harbour.geojson", bytes}}, ChartOptions{});
  ASSERT_TRUE(from_file.ok() && from_bytes.ok()) << from_bytes.status();
  EXPECT_DOUBLE_EQ(from_bytes->summary().total_area_m2, from_file->summary().total_area_m2);
  const std::string zip = MakeZip({{"upload/harbour.geojson", bytes},
                                   {"upload/readme.txt", "hello"},
                                   {"upload/metadata.json", "{\"not\": \"a chart\"}"}});
  auto from_zip = LoadChartBytes({{"chart.zip", zip}}, ChartOptions{});
  ASSERT_TRUE(from_zip.ok()) << from_zip.status();
  EXPECT_DOUBLE_EQ(from_zip->summary().total_area_m2, from_file->summary().total_area_m2);
  EXPECT_EQ(from_zip->summary().features_per_layer.at("harbour"), 3);
  // The stray metadata.json is skipped with a warning naming it.
  ASSERT_FALSE(from_zip->summary().warnings.empty());
  EXPECT_NE(from_zip->summary().warnings.back().find("metadata.json"), std::string::npos);
}

TEST(ChartLoader, SeabedLayersChooseTheDeepestAtMostMinDepth) {
  // Chart box 6.10-6.12 E, 62.47-62.48 N; "sea deeper than N m" shrinks with N.
  auto rect = [](double lon0, double lat0, double lon1, double lat1) {
    char buf[512];
    std::snprintf(
        buf, sizeof(buf),
        "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
        "\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[[[%f,%f],[%f,%f],[%f,%f],[%f,%f],[%f,%"
        "f]]]}}]}",
        lon0, lat0, lon1, lat0, lon1, lat1, lon0, lat1, lon0, lat0);
    return std::string(buf);
  };
  const std::vector<ChartFile> files = {
      {"land.geojson", rect(6.100, 62.470, 6.102, 62.480)},
      {"seabed0m.geojson", rect(6.102, 62.470, 6.120, 62.480)},
      {"seabed5m.geojson", rect(6.105, 62.470, 6.120, 62.480)},
      {"seabed10m.geojson", rect(6.110, 62.470, 6.120, 62.480)},
  };
  ChartOptions o;
  o.safety_buffer_m = 0;
  o.simplify_tolerance_m = 0;
  for (const auto& [depth, layer, free_lon] :
       {std::tuple{7.0, "chart_box-minus-seabed5m", 6.106},
        std::tuple{10.0, "chart_box-minus-seabed10m", 6.111},
        std::tuple{0.0, "chart_box-minus-seabed0m", 6.103}}) {
    o.min_depth_m = depth;
    auto map = LoadChartBytes(files, o);
    ASSERT_TRUE(map.ok()) << map.status();
    EXPECT_EQ(map->summary().features_per_layer.count(layer), 1u) << depth;
    ObstacleQuery q(*map);
    EXPECT_FALSE(q.Inside(map->frame().ToLocal({62.475, free_lon}))) << depth;
    EXPECT_TRUE(q.Inside(map->frame().ToLocal({62.475, free_lon - 0.0015}))) << depth;
  }
  o.min_depth_m = 3;
  auto missing = LoadChartBytes({files[0], files[2]}, o);  // only seabed5m
  ASSERT_EQ(missing.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(missing.status().message().find("seabed"), absl::string_view::npos);
}

TEST(ChartLoader, SelfIntersectingPolygonIsRepaired) {
  const std::string bowtie =
      "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
      "\"geometry\":"
      "{\"type\":\"Polygon\",\"coordinates\":[[[6.10,62.47],[6.11,62.48],[6.11,62.47],[6.10,62.48],"
      "[6.10,62.47]]]}}]}";
  auto map = LoadChartBytes({{"obstacles.geojson", bowtie}}, ChartOptions{});
  ASSERT_TRUE(map.ok()) << map.status();
  ASSERT_FALSE(map->summary().warnings.empty());
  EXPECT_NE(map->summary().warnings[0].find("repaired"), std::string::npos);
  EXPECT_GT(map->summary().total_area_m2, 0.0);
}

TEST(ChartLoader, BadInputGivesClearErrors) {
  auto garbage = LoadChartBytes({{"US0BAD00.000", std::string(5000, '\x42')}}, ChartOptions{});
  ASSERT_EQ(garbage.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(garbage.status().message().find("US0BAD00.000"), absl::string_view::npos)
      << garbage.status();

  auto not_json = LoadChartBytes({{"chart.geojson", "{ this is not json"}}, ChartOptions{});
  ASSERT_EQ(not_json.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(not_json.status().message().find("chart.geojson"), absl::string_view::npos);

  auto empty = LoadChartBytes(
      {{"empty.geojson", "{\"type\":\"FeatureCollection\",\"features\":[]}"}}, ChartOptions{});
  ASSERT_EQ(empty.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(empty.status().message().find("no features"), absl::string_view::npos)
      << empty.status();

  auto bad_zip =
      LoadChartBytes({{"upload.zip", "PK\x03\x04 definitely not a zip"}}, ChartOptions{});
  ASSERT_EQ(bad_zip.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(bad_zip.status().message().find("zip"), absl::string_view::npos) << bad_zip.status();

  const std::string zip = MakeZip({{"docs/readme.txt", "no chart in here"}});
  auto no_chart = LoadChartBytes({{"upload.zip", zip}}, ChartOptions{});
  ASSERT_EQ(no_chart.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(no_chart.status().message().find("no chart found"), absl::string_view::npos)
      << no_chart.status();

  EXPECT_EQ(LoadChartFile("/nonexistent/chart.000", ChartOptions{}).status().code(),
            absl::StatusCode::kNotFound);
  EXPECT_EQ(LoadChartBytes({}, ChartOptions{}).status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_EQ(LoadChartBytes({{"../etc/passwd", "x"}}, ChartOptions{}).status().code(),
            absl::StatusCode::kInvalidArgument);
  ChartOptions bad;
  bad.min_depth_m = -3;
  EXPECT_EQ(LoadChartFile(HarbourPath(), bad).status().code(), absl::StatusCode::kInvalidArgument);
  bad = {};
  bad.frame_epsg = 4326;
  EXPECT_EQ(LoadChartFile(HarbourPath(), bad).status().code(), absl::StatusCode::kInvalidArgument);

  // Coordinates that are not positions (a projected file without .prj read as lon/lat).
  const std::string far =
      "{\"type\":\"FeatureCollection\",\"features\":[{\"type\":\"Feature\",\"properties\":{},"
      "\"geometry\":"
      "{\"type\":\"Polygon\",\"coordinates\":[[[400000,6900000],[400100,6900000],[400100,6900100],["
      "400000,6900000]]]}}]}";
  auto projected = LoadChartBytes({{"land.geojson", far}}, ChartOptions{});
  ASSERT_EQ(projected.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(projected.status().message().find("coordinate system"), absl::string_view::npos)
      << projected.status();
}

}  // namespace
}  // namespace seaplan::chart
