// Level-2 route optimisation (MISSION.md 3.3, paper 002 eq. 11-14): move the
// waypoints of each Level-1 alternative and choose an MSO mode per segment.
//
// Per alternative the polyline is cut into `segments` equal parts; the
// references r_0..r_N (N = segments) are the cut points, r_0 = start and
// r_N = goal stay fixed, r_1..r_{N-1} are moved. Waypoint k costs
//   C_k(w, m) = C_path + C_grounding + C_mso
//   C_path      = mu1 |w - r_k|^2 + mu2 (|w - r_{k-1}| - |w - r_{k+1}|)^6
//   C_grounding = C_G (mu3 sum_obstacles exp(-zeta1 d_i(w)) + mu4 P_m(G | w))
//   C_mso       = consumption(m) mu5 |w - r_{k+1}|
// where P_m(G | w) comes from a time-to-grounding (TTG) drift simulation that
// starts at w with heading along r_{k-1} -> r_{k+1} and surge 2 m/s (as the
// public code), fed to the mode's event trees (grounding_risk.h). Segment 0
// gets its mode from the same mode costs evaluated at the fixed start; the
// goal has no segment (its reported mode repeats the last one).
//
// Search, per movable waypoint (independent: the cost depends on references
// only, so waypoints run in parallel):
//  1. PSO over (x, y); the mode of a candidate is the argmin of its cost over
//     the modes (as the public code does; a continuous swarm over a 3-valued
//     variable would only add noise). Personal bests are copies, no early stop
//     on "fitness < 1" (both are bugs of the public code).
//  2. Mode assignment with switching cost: the paper has no cost for changing
//     mode, so the per-waypoint argmin can flip PTO/MEC from one segment to the
//     next. Because waypoints are independent, the switching cost cannot live
//     in the per-waypoint PSO; it is applied afterwards by dynamic programming
//     (Viterbi) over the per-segment mode costs C_grounding + C_mso along the
//     route: minimise sum_k cost_k(m_k) + mode_switch_cost * [m_k != m_{k-1}].
//  3. NLopt local polish (LN_BOBYQA) of each waypoint's position with its DP
//     mode fixed; accepted only if it lowers that waypoint's cost. Then the DP
//     runs again on the polished positions.
//  4. Safety repair: the waypoints are optimised one by one, so the segment
//     between two of them can cut an obstacle the Level-1 path went round.
//     A waypoint inside an obstacle, and both ends of a segment that touches
//     one, go back to their references on the Level-1 polyline; where the
//     chord between two references still touches, the route follows the
//     Level-1 polyline between them (its vertices are inserted, evaluated
//     like the others, not moved). The DP runs again on the repaired route.
//     A route is therefore obstacle-free whenever its Level-1 path is, and
//     has segments + 1 waypoints plus the inserted ones. The same repair
//     sends back to its reference a moved waypoint whose turn the hull
//     cannot sail: a course change theta needs R tan(theta / 2) of each
//     adjacent leg to turn on a circle of radius R (turn_radius_m), and the
//     waypoints optimised one by one can zigzag on legs of 100 m, which a
//     hull turning on ~300 m overshoots by hundreds of metres.
//  5. Turns: the corners that remain (the Level-1 path's own, at the
//     obstacles' dilated hull vertices, often 70-90 deg) are replaced by
//     fillets round the ship's turning circle, moved outwards where the
//     water allows (turn_fillet.h); their vertices are inserted like the
//     Level-1 vertices of step 4. A corner that cannot be filleted stays
//     and is reported in unsailable_turns.
//  6. Sail check (sail_check.h): the route is sailed from rest in the
//     simulation client's closed loop (hull, autopilot, path follower) and
//     its track checked against the obstacles, which include the safety
//     buffer: the band the hull sweeps, not the polyline. The hull lags a
//     fillet's run of small corners and overshoots corners between short
//     legs, 100 m and more at times. While the track enters an obstacle or
//     does not arrive, the next candidate is sailed: the repaired route
//     with its corners sharp (the follower's wheel-over sails them), its
//     fillets on a 1.5x wider circle, then the Level-1 polyline the same
//     three ways; the first clear one is kept, else the one whose track
//     keeps the most clearance (RouteSource and sailed_* in
//     AlternativeResult say which and how close). When no candidate of any
//     alternative keeps clear, the kept ones are repaired, cheapest first
//     until one keeps clear: bent away from the obstacle where the track
//     comes closest to it, by its depth plus a margin, and sailed again
//     (sail_check.h RepairSailedRoute, at most sail_repair.max_sails
//     sailings per alternative; sail_bends says how many repairs were kept).
// The chosen alternative is the obstacle-free one with the lowest expected
// cost, one whose sailed track keeps clear before any that does not (sum of C_grounding + C_mso +
// switching; C_path only shapes the route and is not a cost of sailing it, so it is reported but
// not compared). The alternatives are sailed cheapest first (by the lowest cost their candidates
// not yet sailed could have), and no more once a clear one costs no more than any other could:
// the same choice as sailing them all, without sailing the alternatives that lose on cost (they
// are reported as step 5 made them, sail_checked false).
//
// Fast and exact risk evaluation (RiskEvaluation): the drifting ship's motion
// does not depend on where it starts (uniform wind and current), so kFast
// simulates the drift ONCE per waypoint (its heading is fixed per waypoint)
// and tests the hull at w + offset_i; P(G) depends on the TTG only, which the
// Euler loop quantises to multiples of the step, so it is tabulated once.
// Both are the same numbers the per-evaluation simulation gives (up to
// floating-point rounding of the offsets), not approximations. kExact
// simulates the drift, tests the hull by brute force over every obstacle edge
// and evaluates the event trees at every cost evaluation: the baseline of
// bench/route.
//
// Determinism: each waypoint's swarm has its own RNG seeded from
// (seed, alternative, waypoint); results are written to fixed slots, so any
// thread count gives identical results.
#pragma once

#include <cstdint>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/route/grounding_risk.h"
#include "seaplan/route/obstacle_field.h"
#include "seaplan/route/sail_check.h"
#include "seaplan/route/turn_fillet.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::route {

// Weights of eq. 11-14 plus the mode-switching cost. Cost unit: the public
// code's (its mso scale 1e-4 x probability scale 5e10 gives C_G = 5e6), so
// that results compare with the paper's figures. Defaults and why:
struct CostWeights {
  // Path deviation: 100 m off the reference costs 1.
  double mu1_per_m2 = 1e-4;
  // Spacing (|w-r_{k-1}| - |w-r_{k+1}|)^6: a 50 m along-track shift
  // (difference 100 m) costs 1; keeps waypoints evenly spread.
  double mu2_per_m6 = 1e-12;
  // Grounding consequence C_G (public code: 5e10 x 1e-4).
  double grounding_cost = 5e6;
  // Obstacle proximity: C_G mu3 = 100, so a shore 50 m away costs 13.5,
  // 100 m costs 1.8, 200 m costs 0.03 (the public code's version 12 used
  // 1e4 exp(-0.04 d); 100 balances it against the path terms above).
  double mu3 = 2e-5;
  double zeta1_per_m = 0.04;  // public code: 0.04
  // Probability term: C_G mu4 P(G) (public code: 5e6 P).
  double mu4 = 1.0;
  // MSO: consumption(m) mu5 |w - r_{k+1}|; public code's relative fuel rates
  // PTO 1.5, MEC 2.5, PTI 2.0 and scale 1e-4 per metre.
  double mu5_per_m = 1e-4;
  ModeArray consumption = {1.5, 2.5, 2.0};
  // Cost of one mode change (start/stop of an engine). 0.01 = half the
  // MEC-PTO fuel difference over one 200 m segment: it removes flip-flops
  // whose gain is marginal (< 0.02 for a one-segment excursion, which needs
  // two changes), yet lets one shore-exposed segment go robust (at TTG 150 s
  // MEC saves ~0.03 of grounding cost net of fuel; on the Alesund case 0.02
  // would keep such single segments in PTO).
  double mode_switch_cost = 0.01;

  absl::Status Validate() const;
};

struct PsoOptions {
  int particles = 30;
  int iterations = 100;
  double inertia = 0.75;
  double cognitive = 1.0;
  double social = 2.0;
  // Velocity limit in units of the waypoint's search scale s (half the
  // distance r_{k-1} -> r_{k+1}, i.e. one segment length, which is also the
  // initial perpendicular spread): |v_x|, |v_y| <= velocity_limit * s metres
  // per iteration. The public code's V_LIMIT = 1 multiplied the attraction
  // terms in metres, i.e. no limit at all; a limit of one segment per
  // iteration keeps particles from leaping across islands.
  double velocity_limit = 1.0;
  uint64_t seed = 0;

  absl::Status Validate() const;
};

struct PolishOptions {
  int max_evaluations = 150;  // 0 disables the NLopt polish
  double initial_step_m = 10.0;
  double xtol_m = 0.05;
};

enum class RiskEvaluation {
  kFast,   // one drift simulation per waypoint + tabulated P(G), indexed field
  kExact,  // drift simulation, brute-force hull test, event trees per evaluation
};

struct Level2Options {
  int segments = 20;  // 19 movable waypoints
  PsoOptions pso;
  PolishOptions polish;
  CostWeights weights;
  // TTG simulation (public code: 2 m/s, 600 s, 30 s steps).
  double drift_initial_speed_mps = 2.0;
  double ttg_horizon_s = 600.0;
  double ttg_step_s = 30.0;
  int threads = 2;
  RiskEvaluation risk_evaluation = RiskEvaluation::kFast;
  // The radius the ship turns on as it sails the route (this hull: ~240 m
  // at full rudder; the simulation client's path follower starts its
  // turns for 450 m, the hull under its autopilot turning wider). A moved waypoint whose course
  // change needs more of an adjacent leg than half of it (the whole of a leg from the start or to
  // the goal) goes back to its reference (step 4). 0: no turn check.
  double turn_radius_m = 300.0;
  // Step 5: every corner of the repaired route that turns by 15 deg or more
  // becomes a fillet, a polygon round a circle of fillet_radius_m (0:
  // turn_radius_m; 450 m, the path follower's wheel-over radius: on 200
  // pairs per chart fewer sailed tracks went aground than with 300 m,
  // bench/route/README.md) moved outwards where the water allows, preferably
  // keeping fillet_clearance_m from the obstacles (turn_fillet.h). A corner
  // that cannot be filleted stays and is reported (unsailable_turns).
  // fillet_min_radius_m > 0: a corner no fillet of that radius clears is
  // tried on circles down to it (at most the fillet radius) before it is
  // reported. 300 m (the turn check's circle): the corners the 450 m
  // circle leaves (legs too short) are still filleted, as with 300 m
  // before; down to 240 m (this hull at full rudder) with 300 m fillets
  // did not improve the sailed tracks (bench/route/README.md).
  // Step 6: candidates sailed at sail_speed_mps (the fjord scenarios'
  // ordered speed; the hull's PTO service speed is 9.15 m/s; RoutePlanner
  // sails at the ship's ordered speed when it has one).
  bool sail_check = true;
  double sail_speed_mps = 9.0;
  bool fillet_turns = true;
  double fillet_radius_m = 450.0;
  double fillet_clearance_m = 50.0;
  double fillet_min_radius_m = 300.0;
  // Step 6's repair when no candidate's track keeps clear (sail_check.h
  // RepairSailedRoute; max_sails 0: off).
  SailRepairOptions sail_repair;

  // The options step 5 passes to FilletTurns: radius fillet_radius_m (0:
  // turn_radius_m), clearance fillet_clearance_m, smallest radius
  // fillet_min_radius_m (at most the radius). Validate() checks them
  // with TurnFilletOptions::Validate, the one definition of their ranges.
  TurnFilletOptions Fillet() const;
  // Step 5 runs: fillet_turns on and a radius (turn_radius_m 0 with
  // fillet_radius_m 0 turns it off with the turn check).
  bool FilletsOn() const { return fillet_turns && Fillet().radius_m > 0.0; }

  absl::Status Validate() const;
};

struct Level2Problem {
  // Not owned; must outlive the call. The field's hull is the drifting hull.
  const ObstacleField* field = nullptr;
  const ModeGroundingModel* grounding = nullptr;
  ship::ShipParams drift_ship;    // hull dynamics of the drifting ship
  ship::Environment environment;  // wind and current
  // Level-1 alternatives, each a polyline start..goal (>= 2 points).
  std::vector<std::vector<EastNorth>> alternatives;
};

struct WaypointResult {
  EastNorth position;
  EastNorth reference;
  double heading_rad = 0.0;  // drift heading (r_{k-1} -> r_{k+1})
  // Segment k -> k+1 (unset for the goal, the last waypoint).
  MsoMode mode = MsoMode::kPto;
  double ttg_s = 0.0;
  ModeArray grounding_probability{};  // P(G) per mode
  double proximity = 0.0;             // sum_i exp(-zeta1 d_i)
  ModeArray mode_cost{};              // C_grounding + C_mso per mode
  double path_cost = 0.0;             // C_path
};

// Which candidate of step 6 a route is.
enum class RouteSource {
  kOptimised,       // the optimised, repaired route, its corners filleted (step 5)
  kOptimisedSharp,  // the same without fillets
  kLevel1,          // the Level-1 polyline, filleted
  kLevel1Sharp,     // the Level-1 polyline as it is
};

struct AlternativeResult {
  std::vector<WaypointResult> waypoints;  // start .. goal: segments + 1 (+ inserted)
  double expected_cost = 0.0;             // sum of mode_cost[mode] + switching
  double grounding_cost = 0.0;            // sum of C_grounding at the chosen modes
  double mso_cost = 0.0;
  double switching_cost = 0.0;
  double path_cost = 0.0;
  double objective = 0.0;  // expected_cost + path_cost
  int mode_switches = 0;
  // A waypoint or segment touches an obstacle: after the repair (see below)
  // only when the Level-1 polyline itself does.
  bool crosses_obstacle = false;
  // Safety repair: waypoints moved back to their references, and Level-1
  // vertices inserted where the chord between two references cut a corner.
  int snapped_waypoints = 0;
  int inserted_waypoints = 0;  // Level-1 vertices and fillet vertices
  // Step 5: corners replaced by fillets, and those the hull cannot sail
  // that could not be (water too narrow or legs too short for the circle).
  int filleted_turns = 0;
  int tightened_turns = 0;  // of filleted_turns, on a circle under the fillet radius
  std::vector<UnsailableTurn> unsailable_turns;
  // Step 6: the candidate kept and its sailed track (sail_checked: the
  // alternative was sailed; sailed_clear: the track arrives and never enters the
  // obstacles; clearance: the smallest signed distance of its points from
  // them, <= 0 when it enters, and where).
  RouteSource source = RouteSource::kOptimised;
  bool sail_checked = false;
  bool sailed_clear = false;
  bool sailed_arrived = false;
  double sailed_clearance_m = 0.0;
  EastNorth sailed_closest;
  // Repairs (bends or corner pushes) step 6 put in the kept candidate (0:
  // none; see RepairSailedRoute in sail_check.h).
  int sail_bends = 0;
  int64_t evaluations = 0;
};

struct Level2Result {
  std::vector<AlternativeResult> alternatives;
  int chosen = -1;       // -1: every alternative crosses an obstacle
  bool stopped = false;  // the StopToken fired: results are partial
  int64_t evaluations = 0;
  double wall_s = 0.0;
};

// Time to grounding of a ship drifting from `start` (local frame) with
// `heading_rad` and surge `speed_mps`: the time of the first Euler step whose
// hull touches an obstacle, or the loop's end time (horizon + step) if none.
// Exact (per-call simulation). Errors: InvalidArgument for bad ship params.
StatusOr<double> SimulateTimeToGrounding(const ObstacleField& field, const ship::ShipParams& ship,
                                         const ship::Environment& env, EastNorth start,
                                         double heading_rad, double speed_mps, double horizon_s,
                                         double step_s);

// Errors: InvalidArgument for bad options or problem (null field/model, an
// alternative with < 2 points or non-finite coordinates).
StatusOr<Level2Result> OptimizeLevel2(const Level2Problem& problem, const Level2Options& options,
                                      const StopToken& stop = StopToken());

}  // namespace seaplan::route
