// The route planner on the three real charts of the shared data (NOAA
// US4MD81M with its updates, Kartverket's Trondheim FileGDB, the Alesund
// seacharts set): every seeded random pair of navigable points that Level 1
// connects gets a route, and no route comes within the chart's safety buffer
// of a charted (unbuffered) obstacle. Fewer pairs than the benchmark
// (bench/route/route_pairs_bench runs 200 per chart) to stay fast; the seed
// differs from the benchmark's so the two sample different pairs.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "seaplan/route/route_sweep.h"
#include "seaplan/testing/shared_data.h"

namespace seaplan::route {
namespace {

void ExpectEveryConnectedPairRoutedClear(const std::filesystem::path& chart, double min_depth_m) {
  chart::ChartOptions co;
  co.min_depth_m = min_depth_m;
  auto map = chart::LoadChartFile(chart.string(), co);
  ASSERT_TRUE(map.ok()) << map.status();
  auto shared_map = std::make_shared<const chart::ObstacleMap>(std::move(*map));
  RouteOptions options;
  options.min_depth_m = min_depth_m;
  // Fewer particles and iterations than the default: the property under
  // test (routes exist and keep clear) does not depend on how well the swarm
  // converges, and the test stays fast.
  options.level2.pso.particles = 10;
  options.level2.pso.iterations = 20;
  auto planner = RoutePlanner::Create(shared_map, ShipParticulars{}, options);
  ASSERT_TRUE(planner.ok()) << planner.status();
  SweepOptions sweep;
  sweep.pairs = 12;
  sweep.seed = 7;
  auto result = RunRouteSweep(*planner, *shared_map, Environment{}, sweep);
  ASSERT_TRUE(result.ok()) << result.status();
  EXPECT_TRUE(result->clearance_exact);
  EXPECT_GT(result->connected, 0);
  EXPECT_EQ(result->routed, result->connected);
  EXPECT_EQ(result->within_margin, 0);
  for (const PairOutcome& p : result->pairs) {
    if (!p.level1_connected) continue;
    EXPECT_TRUE(p.routed) << "(" << p.from.east_m << ", " << p.from.north_m << ") -> ("
                          << p.to.east_m << ", " << p.to.north_m << "): " << p.error;
    if (p.routed) {
      EXPECT_GE(p.clearance_m, result->margin_m - 1e-3);
    }
  }
}

TEST(RouteSweepDataTest, NoaaUs4md81mWithUpdates) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/noaa-US4MD81M");
  ExpectEveryConnectedPairRoutedClear(dir / "US4MD81M.000", 8.0);
}

TEST(RouteSweepDataTest, TrondheimFileGdb) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/trondheim/Trondheim.gdb");
  ExpectEveryConnectedPairRoutedClear(dir, 8.0);
}

TEST(RouteSweepDataTest, AlesundShapefiles) {
  SEAPLAN_REQUIRE_SHARED(dir, "enc/alesund/shapefiles");
  ExpectEveryConnectedPairRoutedClear(dir, 5.0);
}

}  // namespace
}  // namespace seaplan::route
