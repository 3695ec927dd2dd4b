// Collision avoidance for the own ship under COLREG: one Step per control
// step, from the own ship (model state and autopilot), the desired motion
// (the path follower's course and the route's speed), the path and the
// traffic, to the commanded course and speed and the events to log.
//
// Two policies:
//
// * Scenario-based MPC (the default; Johansen, Perez & Cristofaro, "Ship
//   collision avoidance and COLREGS compliance using simulation-based
//   control behavior selection with predictive hazard assessment", IEEE
//   T-ITS 2016). A finite set of control behaviours (a course offset added
//   to the path follower's course or a track parallel to the path, a factor
//   on the route's speed) is each simulated over the horizon with the ship
//   model (engine/ship), this autopilot and the path follower, the traffic
//   moving straight on (a vessel lying still with a margin that grows with
//   the time ahead: it may get under way). Each is
//   scored for collision risk, COLREG compliance, grounding and the
//   deviation it costs, with a cost on changing the behaviour (hysteresis);
//   the cheapest is commanded until the next decision. The predicted
//   manoeuvre ends when every vessel it is for has been passed: the ship
//   then returns to its path, so a scenario is "offset, pass, rejoin", the
//   way it is sailed, and its land check covers the return.
// * Velocity obstacles (Kuwata et al. 2014, velocity_obstacle.h), the
//   policy the simulation client had before, kept to be measured against.
//
// Why the MPC: this hull turns about 1 deg/s after a ~20 s lag at 9 m/s.
// A velocity obstacle assumes the new velocity is taken at once; modelling
// the delay inside it (straight line, then the new velocity) still
// misjudged curved tracks, path turns and the return to the route, and it
// passed the fjord's ferry at 57 m against 120 m. Simulating the closed loop
// predicts what the ship does, including the rejoining of the route.
//
// COLREG (rules 8, 13-17): the role towards a vessel is fixed when the
// encounter starts and kept until it is passed. Head-on and crossing
// give-way: port turns and passes with the other on our starboard side cost
// extra (head-on passes port to port, the give-way ship goes astern of a
// crossing one). Overtaking: either side, keeping clear. Stand-on (crossing
// from port, being overtaken): the nominal behaviour is kept until rule 17
// applies (the vessel comes within the planning distance less than
// rule17_time_s ahead); then the ship acts, not to port for a vessel on its
// port side (rule 17 c). Course offsets are at least 30 deg and speed
// changes at least half the speed: readily apparent (rule 8).
//
// Frame: local metric, x east, y north; courses clockwise from north.
// Thread-compatible; one instance per own ship.
#pragma once

#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "seaplan/colav/autopilot.h"
#include "seaplan/colav/geometry.h"
#include "seaplan/colav/path_follower.h"
#include "seaplan/colav/velocity_obstacle.h"
#include "seaplan/ship/ship_model.h"

namespace seaplan::colav {

enum class Policy { kScenarioMpc, kVelocityObstacle };
std::string_view PolicyName(Policy p);  // "sbmpc", "vo"

struct ScenarioMpcWeights {
  double collision = 50.0;           // at the planning distance's edge reaching the safety distance
  double inside_safety = 200.0;      // step on entering the safety distance
  double inside_safety_per_m = 4.0;  // and per metre further in
  double colreg_side = 40.0;         // give-way vessel passed on the wrong side
  double colreg_port_turn = 30.0;    // port offset where rules 14, 15 or 17 c want starboard
  double course_offset = 6.0;        // at 90 deg; quadratic in the offset
  double track_offset = 1.5;         // at one safety distance; quadratic in the offset
  double port_factor = 1.5;          // port offsets cost this much more
  double speed_reduction = 8.0;      // per unit of (1 - factor)
  double change_course = 3.0;        // hysteresis, per 90 deg of change
  double change_speed = 3.0;         // hysteresis, per unit of factor change
  double land = 300.0;               // at zero clearance, quadratic within land_clearance_m
  double aground = 5000.0;           // a predicted track that touches the land
};

struct CollisionAvoidanceOptions {
  Policy policy = Policy::kScenarioMpc;
  double safety_distance_m = 150.0;  // no CPA below this
  // Manoeuvres are planned to keep this factor times the safety distance
  // (the planning distance): the traffic does not hold its velocity exactly.
  double margin_factor = 1.5;
  double horizon_s = 420.0;
  double prediction_step_s = 2.0;
  double decision_interval_s = 5.0;
  std::vector<double> course_offsets_deg = {-90, -60, -45, -30, 0, 30, 45, 60, 90};
  std::vector<double> speed_factors = {1.0, 0.5, 0.25};
  // Tracks parallel to the path's leg, this far to starboard (> 0) or port,
  // each with every speed factor: the ship turns onto one by the smallest
  // course offset (readily apparent) and follows it until the vessels are
  // past, as a ship keeps to the starboard side of a channel (rule 9) where
  // holding a course offset would soon meet the bank.
  std::vector<double> track_offsets_m = {-150, -75, 75, 150};
  // A vessel lying still may get under way at any moment, in a direction
  // its zero velocity does not tell: the distance kept from it grows by
  // uncertain_speed_mps per second of prediction, up to
  // uncertain_margin_factor x the safety distance (the room its departure
  // takes before the next decisions can react to it). That room must not
  // come out of the room kept from the shore: the margin is at most the
  // ship's predicted distance to the land less margin_land_clearance_m,
  // and a behaviour that comes closer to the land than the nominal one does
  // (within margin_land_clearance_m of it) gains nothing from the margin it
  // opens. Where the water is narrow the ship passes at the planning
  // distance, on the side with more water, or slows, instead of edging
  // towards the land.
  double uncertain_speed_mps = 2.0;
  double uncertain_margin_factor = 1.0;
  double margin_land_clearance_m = 120.0;
  // Rule 17: a stand-on ship acts once the vessel comes within the planning
  // distance less than this far ahead (and it has not given way).
  double rule17_time_s = 240.0;
  ColregOptions colreg;
  ScenarioMpcWeights weights;
  // Land (not owned, may be null): predicted tracks closer than
  // land_clearance_m to it cost `weights.land`, touching it `aground`.
  const LandIndex* land = nullptr;
  double land_clearance_m = 60.0;
  // The hard minimum: a behaviour whose predicted track comes closer than
  // this to the land (or than the path ahead does, where the path runs
  // closer) loses against every behaviour that does not, whatever their
  // traffic costs; among behaviours that all do, the one that stays
  // furthest off (to land_step_m) wins. Half this hull's length: the land
  // cost alone, weighed against the room given to traffic, let the ship
  // come within a few metres of the shore.
  double min_land_clearance_m = 40.0;
  double land_step_m = 5.0;
  // Near the path's end the speed falls linearly to min_approach_speed_mps
  // over the last slow_down_distance_m, and the ship stops within
  // arrival_radius_m (as the simulation client sails a move).
  double slow_down_distance_m = 400.0;
  double min_approach_speed_mps = 1.0;
  double arrival_radius_m = 60.0;
  // After a manoeuvre the ship is still off its path for traffic until it
  // is back within this distance of it (Command::collision_avoidance_active):
  // a mission planner that replans for the deviation meanwhile would route
  // a ship under way from where its own path follower is already taking it
  // back (and the new route can start behind it).
  double rejoined_cross_track_m = 50.0;
  // Velocity-obstacle policy only: this hull's manoeuvrability (about 1 deg/s
  // at full rudder, ~20 s before the turn develops) and the path-ahead check
  // that slows the ship (x0.75, 0.5, 0.3) while a vessel would come within
  // the planning distance of its route ahead.
  double turn_rate_rad_s = 0.0175;
  double manoeuvre_lag_s = 20.0;
  double path_lookahead_s = 180.0;
  Status Validate() const;
};

struct OwnShip {
  double time_s = 0.0;
  const ship::ShipModel* model = nullptr;  // state, mode, environment (not owned)
  const Autopilot* autopilot = nullptr;    // its present state (not owned)
};

struct DesiredMotion {
  double course_rad = 0.0;        // the path follower's course now
  double speed_mps = 0.0;         // the speed wanted now
  double cruise_speed_mps = 0.0;  // the route's speed (before slowing for the arrival)
};

enum class EventKind {
  kPotentialCollision,  // a vessel came into a potential collision situation
  kManoeuvreStarted,
  kManoeuvreEnded,
  kSpeedReduced,  // velocity obstacles: the path-ahead check slowed the ship
};

struct Event {
  EventKind kind = EventKind::kPotentialCollision;
  int vessel_id = -1;
  Role role = Role::kNone;
  std::string detail;  // e.g. "starboard 30 deg, speed 100 %"
};

struct Command {
  double course_rad = 0.0;
  double speed_mps = 0.0;
  bool manoeuvring = false;  // differs from the desired motion because of traffic
  int vessel_id = -1;        // the vessel the manoeuvre is mainly for
  Role role = Role::kNone;
  // Manoeuvring, or returning to the path after a manoeuvre until within
  // options.rejoined_cross_track_m of it: the ship's deviation from its
  // route is for traffic and is being corrected by the ship itself.
  bool collision_avoidance_active = false;
  std::vector<Event> events;
};

class CollisionAvoidance {
 public:
  static StatusOr<CollisionAvoidance> Create(const CollisionAvoidanceOptions& options);

  // `path` is the follower the ship steers with (its state as updated this
  // step; copied for the predictions). `traffic` holds each vessel's present
  // position and velocity.
  Command Step(const OwnShip& own, const DesiredMotion& desired, const PathFollower& path,
               const std::vector<Obstacle>& traffic);

  // The role fixed for a vessel while its encounter lasts (kNone: none).
  Role RoleOf(int vessel_id) const;
  const CollisionAvoidanceOptions& options() const { return options_; }
  void set_land(const LandIndex* land) { options_.land = land; }

 private:
  struct Behaviour {
    double offset_rad = 0.0;
    double speed_factor = 1.0;
    double track_offset_m = 0.0;  // != 0: follow a track this far beside the path's leg
    bool operator==(const Behaviour&) const = default;
  };
  struct VesselPrediction {
    double min_distance_m = 0.0;
    double min_margin_m = 0.0;  // the distance less the vessel's uncertainty margin, lowest
    double time_s = 0.0;        // of the closest approach
    double bearing_rad = 0.0;   // relative bearing of the vessel then, starboard positive
  };
  struct Prediction {
    std::vector<VesselPrediction> vessels;  // per traffic entry
    double collision_cost = 0.0;
    double certain_collision_cost = 0.0;  // the same without the uncertainty margins
    double land_cost = 0.0;
    // The predicted track's smallest distance to the land, at most the
    // largest of land_clearance_m, min_land_clearance_m and
    // margin_land_clearance_m.
    double min_land_m = std::numeric_limits<double>::infinity();
  };
  explicit CollisionAvoidance(const CollisionAvoidanceOptions& options);
  Command StepScenarioMpc(const OwnShip& own, const DesiredMotion& desired,
                          const PathFollower& path, const std::vector<Obstacle>& traffic);
  Command StepVelocityObstacle(const OwnShip& own, const DesiredMotion& desired,
                               const PathFollower& path, const std::vector<Obstacle>& traffic);
  // Simulates `b` over the horizon; `release` lists the traffic entries the
  // behaviour is for (it ends once they are all passed; empty: never).
  Prediction Predict(const OwnShip& own, const DesiredMotion& desired, const PathFollower& path,
                     const std::vector<Obstacle>& traffic, Behaviour b,
                     const std::vector<bool>& release) const;
  double PenaltyAt(double distance_m) const;
  // The course that turns onto a parallel track (from the path, by the
  // smallest course offset) and follows it, for a follower updated at the
  // ship's position.
  double TrackCourse(const PathFollower& follower, double track_offset_m) const;
  // The course behaviour `b` commands when the path follower asks for
  // `path_course_rad`: a parallel track's, or that course plus b's offset.
  double CommandedCourse(double path_course_rad, const PathFollower& path, Behaviour b) const;
  // Per traffic entry: the uncertainty margin's growth (m/s of
  // prediction), 0 for a vessel under way.
  std::vector<double> UncertainGrowth(const std::vector<Obstacle>& traffic) const;
  // The path's smallest distance to the land from the leg the ship is on
  // over `reach_m` of path, at most `limit_m`.
  double PathLandClearance(const PathFollower& path, double reach_m, double limit_m) const;
  Command Hold(const DesiredMotion& desired) const;
  // Events for the vessels that came into a potential collision situation.
  void NoteEncounters(const std::set<int>& now, Command* out);

  CollisionAvoidanceOptions options_;
  AvoidanceOptions vo_;  // the velocity-obstacle policy's options (planning distance, delay)
  double next_decision_s_ = -1e18;
  Behaviour behaviour_;  // the one commanded until the next decision
  bool manoeuvring_ = false;
  bool rejoining_ = false;  // a manoeuvre ended; the ship is not back on its path yet
  int manoeuvre_vessel_ = -1;
  Role manoeuvre_role_ = Role::kNone;
  std::map<int, Role> roles_;      // fixed per encounter
  std::set<int> rule17_;           // stand-on encounters in which rule 17 applies
  std::set<int> dangerous_;        // vessels in a potential collision situation
  std::vector<double> growth_;     // UncertainGrowth of this decision
  double min_turn_rad_ = 0.0;      // the smallest non-zero course offset
  bool path_slowed_ = false;       // velocity obstacles: the path-ahead check holds the speed
  std::vector<Obstacle> scratch_;  // velocity obstacles: the encounters of this step
};

}  // namespace seaplan::colav
