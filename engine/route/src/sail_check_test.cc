#include "seaplan/route/sail_check.h"

#include <gtest/gtest.h>

#include <cmath>

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

TEST(SailRouteTest, RejectsBadInput) {
  EXPECT_FALSE(SailRoute({{0, 0}, {1000, 0}}, 0.0, nullptr).ok());
  EXPECT_FALSE(SailRoute({{0, 0}, {0.5, 0}}, 9.0, nullptr).ok());  // < 1 m apart
  EXPECT_FALSE(SailRoute({{0, 0}, {NAN, 0}}, 9.0, nullptr).ok());
}

}  // namespace
}  // namespace seaplan::route
