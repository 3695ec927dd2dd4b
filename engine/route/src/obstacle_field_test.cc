#include "seaplan/route/obstacle_field.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace seaplan::route {
namespace {

ObstaclePolygon Circle(EastNorth c, double r, int n = 48) {
  ObstaclePolygon p;
  p.rings.emplace_back();
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    p.rings[0].push_back({c.east_m + r * std::cos(a), c.north_m + r * std::sin(a)});
  }
  return p;
}

ObstaclePolygon Square(EastNorth lo, EastNorth hi) {
  return ObstaclePolygon{{{{lo.east_m, lo.north_m},
                           {hi.east_m, lo.north_m},
                           {hi.east_m, hi.north_m},
                           {lo.east_m, hi.north_m}}}};
}

ObstacleField MakeField() {
  std::vector<ObstaclePolygon> obs = {Circle({0, 0}, 300), Square({600, -200}, {700, 900}),
                                      Circle({-800, 500}, 60, 7)};
  // A square with a hole (a lagoon): inside the hole is water.
  ObstaclePolygon lagoon = Square({-900, -900}, {-300, -300});
  lagoon.rings.push_back({{-700, -700}, {-500, -700}, {-500, -500}, {-700, -500}});
  obs.push_back(lagoon);
  auto f = ObstacleField::Build(obs, {-1500, -1500}, {1500, 1500}, {});
  EXPECT_TRUE(f.ok()) << f.status();
  return std::move(f).value();
}

TEST(ObstacleFieldTest, DistancesMatchHandComputedValues) {
  ObstacleField f = MakeField();
  // 100 m outside the 300 m circle (polygon with 48 sides: within ~0.7 m).
  EXPECT_NEAR(f.SignedDistance({-400, 0}), 100.0, 1.0);
  EXPECT_NEAR(f.SignedDistance({0, -150}), -150.0, 1.5);
  // Inside the lagoon's hole: water, 100 m from the hole's walls.
  EXPECT_NEAR(f.SignedDistance({-600, -600}), 100.0, 1e-9);
  EXPECT_FALSE(f.Inside({-600, -600}));
  EXPECT_TRUE(f.Inside({-850, -850}));
  EXPECT_NEAR(f.SignedDistance({550, 0}), 50.0, 1e-9);
}

TEST(ObstacleFieldTest, GridQueriesEqualBruteForceEverywhere) {
  ObstacleField f = MakeField();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1700, 1700), h(-M_PI, M_PI);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    const EastNorth p{u(rng), u(rng)};
    const double psi = h(rng);
    const double sd = f.SignedDistanceBruteForce(p);
    if (std::abs(sd) < 700) {
      EXPECT_NEAR(f.SignedDistance(p), sd, 1e-9) << p.east_m << "," << p.north_m;
    }
    EXPECT_NEAR(f.SumExpDistance(p, 0.04), f.SumExpDistanceBruteForce(p, 0.04),
                1e-9 * (1 + f.SumExpDistanceBruteForce(p, 0.04)));
    const bool hit = f.HullHitsBruteForce(p, psi);
    EXPECT_EQ(f.HullHits(p, psi), hit) << p.east_m << "," << p.north_m << " psi " << psi;
    hits += hit;
  }
  EXPECT_GT(hits, 1000);  // the test exercises both answers
}

TEST(ObstacleFieldTest, LargeJaggedCoastEqualsBruteForceAndDeepInsideIsInside) {
  // A chart-sized jagged "coast" (400 vertices, radius 2000-2600 m) and a
  // small rock: exercises the block pruning and the deep-inside entries.
  ObstaclePolygon coast;
  coast.rings.emplace_back();
  for (int i = 0; i < 400; ++i) {
    const double a = 2 * M_PI * i / 400, r = 2300 + 300 * std::sin(17 * a) * std::cos(5 * a);
    coast.rings[0].push_back({r * std::cos(a), r * std::sin(a)});
  }
  auto built =
      ObstacleField::Build({coast, Circle({3200, 0}, 40, 9)}, {-4000, -4000}, {4000, 4000}, {});
  ASSERT_TRUE(built.ok()) << built.status();
  const ObstacleField& f = *built;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-4500, 4500), h(-M_PI, M_PI);
  for (int i = 0; i < 20000; ++i) {
    const EastNorth p{u(rng), u(rng)};
    const double sd = f.SignedDistanceBruteForce(p), psi = h(rng);
    EXPECT_EQ(f.HullHits(p, psi), f.HullHitsBruteForce(p, psi)) << p.east_m << "," << p.north_m;
    EXPECT_EQ(f.Inside(p), sd <= 0.0) << p.east_m << "," << p.north_m;
    if (std::abs(sd) < 700) {
      EXPECT_NEAR(f.SignedDistance(p), sd, 1e-9) << p.east_m << "," << p.north_m;
      EXPECT_NEAR(f.SumExpDistance(p, 0.04), f.SumExpDistanceBruteForce(p, 0.04), 1e-9);
    }
  }
  // Deep inside: clipped to -cutoff, still inside.
  EXPECT_LE(f.SignedDistance({0, 0}), -700.0);
  EXPECT_TRUE(f.HullHits({0, 0}, 0.3));
}

TEST(ObstacleFieldTest, InsideIsExactOnGridRowBoundariesAndAtVertexNorthings) {
  // The grid's even-odd test looks only at the edges that reach a point's
  // row: points on the rows' boundaries and at the northing of a vertex
  // (an edge ending exactly there) give the brute-force answer. An islet
  // north of the coast has an index of its own few rows beside the coast's.
  ObstaclePolygon coast, islet;
  coast.rings.emplace_back();
  for (int i = 0; i < 400; ++i) {
    const double a = 2 * M_PI * i / 400, r = 2300 + 300 * std::sin(17 * a) * std::cos(5 * a);
    coast.rings[0].push_back({r * std::cos(a), r * std::sin(a)});
  }
  islet.rings.push_back({{-150, 3000}, {150, 3000}, {150, 3230}, {-150, 3230}});
  auto built = ObstacleField::Build({coast, islet}, {-4000, -4000}, {4000, 4000}, {});
  ASSERT_TRUE(built.ok()) << built.status();
  const ObstacleField& f = *built;
  const double origin = f.area_min().north_m - f.options().margin_m, cell = f.options().cell_m;
  std::vector<double> northings;
  for (double y = origin; y < 4000; y += cell) {
    northings.insert(northings.end(), {y, std::nextafter(y, -1e9), std::nextafter(y, 1e9)});
  }
  for (const EastNorth& v : coast.rings[0]) northings.push_back(v.north_m);
  for (const EastNorth& v : islet.rings[0]) northings.push_back(v.north_m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3000, 3000), near_islet(-300, 300);
  int inside = 0;
  for (double y : northings) {
    for (int i = 0; i < 8; ++i) {
      const EastNorth p{i % 2 == 0 ? u(rng) : near_islet(rng), y};
      const bool expected = f.SignedDistanceBruteForce(p) <= 0.0;
      EXPECT_EQ(f.Inside(p), expected) << p.east_m << "," << p.north_m;
      inside += expected;
    }
  }
  EXPECT_GT(inside, 100);  // both answers exercised
}

TEST(ObstacleFieldTest, HullTouchesShoreOnlyWhenCloseEnough) {
  ObstacleField f = MakeField();
  // Square's west face at x = 600. Ship heading north (along the face):
  // half beam 8 m. Centre at x = 590 -> 10 m gap -> free; at 593 -> touches.
  EXPECT_FALSE(f.HullHits({590, 300}, 0.0));
  EXPECT_TRUE(f.HullHits({593, 300}, 0.0));
  // Heading east (bow toward the face): bow 40 m ahead.
  EXPECT_FALSE(f.HullHits({559, 300}, M_PI / 2));
  EXPECT_TRUE(f.HullHits({561, 300}, M_PI / 2));
  // A small obstacle entirely inside the hull footprint is a hit.
  auto small = ObstacleField::Build({Square({-2, -2}, {2, 2})}, {-100, -100}, {100, 100}, {});
  ASSERT_TRUE(small.ok());
  EXPECT_TRUE(small->HullHits({0, 20}, 0.0));
  EXPECT_FALSE(small->HullHits({0, 45}, 0.0));
}

TEST(ObstacleFieldTest, SegmentHits) {
  ObstacleField f = MakeField();
  EXPECT_TRUE(f.SegmentHits({-1000, 0}, {1000, 0}));
  EXPECT_FALSE(f.SegmentHits({-1000, 1200}, {500, 1200}));
}

TEST(ObstacleFieldTest, RejectsBadInput) {
  EXPECT_FALSE(
      ObstacleField::Build({ObstaclePolygon{{{{0, 0}, {1, 1}}}}}, {0, 0}, {10, 10}, {}).ok());
  EXPECT_FALSE(ObstacleField::Build({}, {0, 0}, {0, 10}, {}).ok());
  ObstacleFieldOptions o;
  o.cell_m = 0;
  EXPECT_FALSE(ObstacleField::Build({}, {0, 0}, {10, 10}, o).ok());
  o = {};
  o.cell_m = 1;
  EXPECT_EQ(ObstacleField::Build({}, {0, 0}, {1e6, 1e6}, o).status().code(),
            absl::StatusCode::kResourceExhausted);
}

}  // namespace
}  // namespace seaplan::route
