#include "seaplan/route/level2_optimizer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "obstacle_test_fields.h"
#include "seaplan/route/sail_check.h"

namespace seaplan::route {
namespace {

// One long island between start (-2000, 0) and goal (2000, 0); alternatives
// pass it 100 m off its north and south shores. Wind 20 m/s from the south
// and a 1 m/s current toward the north push a drifting ship north: the
// island is the downwind shore of the SOUTH alternative only.
ObstaclePolygon Island() {
  // A long island, x in [-800, 800], y in [-200, 200].
  return ObstaclePolygon{{{{-800, -200}, {800, -200}, {800, 200}, {-800, 200}}}};
}

struct Scenario {
  Scenario(ObstacleField f, risk::DriftingGroundingModel m)
      : field(std::move(f)), risk_model(std::move(m)), grounding(risk_model), problem{} {}
  ObstacleField field;
  risk::DriftingGroundingModel risk_model;
  DriftingGroundingAdapter grounding;
  Level2Problem problem;
};

std::unique_ptr<Scenario> MakeScenario() {
  ObstacleFieldOptions fo;
  fo.far_cutoff_m = 750;
  auto field = ObstacleField::Build({Island()}, {-2500, -1500}, {2500, 1500}, fo);
  EXPECT_TRUE(field.ok()) << field.status();
  auto model = risk::DriftingGroundingModel::Create();
  EXPECT_TRUE(model.ok()) << model.status();
  auto s = std::make_unique<Scenario>(std::move(field).value(), std::move(model).value());
  s->problem.field = &s->field;
  s->problem.grounding = &s->grounding;
  s->problem.environment.wind_speed_mps = 20.0;
  s->problem.environment.wind_direction_from_rad = M_PI;  // from the south
  s->problem.environment.current_north_mps = 1.0;
  s->problem.alternatives = {{{-2000, 0}, {-1000, 300}, {1000, 300}, {2000, 0}},     // north
                             {{-2000, 0}, {-1000, -300}, {1000, -300}, {2000, 0}}};  // south
  return s;
}

Level2Options SmallOptions() {
  Level2Options o;
  o.pso.particles = 12;
  o.pso.iterations = 25;
  o.polish.max_evaluations = 40;
  return o;
}

TEST(Level2OptimizerTest, SegmentsThatWouldCutTheIslandFollowTheLevel1Path) {
  // Two segments on the north alternative: the references are start, the
  // path's midpoint (0, 300) and goal, and both chords between them cut the
  // island's corners (at x = -800 the first is at y = 180 < 200). With one
  // particle and no iterations the waypoint stays on its reference, so only
  // the repair can make the route safe: it inserts the Level-1 vertices.
  auto s = MakeScenario();
  s->problem.alternatives.resize(1);
  Level2Options o;
  o.segments = 2;
  o.pso.particles = 1;
  o.pso.iterations = 0;
  o.polish.max_evaluations = 0;
  o.fillet_turns = false;  // the repair alone (the fillets: below)
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok()) << r.status();
  const AlternativeResult& north = r->alternatives[0];
  EXPECT_FALSE(north.crosses_obstacle);
  EXPECT_EQ(r->chosen, 0);
  EXPECT_EQ(north.inserted_waypoints, 2);
  ASSERT_EQ(north.waypoints.size(), 5u);
  const double expected[5][2] = {{-2000, 0}, {-1000, 300}, {0, 300}, {1000, 300}, {2000, 0}};
  for (size_t k = 0; k < 5; ++k) {
    EXPECT_NEAR(north.waypoints[k].position.east_m, expected[k][0], 1e-6) << k;
    EXPECT_NEAR(north.waypoints[k].position.north_m, expected[k][1], 1e-6) << k;
    if (k > 0) {
      EXPECT_FALSE(
          s->field.SegmentHits(north.waypoints[k - 1].position, north.waypoints[k].position))
          << k;
    }
    // Inserted waypoints are evaluated like the others (TTG and P(G) set).
    EXPECT_GT(north.waypoints[k].ttg_s, 0.0) << k;
  }
  // Without the inserted vertices the two chords would cut the island.
  EXPECT_TRUE(s->field.SegmentHits({-2000, 0}, {0, 300}));
  EXPECT_TRUE(s->field.SegmentHits({0, 300}, {2000, 0}));
}

TEST(Level2OptimizerTest, CoarseOptimisedRoutesTouchNoObstacle) {
  // Three segments of ~1.4 km around a 1.6 km island: chords between freely
  // moved waypoints can cut it; whatever the swarm does, the returned routes
  // (after the repair) keep off every obstacle.
  auto s = MakeScenario();
  Level2Options o = SmallOptions();
  o.segments = 3;
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok()) << r.status();
  for (const AlternativeResult& alt : r->alternatives) {
    EXPECT_FALSE(alt.crosses_obstacle);
    for (size_t k = 1; k < alt.waypoints.size(); ++k) {
      EXPECT_FALSE(s->field.Inside(alt.waypoints[k].position)) << k;
      EXPECT_FALSE(s->field.SegmentHits(alt.waypoints[k - 1].position, alt.waypoints[k].position))
          << k;
    }
  }
}

// The corners at moved waypoints (off their Level-1 reference) that a hull
// turning on `radius_m` cannot sail: R tan(theta / 2) must fit in half of
// each adjacent leg (the whole of the first and the last).
int UnsailableMovedCorners(const AlternativeResult& alt, double radius_m) {
  const std::vector<WaypointResult>& w = alt.waypoints;
  int count = 0;
  for (size_t k = 1; k + 1 < w.size(); ++k) {
    const EastNorth a = w[k - 1].position, b = w[k].position, c = w[k + 1].position;
    if (std::hypot(b.east_m - w[k].reference.east_m, b.north_m - w[k].reference.north_m) < 1e-6) {
      continue;
    }
    const double in_m = std::hypot(b.east_m - a.east_m, b.north_m - a.north_m);
    const double out_m = std::hypot(c.east_m - b.east_m, c.north_m - b.north_m);
    const double theta =
        std::abs(std::remainder(std::atan2(c.east_m - b.east_m, c.north_m - b.north_m) -
                                    std::atan2(b.east_m - a.east_m, b.north_m - a.north_m),
                                2 * M_PI));
    const double need_m = radius_m * std::tan(theta / 2);
    if (need_m > (k == 1 ? 1.0 : 0.5) * in_m + 1e-6 ||
        need_m > (k + 2 == w.size() ? 1.0 : 0.5) * out_m + 1e-6) {
      ++count;
    }
  }
  return count;
}

TEST(Level2OptimizerTest, MovedWaypointsOnlyWhereTheHullCanTurn) {
  // 100 segments of ~45 m: the swarm moves each waypoint on its own and the
  // route zigzags; a waypoint whose turn needs more than half of a leg on a
  // 300 m circle goes back to the Level-1 path (turn_radius_m 0: it stays).
  auto s = MakeScenario();
  Level2Options o = SmallOptions();
  o.segments = 100;
  o.turn_radius_m = 0.0;
  auto free = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(free.ok()) << free.status();
  int free_unsailable = 0;
  for (const AlternativeResult& alt : free->alternatives) {
    free_unsailable += UnsailableMovedCorners(alt, 300.0);
  }
  EXPECT_GT(free_unsailable, 0) << "the scenario no longer zigzags: the test proves nothing";
  o.turn_radius_m = 300.0;
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok()) << r.status();
  for (const AlternativeResult& alt : r->alternatives) {
    EXPECT_EQ(UnsailableMovedCorners(alt, 300.0), 0);
    EXPECT_FALSE(alt.crosses_obstacle);
    EXPECT_GT(alt.snapped_waypoints, 0);
  }
  o.turn_radius_m = -1.0;
  EXPECT_FALSE(OptimizeLevel2(s->problem, o).ok());
}

TEST(Level2OptimizerTest, Level1CornersBecomeFilletsTheHullCanSail) {
  // A Level-1 path along the island's north shore that turns south by 90 deg
  // 60 m off its north-east corner. Two segments whose waypoint stays on its
  // reference: the chord to the goal cuts the island, so the repair puts the
  // corner (860, 260) back, and step 5 replaces it by a fillet round a 300 m
  // circle, moved outwards so that the arc passes where the corner was.
  // (300 m, not the default 450 m: the figures below are this circle's.)
  auto s = MakeScenario();
  s->problem.alternatives = {{{-2000, 260}, {860, 260}, {860, -1400}}};
  Level2Options o;
  o.fillet_radius_m = 300.0;
  o.segments = 2;
  o.pso.particles = 1;
  o.pso.iterations = 0;
  o.polish.max_evaluations = 0;
  auto max_turn = [](const AlternativeResult& alt) {
    double m = 0.0;
    for (size_t k = 1; k + 1 < alt.waypoints.size(); ++k) {
      m = std::max(m, std::abs(TurnAngle(alt.waypoints[k - 1].position, alt.waypoints[k].position,
                                         alt.waypoints[k + 1].position)));
    }
    return m;
  };
  o.fillet_turns = false;
  auto sharp = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(sharp.ok()) << sharp.status();
  EXPECT_NEAR(max_turn(sharp->alternatives[0]), M_PI / 2, 1e-6);
  EXPECT_EQ(sharp->alternatives[0].filleted_turns, 0);

  o.fillet_turns = true;
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok()) << r.status();
  const AlternativeResult& alt = r->alternatives[0];
  EXPECT_EQ(r->chosen, 0);
  EXPECT_FALSE(alt.crosses_obstacle);
  EXPECT_EQ(alt.filleted_turns, 1);
  EXPECT_TRUE(alt.unsailable_turns.empty());
  EXPECT_LE(max_turn(alt), 15.0 * M_PI / 180.0 + 1e-9);
  // Every corner fits a 300 m circle (this helper skips the references).
  AlternativeResult as_moved = alt;
  for (WaypointResult& w : as_moved.waypoints) w.reference = {1e9, 1e9};
  EXPECT_EQ(UnsailableMovedCorners(as_moved, 300.0), 0);
  const double corner_clearance = s->field.SignedDistance({860, 260});
  int near_corner = 0;
  for (const WaypointResult& w : alt.waypoints) {
    EXPECT_GT(w.ttg_s, 0.0);  // fillet vertices are evaluated like the others
    if (Distance(w.position, {860, 260}) > 450.0) continue;
    ++near_corner;
    EXPECT_GE(s->field.SignedDistance(w.position), corner_clearance - 3.0);
  }
  // ~90 deg (a little more once the corner moves out) in steps of <= 15 deg.
  EXPECT_GE(near_corner, 6);
  EXPECT_LE(near_corner, 7);
}

TEST(Level2OptimizerTest, SailCheckKeepsACandidateWhoseTrackStaysOutOfTheObstacles) {
  // The corner of the test above, on the default 450 m fillets. Sailed in
  // the closed loop the hull swings wide of the fillet; a rock put where it
  // swings widest (off the fillet's polyline) is hit by the track of that
  // route, so step 6 keeps another candidate, whose track misses it.
  auto s = MakeScenario();
  s->problem.alternatives = {{{-2000, 260}, {860, 260}, {860, -1400}}};
  Level2Options o;
  o.segments = 2;
  o.pso.particles = 1;
  o.pso.iterations = 0;
  o.polish.max_evaluations = 0;
  auto polyline = [](const AlternativeResult& alt) {
    std::vector<EastNorth> line;
    for (const WaypointResult& w : alt.waypoints) line.push_back(w.position);
    return line;
  };
  o.sail_check = false;
  auto unchecked = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(unchecked.ok()) << unchecked.status();
  EXPECT_FALSE(unchecked->alternatives[0].sail_checked);
  const std::vector<EastNorth> route = polyline(unchecked->alternatives[0]);
  auto sailed = SailRoute(route, o.sail_speed_mps, nullptr);
  ASSERT_TRUE(sailed.ok()) << sailed.status();
  const auto [widest, widest_m] = test_fields::WidestSwing(route, sailed->track);
  EXPECT_GT(widest_m, 100.0);  // 284 m
  ObstacleFieldOptions fo;
  fo.far_cutoff_m = 750;
  auto field = ObstacleField::Build(
      {Island(), ObstaclePolygon{{{{widest.east_m - 15, widest.north_m - 15},
                                   {widest.east_m + 15, widest.north_m - 15},
                                   {widest.east_m + 15, widest.north_m + 15},
                                   {widest.east_m - 15, widest.north_m + 15}}}}},
      {-2500, -1500}, {2500, 1500}, fo);
  ASSERT_TRUE(field.ok()) << field.status();
  for (size_t k = 1; k < route.size(); ++k)
    EXPECT_FALSE(field->SegmentHits(route[k - 1], route[k]));
  auto hit = SailRoute(route, o.sail_speed_mps, &*field);
  ASSERT_TRUE(hit.ok()) << hit.status();
  EXPECT_TRUE(hit->touches);
  s->problem.field = &*field;
  o.sail_check = true;
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok()) << r.status();
  const AlternativeResult& alt = r->alternatives[0];
  EXPECT_EQ(r->chosen, 0);
  EXPECT_FALSE(alt.crosses_obstacle);
  EXPECT_TRUE(alt.sail_checked);
  EXPECT_TRUE(alt.sailed_clear);
  EXPECT_NE(alt.source, RouteSource::kOptimised);  // the sharp corner: 21 m off the rock
  auto kept = SailRoute(polyline(alt), o.sail_speed_mps, &*field);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_FALSE(kept->touches);
  EXPECT_NEAR(kept->clearance_m, alt.sailed_clearance_m, 1e-6);
}

TEST(Level2OptimizerTest, SailCheckRepairsARouteNoCandidateOfWhichKeepsClear) {
  // The corner of the tests above with a shoal east of its southbound leg,
  // where the hull swings out of the turn whichever candidate it sails
  // (sharp, on the 450 m fillet or the wider one): no candidate keeps
  // clear, so step 6 bends the route away from the shoal and sails it again.
  ObstacleFieldOptions fo;
  fo.far_cutoff_m = 750;
  auto field = ObstacleField::Build(
      {Island(), ObstaclePolygon{{{{960, -1200}, {2400, -1200}, {2400, -500}, {960, -500}}}}},
      {-2500, -1500}, {2500, 1500}, fo);
  ASSERT_TRUE(field.ok()) << field.status();
  auto s = MakeScenario();
  s->problem.field = &*field;
  s->problem.alternatives = {{{-2000, 260}, {860, 260}, {860, -1400}}};
  Level2Options o;
  o.segments = 2;
  o.pso.particles = 1;
  o.pso.iterations = 0;
  o.polish.max_evaluations = 0;
  auto polyline = [](const AlternativeResult& alt) {
    std::vector<EastNorth> line;
    for (const WaypointResult& w : alt.waypoints) line.push_back(w.position);
    return line;
  };
  o.sail_repair.max_sails = 0;
  auto unrepaired = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(unrepaired.ok()) << unrepaired.status();
  ASSERT_TRUE(unrepaired->alternatives[0].sail_checked);
  ASSERT_FALSE(unrepaired->alternatives[0].sailed_clear);
  EXPECT_EQ(unrepaired->alternatives[0].sail_bends, 0);

  o.sail_repair = SailRepairOptions{};
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok()) << r.status();
  const AlternativeResult& alt = r->alternatives[0];
  EXPECT_EQ(r->chosen, 0);
  EXPECT_FALSE(alt.crosses_obstacle);
  EXPECT_TRUE(alt.sailed_clear);
  EXPECT_GE(alt.sail_bends, 1);
  EXPECT_GT(alt.inserted_waypoints, unrepaired->alternatives[0].inserted_waypoints);
  for (const WaypointResult& w : alt.waypoints) EXPECT_GT(w.ttg_s, 0.0);  // evaluated
  auto kept = SailRoute(polyline(alt), o.sail_speed_mps, &*field);
  ASSERT_TRUE(kept.ok()) << kept.status();
  EXPECT_TRUE(kept->Clear());
  EXPECT_NEAR(kept->clearance_m, alt.sailed_clearance_m, 1e-6);
}

TEST(Level2OptimizerTest, RobustModeOnDownwindShoreSegmentAndSaferAlternativeChosen) {
  auto s = MakeScenario();
  auto r = OptimizeLevel2(s->problem, Level2Options{});
  ASSERT_TRUE(r.ok()) << r.status();
  ASSERT_EQ(r->alternatives.size(), 2u);
  const AlternativeResult& north = r->alternatives[0];
  const AlternativeResult& south = r->alternatives[1];
  EXPECT_FALSE(north.crosses_obstacle);
  EXPECT_FALSE(south.crosses_obstacle);
  // The south route's drift runs onto the island: higher P(G) there.
  double max_p_south = 0, max_p_north = 0;
  for (const auto& w : south.waypoints)
    max_p_south = std::max(max_p_south, w.grounding_probability[0]);
  for (const auto& w : north.waypoints)
    max_p_north = std::max(max_p_north, w.grounding_probability[0]);
  EXPECT_GT(max_p_south, 10 * max_p_north);
  // MEC on the segments passing south of (upwind of) the island, PTO at the
  // open-water ends and everywhere on the north route.
  int mec_south = 0;
  for (int k = 0; k < 20; ++k) {
    const auto& w = south.waypoints[k];
    if (w.mode == MsoMode::kMec) {
      ++mec_south;
      EXPECT_LT(std::abs(w.position.east_m), 1200) << "MEC far from the island at waypoint " << k;
      EXPECT_LT(w.ttg_s, 630) << k;
    }
  }
  EXPECT_GE(mec_south, 1);
  EXPECT_EQ(south.waypoints[0].mode, MsoMode::kPto);
  EXPECT_EQ(south.waypoints[19].mode, MsoMode::kPto);
  for (int k = 0; k < 20; ++k) EXPECT_EQ(north.waypoints[k].mode, MsoMode::kPto) << k;
  // Chosen: the one with the lower expected cost (the north one).
  EXPECT_LT(north.expected_cost, south.expected_cost);
  EXPECT_EQ(r->chosen, 0);
  // A waypoint moved by the optimiser stays out of the island.
  for (const auto& w : south.waypoints) EXPECT_GT(s->field.SignedDistance(w.position), 0.0);
}

TEST(Level2OptimizerTest, DeterministicForASeedAndIndependentOfThreads) {
  auto s = MakeScenario();
  Level2Options o = SmallOptions();
  o.threads = 2;
  auto a = OptimizeLevel2(s->problem, o);
  auto b = OptimizeLevel2(s->problem, o);
  o.threads = 1;
  auto c = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  for (size_t i = 0; i < 2; ++i) {
    for (size_t k = 0; k < a->alternatives[i].waypoints.size(); ++k) {
      const auto& wa = a->alternatives[i].waypoints[k];
      for (const auto* other :
           {&b->alternatives[i].waypoints[k], &c->alternatives[i].waypoints[k]}) {
        EXPECT_EQ(wa.position.east_m, other->position.east_m);
        EXPECT_EQ(wa.position.north_m, other->position.north_m);
        EXPECT_EQ(wa.mode, other->mode);
      }
    }
    EXPECT_EQ(a->alternatives[i].expected_cost, c->alternatives[i].expected_cost);
  }
  // Another seed explores differently.
  o.pso.seed = 99;
  auto d = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(d.ok());
  bool differs = false;
  for (size_t k = 1; k < 20; ++k) {
    differs |= d->alternatives[1].waypoints[k].position.east_m !=
               a->alternatives[1].waypoints[k].position.east_m;
  }
  EXPECT_TRUE(differs);
}

TEST(Level2OptimizerTest, FastEvaluationEqualsExactEvaluation) {
  auto s = MakeScenario();
  Level2Options o = SmallOptions();
  o.pso.iterations = 8;
  auto fast = OptimizeLevel2(s->problem, o);
  o.risk_evaluation = RiskEvaluation::kExact;
  auto exact = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(fast.ok() && exact.ok());
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(fast->alternatives[i].expected_cost, exact->alternatives[i].expected_cost,
                1e-6 * exact->alternatives[i].expected_cost);
    for (size_t k = 0; k < fast->alternatives[i].waypoints.size(); ++k) {
      EXPECT_EQ(fast->alternatives[i].waypoints[k].ttg_s,
                exact->alternatives[i].waypoints[k].ttg_s);
    }
  }
  EXPECT_EQ(fast->chosen, exact->chosen);
}

TEST(Level2OptimizerTest, SwitchingCostSmoothsModes) {
  auto s = MakeScenario();
  Level2Options o = SmallOptions();
  o.weights.mode_switch_cost = 1e3;  // never worth switching
  auto r = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(r.ok());
  for (const auto& alt : r->alternatives) EXPECT_EQ(alt.mode_switches, 0);
  o.weights.mode_switch_cost = 0.0;
  auto free_switch = OptimizeLevel2(s->problem, o);
  ASSERT_TRUE(free_switch.ok());
  EXPECT_GE(free_switch->alternatives[1].mode_switches, 1);
}

TEST(Level2OptimizerTest, RejectsBadInput) {
  auto s = MakeScenario();
  Level2Options o;
  o.pso.particles = 0;
  EXPECT_EQ(OptimizeLevel2(s->problem, o).status().code(), absl::StatusCode::kInvalidArgument);
  Level2Problem p = s->problem;
  p.alternatives = {{{0, 0}}};
  EXPECT_EQ(OptimizeLevel2(p, {}).status().code(), absl::StatusCode::kInvalidArgument);
  p = s->problem;
  p.field = nullptr;
  EXPECT_EQ(OptimizeLevel2(p, {}).status().code(), absl::StatusCode::kInvalidArgument);
}

TEST(Level2OptimizerTest, FilletOptionsAreCheckedByTheFilletsOwnValidation) {
  // The options step 5 uses are those FilletTurns checks: the same ranges
  // whether or not the fillets are on.
  Level2Options o;
  EXPECT_TRUE(o.Validate().ok());
  EXPECT_DOUBLE_EQ(o.Fillet().radius_m, 450.0);  // the path follower's wheel-over radius
  o.fillet_radius_m = 0.0;
  EXPECT_DOUBLE_EQ(o.Fillet().radius_m, o.turn_radius_m);  // 0: the turn radius
  o.fillet_radius_m = 200.0;
  EXPECT_DOUBLE_EQ(o.Fillet().radius_m, 200.0);
  EXPECT_TRUE(o.Validate().ok());
  for (double bad : {-1.0, 1e5, std::nan("")}) {
    for (bool on : {true, false}) {
      Level2Options b;
      b.fillet_turns = on;
      b.fillet_radius_m = bad;
      EXPECT_EQ(b.Validate().code(), absl::StatusCode::kInvalidArgument) << bad << " " << on;
      EXPECT_EQ(b.Validate().code(), b.Fillet().Validate().code()) << bad << " " << on;
    }
  }
  for (double bad : {-1.0, HUGE_VAL}) {
    Level2Options b;
    b.fillet_clearance_m = bad;
    EXPECT_FALSE(b.Validate().ok()) << bad;
    EXPECT_FALSE(b.Fillet().Validate().ok()) << bad;
  }
  // No turn radius and no fillet radius: no fillets, the options still valid.
  Level2Options off;
  off.turn_radius_m = 0.0;
  off.fillet_radius_m = 0.0;
  EXPECT_TRUE(off.Validate().ok());
  EXPECT_FALSE(off.FilletsOn());
}

TEST(Level2OptimizerTest, StopTokenEndsEarlyWithPartialResult) {
  auto s = MakeScenario();
  StopToken stop;
  stop.Cancel();
  auto r = OptimizeLevel2(s->problem, Level2Options{}, stop);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->stopped);
  EXPECT_LT(r->evaluations, 2 * 19 * 30 * 3);
}

}  // namespace
}  // namespace seaplan::route
