// Chart loading / obstacle building / query timings on the shared charts.
// Usage: chart_bench [shared_dir] [min_depth_m]   (default ../shared, 5 m)
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "seaplan/chart/alternatives.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"

namespace {

using Clock = std::chrono::steady_clock;
double Ms(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

struct Case {
  const char* name;
  std::string path;
  int frame_epsg;
  seaplan::chart::LatLon from, to;  // two sea points for an A1 run
};

}  // namespace

int main(int argc, char** argv) {
  using namespace seaplan::chart;
  const std::string shared = argc > 1 ? argv[1] : "../shared";
  // Stage timings of the loader are logged at debug level.
  seaplan::log::SetLevel(seaplan::log::Level::kDebug);
  const double min_depth = argc > 2 ? std::atof(argv[2]) : 5.0;
  const std::vector<Case> cases = {
      {"noaa-US4MD81M", shared + "/enc/noaa-US4MD81M/US4MD81M.000", 0, {38.98, -76.38}, {38.40, -76.20}},
      {"trondheim", shared + "/enc/trondheim/Trondheim.gdb", 0, {63.45, 10.30}, {63.47, 10.65}},
      {"alesund", shared + "/enc/alesund/shapefiles", 25833, {0, 0}, {0, 0}},
  };
  std::printf("%-14s %9s %9s %9s %8s %8s %12s %12s %10s\n", "chart", "load_ms", "query_ms", "ser_ms", "deser_ms",
              "polys", "vertices", "dist_q/s", "a1_ms");
  int failures = 0;
  for (const Case& c : cases) {
    ChartOptions options;
    options.min_depth_m = min_depth;
    options.frame_epsg = c.frame_epsg;
    const auto t0 = Clock::now();
    auto map = LoadChartFile(c.path, options);
    const auto t1 = Clock::now();
    if (!map.ok()) {
      std::printf("%-14s FAILED: %s\n", c.name, std::string(map.status().message()).c_str());
      ++failures;
      continue;
    }
    ObstacleQuery query(*map);
    const auto t2 = Clock::now();
    const std::string blob = SerializeObstacleMap(*map);
    const auto t3 = Clock::now();
    auto again = DeserializeObstacleMap(blob);
    const auto t4 = Clock::now();
    if (!again.ok()) ++failures;
    // Random distance queries inside the obstacle bounds.
    const LocalBox b = map->bounds();
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> ux(b.min.x_m, b.max.x_m), uy(b.min.y_m, b.max.y_m);
    constexpr int kQueries = 20000;
    double sink = 0;
    const auto t5 = Clock::now();
    for (int i = 0; i < kQueries; ++i) sink += query.DistanceM({ux(rng), uy(rng)});
    const auto t6 = Clock::now();
    double a1_ms = -1;
    if (c.from.lat_deg != 0) {
      const auto t7 = Clock::now();
      auto alts = PlanAlternatives(*map, map->frame().ToLocal(c.from), map->frame().ToLocal(c.to));
      a1_ms = Ms(t7, Clock::now());
      if (!alts.ok()) std::printf("  A1: %s\n", std::string(alts.status().message()).c_str());
    }
    std::printf("%-14s %9.1f %9.1f %9.1f %8.1f %8d %12d %12.0f %10.1f\n", c.name, Ms(t0, t1), Ms(t1, t2), Ms(t2, t3),
                Ms(t3, t4), map->summary().polygon_count, map->summary().vertex_count,
                kQueries / (Ms(t5, t6) / 1000.0), a1_ms);
    std::printf("  layers:");
    for (const auto& [layer, count] : map->summary().features_per_layer) std::printf(" %s=%d", layer.c_str(), count);
    std::printf("  frame EPSG:%d  area %.2f km2  blob %zu B%s\n", map->frame().epsg(),
                map->summary().total_area_m2 / 1e6, blob.size(), sink < 0 ? "!" : "");
  }
  return failures == 0 ? 0 : 1;
}
