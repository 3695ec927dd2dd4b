// Route planner coverage and safety on the real charts: seeded random
// origin/destination pairs in navigable water (engine/route route_sweep.h),
// per chart: how many pairs Level 1 connects, how many of those get a route,
// how many routes come within the safety margin of an UNBUFFERED obstacle
// (exact GEOS distance), and the time per route (median, p95) with its ratio
// to the Level-1 time measured in the same run.
//
// Usage: route_pairs_bench [shared_dir] [--pairs N] [--seed S] [--chart noaa|trondheim|alesund]
//                          [--min-depth M] [--verbose]
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"
#include "seaplan/route/route_planner.h"
#include "seaplan/route/route_sweep.h"

using namespace seaplan;

namespace {

struct ChartCase {
  std::string name;
  std::string path;  // under the shared folder
  double min_depth_m;
};

int RunCase(const std::string& shared, const ChartCase& c, const route::SweepOptions& sweep,
            bool verbose) {
  chart::ChartOptions copt;
  copt.min_depth_m = c.min_depth_m;
  auto map = chart::LoadChartFile(shared + "/" + c.path, copt);
  if (!map.ok()) {
    std::printf("%-10s load failed: %s\n", c.name.c_str(), map.status().ToString().c_str());
    return 1;
  }
  auto shared_map = std::make_shared<const chart::ObstacleMap>(std::move(*map));
  route::RouteOptions ropt;
  ropt.min_depth_m = c.min_depth_m;
  auto planner = route::RoutePlanner::Create(shared_map, route::ShipParticulars{}, ropt);
  if (!planner.ok()) {
    std::printf("%-10s planner failed: %s\n", c.name.c_str(), planner.status().ToString().c_str());
    return 1;
  }
  auto result = route::RunRouteSweep(*planner, *shared_map, route::Environment{}, sweep);
  if (!result.ok()) {
    std::printf("%-10s sweep failed: %s\n", c.name.c_str(), result.status().ToString().c_str());
    return 1;
  }
  std::vector<double> route_s, level1_s;
  double min_clearance = 1e300;
  int failures_shown = 0;
  for (const route::PairOutcome& p : result->pairs) {
    if (!p.level1_connected) continue;
    route_s.push_back(p.route_wall_s);
    level1_s.push_back(p.level1_wall_s);
    if (p.routed) min_clearance = std::min(min_clearance, p.clearance_m);
    const bool bad = !p.routed || p.clearance_m < result->margin_m - 1e-3;
    if (bad && (verbose || failures_shown < 3)) {
      ++failures_shown;
      std::printf("    %s (%.0f, %.0f) -> (%.0f, %.0f): %s clearance %.2f m\n",
                  p.routed ? "CLOSE" : "FAILED", p.from.east_m, p.from.north_m, p.to.east_m,
                  p.to.north_m, p.error.c_str(), p.clearance_m);
    }
  }
  const double med = route::Percentile(route_s, 0.5), p95 = route::Percentile(route_s, 0.95);
  const double l1_med = route::Percentile(level1_s, 0.5);
  std::printf(
      "%-10s draft %.0f m, margin %.0f m: %zu pairs, Level 1 connects %d, routed %d (%.1f %%), "
      "within margin %d, min clearance %.2f m%s; route time median %.3f s, p95 %.3f s "
      "(median %.0fx Level 1's %.4f s)\n",
      c.name.c_str(), c.min_depth_m, result->margin_m, result->pairs.size(), result->connected,
      result->routed, result->connected > 0 ? 100.0 * result->routed / result->connected : 0.0,
      result->within_margin, min_clearance, result->clearance_exact ? "" : " (buffered check)", med,
      p95, l1_med > 0 ? med / l1_med : 0.0, l1_med);
  std::fflush(stdout);
  const bool pass = result->routed == result->connected && result->within_margin == 0;
  return pass ? 0 : 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string shared = "../shared";
  if (const char* env = std::getenv("SEAPLAN_SHARED")) shared = env;
  route::SweepOptions sweep;
  std::string only;
  double min_depth_override = 0.0;
  bool verbose = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--pairs" && i + 1 < argc) {
      sweep.pairs = std::atoi(argv[++i]);
    } else if (a == "--seed" && i + 1 < argc) {
      sweep.seed = std::strtoull(argv[++i], nullptr, 10);
    } else if (a == "--chart" && i + 1 < argc) {
      only = argv[++i];
    } else if (a == "--min-depth" && i + 1 < argc) {
      min_depth_override = std::atof(argv[++i]);
    } else if (a == "--verbose") {
      verbose = true;
    } else if (!a.empty() && a[0] != '-') {
      shared = a;
    } else {
      std::fprintf(stderr,
                   "usage: route_pairs_bench [shared_dir] [--pairs N] [--seed S] "
                   "[--chart noaa|trondheim|alesund] [--min-depth M] [--verbose]\n");
      return 2;
    }
  }
  log::SetLevel(log::Level::kWarn);
  // Drafts: the NOAA call that used to fail (8 m), the same for Trondheim,
  // and Alesund's own 5 m set (its layers give depths 0/5/10/50/100 m).
  const std::vector<ChartCase> cases = {
      {"noaa", "enc/noaa-US4MD81M/US4MD81M.000", 8.0},
      {"trondheim", "enc/trondheim/Trondheim.gdb", 8.0},
      {"alesund", "enc/alesund/shapefiles", 5.0},
  };
  std::printf("route_pairs_bench: %d pairs per chart, seed %llu\n", sweep.pairs,
              static_cast<unsigned long long>(sweep.seed));
  int status = 0;
  for (ChartCase c : cases) {
    if (!only.empty() && c.name != only) continue;
    if (min_depth_override > 0) c.min_depth_m = min_depth_override;
    status = std::max(status, RunCase(shared, c, sweep, verbose));
  }
  return status;
}
