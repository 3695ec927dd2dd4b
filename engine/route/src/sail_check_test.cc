#include "seaplan/route/sail_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "obstacle_test_fields.h"

namespace seaplan::route {
namespace {

using test_fields::Field;
using test_fields::Rect;

TEST(SailRouteTest, TheTrackOfASharpCornerIsCheckedNotThePolyline) {
  // North for 2 km, then a right angle to the east. The hull under its
  // autopilot cannot turn on the corner: it swings out to the north of the
  // eastbound leg before it rejoins it.
  const std::vector<EastNorth> route = {{0, -2000}, {0, 0}, {2000, 0}};
  auto free = SailRoute(route, 9.0, nullptr);
  ASSERT_TRUE(free.ok()) << free.status();
  EXPECT_TRUE(free->arrived);
  double overshoot_m = 0.0;
  for (const EastNorth& p : free->track) overshoot_m = std::max(overshoot_m, p.north_m);
  EXPECT_GT(overshoot_m, 100.0);

  // A shoal 60 m north of the eastbound leg: the polyline keeps clear of
  // it, the sailed track does not.
  const ObstacleField shoal = Field({Rect(100, 60, 1500, 600)});
  EXPECT_FALSE(shoal.SegmentHits(route[0], route[1]));
  EXPECT_FALSE(shoal.SegmentHits(route[1], route[2]));
  auto s = SailRoute(route, 9.0, &shoal);
  ASSERT_TRUE(s.ok()) << s.status();
  EXPECT_TRUE(s->touches);
  EXPECT_LE(s->clearance_m, 0.0);
  EXPECT_GT(s->closest.north_m, 60.0 - 20.0);

  // The same shoal beyond the swing: the track keeps clear, by about the
  // distance between the shoal and the farthest point of the swing.
  const ObstacleField far = Field({Rect(100, overshoot_m + 50.0, 1500, overshoot_m + 600.0)});
  auto c = SailRoute(route, 9.0, &far);
  ASSERT_TRUE(c.ok()) << c.status();
  EXPECT_FALSE(c->touches);
  EXPECT_NEAR(c->clearance_m, 50.0, 5.0);
}

std::vector<EastNorth> Line(const std::vector<FilletPoint>& points) {
  std::vector<EastNorth> line;
  for (const FilletPoint& p : points) line.push_back(p.position);
  return line;
}

TEST(RepairSailedRouteTest, ACornerWhoseTrackGroundsIsBentUntilTheTrackKeepsClear) {
  // The right angle of the test above with the shoal 60 m north of the
  // eastbound leg: the polyline keeps clear, the track does not.
  const std::vector<EastNorth> route = {{0, -2000}, {0, 0}, {2000, 0}};
  const ObstacleField shoal = Field({Rect(100, 60, 1500, 600)});
  auto s = SailRoute(route, 9.0, &shoal);
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_TRUE(s->touches);

  SailRepairOptions off;
  off.max_sails = 0;
  auto none = RepairSailedRoute(shoal, route, *s, 9.0, off);
  ASSERT_TRUE(none.ok()) << none.status();
  EXPECT_EQ(none->bends, 0);
  EXPECT_EQ(Line(none->points), route);
  EXPECT_FALSE(none->track.Clear());

  auto fix = RepairSailedRoute(shoal, route, *s, 9.0, SailRepairOptions{});
  ASSERT_TRUE(fix.ok()) << fix.status();
  EXPECT_GE(fix->bends, 1);
  EXPECT_LE(fix->sails, SailRepairOptions{}.max_sails);
  EXPECT_TRUE(fix->track.Clear()) << fix->track.clearance_m;
  const std::vector<EastNorth> bent = Line(fix->points);
  EXPECT_EQ(bent.front(), route.front());
  EXPECT_EQ(bent.back(), route.back());
  for (size_t i = 1; i < bent.size(); ++i) EXPECT_FALSE(shoal.SegmentHits(bent[i - 1], bent[i]));
  // The repaired route sailed again: the track the repair reports.
  auto again = SailRoute(bent, 9.0, &shoal);
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_TRUE(again->Clear());
  EXPECT_NEAR(again->clearance_m, fix->track.clearance_m, 1e-9);
  // The input points it kept are where they were.
  for (const FilletPoint& p : fix->points) {
    if (p.source >= 0) {
      EXPECT_EQ(p.position, route[p.source]);
    }
  }
}

// A rock put where the track of `route` sailed in open water strays
// farthest from it (at least `min_swing_m`, off the polyline itself): the
// track sailed among it grounds, and the repair bends the route, clear of
// the rock, until its track keeps clear.
void ExpectRepairClearsARockWhereTheTrackSwings(const std::vector<EastNorth>& route,
                                                double min_swing_m) {
  auto free = SailRoute(route, 9.0, nullptr);
  ASSERT_TRUE(free.ok()) << free.status();
  const auto [widest, widest_m] = test_fields::WidestSwing(route, free->track);
  ASSERT_GT(widest_m, min_swing_m);
  const ObstacleField rock = Field(
      {Rect(widest.east_m - 15, widest.north_m - 15, widest.east_m + 15, widest.north_m + 15)});
  for (size_t i = 1; i < route.size(); ++i) ASSERT_FALSE(rock.SegmentHits(route[i - 1], route[i]));
  auto s = SailRoute(route, 9.0, &rock);
  ASSERT_TRUE(s.ok()) << s.status();
  ASSERT_FALSE(s->Clear());
  auto fix = RepairSailedRoute(rock, route, *s, 9.0, SailRepairOptions{});
  ASSERT_TRUE(fix.ok()) << fix.status();
  EXPECT_GE(fix->bends, 1);
  EXPECT_TRUE(fix->track.Clear()) << fix->track.clearance_m;
  const std::vector<EastNorth> bent = Line(fix->points);
  for (size_t i = 1; i < bent.size(); ++i) EXPECT_FALSE(rock.SegmentHits(bent[i - 1], bent[i]));
  auto again = SailRoute(bent, 9.0, &rock);
  ASSERT_TRUE(again.ok()) << again.status();
  EXPECT_TRUE(again->Clear());
}

TEST(RepairSailedRouteTest, AnSBendWhoseTrackGroundsIsBentUntilTheTrackKeepsClear) {
  // Two opposite 90 deg arcs of 450 m (15 deg chords) with no straight
  // between them. The hull lags the first and comes out of it wide, on the
  // inside of the second: a rock put where the track strays farthest from
  // the route (off the polyline) is hit by the track.
  std::vector<EastNorth> route = {{-2000, 0}};
  for (int k = 0; k <= 6; ++k) {  // left about (0, 450)
    const double a = -M_PI / 2 + k * M_PI / 12;
    route.push_back({450 * std::cos(a), 450 + 450 * std::sin(a)});
  }
  for (int k = 1; k <= 6; ++k) {  // right about (900, 450)
    const double a = M_PI - k * M_PI / 12;
    route.push_back({900 + 450 * std::cos(a), 450 + 450 * std::sin(a)});
  }
  route.push_back({2900, 900});
  ExpectRepairClearsARockWhereTheTrackSwings(route, 60.0);
}

TEST(RepairSailedRouteTest, AHairpinWhoseTrackGroundsIsRepairedUntilTheTrackKeepsClear) {
  // Out and back round a point, the legs 400 m apart at the start: the
  // hull cannot turn 170 deg on the corner (its circle at full rudder is
  // ~240 m in radius) and swings far off the route; a rock where it swings
  // farthest (off the polyline) is hit by the track.
  const std::vector<EastNorth> route = {{-2500, 200}, {0, 0}, {-2500, -200}};
  ExpectRepairClearsARockWhereTheTrackSwings(route, 100.0);
}

TEST(RepairSailedRouteTest, RejectsBadOptions) {
  const std::vector<EastNorth> route = {{0, -2000}, {0, 0}, {2000, 0}};
  const ObstacleField shoal = Field({Rect(100, 60, 1500, 600)});
  auto s = SailRoute(route, 9.0, &shoal);
  ASSERT_TRUE(s.ok()) << s.status();
  SailRepairOptions bad;
  bad.window_m = 0.0;
  EXPECT_FALSE(RepairSailedRoute(shoal, route, *s, 9.0, bad).ok());
  bad = SailRepairOptions{};
  bad.max_sails = -1;
  EXPECT_FALSE(RepairSailedRoute(shoal, route, *s, 9.0, bad).ok());
}

TEST(SailRouteTest, RejectsBadInput) {
  EXPECT_FALSE(SailRoute({{0, 0}, {1000, 0}}, 0.0, nullptr).ok());
  EXPECT_FALSE(SailRoute({{0, 0}, {0.5, 0}}, 9.0, nullptr).ok());  // < 1 m apart
  EXPECT_FALSE(SailRoute({{0, 0}, {NAN, 0}}, 9.0, nullptr).ok());
}

}  // namespace
}  // namespace seaplan::route
