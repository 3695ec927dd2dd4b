// Developer tool: load a chart, print an ASCII map of its obstacles, run A1
// between two points and optionally write GeoJSON.
// Usage: chart_probe <chart> <min_depth_m> [frame_epsg] [x0 y0 x1 y1 (local) | lat0 lon0 lat1 lon1
// --latlon]
//        [--geojson out.json] [--cols N]
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "seaplan/chart/alternatives.h"
#include "seaplan/chart/geojson.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"

int main(int argc, char** argv) {
  using namespace seaplan::chart;
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: chart_probe <chart> <min_depth_m> [frame_epsg] [a b c d [--latlon]] "
                 "[--geojson f]\n");
    return 2;
  }
  std::vector<std::string> args(argv + 1, argv + argc);
  std::string geojson;
  bool latlon = false;
  int cols = 110;
  std::vector<std::string> pos;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--geojson" && i + 1 < args.size()) {
      geojson = args[++i];
    } else if (args[i] == "--latlon") {
      latlon = true;
    } else if (args[i] == "--cols" && i + 1 < args.size()) {
      cols = std::atoi(args[++i].c_str());
    } else {
      pos.push_back(args[i]);
    }
  }
  if (std::getenv("CHART_PROBE_DEBUG") != nullptr)
    seaplan::log::SetLevel(seaplan::log::Level::kDebug);
  ChartOptions options;
  options.min_depth_m = std::atof(pos[1].c_str());
  if (pos.size() > 2) options.frame_epsg = std::atoi(pos[2].c_str());
  auto map = LoadChartFile(pos[0], options);
  if (!map.ok()) {
    std::printf("load failed: %s\n", std::string(map.status().message()).c_str());
    return 1;
  }
  const LocalBox cov = map->summary().coverage;
  std::printf("EPSG:%d coverage (%.0f %.0f)-(%.0f %.0f), %d polygons\n", map->frame().epsg(),
              cov.min.east_m, cov.min.north_m, cov.max.east_m, cov.max.north_m,
              map->summary().polygon_count);
  std::vector<seaplan::EastNorth> ends;
  if (pos.size() >= 7) {
    for (int k = 0; k < 2; ++k) {
      const double a = std::atof(pos[3 + 2 * k].c_str()), b = std::atof(pos[4 + 2 * k].c_str());
      ends.push_back(latlon ? map->frame().ToLocal({a, b}) : seaplan::EastNorth{a, b});
    }
  }
  std::vector<NamedRoute> routes;
  if (ends.size() == 2) {
    auto alts = PlanAlternatives(*map, ends[0], ends[1]);
    if (!alts.ok()) {
      std::printf("A1: %s\n", std::string(alts.status().message()).c_str());
    } else {
      std::printf("A1: %zu alternative(s), fallback=%d, note: %s\n", alts->alternatives.size(),
                  alts->used_fallback, alts->note.c_str());
      for (size_t i = 0; i < alts->alternatives.size(); ++i) {
        const auto& a = alts->alternatives[i];
        std::printf("  #%zu length %.0f m:", i, a.length_m);
        for (const auto& p : a.waypoints) std::printf(" (%.0f %.0f)", p.east_m, p.north_m);
        std::printf("\n");
        routes.push_back({"alt" + std::to_string(i), a.waypoints});
      }
    }
  }
  // ASCII map: '#' obstacle, '.' free, digits = route i, S/G ends.
  ObstacleQuery q(*map);
  const int rows = static_cast<int>(cols * (cov.max.north_m - cov.min.north_m) /
                                    (cov.max.east_m - cov.min.east_m) / 2.0);
  std::vector<std::string> grid(rows, std::string(cols, '.'));
  const double dx = (cov.max.east_m - cov.min.east_m) / cols,
               dy = (cov.max.north_m - cov.min.north_m) / rows;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (q.Inside({cov.min.east_m + (c + 0.5) * dx, cov.max.north_m - (r + 0.5) * dy}))
        grid[r][c] = '#';
    }
  }
  auto plot = [&](seaplan::EastNorth p, char ch) {
    const int c = static_cast<int>((p.east_m - cov.min.east_m) / dx),
              r = static_cast<int>((cov.max.north_m - p.north_m) / dy);
    if (r >= 0 && r < rows && c >= 0 && c < cols) grid[r][c] = ch;
  };
  for (size_t i = 0; i < routes.size(); ++i) {
    const auto& w = routes[i].waypoints;
    for (size_t k = 1; k < w.size(); ++k) {
      for (int s = 0; s <= 200; ++s) {
        plot({w[k - 1].east_m + (w[k].east_m - w[k - 1].east_m) * s / 200,
              w[k - 1].north_m + (w[k].north_m - w[k - 1].north_m) * s / 200},
             static_cast<char>('0' + i % 10));
      }
    }
  }
  if (ends.size() == 2) {
    plot(ends[0], 'S');
    plot(ends[1], 'G');
  }
  for (const auto& line : grid) std::printf("%s\n", line.c_str());
  if (!geojson.empty()) {
    std::ofstream(geojson) << ToGeoJson(*map, routes);
  }
  return 0;
}
