// Chart benchmark: time to load a chart and build its obstacles (GDAL read,
// projection, GEOS union/buffer/simplify), to (de)serialize the stored blob,
// point-distance query throughput, and one Level-1 (A1) planning call between
// two named sea points. Target: NOAA US4MD81M load + build < 2 s.
//
// Usage: chart_bench [shared_dir=../shared] [min_depth_m=5] [repeats=3]
#include <algorithm>
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
  // Two sea points for A1: lat/lon, or frame coordinates when local is set.
  bool local;
  double a0, a1, b0, b1;
};

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  using namespace seaplan::chart;
  const std::string shared = argc > 1 ? argv[1] : "../shared";
  const double min_depth = argc > 2 ? std::atof(argv[2]) : 5.0;
  const int repeats = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  seaplan::log::SetLevel(seaplan::log::Level::kWarn);
  const std::vector<Case> cases = {
      // Chesapeake Bay off Annapolis -> east of Cove Point.
      {"noaa-US4MD81M", shared + "/enc/noaa-US4MD81M/US4MD81M.000", 0, false, 38.950, -76.405,
       38.400, -76.330},
      // Off Trondheim harbour (Ila) -> the fjord off Stjordal.
      {"trondheim", shared + "/enc/trondheim/Trondheim.gdb", 0, false, 63.4417, 10.3794, 63.4837,
       10.6114},
      // route1.csv waypoints 2 -> 3 (UTM33), around the island.
      {"alesund", shared + "/enc/alesund/shapefiles", 25833, true, 41200, 6959900, 38000, 6961100},
  };
  std::printf("min depth %.1f m, %d repeat(s); times in ms (median, min)\n", min_depth, repeats);
  std::printf("%-14s %15s %8s %8s %7s %9s %11s %9s %5s\n", "chart", "load+build", "query0", "ser",
              "deser", "polygons", "dist_q/s", "a1", "alts");
  int failures = 0;
  for (const Case& c : cases) {
    ChartOptions options;
    options.min_depth_m = min_depth;
    options.frame_epsg = c.frame_epsg;
    std::vector<double> load_ms;
    seaplan::StatusOr<ObstacleMap> map = absl::UnknownError("not run");
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = Clock::now();
      map = LoadChartFile(c.path, options);
      load_ms.push_back(Ms(t0, Clock::now()));
      if (!map.ok()) break;
    }
    if (!map.ok()) {
      std::printf("%-14s FAILED: %s\n", c.name, std::string(map.status().message()).c_str());
      ++failures;
      continue;
    }
    const auto t1 = Clock::now();
    ObstacleQuery query(*map);
    const auto t2 = Clock::now();
    const std::string blob = SerializeObstacleMap(*map);
    const auto t3 = Clock::now();
    auto again = DeserializeObstacleMap(blob);
    const auto t4 = Clock::now();
    if (!again.ok()) ++failures;
    const LocalBox b = map->bounds();
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> ux(b.min.east_m, b.max.east_m),
        uy(b.min.north_m, b.max.north_m);
    constexpr int kQueries = 20000;
    double sink = 0;
    const auto t5 = Clock::now();
    for (int i = 0; i < kQueries; ++i) sink += query.DistanceM({ux(rng), uy(rng)});
    const auto t6 = Clock::now();
    const seaplan::EastNorth from =
        c.local ? seaplan::EastNorth{c.a0, c.a1} : map->frame().ToLocal({c.a0, c.a1});
    const seaplan::EastNorth to =
        c.local ? seaplan::EastNorth{c.b0, c.b1} : map->frame().ToLocal({c.b0, c.b1});
    const auto t7 = Clock::now();
    auto alts = PlanAlternatives(*map, from, to);
    const double a1_ms = Ms(t7, Clock::now());
    if (!alts.ok()) {
      std::printf("  A1 failed: %s\n", std::string(alts.status().message()).c_str());
      ++failures;
    }
    char load[32];
    std::snprintf(load, sizeof(load), "%.0f, %.0f", Median(load_ms),
                  *std::min_element(load_ms.begin(), load_ms.end()));
    std::printf("%-14s %15s %8.1f %8.1f %7.1f %9d %11.0f %9.1f %5zu\n", c.name, load, Ms(t1, t2),
                Ms(t2, t3), Ms(t3, t4), map->summary().polygon_count,
                kQueries / (Ms(t5, t6) / 1000.0), a1_ms, alts.ok() ? alts->alternatives.size() : 0);
    std::printf("  layers:");
    for (const auto& [layer, count] : map->summary().features_per_layer)
      std::printf(" %s=%d", layer.c_str(), count);
    std::printf("\n  frame EPSG:%d, %d vertices, %.2f km2, blob %zu bytes%s%s\n",
                map->frame().epsg(), map->summary().vertex_count,
                map->summary().total_area_m2 / 1e6, blob.size(),
                alts.ok() && alts->used_fallback ? ", A1 used the visibility-graph fallback" : "",
                sink < 0 ? "!" : "");
  }
  return failures == 0 ? 0 : 1;
}
