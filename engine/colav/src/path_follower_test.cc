#include "seaplan/colav/path_follower.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace seaplan::colav {
namespace {

TEST(PathFollowerTest, RejectsBadPaths) {
  EXPECT_FALSE(PathFollower::Create({{0, 0}}).ok());
  EXPECT_FALSE(PathFollower::Create({{0, 0}, {0, 0}}).ok());
  EXPECT_FALSE(PathFollower::Create({{0, 0}, {NAN, 1}}).ok());
  PathFollowerOptions bad;
  bad.lookahead_m = 0;
  EXPECT_FALSE(PathFollower::Create({{0, 0}, {1, 0}}, bad).ok());
}

TEST(PathFollowerTest, SteersBackTowardsTheLegWithBoundedApproach) {
  auto f = PathFollower::Create({{0, 0}, {2000, 0}, {2000, 2000}});
  ASSERT_TRUE(f.ok());
  // 500 m north (port side) of the eastbound first leg: head south-east, not further away.
  double c = f->Update({800, 500});
  EXPECT_EQ(f->leg(), 0);
  EXPECT_NEAR(f->cross_track_m(), -500, 1e-9);
  EXPECT_GT(c, M_PI / 2);
  EXPECT_LT(c, M_PI);  // never beyond perpendicular to the leg
}

TEST(PathFollowerTest, ChoosesTheLegByProgressAfterLeavingThePath) {
  // The ship was pushed well clear of the corner at (2000, 0) (it never came
  // near that waypoint) and is now beside the second leg: it follows the
  // second leg, it does not go back to the corner.
  auto f = PathFollower::Create({{0, 0}, {2000, 0}, {2000, 2000}, {4000, 2000}});
  ASSERT_TRUE(f.ok());
  f->Update({100, 0});
  EXPECT_EQ(f->leg(), 0);
  double c = f->Update({2400, 900});
  EXPECT_EQ(f->leg(), 1);
  EXPECT_NEAR(f->cross_track_m(), 400, 1e-9);  // east of a northbound leg = starboard
  EXPECT_LT(c, 0.01 + 2 * M_PI);
  EXPECT_GT(c, 1.5 * M_PI);  // north-west: back to the leg while progressing
  // Never back to an earlier leg.
  f->Update({1000, 10});
  EXPECT_EQ(f->leg(), 1);
}

TEST(PathFollowerTest, KinematicShipConvergesAndReachesTheEnd) {
  auto f = PathFollower::Create({{0, 0}, {1500, 0}, {1500, 1500}, {3000, 1500}});
  ASSERT_TRUE(f.ok());
  EastNorth p{600, -700};  // far off, as after a long avoidance manoeuvre
  double course = 0;
  const double max_turn = 0.02;  // rad per 1 s step: a slow-turning hull
  double worst_late = 0;
  for (int t = 0; t < 3000 && (p - EastNorth{3000, 1500}).Norm() > 60; ++t) {
    double want = f->Update(p);
    double dc = std::remainder(want - course, 2 * M_PI);
    course += std::clamp(dc, -max_turn, max_turn);
    p = p + VelocityOf(course, 4.0);
    if (t > 600) worst_late = std::max(worst_late, std::abs(f->cross_track_m()));
  }
  EXPECT_LT((p - EastNorth{3000, 1500}).Norm(), 60);
  EXPECT_LT(worst_late, 150);
}

TEST(PathFollowerTest, WheelOverStartsTheTurnBeforeTheCorner) {
  // A right-angle corner at (2000, 0), waypoints every 100 m before it.
  std::vector<EastNorth> path;
  for (int x = 0; x <= 2000; x += 100) path.push_back({static_cast<double>(x), 0});
  path.push_back({2000, 2000});
  PathFollowerOptions late;
  auto plain = PathFollower::Create(path, late);
  PathFollowerOptions early;
  early.turn_radius_m = 300;  // switches 300 tan(40.5 deg) = 256 m before the corner
  auto wheel = PathFollower::Create(path, early);
  ASSERT_TRUE(plain.ok() && wheel.ok());
  for (double x = 0; x <= 1800; x += 50) {
    plain->Update({x, 0});
    wheel->Update({x, 0});
  }
  EXPECT_EQ(plain->leg(), 18);                    // still on the leg 1800-1900
  EXPECT_EQ(wheel->leg(), 20);                    // already steering for the northbound leg
  EXPECT_LT(wheel->Update({1800, 0}), M_PI / 2);  // turning left of east, towards north
  PathFollowerOptions bad;
  bad.turn_radius_m = -1;
  EXPECT_FALSE(bad.Validate().ok());
}

TEST(PathFollowerTest, TheChordAlongThePathLeadsTheCornerAndMatchesOnAStraight) {
  const std::vector<EastNorth> path = {{0, 0}, {1000, 0}, {1000, 1000}};
  PathFollowerOptions on_leg;
  PathFollowerOptions along;
  along.chord_s = 100;  // 400 m at 4 m/s
  auto leg = PathFollower::Create(path, on_leg);
  auto ahead = PathFollower::Create(path, along);
  ASSERT_TRUE(leg.ok() && ahead.ok());
  // 50 m north of the first leg, far from the corner: both steer east and
  // back south by atan(50 / 400).
  const double straight = M_PI / 2 + std::atan(50.0 / 400.0);
  EXPECT_NEAR(leg->Update({100, 50}), straight, 1e-9);
  EXPECT_NEAR(ahead->Update({100, 50}, 4.0), straight, 1e-9);
  // 200 m before the corner, on the leg: the chord's end is 200 m up the
  // northbound leg, 45 deg left of the leg's course; on the leg: due east.
  EXPECT_NEAR(leg->Update({800, 0}), M_PI / 2, 1e-9);
  EXPECT_NEAR(ahead->Update({800, 0}, 4.0), M_PI / 4, 1e-9);
  // Slower, a shorter chord: 300 m ends 100 m up the northbound leg.
  EXPECT_NEAR(ahead->Update({800, 0}, 3.0), std::atan2(200.0, 100.0), 1e-9);
  EXPECT_NEAR(ahead->Update({800, 0}), M_PI / 2, 1e-9);  // at rest: no chord
  // Past the path's end the chord runs on along the last leg's line.
  EXPECT_NEAR(ahead->Update({1000, 1200}, 4.0), 0.0, 1e-9);
}

}  // namespace
}  // namespace seaplan::colav
