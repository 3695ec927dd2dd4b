#include "seaplan/colav/geometry.h"

#include <gtest/gtest.h>

#include <cmath>

namespace seaplan::colav {
namespace {

constexpr double kNorth = 0.0, kEast = M_PI / 2, kSouth = M_PI, kWest = 3 * M_PI / 2;

TEST(CpaTest, HandComputedCrossing) {
  Kinematics own{{0, 0}, VelocityOf(kNorth, 5)};
  // Relative position (1000, 500), relative velocity (-5, -5):
  // t = (5000 + 2500) / 50 = 150 s, closest (1000-750, 500-750) = (250, -250).
  Kinematics other{{1000, 500}, VelocityOf(kWest, 5)};
  Cpa c = ComputeCpa(own, other);
  EXPECT_NEAR(c.tcpa_s, 150.0, 1e-9);
  EXPECT_NEAR(c.dcpa_m, std::hypot(250, 250), 1e-9);
  // Collision course: they meet at (0, 1000) after 200 s.
  Cpa hit = ComputeCpa(own, {{1000, 1000}, VelocityOf(kWest, 5)});
  EXPECT_NEAR(hit.tcpa_s, 200.0, 1e-9);
  EXPECT_NEAR(hit.dcpa_m, 0.0, 1e-9);
  // Diverging: CPA is now.
  Cpa away = ComputeCpa(own, {{0, -300}, VelocityOf(kSouth, 2)});
  EXPECT_DOUBLE_EQ(away.tcpa_s, 0.0);
  EXPECT_NEAR(away.dcpa_m, 300.0, 1e-9);
}

TEST(ColregTest, HeadOnCrossingOvertaking) {
  Kinematics own{{0, 0}, VelocityOf(kNorth, 5)};
  EXPECT_EQ(ClassifyEncounter(own, {{50, 2000}, VelocityOf(kSouth, 5)}), Role::kHeadOn);
  Kinematics from_starboard{{1000, 1000}, VelocityOf(kWest, 5)};
  EXPECT_EQ(ClassifyEncounter(own, from_starboard), Role::kCrossingGiveWay);
  EXPECT_EQ(ClassifyEncounter(from_starboard, own), Role::kCrossingStandOn);
  Kinematics slow_ahead{{0, 500}, VelocityOf(kNorth, 3)};
  Kinematics fast{{0, 0}, VelocityOf(kNorth, 6)};
  EXPECT_EQ(ClassifyEncounter(fast, slow_ahead), Role::kOvertaking);
  EXPECT_EQ(ClassifyEncounter(slow_ahead, fast), Role::kOvertaken);
  EXPECT_TRUE(IsGiveWay(Role::kHeadOn));
  EXPECT_FALSE(IsGiveWay(Role::kCrossingStandOn));
}

TEST(LandClearanceTest, CrossingInsideAndDistance) {
  const std::vector<std::vector<EastNorth>> land = {{{0, 100}, {1000, 100}, {1000, 300}, {0, 300}}};
  EXPECT_EQ(LandClearance(land, {500, 0}, {500, 200}), 0.0);    // crosses the shore
  EXPECT_EQ(LandClearance(land, {500, 150}, {510, 160}), 0.0);  // starts on land
  EXPECT_NEAR(LandClearance(land, {0, 40}, {1000, 40}), 60.0, 1e-9);
  EXPECT_NEAR(LandClearance(land, {1100, 0}, {1100, 400}), 100.0, 1e-9);
  // The grid index agrees (capped at its limit), with cells smaller than
  // the rectangle so edges span several cells.
  const LandIndex index(land, 150.0);
  EXPECT_EQ(index.Clearance({500, 0}, {500, 200}, 80), 0.0);
  EXPECT_NEAR(index.Clearance({0, 40}, {1000, 40}, 80), 60.0, 1e-9);
  EXPECT_NEAR(index.Clearance({1100, 0}, {1100, 400}, 80), 80.0, 1e-9);  // beyond the limit
  EXPECT_NEAR(index.Clearance({-700, -500}, {-600, -500}, 1000),
              LandClearance(land, {-700, -500}, {-600, -500}), 1e-9);
}

// Giving way to starboard would run the ship onto the shore just south of
// it: the avoidance picks a velocity whose track stays clear of the land.
TEST(PathAheadTest, SeesAConflictPastTheTurnThatTheStraightLineMisses) {
  // East 900 m, then south; a vessel heading west along y = -600.
  const std::vector<EastNorth> path = {{0, 0}, {900, 0}, {900, -2000}};
  const Kinematics own{{0, 0}, VelocityOf(kEast, 9)};
  const Kinematics other{{1700, -600}, VelocityOf(kWest, 5)};
  EXPECT_GT(ComputeCpa(own, other).dcpa_m, 500.0);
  const PathApproach fast = PathAheadClosestApproach(path, 1, own.position, 9.0, other, 300.0, 1.0);
  EXPECT_LT(fast.distance_m, 60.0);
  EXPECT_NEAR(fast.time_s, 167.0, 10.0);  // 900 m east + 600 m south at 9 m/s
  const PathApproach slow = PathAheadClosestApproach(path, 1, own.position, 4.5, other, 300.0, 1.0);
  EXPECT_GT(slow.distance_m, 300.0);
  // The path's end is held: no extrapolation past the last point.
  const PathApproach end =
      PathAheadClosestApproach({{0, 0}, {100, 0}}, 1, {0, 0}, 10.0, {{100, 500}, {0, 0}}, 300.0);
  EXPECT_NEAR(end.distance_m, 500.0, 1e-9);
}

// A ship leaving its berth reaches a crossing point later than one already
// at speed: with the speed ramp the prediction sees the meeting that the
// instant-speed one misses.
TEST(PathAheadTest, SpeedRampFromRestDelaysTheArrival) {
  const std::vector<EastNorth> path = {{0, 0}, {3000, 0}};
  const Kinematics crossing{{800, -450}, VelocityOf(kNorth, 2.5)};  // at (800, 0) at t = 180 s
  const PathApproach instant = PathAheadClosestApproach(path, 1, {0, 0}, 9.0, crossing, 300.0, 1.0);
  EXPECT_GT(instant.distance_m, 150.0);
  // From rest at 0.05 m/s^2: 810 m after 180 s.
  const PathApproach ramped =
      PathAheadClosestApproach(path, 1, {0, 0}, 9.0, crossing, 300.0, 1.0, 0.0, 0.05);
  EXPECT_LT(ramped.distance_m, 50.0);
  EXPECT_NEAR(ramped.time_s, 180.0, 10.0);
}

TEST(LandIndexTest, InsideAndSignedClearanceAgreeWithTheFullScan) {
  // A square island with a square lagoon (a hole drawn as a second ring).
  const std::vector<std::vector<EastNorth>> land = {
      {{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}},
      {{400, 400}, {600, 400}, {600, 600}, {400, 600}}};
  const LandIndex index(land, 150.0);
  EXPECT_TRUE(index.Inside({100, 500}));
  EXPECT_FALSE(index.Inside({500, 500})) << "the lagoon is water";
  EXPECT_FALSE(index.Inside({-50, 500}));
  EXPECT_FALSE(index.Inside({1500, 2000}));
  EXPECT_NEAR(index.SignedClearance({-50, 500}, 1000), 50.0, 1e-9);
  EXPECT_NEAR(index.SignedClearance({100, 500}, 1000), -100.0, 1e-9);
  EXPECT_NEAR(index.SignedClearance({500, 500}, 1000), 100.0, 1e-9);
  EXPECT_NEAR(index.SignedClearance({5000, 500}, 1000), 1000.0, 1e-9) << "capped at the limit";
  // Against brute force: even-odd over all edges, distance to the nearest edge.
  for (double x = -200; x <= 1200; x += 37) {
    for (double y = -200; y <= 1200; y += 41) {
      bool in = false;
      double dist = 1e18;
      for (const auto& ring : land) {
        for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
          const EastNorth c = ring[j], d = ring[i];
          if ((c.north_m > y) != (d.north_m > y) &&
              x < (d.east_m - c.east_m) * (y - c.north_m) / (d.north_m - c.north_m) + c.east_m)
            in = !in;
          const EastNorth e = d - c;
          const double t = std::clamp(((EastNorth{x, y} - c).Dot(e)) / e.Dot(e), 0.0, 1.0);
          dist = std::min(dist, (EastNorth{x, y} - (c + e * t)).Norm());
        }
      }
      EXPECT_EQ(index.Inside({x, y}), in) << x << ", " << y;
      EXPECT_NEAR(index.SignedClearance({x, y}, 5000), in ? -dist : dist, 1e-6) << x << ", " << y;
    }
  }
}

}  // namespace
}  // namespace seaplan::colav
