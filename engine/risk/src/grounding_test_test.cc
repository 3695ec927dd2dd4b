#include "seaplan/risk/grounding_test.h"

#include <cmath>
#include <numbers>

#include "gtest/gtest.h"

namespace seaplan::risk {
namespace {

using Vec = Eigen::Vector2d;

TEST(HullPolygonTest, RectangleCornersFollowHeading) {
  // Heading north: bow at N = +40, beam along E.
  HullPolygon h = HullPolygon::Rectangle(100, 200, 0.0, 80, 16);
  EXPECT_TRUE(h.corners_ne[0].isApprox(Vec(140, 192)));
  EXPECT_TRUE(h.corners_ne[1].isApprox(Vec(140, 208)));
  EXPECT_TRUE(h.corners_ne[2].isApprox(Vec(60, 208)));
  EXPECT_DOUBLE_EQ(h.bounds.max[0], 140);
  // Heading east: bow at E = +40.
  h = HullPolygon::Rectangle(0, 0, std::numbers::pi / 2, 80, 16);
  EXPECT_NEAR(h.bounds.max[1], 40, 1e-9);
  EXPECT_NEAR(h.bounds.max[0], 8, 1e-9);
}

PolygonObstacles Square(double n0, double e0, double size) {
  auto obs = PolygonObstacles::Create(
      {{{n0, e0}, {n0 + size, e0}, {n0 + size, e0 + size}, {n0, e0 + size}}});
  EXPECT_TRUE(obs.ok());
  return *std::move(obs);
}

TEST(PolygonObstaclesTest, IntersectionCases) {
  const PolygonObstacles sq = Square(0, 100, 100);  // N 0..100, E 100..200
  // Far away.
  EXPECT_FALSE(sq.HullIntersects(HullPolygon::Rectangle(50, 0, 0, 80, 16)));
  // Hull edge crossing the square's west edge (hull E extent 85..101).
  EXPECT_TRUE(sq.HullIntersects(HullPolygon::Rectangle(50, 93, 0, 80, 16)));
  // Exactly touching counts (hull E max = 100).
  EXPECT_TRUE(sq.HullIntersects(HullPolygon::Rectangle(50, 92, 0, 80, 16)));
  // Hull entirely inside the obstacle.
  EXPECT_TRUE(sq.HullIntersects(HullPolygon::Rectangle(50, 150, 0, 20, 10)));
  // Small obstacle entirely inside the hull.
  const PolygonObstacles rock = Square(-2, -2, 4);
  EXPECT_TRUE(rock.HullIntersects(HullPolygon::Rectangle(0, 0, 0.3, 80, 16)));
  // Rotation matters: a ship pointing east reaches 40 m east, pointing north 8 m.
  const PolygonObstacles east_rock = Square(-1, 30, 2);
  EXPECT_TRUE(east_rock.HullIntersects(HullPolygon::Rectangle(0, 0, std::numbers::pi / 2, 80, 16)));
  EXPECT_FALSE(east_rock.HullIntersects(HullPolygon::Rectangle(0, 0, 0, 80, 16)));
}

TEST(PolygonObstaclesTest, NonConvexPolygon) {
  // A "U" open to the north: the notch N 20..100, E 40..60 is water.
  auto u = PolygonObstacles::Create(
      {{{0, 0}, {100, 0}, {100, 40}, {20, 40}, {20, 60}, {100, 60}, {100, 100}, {0, 100}}});
  ASSERT_TRUE(u.ok());
  EXPECT_FALSE(u->HullIntersects(HullPolygon::Rectangle(60, 50, 0, 40, 10)));
  EXPECT_TRUE(u->HullIntersects(HullPolygon::Rectangle(60, 50, 0, 40, 30)));
  EXPECT_TRUE(u->HullIntersects(HullPolygon::Rectangle(10, 50, 0, 10, 10)));
}

TEST(PolygonObstaclesTest, ClearanceByHand) {
  const PolygonObstacles sq = Square(0, 100, 100);
  // Hull E extent 42..58 (heading north, centre E 50): 42 m to the square.
  EXPECT_NEAR(sq.Clearance(HullPolygon::Rectangle(50, 50, 0, 80, 16)), 42.0, 1e-9);
  EXPECT_EQ(sq.Clearance(HullPolygon::Rectangle(50, 150, 0, 80, 16)), 0.0);
}

TEST(PolygonObstaclesTest, RejectsDegeneratePolygons) {
  EXPECT_FALSE(PolygonObstacles::Create({{{0, 0}, {1, 1}}}).ok());
  EXPECT_FALSE(PolygonObstacles::Create({{{0, 0}, {1, 1}, {NAN, 1}}}).ok());
  // Closed ring with repeated first vertex is accepted.
  EXPECT_TRUE(PolygonObstacles::Create({{{0, 0}, {1, 0}, {1, 1}, {0, 0}}}).ok());
}

}  // namespace
}  // namespace seaplan::risk
