#include "encounter.h"

#include <gtest/gtest.h>

#include <cmath>

namespace seaplan::sim {
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

// Kinematic ships (velocity changes at once) stepping 1 s.
double RunEncounter(Kinematics own, EastNorth desired, Kinematics other, const AvoidanceOptions& o,
                    EastNorth* first_manoeuvre) {
  double min_d = 1e9;
  bool first = true;
  for (int t = 0; t < 800; ++t) {
    AvoidanceDecision d = ChooseVelocity(own, desired, {{other, 7}}, o);
    if (d.manoeuvring && first) {
      *first_manoeuvre = d.velocity;
      first = false;
    }
    own.velocity = d.velocity;
    own.position = own.position + own.velocity;
    other.position = other.position + other.velocity;
    min_d = std::min(min_d, (own.position - other.position).Norm());
  }
  return min_d;
}

TEST(AvoidanceTest, CrossingGiveWayKeepsCpaAboveSafetyAndTurnsToStarboard) {
  AvoidanceOptions o;
  o.safety_distance_m = 200;
  EastNorth manoeuvre{0, 0};
  double min_d = RunEncounter({{0, 0}, VelocityOf(kNorth, 5)}, VelocityOf(kNorth, 5),
                              {{1000, 1000}, VelocityOf(kWest, 5)}, o, &manoeuvre);
  EXPECT_GE(min_d, o.safety_distance_m * 0.97);
  EXPECT_GT(manoeuvre.east_m, 0.0) << "give way by turning to starboard (east)";
  // Without avoidance they would collide.
  EXPECT_NEAR(
      ComputeCpa({{0, 0}, VelocityOf(kNorth, 5)}, {{1000, 1000}, VelocityOf(kWest, 5)}).dcpa_m, 0,
      1e-9);
}

TEST(AvoidanceTest, HeadOnBothStarboardAndStandOnKeepsCourse) {
  AvoidanceOptions o;
  o.safety_distance_m = 150;
  EastNorth manoeuvre{0, 0};
  double min_d = RunEncounter({{0, 0}, VelocityOf(kNorth, 5)}, VelocityOf(kNorth, 5),
                              {{20, 3000}, VelocityOf(kSouth, 5)}, o, &manoeuvre);
  EXPECT_GE(min_d, o.safety_distance_m * 0.97);
  EXPECT_GT(manoeuvre.east_m, 0.0);
  // Crossing from port, far enough: stand on (no manoeuvre yet).
  Kinematics own{{0, 0}, VelocityOf(kNorth, 5)};
  AvoidanceDecision d =
      ChooseVelocity(own, own.velocity, {{{{-2000, 2000}, VelocityOf(kEast, 5)}, 3}}, o);
  EXPECT_FALSE(d.manoeuvring);
  EXPECT_EQ(d.role, Role::kCrossingStandOn);
  // Rule 17: close and still on collision course, the stand-on vessel acts.
  AvoidanceDecision late =
      ChooseVelocity(own, own.velocity, {{{{-400, 400}, VelocityOf(kEast, 5)}, 3}}, o);
  EXPECT_TRUE(late.manoeuvring);
}

}  // namespace
}  // namespace seaplan::sim

namespace seaplan::sim {
namespace {

// A slow-turning ship: the course follows the commanded one at most
// `turn_rate` rad/s, after a lag; speed changes at `accel`.
double RunSlowTurningEncounter(Kinematics own, EastNorth desired, Kinematics other,
                               const AvoidanceOptions& o, double turn_rate, int lag_steps,
                               Role* role) {
  double min_d = 1e9;
  std::vector<EastNorth> commands;
  double course = CourseOf(own.velocity), speed = own.velocity.Norm();
  for (int t = 0; t < 900; ++t) {
    AvoidanceDecision d = ChooseVelocity(own, desired, {{other, 7}}, o);
    if (d.manoeuvring && *role == Role::kNone) *role = d.role;
    commands.push_back(d.velocity);
    EastNorth cmd = commands[std::max(0, static_cast<int>(commands.size()) - 1 - lag_steps)];
    double dc = std::remainder(CourseOf(cmd) - course, 2 * M_PI);
    course += std::clamp(dc, -turn_rate, turn_rate);
    speed += std::clamp(cmd.Norm() - speed, -0.05, 0.05);
    own.velocity = VelocityOf(course, speed);
    own.position = own.position + own.velocity;
    other.position = other.position + other.velocity;
    min_d = std::min(min_d, (own.position - other.position).Norm());
  }
  return min_d;
}

TEST(AvoidanceTest, SlowTurningHullKeepsTheSafetyDistanceWhenTheDelayIsModelled) {
  AvoidanceOptions o;
  o.safety_distance_m = 120;
  o.turn_rate_rad_s = 0.0175;
  o.manoeuvre_lag_s = 20;
  const double kNorthC = 0.0;
  // The other crosses from starboard (we give way) at a late-ish detection.
  Role role = Role::kNone;
  double min_d =
      RunSlowTurningEncounter({{0, 0}, VelocityOf(kEast, 3.6)}, VelocityOf(kEast, 3.6),
                              {{1300, -500}, VelocityOf(kNorthC, 1.6)}, o, 0.0175, 10, &role);
  EXPECT_EQ(role, Role::kCrossingGiveWay);
  EXPECT_GE(min_d, o.safety_distance_m) << "CPA with the turning delay modelled";
}

}  // namespace
}  // namespace seaplan::sim

namespace seaplan::sim {
namespace {

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
TEST(AvoidanceTest, GiveWayManoeuvreKeepsClearOfLand) {
  const std::vector<std::vector<EastNorth>> south_shore = {
      {{-5000, -100}, {5000, -100}, {5000, -2000}, {-5000, -2000}}};
  AvoidanceOptions o;
  o.safety_distance_m = 120;
  const Kinematics own{{0, 0}, VelocityOf(kEast, 9)};
  // Crossing from starboard (south-east), on a collision course.
  const Kinematics other{{1200, -60}, VelocityOf(kNorth, 0.5)};
  AvoidanceDecision blind = ChooseVelocity(own, own.velocity, {{other, 1}}, o);
  ASSERT_TRUE(blind.manoeuvring);
  EXPECT_LT(
      LandClearance(south_shore, own.position, own.position + blind.velocity * o.land_lookahead_s),
      o.land_clearance_m)
      << "the scenario must make the land-blind choice head for the shore";
  const LandIndex index(south_shore);
  o.land = &index;
  AvoidanceDecision aware = ChooseVelocity(own, own.velocity, {{other, 1}}, o);
  ASSERT_TRUE(aware.manoeuvring);
  EXPECT_GE(
      LandClearance(south_shore, own.position, own.position + aware.velocity * o.land_lookahead_s),
      o.land_clearance_m);
}

// Overtaken in a narrow channel by a vessel that does not keep clear: land
// blocks every turn and slowing down only lets it catch up sooner, so the
// way out is to speed up, which the avoidance tries only when it knows the
// hull's top speed.
TEST(AvoidanceTest, OvertakenInAChannelSpeedsUpWhenTurningIsBlocked) {
  const std::vector<std::vector<EastNorth>> banks = {
      {{-500, -3000}, {-70, -3000}, {-70, 3000}, {-500, 3000}},
      {{70, -3000}, {500, -3000}, {500, 3000}, {70, 3000}}};
  const LandIndex index(banks);
  AvoidanceOptions o;
  o.safety_distance_m = 100;
  o.land = &index;
  const Kinematics own{{0, 0}, VelocityOf(kNorth, 3)};
  const Kinematics overtaker{{0, -250},
                             VelocityOf(kNorth, 4)};  // CPA 0 in 250 s: rule 17 lets us act
  AvoidanceDecision unknown_top = ChooseVelocity(own, own.velocity, {{overtaker, 1}}, o);
  EXPECT_EQ(unknown_top.role, Role::kOvertaken);
  EXPECT_FALSE(unknown_top.feasible) << "without a top speed only turns and slowing down are tried";
  o.max_speed_mps = 6;
  AvoidanceDecision d = ChooseVelocity(own, own.velocity, {{overtaker, 1}}, o);
  EXPECT_TRUE(d.feasible);
  EXPECT_TRUE(d.manoeuvring);
  EXPECT_GT(d.velocity.Norm(), 3.5);
  EXPECT_LE(d.velocity.Norm(), 6.0 + 1e-9);
  EXPECT_GE(LandClearance(banks, own.position, own.position + d.velocity * o.land_lookahead_s),
            o.land_clearance_m);
  const Cpa cpa = ComputeCpa({own.position, d.velocity}, overtaker);  // within the horizon
  const EastNorth rel = overtaker.velocity - d.velocity;
  const double t = cpa.tcpa_s > 0 ? std::min(cpa.tcpa_s, o.horizon_s) : 0.0;
  EXPECT_GE((overtaker.position + rel * t - own.position).Norm(), o.safety_distance_m - 1e-6);
}

// When every candidate cuts into the safety circle, the one chosen keeps the
// most distance under the manoeuvre delay, not the one whose straight-line
// CPA (ignoring the delay) looks best.
TEST(AvoidanceTest, LeastBadCandidateKeepsTheMostDistanceUnderTheDelay) {
  AvoidanceOptions o;
  o.safety_distance_m = 300;
  o.turn_rate_rad_s = 0.0175;
  o.manoeuvre_lag_s = 20;
  const Kinematics own{{0, 0}, VelocityOf(kNorth, 8)};
  const Kinematics other{{0, 800}, VelocityOf(kSouth, 2)};  // head-on, 80 s apart
  AvoidanceDecision d = ChooseVelocity(own, own.velocity, {{other, 1}}, o);
  ASSERT_FALSE(d.feasible);
  EXPECT_TRUE(d.manoeuvring);
  // Every candidate: present velocity for the delay, then the candidate.
  auto min_distance = [&](EastNorth v) {
    double best = 1e9;
    for (double t = 0; t <= o.horizon_s; t += 0.25) {
      const double turn = std::abs(std::remainder(CourseOf(v) - CourseOf(own.velocity), 2 * M_PI));
      const double delay =
          turn / o.turn_rate_rad_s + std::abs(v.Norm() - 8.0) / o.acceleration_mps2;
      const double lagged = delay > 1e-3 ? delay + o.manoeuvre_lag_s : 0.0;
      const EastNorth p = t < lagged ? own.velocity * t : own.velocity * lagged + v * (t - lagged);
      best = std::min(best, (other.position + other.velocity * t - p).Norm());
    }
    return best;
  };
  // Ties within a tenth of the safety distance are broken by the clearance
  // the velocity would give at once (see ChooseVelocity).
  const double chosen = min_distance(d.velocity);
  for (double c = -M_PI / 2; c <= M_PI / 2 + 1e-9; c += M_PI / 36) {
    EXPECT_GE(chosen + 0.1 * o.safety_distance_m + 2.0, min_distance(VelocityOf(c, 8)))
        << "course " << c * 180 / M_PI;
  }
  EXPECT_GT(chosen, min_distance(own.velocity) + 50.0) << "holding on is the worst choice";
}

// A conflict past a turn of the route: the straight-line CPA sees none, the
// path-ahead prediction does, and at a lower speed it is gone.
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
}  // namespace seaplan::sim
