// A deliberately naive C++ port of the public Python (AMM thesis/models
// transit.py, risks.py, events.py), kept only as the benchmark's baseline:
// dynamic-size Eigen matrices rebuilt and inverted every step (as numpy's
// np.linalg.inv calls), a new model object per evaluation, heap-built hull
// polygons, and event trees built per call whose events recompute their
// lognormal parameters and CDFs once per path element. Same numbers as the
// library (tested in the benchmark's self-check), different cost.
#pragma once

#include "seaplan/risk/drifting_grounding.h"
#include "seaplan/risk/grounding_test.h"
#include "seaplan/risk/time_to_grounding.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::bench {

risk::TtgResult NaiveTimeToGrounding(const ship::ShipParams& params, const ship::ShipState& start,
                                     const ship::Environment& env,
                                     const risk::GroundingTest& obstacles, double horizon_s,
                                     double dt_s);

double NaiveGroundingProbability(const risk::DriftingGroundingParams& params, ship::MsoMode mode,
                                 double ttg_s);

}  // namespace seaplan::bench
