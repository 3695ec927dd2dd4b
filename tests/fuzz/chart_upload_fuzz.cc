// libFuzzer target: uploaded chart bytes -> obstacle map, as UploadChart
// loads them (chart::LoadChartBytes: GDAL reading from /vsimem, GEOS), then
// the stored form back (SerializeObstacleMap / DeserializeObstacleMap).
// Input: first byte picks the uploaded file's name (so the driver GDAL
// tries), the rest is the file. Any bytes end in an error status or a map,
// never a crash; a map round-trips through its stored form.
//
// Also fed to DeserializeObstacleMap directly: the stored blob is read back
// from the database, where it could be damaged.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"

namespace {

// Names whose extensions pick the drivers a chart upload can reach.
constexpr const char* kNames[] = {"chart.geojson", "chart.json", "cell.000",  "chart.zip",
                                  "land.shp",      "chart.gml",  "chart.kml", "chart"};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const bool quiet = [] {
    seaplan::log::SetLevel(seaplan::log::Level::kOff);  // a line per input drowns the fuzzer's
    return true;
  }();
  (void)quiet;
  if (size == 0) return 0;
  const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  (void)seaplan::chart::DeserializeObstacleMap(rest);

  seaplan::chart::ChartOptions options;
  const std::string name = kNames[data[0] % (sizeof(kNames) / sizeof(kNames[0]))];
  auto map = seaplan::chart::LoadChartBytes({{name, std::string(rest)}}, options);
  if (!map.ok()) return 0;
  const std::string stored = seaplan::chart::SerializeObstacleMap(*map);
  auto back = seaplan::chart::DeserializeObstacleMap(stored);
  if (!back.ok()) std::abort();
  if (back->summary().polygon_count != map->summary().polygon_count) std::abort();
  return 0;
}
