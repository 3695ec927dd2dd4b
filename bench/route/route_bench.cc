// Level-2 route optimisation on the Alesund case of paper 002, fast vs exact.
//
// Same run, same options (paper settings: 2 alternatives, 20 segments = 19
// movable waypoints, 30 particles, 100 iterations, TTG horizon 600 s in 30 s
// steps, 2 threads): first RiskEvaluation::kFast (one drift simulation per
// waypoint, tabulated P(G), grid-indexed exact geometry), then kExact (drift
// simulated, hull tested against every obstacle edge and event trees
// evaluated at every cost evaluation). Prints wall times, chosen alternative
// and its expected cost for both, the speed ratio and the cost difference.
//
// Usage: route_bench [shared_dir] [--threads N] [--repeat N]
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "seaplan/chart/alternatives.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"
#include "seaplan/route/level2_optimizer.h"
#include "seaplan/route/route_planner.h"

using namespace seaplan;
using Clock = std::chrono::steady_clock;

static double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}
// Process CPU time (all threads): the machine is shared, so wall time alone
// says little about the code when others load the cores.
static double CpuSeconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static void PrintAlternatives(const route::Level2Result& r) {
  for (size_t a = 0; a < r.alternatives.size(); ++a) {
    const auto& alt = r.alternatives[a];
    std::string modes;
    for (size_t k = 0; k + 1 < alt.waypoints.size(); ++k) {
      const route::MsoMode m = alt.waypoints[k].mode;
      modes += m == route::MsoMode::kPto ? 'o' : m == route::MsoMode::kMec ? 'M' : 'i';
    }
    double min_ttg = 1e9;
    for (const auto& w : alt.waypoints) min_ttg = std::min(min_ttg, w.ttg_s);
    std::printf(
        "    alt %zu: expected %.4f (grounding %.4f, mso %.4f, switches %d x) path %.4f  min TTG "
        "%.0f s  modes %s%s\n",
        a, alt.expected_cost, alt.grounding_cost, alt.mso_cost, alt.mode_switches, alt.path_cost,
        min_ttg, modes.c_str(), alt.crosses_obstacle ? "  CROSSES OBSTACLE" : "");
    if (std::getenv("ROUTE_BENCH_VERBOSE") != nullptr) {
      for (const auto& w : alt.waypoints) {
        std::printf(
            "      E %9.1f N %10.1f (ref %9.1f %10.1f) TTG %4.0f P %.3g/%.3g/%.3g prox %.3g cost "
            "%.4f/%.4f/%.4f %s\n",
            w.position.east_m, w.position.north_m, w.reference.east_m, w.reference.north_m, w.ttg_s,
            w.grounding_probability[0], w.grounding_probability[1], w.grounding_probability[2],
            w.proximity, w.mode_cost[0], w.mode_cost[1], w.mode_cost[2],
            std::string(route::MsoModeName(w.mode)).c_str());
      }
    }
  }
}

int main(int argc, char** argv) {
  std::string shared = "../shared";
  if (const char* env = std::getenv("SEAPLAN_SHARED")) shared = env;
  int threads = 2, repeat = 3;
  std::string field_only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--field-only" && i + 1 < argc)
      field_only = argv[++i];
    else if (a == "--threads" && i + 1 < argc)
      threads = std::atoi(argv[++i]);
    else if (a == "--repeat" && i + 1 < argc)
      repeat = std::atoi(argv[++i]);
    else
      shared = a;
  }
  log::SetLevel(log::Level::kWarn);
  if (!field_only.empty()) {
    // Obstacle-field build time on another chart (scalability check).
    auto t0 = Clock::now();
    auto m = chart::LoadChartFile(field_only, chart::ChartOptions{});
    if (!m.ok()) {
      std::fprintf(stderr, "cannot load %s: %s\n", field_only.c_str(),
                   std::string(m.status().message()).c_str());
      return 2;
    }
    const double load = Since(t0);
    auto sm = std::make_shared<const chart::ObstacleMap>(std::move(m).value());
    t0 = Clock::now();
    auto p = route::RoutePlanner::Create(sm, route::ShipParticulars{}, route::RouteOptions{});
    std::printf("%s: load %.3f s, %d polygons, %d vertices; obstacle field %s in %.3f s\n",
                field_only.c_str(), load, sm->summary().polygon_count, sm->summary().vertex_count,
                p.ok() ? "built" : std::string(p.status().message()).c_str(), Since(t0));
    return p.ok() ? 0 : 1;
  }
  const std::string dir = shared + "/enc/alesund/shapefiles";
  chart::ChartOptions co;
  co.min_depth_m = 5.0;
  co.frame_epsg = 25833;
  auto t = Clock::now();
  auto map = chart::LoadChartFile(dir, co);
  if (!map.ok()) {
    std::fprintf(stderr, "cannot load %s: %s\n", dir.c_str(),
                 std::string(map.status().message()).c_str());
    return 2;
  }
  const double load_s = Since(t);
  auto shared_map = std::make_shared<const chart::ObstacleMap>(std::move(map).value());

  route::RouteOptions options;
  options.level2.threads = threads;
  t = Clock::now();
  auto planner = route::RoutePlanner::Create(shared_map, route::ShipParticulars{}, options);
  if (!planner.ok()) {
    std::fprintf(stderr, "planner: %s\n", std::string(planner.status().message()).c_str());
    return 2;
  }
  const double field_s = Since(t);

  // route1.csv rows 2 and 3 (the in-chart leg the public code plans).
  const EastNorth start{41200, 6959900}, goal{38000, 6961100};
  t = Clock::now();
  auto level1 = chart::PlanAlternatives(*shared_map, start, goal, options.alternatives);
  if (!level1.ok()) {
    std::fprintf(stderr, "level 1: %s\n", std::string(level1.status().message()).c_str());
    return 2;
  }
  const double level1_s = Since(t);

  auto risk_model = risk::DriftingGroundingModel::Create(options.risk);
  if (!risk_model.ok()) return 2;
  route::DriftingGroundingAdapter grounding(*risk_model);
  route::Level2Problem problem;
  problem.field = &planner->field();
  problem.grounding = &grounding;
  route::Environment env{10.0, -110.0, 1.0, -110.0};
  problem.environment = route::ToShipEnvironment(env);
  for (size_t a = 0; a < std::min<size_t>(2, level1->alternatives.size()); ++a) {
    std::vector<EastNorth> line;
    for (const auto& p : level1->alternatives[a].waypoints) line.push_back({p.east_m, p.north_m});
    problem.alternatives.push_back(line);
  }

  std::printf(
      "Alesund case (paper 002): %zu alternatives, %d segments, %d particles x %d iterations, TTG "
      "%g s / %g s, %d threads\n",
      problem.alternatives.size(), options.level2.segments, options.level2.pso.particles,
      options.level2.pso.iterations, options.level2.ttg_horizon_s, options.level2.ttg_step_s,
      threads);
  std::printf(
      "  chart load %.3f s (%d polygons, %d vertices), obstacle field build %.3f s, level 1 %.3f "
      "s\n",
      load_s, shared_map->summary().polygon_count, shared_map->summary().vertex_count, field_s,
      level1_s);

  route::Level2Options fast_o = options.level2;
  double best_fast = 1e9, best_fast_cpu = 1e9;
  route::Level2Result fast;
  for (int i = 0; i < std::max(1, repeat); ++i) {
    t = Clock::now();
    const double c0 = CpuSeconds();
    auto r = route::OptimizeLevel2(problem, fast_o);
    const double s = Since(t);
    best_fast_cpu = std::min(best_fast_cpu, CpuSeconds() - c0);
    if (!r.ok()) {
      std::fprintf(stderr, "fast: %s\n", std::string(r.status().message()).c_str());
      return 2;
    }
    if (s < best_fast) best_fast = s;
    fast = *r;
  }
  route::Level2Options exact_o = options.level2;
  exact_o.risk_evaluation = route::RiskEvaluation::kExact;
  if (std::getenv("ROUTE_BENCH_FAST_ONLY") != nullptr) {
    std::printf("  FAST : wall %.3f s\n", best_fast);
    PrintAlternatives(fast);
    return 0;
  }
  t = Clock::now();
  const double c0 = CpuSeconds();
  auto exact = route::OptimizeLevel2(problem, exact_o);
  const double exact_s = Since(t);
  const double exact_cpu = CpuSeconds() - c0;
  if (!exact.ok()) {
    std::fprintf(stderr, "exact: %s\n", std::string(exact.status().message()).c_str());
    return 2;
  }
  const double fast_cost = fast.alternatives[fast.chosen].expected_cost;
  const double exact_cost = exact->alternatives[exact->chosen].expected_cost;
  std::printf(
      "  FAST : wall %.3f s, cpu %.3f s (best of %d; +%.3f s field build = %.3f s wall), %lld "
      "evaluations, chosen alt %d, expected cost %.4f\n",
      best_fast, best_fast_cpu, repeat, field_s, best_fast + field_s,
      static_cast<long long>(fast.evaluations), fast.chosen, fast_cost);
  PrintAlternatives(fast);
  std::printf(
      "  EXACT: wall %.3f s, cpu %.3f s, %lld evaluations, chosen alt %d, expected cost %.4f\n",
      exact_s, exact_cpu, static_cast<long long>(exact->evaluations), exact->chosen, exact_cost);
  PrintAlternatives(*exact);
  std::printf(
      "  ratio exact/fast: wall %.1fx (incl. field build %.1fx), cpu %.1fx; cost difference %+.4f "
      "%%, same choice: %s\n",
      exact_s / best_fast, exact_s / (best_fast + field_s), exact_cpu / best_fast_cpu,
      100.0 * (fast_cost - exact_cost) / exact_cost, fast.chosen == exact->chosen ? "yes" : "NO");
  std::printf("  modes: o = PTO, M = MEC, i = PTI (segment 0..%d)\n", options.level2.segments - 1);
  return 0;
}
