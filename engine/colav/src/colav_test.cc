#include "seaplan/colav/colav.h"

#include <gtest/gtest.h>

#include <cmath>

#include "seaplan/colav/encounter_sim.h"

namespace seaplan::colav {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The own ship at the origin heading north at 9 m/s, on a path north.
struct Fixture {
  ship::ShipModel model;
  Autopilot autopilot;
  PathFollower path;
  static Fixture Make() {
    auto ship = ShipUnderWay({0, 0}, 0.0, 9.0);
    EXPECT_TRUE(ship.ok()) << ship.status();
    return {ship->model, ship->autopilot, *PathFollower::Create({{0, 0}, {0, 9000}})};
  }
  Command Step(CollisionAvoidance& ca, double t, const std::vector<Obstacle>& traffic) {
    const double course = path.Update({model.state().east_m(), model.state().north_m()});
    return ca.Step({t, &model, &autopilot}, {course, 9.0, 9.0}, path, traffic);
  }
};

// A vessel on `course_deg` at `speed` reaching (0, 9 * t_meet) at t_meet.
Obstacle Meeting(double course_deg, double speed, double t_meet) {
  const EastNorth v = VelocityOf(course_deg * kDeg, speed);
  return {{EastNorth{0, 9.0 * t_meet} - v * t_meet, v}, 7};
}

TEST(CollisionAvoidanceTest, RejectsBadOptions) {
  CollisionAvoidanceOptions o;
  o.safety_distance_m = 0;
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.margin_factor = 0.5;
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.speed_factors.clear();
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.course_offsets_deg = {270};
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.track_offsets_m = {0};
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.uncertain_speed_mps = -1;
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.min_land_clearance_m = -1;
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.land_step_m = 0;
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  o = {};
  o.margin_land_clearance_m = -1;
  EXPECT_FALSE(CollisionAvoidance::Create(o).ok());
  EXPECT_TRUE(CollisionAvoidance::Create({}).ok());
}

TEST(CollisionAvoidanceTest, WithoutTrafficTheDesiredMotionIsCommanded) {
  Fixture f = Fixture::Make();
  auto ca = CollisionAvoidance::Create({});
  ASSERT_TRUE(ca.ok());
  const Command c = f.Step(*ca, 0, {});
  EXPECT_FALSE(c.manoeuvring);
  EXPECT_TRUE(c.events.empty());
  EXPECT_NEAR(c.course_rad, 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(c.speed_mps, 9.0);
  // A vessel far off and diverging is no encounter either.
  const Command far = f.Step(*ca, 10, {{{{5000, -5000}, VelocityOf(135 * kDeg, 9)}, 3}});
  EXPECT_FALSE(far.manoeuvring);
  EXPECT_TRUE(far.events.empty());
}

TEST(CollisionAvoidanceTest, HeadOnTurnsToStarboardAndHoldsTheBehaviourBetweenDecisions) {
  Fixture f = Fixture::Make();
  auto ca = CollisionAvoidance::Create({});
  ASSERT_TRUE(ca.ok());
  const std::vector<Obstacle> traffic = {Meeting(180, 9, 300)};
  const Command c = f.Step(*ca, 0, traffic);
  ASSERT_TRUE(c.manoeuvring);
  EXPECT_EQ(ca->RoleOf(7), Role::kHeadOn);
  EXPECT_GE(c.course_rad, 30 * kDeg - 1e-9);  // starboard, readily apparent
  ASSERT_EQ(c.events.size(), 2u);
  EXPECT_EQ(c.events[0].kind, EventKind::kPotentialCollision);
  EXPECT_EQ(c.events[1].kind, EventKind::kManoeuvreStarted);
  EXPECT_NE(c.events[1].detail.find("starboard"), std::string::npos) << c.events[1].detail;
  // Before the next decision the same offset is applied to the path's course.
  const Command held = f.Step(*ca, 2, traffic);
  EXPECT_TRUE(held.manoeuvring);
  EXPECT_TRUE(held.events.empty());
  EXPECT_NEAR(held.course_rad, c.course_rad, 1e-6);
}

TEST(CollisionAvoidanceTest, StandOnKeepsCourseUntilRule17ThenNotToPort) {
  CollisionAvoidanceOptions o;
  auto ca = CollisionAvoidance::Create(o);
  ASSERT_TRUE(ca.ok());
  Fixture f = Fixture::Make();
  // From port on a collision course, 400 s out: stand on.
  const Command early = f.Step(*ca, 0, {Meeting(90, 9, 400)});
  EXPECT_FALSE(early.manoeuvring);
  EXPECT_EQ(ca->RoleOf(7), Role::kCrossingStandOn);
  ASSERT_EQ(early.events.size(), 1u);
  EXPECT_EQ(early.events[0].kind, EventKind::kPotentialCollision);
  // The same geometry 200 s out (the other has not given way): rule 17.
  Fixture g = Fixture::Make();
  auto late_ca = CollisionAvoidance::Create(o);
  ASSERT_TRUE(late_ca.ok());
  const Command late = g.Step(*late_ca, 0, {Meeting(90, 9, 200)});
  EXPECT_TRUE(late.manoeuvring);
  EXPECT_GE(late.course_rad, -1e-9) << "rule 17 c: no turn to port for a vessel on the port side";
}

TEST(CollisionAvoidanceTest, AVesselLyingStillNearThePathIsGivenMoreRoom) {
  // Lying still 300 m east of the path, 2 km ahead: on its present
  // velocity it stays beyond the planning distance (225 m), but it may get
  // under way towards the path before the ship is past.
  const std::vector<Obstacle> still = {{{{300, 2000}, {0, 0}}, 7}};
  CollisionAvoidanceOptions certain;
  certain.uncertain_speed_mps = 0;
  Fixture f = Fixture::Make();
  auto ca = CollisionAvoidance::Create(certain);
  ASSERT_TRUE(ca.ok());
  const Command ignored = f.Step(*ca, 0, still);
  EXPECT_FALSE(ignored.manoeuvring);
  EXPECT_TRUE(ignored.events.empty());
  Fixture g = Fixture::Make();
  auto robust = CollisionAvoidance::Create({});
  ASSERT_TRUE(robust.ok());
  const Command c = g.Step(*robust, 0, still);
  ASSERT_FALSE(c.events.empty());
  EXPECT_EQ(c.events[0].kind, EventKind::kPotentialCollision);
  EXPECT_TRUE(c.manoeuvring);
}

TEST(CollisionAvoidanceTest, StaysActiveUntilTheShipIsBackOnItsPath) {
  Fixture f = Fixture::Make();
  auto ca = CollisionAvoidance::Create({});
  ASSERT_TRUE(ca.ok());
  EXPECT_FALSE(f.Step(*ca, 0, {}).collision_avoidance_active);
  const Command give_way = f.Step(*ca, 5, {Meeting(180, 9, 300)});
  ASSERT_TRUE(give_way.manoeuvring);
  EXPECT_TRUE(give_way.collision_avoidance_active);
  // The vessel is gone and the manoeuvre ends with the ship 300 m off its
  // path: it is still away for traffic, on its way back.
  auto move_to = [&](double east_m) {
    ship::ShipState s = f.model.state();
    s.eta[1] = east_m;
    f.model.set_state(s);
  };
  move_to(300);
  const Command ended = f.Step(*ca, 60, {});
  EXPECT_FALSE(ended.manoeuvring);
  ASSERT_FALSE(ended.events.empty());
  EXPECT_EQ(ended.events.back().kind, EventKind::kManoeuvreEnded);
  EXPECT_TRUE(ended.collision_avoidance_active);
  move_to(120);
  EXPECT_TRUE(f.Step(*ca, 120, {}).collision_avoidance_active);
  // Back within rejoined_cross_track_m (50 m): over, and it stays over.
  move_to(30);
  EXPECT_FALSE(f.Step(*ca, 180, {}).collision_avoidance_active);
  move_to(120);
  EXPECT_FALSE(f.Step(*ca, 240, {}).collision_avoidance_active);
}

TEST(CollisionAvoidanceTest, WithTheVesselGoneTheReturnToThePathIsStillWeighedAgainstTheLand) {
  // A give-way manoeuvre, then the vessel is gone with the ship 150 m east
  // of its path heading 290 deg: the nominal return swings across the path
  // towards a bank 60 m west of it. Without traffic the decision still
  // predicts the return (the land check of a manoeuvre that ends) and
  // keeps a behaviour; without the bank the manoeuvre ends.
  for (const bool bank : {true, false}) {
    SCOPED_TRACE(bank ? "bank" : "open water");
    Fixture f = Fixture::Make();
    const LandIndex land(bank ? std::vector<std::vector<EastNorth>>{{{-60, -1000},
                                                                     {-2000, -1000},
                                                                     {-2000, 9000},
                                                                     {-60, 9000}}}
                              : std::vector<std::vector<EastNorth>>{});
    auto ca = CollisionAvoidance::Create({});
    ASSERT_TRUE(ca.ok());
    if (bank) ca->set_land(&land);
    ASSERT_TRUE(f.Step(*ca, 0, {Meeting(180, 9, 300)}).manoeuvring);
    ship::ShipState s = f.model.state();
    s.eta[1] = 150.0;
    s.eta[2] = -70.0 * kDeg;
    f.model.set_state(s);
    const Command c = f.Step(*ca, 60, {});
    EXPECT_EQ(c.manoeuvring, bank);
    EXPECT_TRUE(c.collision_avoidance_active);
  }
}

// North for 2 km, a quarter circle of 450 m radius to the east as a
// fillet's polygon (10 deg per corner), then east for 2 km.
std::vector<EastNorth> FilletedCorner() {
  std::vector<EastNorth> path = {{0, -2000}};
  for (int deg = 0; deg <= 90; deg += 10) {
    path.push_back({450.0 - 450.0 * std::cos(deg * kDeg), 450.0 * std::sin(deg * kDeg)});
  }
  path.push_back({2450, 450});
  return path;
}

TEST(EncounterSimTest, TheChordAlongThePathHoldsTheHullCloserToAnArc) {
  EncounterSetup s;
  s.path = FilletedCorner();
  s.max_time_s = 1500;
  s.follower.chord_s = 0;
  auto on_leg = SimulateEncounter(s);
  s.follower.chord_s = 44;  // 400 m at 9 m/s
  auto along = SimulateEncounter(s);
  ASSERT_TRUE(on_leg.ok() && along.ok());
  EXPECT_TRUE(on_leg->arrived);
  EXPECT_TRUE(along->arrived);
  // The polygon's legs followed one after the other: the course error that
  // holds the turn rate comes from ~200 m of cross-track error; the chord
  // leads the bend and halves it.
  EXPECT_GT(on_leg->max_path_deviation_m, 180.0);
  EXPECT_LT(along->max_path_deviation_m, 0.6 * on_leg->max_path_deviation_m);
}

TEST(CollisionAvoidanceTest, StaysOffTheLandWhenTheStarboardSideIsBlocked) {
  // Head-on in a channel whose east bank lies 250 m to starboard.
  EncounterSetup s;
  s.path = {{0, 0}, {0, 6000}};
  s.traffic = {{1, "A", {-60, 3600}, VelocityOf(M_PI, 8)}};
  s.land = {{{250, -1000}, {2000, -1000}, {2000, 8000}, {250, 8000}},
            {{-700, -1000}, {-2000, -1000}, {-2000, 8000}, {-700, 8000}}};
  s.max_time_s = 1200;
  auto r = SimulateEncounter(s);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_TRUE(r->arrived);
  EXPECT_GT(r->min_land_clearance_m, 0);
  EXPECT_EQ(r->aground_s, 0);
  EXPECT_GE(r->vessels[0].min_distance_m, s.avoidance.safety_distance_m);
  EXPECT_LT(r->vessels[0].bearing_rad, 0) << "head-on: port to port";
}

// A passage 430 m wide with a vessel lying still 100 m to starboard of the
// track, 80 m off the starboard bank: keeping its growing margin would take
// the ship onto the port bank.
EncounterSetup StillVesselInAPassage() {
  EncounterSetup s;
  s.path = {{0, 0}, {0, 3500}};
  s.traffic = {{1, "A", {100, 2000}, {0, 0}}};
  s.land = {{{180, -1000}, {2000, -1000}, {2000, 5000}, {180, 5000}},
            {{-250, -1000}, {-2000, -1000}, {-2000, 5000}, {-250, 5000}}};
  s.max_time_s = 1500;
  return s;
}

TEST(CollisionAvoidanceTest, NoTrafficCostBuysComingWithinTheHardLandMinimum) {
  // Without the land's weighted cost and without the limit on the margin's
  // room, only the hard minimum keeps the ship off the port bank.
  EncounterSetup s = StillVesselInAPassage();
  s.avoidance.weights.land = 0;
  s.avoidance.margin_land_clearance_m = 0;
  s.avoidance.min_land_clearance_m = 0;  // the rule off: the margin wins
  auto off = SimulateEncounter(s);
  ASSERT_TRUE(off.ok()) << off.status();
  EXPECT_LT(off->min_land_clearance_m, 40.0);
  s.avoidance.min_land_clearance_m = 40;
  auto on = SimulateEncounter(s);
  ASSERT_TRUE(on.ok()) << on.status();
  EXPECT_TRUE(on->arrived);
  EXPECT_GE(on->min_land_clearance_m, 40.0 - 5.0);  // the predictions' step (land_step_m)
  EXPECT_GE(on->vessels[0].min_distance_m, s.avoidance.safety_distance_m);
}

TEST(CollisionAvoidanceTest, TheStillVesselsMarginDoesNotComeOutOfTheLandsRoom) {
  // The default options: the vessel is passed beyond the safety distance
  // and the ship stays outside the land cost's band. With the margin
  // allowed to push towards the land (margin_land_clearance_m 0) it comes
  // closer.
  EncounterSetup s = StillVesselInAPassage();
  auto kept = SimulateEncounter(s);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_TRUE(kept->arrived);
  EXPECT_GE(kept->vessels[0].min_distance_m, s.avoidance.safety_distance_m);
  EXPECT_GE(kept->min_land_clearance_m, s.avoidance.land_clearance_m);
  s.avoidance.margin_land_clearance_m = 0;
  auto pushed = SimulateEncounter(s);
  ASSERT_TRUE(pushed.ok()) << pushed.status();
  EXPECT_LT(pushed->min_land_clearance_m, kept->min_land_clearance_m - 10.0);
}

TEST(CollisionAvoidanceTest, VelocityObstacleBaselineStillAvoids) {
  EncounterSetup s;
  s.path = {{0, 0}, {0, 7000}};
  s.traffic = {{1, "A", Meeting(270, 9, 400).kinematics.position, VelocityOf(270 * kDeg, 9)}};
  s.avoidance.policy = Policy::kVelocityObstacle;
  s.max_time_s = 1500;
  auto r = SimulateEncounter(s);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_TRUE(r->arrived);
  EXPECT_GE(r->vessels[0].min_distance_m, s.avoidance.safety_distance_m);
  EXPECT_GT(r->manoeuvres, 0);
}

}  // namespace
}  // namespace seaplan::colav
