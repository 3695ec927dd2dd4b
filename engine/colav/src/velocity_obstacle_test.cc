#include "seaplan/colav/velocity_obstacle.h"

#include <gtest/gtest.h>

#include <cmath>

namespace seaplan::colav {
namespace {

constexpr double kNorth = 0.0, kEast = M_PI / 2, kSouth = M_PI, kWest = 3 * M_PI / 2;

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
}  // namespace seaplan::colav

namespace seaplan::colav {
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
}  // namespace seaplan::colav

namespace seaplan::colav {
namespace {

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
}  // namespace
}  // namespace seaplan::colav
