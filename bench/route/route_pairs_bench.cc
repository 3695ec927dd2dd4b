// Route planner coverage and safety on the real charts: seeded random
// origin/destination pairs in navigable water (engine/route route_sweep.h),
// per chart: how many pairs Level 1 connects, how many of those get a route,
// how many routes come within the safety margin of an UNBUFFERED obstacle
// (exact GEOS distance), and the time per route (median, p95) with its ratio
// to the Level-1 time measured in the same run. Then each chosen route is
// sailed from rest by the simulation client's closed loop (engine/colav:
// the SITS hull, its autopilot and LOS path follower with the wheel-over,
// at 9 m/s, no traffic, no wind) and the executed track's clearance from
// the unbuffered obstacles is measured the same way: the route's polyline
// keeps the margin, the hull that turns on a circle of ~240 m must too.
//
// Usage: route_pairs_bench [shared_dir] [--pairs N] [--seed S] [--chart noaa|trondheim|alesund]
//                          [--min-depth M] [--turn-radius M] [--no-fillet] [--fillet-radius M]
//                          [--fillet-min-radius M] [--lookahead M] [--wheel-over-radius M]
//                          [--chord S] [--no-sail-check] [--verbose]
// --no-sail-check: Level2Options::sail_check off (the planner without step 6,
// its routes' tracks not sailed); --turn-radius: the route planner's Level2Options::turn_radius_m
// (0: no turn check, the planner as it was); --no-fillet: Level2Options::fillet_turns off (the
// corners as Level 1 placed them); --fillet-radius: its fillet_radius_m; --fillet-min-radius: its
// fillet_min_radius_m (0: the fillet radius only). The routes are sailed with the simulation
// client's path follower; --lookahead and --wheel-over-radius sail the same routes once more with
// those changed and print a line each
// (--wheel-over-radius may be repeated, a comparison of followers in one run); --chord: that
// follower's PathFollowerOptions::chord_s (0: the leg's course; may be repeated too).
// ROUTE_PAIRS_DUMP=1 prints every sailed route ("R east north") and its executed track ("T east
// north").
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "seaplan/chart/obstacle_map.h"
#include "seaplan/colav/encounter_sim.h"
#include "seaplan/common/log.h"
#include "seaplan/route/route_planner.h"
#include "seaplan/route/route_sweep.h"
#include "seaplan/route/sail_check.h"

using namespace seaplan;

namespace {

// The fjord scenarios' ordered speed (the hull's PTO service speed is 9.15 m/s).
constexpr double kSailSpeedMps = 9.0;

struct ChartCase {
  std::string name;
  std::string path;  // under the shared folder
  double min_depth_m;
};

struct Sailed {
  bool arrived = false;
  double clearance_m = 0.0;  // of the executed track from the unbuffered obstacles
  EastNorth closest;
};

// Sails `route` from rest at `speed_mps` in the simulation client's closed
// loop and measures the executed track against the unbuffered obstacles.
StatusOr<Sailed> Sail(const std::vector<EastNorth>& route, double speed_mps,
                      const colav::PathFollowerOptions& follower, chart::ObstacleQuery& query) {
  SEAPLAN_ASSIGN_OR_RETURN(route::SailedTrack out,
                           route::SailRoute(route, speed_mps, nullptr, &follower));
  Sailed s{out.arrived, std::numeric_limits<double>::infinity(), {}};
  if (std::getenv("ROUTE_PAIRS_DUMP") != nullptr) {
    std::printf("PAIR\n");
    for (const EastNorth& p : route) std::printf("R %.1f %.1f\n", p.east_m, p.north_m);
    for (const EastNorth& p : out.track) std::printf("T %.1f %.1f\n", p.east_m, p.north_m);
  }
  if (const std::optional<chart::Clearance> c = query.UnbufferedClearance(out.track)) {
    s.clearance_m = c->distance_m;
    s.closest = c->route_point;
  }
  return s;
}

struct SailTotals {
  int not_arrived = 0;
  int within = 0;
};

// Sails every routed pair with `follower` and prints one line of totals.
SailTotals SailAll(const route::SweepResult& result, const std::string& chart_name,
                   const std::string& label, const colav::PathFollowerOptions& follower,
                   chart::ObstacleQuery& query, bool verbose) {
  SailTotals t;
  int sailed = 0, aground = 0, failures_shown = 0;
  double min_sailed = std::numeric_limits<double>::infinity();
  for (const route::PairOutcome& p : result.pairs) {
    if (!p.routed) continue;
    auto s = Sail(p.route, kSailSpeedMps, follower, query);
    if (!s.ok()) {
      std::printf("    SAIL FAILED (%.0f, %.0f) -> (%.0f, %.0f): %s\n", p.from.east_m,
                  p.from.north_m, p.to.east_m, p.to.north_m, s.status().ToString().c_str());
      ++t.not_arrived;
      continue;
    }
    ++sailed;
    min_sailed = std::min(min_sailed, s->clearance_m);
    if (!s->arrived) ++t.not_arrived;
    if (s->clearance_m <= 0) ++aground;
    const bool close = s->clearance_m < result.margin_m - 1e-3;
    if (close) ++t.within;
    if ((close || !s->arrived) && (verbose || failures_shown < 3)) {
      ++failures_shown;
      std::printf(
          "    SAILED %s (%.0f, %.0f) -> (%.0f, %.0f): track clearance %.2f m at (%.0f, %.0f)\n",
          s->arrived ? "CLOSE" : "NOT ARRIVED", p.from.east_m, p.from.north_m, p.to.east_m,
          p.to.north_m, s->clearance_m, s->closest.east_m, s->closest.north_m);
    }
  }
  std::printf(
      "%-10s sailed from rest at %.0f m/s (%s): %d routes, not arrived %d, track aground %d, "
      "track within margin %d, min track clearance %.2f m\n",
      chart_name.c_str(), kSailSpeedMps, label.c_str(), sailed, t.not_arrived, aground, t.within,
      min_sailed);
  std::fflush(stdout);
  return t;
}

int RunCase(const std::string& shared, const ChartCase& c, const route::SweepOptions& sweep,
            double turn_radius_m, bool fillet_turns, double fillet_radius_m,
            double fillet_min_radius_m, bool sail_check,
            const std::vector<colav::PathFollowerOptions>& followers, bool verbose) {
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
  if (turn_radius_m >= 0) ropt.level2.turn_radius_m = turn_radius_m;
  ropt.level2.fillet_turns = fillet_turns;
  if (fillet_radius_m > 0) ropt.level2.fillet_radius_m = fillet_radius_m;
  if (fillet_min_radius_m >= 0) ropt.level2.fillet_min_radius_m = fillet_min_radius_m;
  ropt.level2.sail_check = sail_check;
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
  int failures_shown = 0, filleted = 0, tightened = 0;
  for (const route::PairOutcome& p : result->pairs) {
    if (!p.level1_connected) continue;
    filleted += p.filleted_turns;
    tightened += p.tightened_turns;
    for (const std::string& w : p.warnings) {
      if (verbose) {
        std::printf("    WARNING (%.0f, %.0f) -> (%.0f, %.0f): %s\n", p.from.east_m, p.from.north_m,
                    p.to.east_m, p.to.north_m, w.c_str());
      }
    }
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
  std::printf(
      "%-10s turns filleted %d (%d of them on a circle under the fillet radius); routes with a "
      "corner left unsailable (warned) %d\n",
      c.name.c_str(), filleted, tightened, result->with_warnings);
  std::fflush(stdout);

  // The executed tracks: with the simulation client's path follower and, when
  // a follower flag is given, once more with the flags' follower (the same
  // routes, so the two lines compare the followers alone).
  chart::ObstacleQuery query(*shared_map);
  const SailTotals sim = SailAll(*result, c.name, "the simulation client's follower",
                                 colav::ShipPathFollowerOptions(), query, verbose);
  for (const colav::PathFollowerOptions& flagged : followers) {
    const std::string label =
        "look-ahead " + std::to_string(static_cast<int>(flagged.lookahead_m)) +
        " m, wheel-over radius " + std::to_string(static_cast<int>(flagged.turn_radius_m)) + " m" +
        ", chord " + std::to_string(static_cast<int>(flagged.chord_s)) + " s";
    SailAll(*result, c.name, label, flagged, query, verbose);
  }
  const bool pass = result->routed == result->connected && result->within_margin == 0 &&
                    sim.not_arrived == 0 && sim.within == 0;
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
  double turn_radius_m = -1.0;  // the planner's default
  bool fillet_turns = true;
  bool sail_check = true;
  double fillet_radius_m = 0.0;       // the planner's default
  double fillet_min_radius_m = -1.0;  // the planner's default
  // The sailings' path followers: the simulation client's with the flags'
  // look-ahead and each flagged wheel-over radius.
  double lookahead_m = 0.0;
  std::vector<double> wheel_over_radii_m;
  std::vector<double> chords_s;

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
    } else if (a == "--turn-radius" && i + 1 < argc) {
      turn_radius_m = std::atof(argv[++i]);
    } else if (a == "--no-sail-check") {
      sail_check = false;
    } else if (a == "--no-fillet") {
      fillet_turns = false;
    } else if (a == "--fillet-radius" && i + 1 < argc) {
      fillet_radius_m = std::atof(argv[++i]);
    } else if (a == "--fillet-min-radius" && i + 1 < argc) {
      fillet_min_radius_m = std::atof(argv[++i]);
    } else if (a == "--lookahead" && i + 1 < argc) {
      lookahead_m = std::atof(argv[++i]);
    } else if (a == "--wheel-over-radius" && i + 1 < argc) {
      wheel_over_radii_m.push_back(std::atof(argv[++i]));
    } else if (a == "--chord" && i + 1 < argc) {
      chords_s.push_back(std::atof(argv[++i]));
    } else if (a == "--verbose") {
      verbose = true;
    } else if (!a.empty() && a[0] != '-') {
      shared = a;
    } else {
      std::fprintf(
          stderr,
          "usage: route_pairs_bench [shared_dir] [--pairs N] [--seed S] "
          "[--chart noaa|trondheim|alesund] [--min-depth M] [--turn-radius M] [--no-fillet] "
          "[--fillet-radius M] [--fillet-min-radius M] [--lookahead M] [--wheel-over-radius M] "
          "[--chord S] [--no-sail-check] [--verbose]\n");
      return 2;
    }
  }
  std::vector<colav::PathFollowerOptions> followers;
  const colav::PathFollowerOptions sim_follower = colav::ShipPathFollowerOptions();
  if ((lookahead_m > 0 || !chords_s.empty()) && wheel_over_radii_m.empty()) {
    wheel_over_radii_m.push_back(sim_follower.turn_radius_m);
  }
  if (chords_s.empty()) chords_s.push_back(sim_follower.chord_s);
  for (double r : wheel_over_radii_m) {
    colav::PathFollowerOptions f = sim_follower;
    if (lookahead_m > 0) f.lookahead_m = lookahead_m;
    f.turn_radius_m = r;
    for (double chord : chords_s) {
      f.chord_s = chord;
      followers.push_back(f);
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
    status =
        std::max(status, RunCase(shared, c, sweep, turn_radius_m, fillet_turns, fillet_radius_m,
                                 fillet_min_radius_m, sail_check, followers, verbose));
  }
  return status;
}
