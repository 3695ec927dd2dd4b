#include "seaplan/chart/chart_grounding_test.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

namespace seaplan::chart {
namespace {

constexpr double kE = 500000.0, kN = 6900000.0;

std::shared_ptr<const ObstacleMap> Island() {
  ChartOptions o;
  o.safety_buffer_m = 0;
  o.simplify_tolerance_m = 0;
  Polygon square{{{kE - 50, kN - 50}, {kE + 50, kN - 50}, {kE + 50, kN + 50}, {kE - 50, kN + 50}},
                 {}};
  auto map = ObstacleMap::FromPolygons({square}, *LocalFrame::FromEpsg(32633), o);
  EXPECT_TRUE(map.ok());
  return std::make_shared<const ObstacleMap>(std::move(map).value());
}

TEST(ChartGroundingTest, AgreesWithPlainPolygonObstacles) {
  const auto map = Island();
  ChartGroundingTest chart(map);
  // The same square for the risk library's dependency-free implementation, in (N, E).
  auto plain = risk::PolygonObstacles::Create(
      {{{kN - 50, kE - 50}, {kN - 50, kE + 50}, {kN + 50, kE + 50}, {kN + 50, kE - 50}}});
  ASSERT_TRUE(plain.ok()) << plain.status();
  for (double de : {-200.0, -95.0, -60.0, 0.0, 70.0, 150.0}) {
    for (double psi : {0.0, 0.5, M_PI / 2}) {
      // 80 x 16 m hull; north of the island's centre by 20 m.
      const auto hull = risk::HullPolygon::Rectangle(kN + 20, kE + de, psi, 80.0, 16.0);
      EXPECT_EQ(chart.HullIntersects(hull), plain->HullIntersects(hull)) << de << " " << psi;
      EXPECT_NEAR(chart.Clearance(hull), plain->Clearance(hull), 1e-6) << de << " " << psi;
    }
  }
  // By hand: hull heading north (length along N) centred 150 m east: its
  // west side is at e + 150 - 8, the island's east side at e + 50.
  EXPECT_NEAR(chart.Clearance(risk::HullPolygon::Rectangle(kN, kE + 150, 0.0, 80.0, 16.0)), 92.0,
              1e-6);
}

TEST(ChartGroundingTest, OriginShiftAndThreads) {
  const auto map = Island();
  ChartGroundingTest shifted(map, EastNorth{kE, kN});  // NED (0,0) = island centre
  EXPECT_TRUE(shifted.HullIntersects(risk::HullPolygon::Rectangle(0, 0, 0.0, 80, 16)));
  EXPECT_NEAR(shifted.Clearance(risk::HullPolygon::Rectangle(0, 150, 0.0, 80, 16)), 92.0, 1e-6);
  std::vector<std::thread> threads;
  threads.reserve(4);
  std::vector<int> hits(4, 0);
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int i = 0; i < 200; ++i) {
        hits[t] +=
            shifted.HullIntersects(risk::HullPolygon::Rectangle(0, -300 + 3.0 * i, 0.0, 80, 16))
                ? 1
                : 0;
      }
    });
  }
  for (auto& th : threads) th.join();
  for (int t = 1; t < 4; ++t) EXPECT_EQ(hits[t], hits[0]);
  // Hull (16 m wide) touches the 100 m island for centres e in [-58, 58].
  EXPECT_EQ(hits[0], 39);
}

}  // namespace
}  // namespace seaplan::chart
