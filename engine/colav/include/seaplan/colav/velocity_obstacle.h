// Collision avoidance with velocity obstacles under COLREG constraints
// (Kuwata et al., "Safe maritime autonomous navigation with COLREGS, using
// velocity obstacles", IEEE JOE 2014): the simulation client's policy before
// the scenario-based MPC (colav.h), kept as the baseline it is measured
// against. A velocity outside every safety-inflated obstacle keeps the CPA
// above the safety distance while the others hold their velocities, and
// COLREG roles map onto it as half-plane constraints. Pure functions.
#pragma once

#include <vector>

#include "seaplan/colav/geometry.h"

namespace seaplan::colav {

struct AvoidanceOptions {
  double safety_distance_m = 150.0;  // keep every CPA above this
  double horizon_s = 600.0;          // look this far ahead
  // Stand-on vessels act only when the give-way vessel evidently does not
  // (rule 17 a ii): CPA under safety and TCPA under this.
  double stand_on_action_tcpa_s = 300.0;
  double max_course_change_rad = 1.5708;  // candidate courses within +-90 deg of desired
  double course_step_rad = 0.0436;        // 2.5 deg
  std::vector<double> speed_factors = {1.0, 0.8, 0.6, 0.4, 0.2};
  // The own ship's top speed, m/s; 0 = unknown. When above the desired
  // speed, faster candidates (x1.25, x1.5, capped here) are tried too: a
  // slow ship overtaken by a vessel that does not keep clear, or caught
  // ahead of a crossing one, gets out of the way by speeding up, which
  // slowing down and turning alone cannot do (the fjord cases at
  // 3.6 m/s).
  double max_speed_mps = 0.0;
  ColregOptions colreg;
  // The own ship's manoeuvrability. A velocity obstacle assumes a new
  // velocity is taken at once; a slow-turning hull keeps its present
  // velocity for lag + |course change| / turn_rate (+ |speed change| /
  // acceleration) first, which is what let a CPA fall below the safety
  // distance. Candidates (and the desired velocity) are checked with that
  // delay: the ship goes on at its present velocity, then at the candidate.
  // turn_rate_rad_s <= 0: velocities change at once (the plain VO).
  double turn_rate_rad_s = 0.0;
  double manoeuvre_lag_s = 0.0;
  double acceleration_mps2 = 0.05;
  // Land (outer rings, local frame; not owned, may be null). A candidate
  // whose straight track over land_lookahead_s comes closer than
  // land_clearance_m to it is taken only when every candidate does: the
  // velocity obstacles alone once sent the ship round the wrong side of an
  // island and onto the shore (the fjord's case C).
  const class LandIndex* land = nullptr;
  double land_clearance_m = 60.0;
  double land_lookahead_s = 45.0;  // ~400 m at the routes' 9 m/s
};

struct AvoidanceDecision {
  EastNorth velocity;        // the velocity to steer for
  bool manoeuvring = false;  // differs from the desired velocity because of another vessel
  int vessel_id = -1;        // the most constraining vessel when manoeuvring
  Role role = Role::kNone;
  bool feasible = true;  // false: no candidate clears every vessel (best effort returned)
};

// Chooses the velocity closest to `desired` that is outside every dangerous
// vessel's velocity obstacle (inflated by the safety distance, within the
// horizon) and respects COLREG: against a head-on or crossing-from-starboard
// vessel only passes that leave it on our port side (we go to starboard /
// astern of it) are allowed; as stand-on the desired velocity is kept unless
// rule 17 applies. Only vessels with a dangerous CPA are considered.
AvoidanceDecision ChooseVelocity(const Kinematics& own, EastNorth desired,
                                 const std::vector<Obstacle>& others,
                                 const AvoidanceOptions& options = {});

}  // namespace seaplan::colav
