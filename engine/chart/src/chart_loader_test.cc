#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include "cpl_vsi.h"
#include "gdal_priv.h"
#include "ogrsf_frmts.h"
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
  const std::string entry_prefix = "/vsizip/" + zip + "/";
  for (const auto& [name, bytes] : files) {
    VSILFILE* f = VSIFOpenL((entry_prefix + name).c_str(), "wb");
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

TEST(ChartLoader, SeabedLayersChooseTheShallowestAtLeastMinDepth) {
  // Chart box 6.10-6.12 E, 62.47-62.48 N; "sea at least N m deep" shrinks
  // with N: 0-5 m water from 6.102 E, 5-10 m from 6.105 E, 10 m+ from 6.110 E.
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
  // (min depth, layer used, first navigable longitude)
  for (const auto& [depth, layer, free_lon] :
       {std::tuple{7.0, "chart_box-minus-seabed10m", 6.110},
        std::tuple{5.0, "chart_box-minus-seabed5m", 6.105},
        std::tuple{10.0, "chart_box-minus-seabed10m", 6.110},
        std::tuple{0.0, "chart_box-minus-seabed0m", 6.102},
        std::tuple{0.5, "chart_box-minus-seabed5m", 6.105}}) {
    o.min_depth_m = depth;
    auto map = LoadChartBytes(files, o);
    ASSERT_TRUE(map.ok()) << map.status();
    EXPECT_EQ(map->summary().features_per_layer.count(layer), 1u) << depth;
    ObstacleQuery q(*map);
    EXPECT_FALSE(q.Inside(map->frame().ToLocal({62.475, free_lon + 0.001}))) << depth;
    // Water shallower than the minimum depth (just before free_lon) is an
    // obstacle: at 7 m the 5-10 m band is, at 0.5 m the 0-5 m band.
    EXPECT_TRUE(q.Inside(map->frame().ToLocal({62.475, free_lon - 0.001}))) << depth;
  }
  // Deeper than every layer: no layer can tell where the water is 12 m deep,
  // so the load fails instead of using seabed10m.
  o.min_depth_m = 12;
  auto too_deep = LoadChartBytes(files, o);
  ASSERT_EQ(too_deep.status().code(), absl::StatusCode::kInvalidArgument);
  EXPECT_NE(too_deep.status().message().find("N >= min depth 12 m"), absl::string_view::npos)
      << too_deep.status();
  EXPECT_NE(too_deep.status().message().find("seabed10m"), absl::string_view::npos)
      << too_deep.status();
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
  for (const char* name :
       {"../etc/passwd", "/etc/passwd", "set//land.geojson", "set/./x", "set/"}) {
    EXPECT_EQ(LoadChartBytes({{name, "x"}}, ChartOptions{}).status().code(),
              absl::StatusCode::kInvalidArgument)
        << name;
  }
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

// Points with a "dybde" (depth) attribute, 2 m and 20 m deep.
std::string Soundings(const std::string& layer_name) {
  return "{\"type\":\"FeatureCollection\"," +
         (layer_name.empty() ? std::string() : "\"name\":\"" + layer_name + "\",") +
         "\"features\":["
         "{\"type\":\"Feature\",\"properties\":{\"dybde\":2.0},"
         "\"geometry\":{\"type\":\"Point\",\"coordinates\":[6.101,62.471]}},"
         "{\"type\":\"Feature\",\"properties\":{\"dybde\":20.0},"
         "\"geometry\":{\"type\":\"Point\",\"coordinates\":[6.109,62.479]}}]}";
}

TEST(ChartLoader, LayersAreRecognisedBySchemaNotByFileName) {
  ChartOptions o;
  o.min_depth_m = 5;
  // The same depth-attributed points under three file names, one of them
  // named like a land-area export: the depth field decides (2 m < 5 m is an
  // obstacle, 20 m is not), whatever the file is called.
  for (const char* file :
       {"soundings.geojson", "trondheim_landareal_points.geojson", "x.geojson"}) {
    auto map = LoadChartBytes({{file, Soundings("")}}, o);
    ASSERT_TRUE(map.ok()) << file << ": " << map.status();
    const std::string layer = std::filesystem::path(file).stem().string();
    EXPECT_EQ(map->summary().features_per_layer.at(layer), 1) << file;
    ObstacleQuery q(*map);
    EXPECT_TRUE(q.Inside(map->frame().ToLocal({62.471, 6.101}))) << file;
    EXPECT_FALSE(q.Inside(map->frame().ToLocal({62.479, 6.109}))) << file;
  }
  // A Kartverket product layer name (the GeoJSON "name" member) is
  // recognised whatever the file is called.
  auto named = LoadChartBytes({{"export.geojson", Soundings("grunne")}}, o);
  ASSERT_TRUE(named.ok()) << named.status();
  EXPECT_EQ(named->summary().features_per_layer.at("grunne"), 1);
}

// Writes a small FileGDB (GDAL's OpenFileGDB writer) with a Kartverket
// "landareal" layer: one land square, 6.100-6.102 E, 62.470-62.472 N.
std::filesystem::path WriteFileGdb(const std::filesystem::path& folder) {
  GDALAllRegister();
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("OpenFileGDB");
  if (driver == nullptr) return {};
  std::filesystem::path gdb = folder / "Harbour.gdb";
  std::unique_ptr<GDALDataset> ds(
      driver->Create(gdb.string().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) return {};
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRLayer* layer = ds->CreateLayer("landareal", &wgs84, wkbPolygon, nullptr);
  if (layer == nullptr) return {};
  OGRPolygon square;
  OGRLinearRing ring;
  for (const auto& [lon, lat] : std::vector<std::pair<double, double>>{
           {6.100, 62.470}, {6.102, 62.470}, {6.102, 62.472}, {6.100, 62.472}, {6.100, 62.470}}) {
    ring.addPoint(lon, lat);
  }
  square.addRing(&ring);
  OGRFeature feature(layer->GetLayerDefn());
  feature.SetGeometry(&square);
  if (layer->CreateFeature(&feature) != OGRERR_NONE) return {};
  return gdb;
}

TEST(ChartLoader, FileGdbAndShapefileFoldersByPathAndAsUploadedFolders) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("seaplan_chart_folder_" + std::to_string(getpid()));
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  const std::filesystem::path gdb = WriteFileGdb(folder);
  ASSERT_FALSE(gdb.empty()) << "GDAL could not write a FileGDB";
  ChartOptions o;
  o.safety_buffer_m = 0;
  o.simplify_tolerance_m = 0;
  auto by_path = LoadChartFile(gdb.string() + "/", o);
  ASSERT_TRUE(by_path.ok()) << by_path.status();
  EXPECT_EQ(by_path->summary().source_format, "OpenFileGDB");
  EXPECT_EQ(by_path->summary().features_per_layer.at("landareal"), 1);
  double per = 0;
  const double area = RectArea(by_path->frame(), 6.100, 62.470, 6.102, 62.472, &per);
  EXPECT_NEAR(by_path->summary().total_area_m2, area, 1e-3 * area);

  // The same folder uploaded file by file, named by paths inside it (what
  // the CLI sends for --chart-file Harbour.gdb).
  std::vector<ChartFile> files;
  for (const auto& entry : std::filesystem::directory_iterator(gdb)) {
    files.push_back({"Harbour.gdb/" + entry.path().filename().string(),
                     testing::ReadFile(entry.path().string())});
  }
  ASSERT_GT(files.size(), 1u);
  auto uploaded = LoadChartBytes(files, o);
  ASSERT_TRUE(uploaded.ok()) << uploaded.status();
  EXPECT_DOUBLE_EQ(uploaded->summary().total_area_m2, by_path->summary().total_area_m2);

  // A folder of sets in subfolders (the seacharts layout), by path and uploaded.
  std::filesystem::create_directories(folder / "set" / "soundings");
  std::ofstream(folder / "set" / "soundings" / "soundings.geojson") << Soundings("");
  o.min_depth_m = 5;
  auto set = LoadChartFile((folder / "set").string(), o);
  ASSERT_TRUE(set.ok()) << set.status();
  EXPECT_EQ(set->summary().features_per_layer.at("soundings"), 1);
  auto set_uploaded = LoadChartBytes({{"set/soundings/soundings.geojson", Soundings("")}}, o);
  ASSERT_TRUE(set_uploaded.ok()) << set_uploaded.status();
  EXPECT_DOUBLE_EQ(set_uploaded->summary().total_area_m2, set->summary().total_area_m2);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace seaplan::chart
