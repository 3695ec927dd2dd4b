// Time-to-grounding (TTG): after a loss of propulsion power the ship drifts
// (seaplan::ship::ShipModelWithoutPropulsion: no thrust, no rudder) under
// wind and current from its current pose and velocity; the hull rectangle is
// tested against the obstacles after every step (AMM thesis/models/risks.py
// TimeToGroundingSimulator; SHIP_MODEL.md §7).
//
// Loop (AMM, SITS convention `while t <= T`):
//   t = 0
//   [if check_initial_pose and the hull already touches: TTG = 0, grounded]
//   while t <= horizon and not grounded: Euler step dt; t += dt; test hull
//   TTG = t
// So a grounding is detected at a multiple of dt, and a drift that does not
// ground stops at the first multiple of dt above the horizon (630 s with the
// defaults). As in AMM, that stopping time is what an ungrounded run reports
// as ttg_s (with grounded = false); the risk model then uses it as the time
// available for recovery.
//
// Cost: one Run is at most horizon/dt + 1 Euler steps (21 with the defaults)
// of fixed-size Eigen arithmetic plus one GroundingTest::HullIntersects per
// step; no heap allocation unless a track vector is passed and must grow.
//
// Thread-safety: TimeToGroundingSimulator is immutable; Run is const and may
// be called concurrently (the GroundingTest must allow that too).
#pragma once

#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/risk/grounding_test.h"
#include "seaplan/ship/hull_dynamics.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::risk {

struct TtgOptions {
  double horizon_s = 600.0;  // AMM max_sim_time; the paper's 10 min
  double dt_s = 30.0;        // AMM integration_step
  // Hull outline; <= 0 means "use ShipParams length_m / beam_m".
  double hull_length_m = 0.0;
  double hull_beam_m = 0.0;
  // Test the starting pose too (AMM does not: it reports dt for a ship that
  // already touches). A ship touching at t = 0 gets TTG 0.
  bool check_initial_pose = true;
  // Upper bound on steps, guards against a tiny dt (horizon/dt + 1 must not
  // exceed it).
  int max_steps = 100'000;
  Status Validate() const;
};

struct TtgResult {
  double ttg_s = 0.0;     // time the drift stopped (see header comment)
  bool grounded = false;  // hull touched an obstacle at ttg_s
  int steps = 0;          // Euler steps taken
};

struct DriftTrackPoint {
  double time_s = 0.0;
  ship::ShipState state;
};

class TimeToGroundingSimulator {
 public:
  static StatusOr<TimeToGroundingSimulator> Create(const ship::ShipParams& ship,
                                                   const TtgOptions& options = {});

  // `start`: pose and body velocity when propulsion is lost. If `track` is
  // non-null it is cleared and receives the state after every step (and the
  // start state first). Inputs are assumed finite (CheckInputs validates).
  TtgResult Run(const ship::ShipState& start, const ship::Environment& env,
                const GroundingTest& obstacles,
                std::vector<DriftTrackPoint>* track = nullptr) const;

  // Validation for untrusted inputs (the optimiser calls Run directly).
  static Status CheckInputs(const ship::ShipState& start, const ship::Environment& env);

  const TtgOptions& options() const { return options_; }
  double hull_length_m() const { return length_m_; }
  double hull_beam_m() const { return beam_m_; }

 private:
  TimeToGroundingSimulator(const ship::ShipParams& ship, const TtgOptions& o);
  ship::HullDynamics dynamics_;
  TtgOptions options_;
  double length_m_, beam_m_;
};

}  // namespace seaplan::risk
