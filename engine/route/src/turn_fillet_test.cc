#include "seaplan/route/turn_fillet.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obstacle_test_fields.h"

namespace seaplan::route {
namespace {

constexpr double kDeg = M_PI / 180.0;

using test_fields::Field;
using test_fields::Rect;

std::vector<EastNorth> Positions(const FilletRoute& f) {
  std::vector<EastNorth> out;
  for (const FilletPoint& p : f.points) out.push_back(p.position);
  return out;
}

// A hull turning on `radius_m` sails every vertex: its turn takes
// radius tan(theta / 2) of each leg, an inner leg shared with the turn at
// its other end.
void ExpectSailable(const std::vector<EastNorth>& w, double radius_m) {
  for (size_t k = 1; k + 1 < w.size(); ++k) {
    const double theta = std::abs(TurnAngle(w[k - 1], w[k], w[k + 1]));
    const double need = radius_m * std::tan(theta / 2.0);
    const double in_share = k == 1 ? 1.0 : 0.5, out_share = k + 2 == w.size() ? 1.0 : 0.5;
    EXPECT_LE(need, in_share * Distance(w[k - 1], w[k]) + 1e-6) << "vertex " << k;
    EXPECT_LE(need, out_share * Distance(w[k], w[k + 1]) + 1e-6) << "vertex " << k;
  }
}

void ExpectClear(const ObstacleField& field, const std::vector<EastNorth>& w) {
  for (size_t k = 1; k < w.size(); ++k) {
    EXPECT_FALSE(field.SegmentHits(w[k - 1], w[k])) << "segment " << k - 1;
  }
}

TEST(TurnFilletTest, RightAngleRoundAnIslandBecomesAnArcThatKeepsTheCornersClearance) {
  // The island's corner at (0, 0); a Level-1 style path turns by 90 deg at
  // (60, -60), next to it: a 300 m circle started at the corner would cut
  // 124 m towards the island.
  const ObstacleField field = Field({Rect(-1000, 0, 0, 1000)});
  const std::vector<EastNorth> route = {{-1500, -60}, {60, -60}, {60, 1500}};
  const double corner_clearance = field.SignedDistance(route[1]);
  TurnFilletOptions o;
  o.radius_m = 300.0;
  auto f = FilletTurns(field, route, o);
  ASSERT_TRUE(f.ok()) << f.status();
  EXPECT_EQ(f->filleted, 1);
  EXPECT_TRUE(f->unsailable.empty());
  const std::vector<EastNorth> w = Positions(*f);
  // ~90 deg (a little more once the corner moves out) in steps of <= 15 deg.
  ASSERT_GE(w.size(), 2u + 6u);
  ASSERT_LE(w.size(), 2u + 7u);
  EXPECT_EQ(f->points.front().source, 0);
  EXPECT_EQ(f->points.back().source, 2);
  EXPECT_EQ(w.front(), route.front());
  EXPECT_EQ(w.back(), route.back());
  for (size_t k = 1; k + 1 < w.size(); ++k) {
    EXPECT_EQ(f->points[k].source, -1);
    EXPECT_LE(std::abs(TurnAngle(w[k - 1], w[k], w[k + 1])), 15.0 * kDeg + 1e-9);
    // Moved outwards: the arc keeps the preferred clearance (the corner had
    // more, 85 m).
    EXPECT_GE(field.SignedDistance(w[k]), std::min(o.clearance_m, corner_clearance) - 3.0) << k;
  }
  ExpectSailable(w, 300.0);
  ExpectClear(field, w);
}

TEST(TurnFilletTest, SmallTurnsStayAsTheyAre) {
  const ObstacleField field = Field({Rect(-1000, 200, 1000, 400)});
  // 10 deg at (0, 0).
  const std::vector<EastNorth> route = {
      {-1500, 0}, {0, 0}, {1500 * std::cos(10 * kDeg), -1500 * std::sin(10 * kDeg)}};
  auto f = FilletTurns(field, route, TurnFilletOptions{});
  ASSERT_TRUE(f.ok()) << f.status();
  EXPECT_EQ(f->filleted, 0);
  EXPECT_TRUE(f->unsailable.empty());
  EXPECT_EQ(Positions(*f), route);
}

TEST(TurnFilletTest, VerticesRoundingABufferAreOneCorner) {
  // A path round the island's corner through three vertices 40-60 m apart,
  // each turning by 30 deg: no leg between them has room for a 300 m
  // circle's turn, together they are one 90 deg corner.
  const ObstacleField field = Field({Rect(-1000, 0, 0, 1000)});
  const double leg = 60.0 / (std::cos(30 * kDeg) + std::cos(60 * kDeg));  // ~44 m
  const EastNorth v1{0, -60};
  const EastNorth v2 = v1 + EastNorth{std::cos(30 * kDeg), std::sin(30 * kDeg)} * leg;
  const EastNorth v3 = v2 + EastNorth{std::cos(60 * kDeg), std::sin(60 * kDeg)} * leg;
  const std::vector<EastNorth> route = {{-1500, -60}, v1, v2, v3, {v3.east_m, 1500}};
  ASSERT_NEAR(v3.east_m, 60.0, 1e-9);
  ASSERT_NEAR(v3.north_m, 0.0, 1e-9);
  for (size_t k = 1; k <= 3; ++k) {
    EXPECT_NEAR(TurnAngle(route[k - 1], route[k], route[k + 1]), 30 * kDeg, 1e-9);
  }
  TurnFilletOptions o;
  auto f = FilletTurns(field, route, o);
  ASSERT_TRUE(f.ok()) << f.status();
  EXPECT_EQ(f->filleted, 1);
  EXPECT_EQ(f->merged_vertices, 2);
  EXPECT_TRUE(f->unsailable.empty());
  const std::vector<EastNorth> w = Positions(*f);
  ExpectSailable(w, o.radius_m);
  ExpectClear(field, w);
}

TEST(TurnFilletTest, NarrowWaterIsReportedNotSilentlyReturned) {
  // An L-shaped channel 60 m wide: a 90 deg turn on a circle of radius R
  // round the inner corner needs a channel wider than R (1 - 1/sqrt 2),
  // 88 m for 300 m.
  const ObstacleField field = Field({
      Rect(-2000, 30, -30, 2000),     // inside of the bend
      Rect(-2000, -2000, 2000, -30),  // south bank
      Rect(30, -30, 2000, 2000),      // east bank
  });
  const std::vector<EastNorth> route = {{-1500, 0}, {0, 0}, {0, 1500}};
  ASSERT_FALSE(field.SegmentHits(route[0], route[1]));
  ASSERT_FALSE(field.SegmentHits(route[1], route[2]));
  auto f = FilletTurns(field, route, TurnFilletOptions{});
  ASSERT_TRUE(f.ok()) << f.status();
  EXPECT_EQ(f->filleted, 0);
  ASSERT_EQ(f->unsailable.size(), 1u);
  EXPECT_EQ(f->unsailable[0].first, 1);
  EXPECT_NEAR(f->unsailable[0].turn_rad, 90 * kDeg, 1e-6);  // a left turn
  EXPECT_EQ(Positions(*f), route);
  // A hull that turns on 40 m fits (it needs 12 m of width).
  TurnFilletOptions tight;
  tight.radius_m = 40.0;
  tight.clearance_m = 0.0;
  auto g = FilletTurns(field, route, tight);
  ASSERT_TRUE(g.ok()) << g.status();
  EXPECT_EQ(g->filleted, 1);
  EXPECT_TRUE(g->unsailable.empty());
  ExpectClear(field, Positions(*g));
}

TEST(TurnFilletTest, ACornerTooNarrowForTheCircleIsTriedOnSmallerOnesDownToTheSmallest) {
  // A bend 80 m wide: a 300 m circle needs 88 m round the inner corner, a
  // 240 m one (the hull at full rudder) 70 m.
  const ObstacleField field = Field({
      Rect(-2000, 40, -40, 2000),
      Rect(-2000, -2000, 2000, -40),
      Rect(40, -40, 2000, 2000),
  });
  const std::vector<EastNorth> route = {{-1500, 0}, {0, 0}, {0, 1500}};
  TurnFilletOptions o;
  auto only = FilletTurns(field, route, o);
  ASSERT_TRUE(only.ok()) << only.status();
  EXPECT_EQ(only->filleted, 0);
  EXPECT_EQ(only->unsailable.size(), 1u);
  o.min_radius_m = 240.0;
  auto f = FilletTurns(field, route, o);
  ASSERT_TRUE(f.ok()) << f.status();
  EXPECT_EQ(f->filleted, 1);
  EXPECT_EQ(f->tightened, 1);
  EXPECT_TRUE(f->unsailable.empty());
  const std::vector<EastNorth> w = Positions(*f);
  ExpectSailable(w, 240.0);
  ExpectClear(field, w);
  // Narrower than the smallest circle allows: reported as before.
  const ObstacleField narrow = Field({
      Rect(-2000, 30, -30, 2000),
      Rect(-2000, -2000, 2000, -30),
      Rect(30, -30, 2000, 2000),
  });
  auto g = FilletTurns(narrow, route, o);
  ASSERT_TRUE(g.ok()) << g.status();
  EXPECT_EQ(g->filleted, 0);
  EXPECT_EQ(g->unsailable.size(), 1u);
  EXPECT_EQ(Positions(*g), route);
}

TEST(TurnFilletTest, ShortLegsAreReported) {
  // Open water, but a 90 deg turn 100 m after the start: a 300 m circle
  // needs 300 m of each leg.
  const ObstacleField field = Field({Rect(2000, 2000, 2500, 2500)});
  const std::vector<EastNorth> route = {{0, 0}, {100, 0}, {100, 1500}};
  auto f = FilletTurns(field, route, TurnFilletOptions{});
  ASSERT_TRUE(f.ok()) << f.status();
  EXPECT_EQ(f->filleted, 0);
  EXPECT_EQ(f->unsailable.size(), 1u);
}

TEST(TurnFilletTest, RejectsBadInput) {
  const ObstacleField field = Field({Rect(0, 0, 10, 10)});
  TurnFilletOptions o;
  EXPECT_FALSE(FilletTurns(field, {{0, 0}}, o).ok());
  EXPECT_FALSE(FilletTurns(field, {{0, 0}, {NAN, 1}}, o).ok());
  o.radius_m = 0.0;
  EXPECT_FALSE(FilletTurns(field, {{0, 0}, {1, 1}}, o).ok());
  o.radius_m = 300.0;
  o.min_radius_m = 301.0;  // above the radius
  EXPECT_FALSE(FilletTurns(field, {{0, 0}, {1, 1}}, o).ok());
  o.min_radius_m = -1.0;
  EXPECT_FALSE(FilletTurns(field, {{0, 0}, {1, 1}}, o).ok());
}

}  // namespace
}  // namespace seaplan::route
