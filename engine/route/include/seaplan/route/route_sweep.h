// Route sweep: plans routes between seeded random origin/destination pairs in
// a chart's navigable water and checks each one, to measure how often the
// route planner answers and how far its routes keep from the charted
// obstacles (bench/route/route_pairs_bench and the route sweep tests).
//
// A pair counts when both points are navigable (outside the buffered
// obstacles, inside the coverage box) and at least min_pair_distance apart.
// Level 1 "connects" a pair when chart::PlanAlternatives finds a route with
// the planner's options; for those pairs RoutePlanner::Plan is timed and the
// chosen route's clearance from the UNBUFFERED obstacles is measured with
// GEOS (ObstacleQuery::UnbufferedClearance), independently of the planner's
// own checks.
//
// Thread-safety: a pure function; runs in the caller's thread (Plan may use
// its own threads).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/status.h"
#include "seaplan/route/route_planner.h"

namespace seaplan::route {

struct SweepOptions {
  int pairs = 200;
  uint64_t seed = 1;
  // Origin and destination at least this fraction of the coverage box's
  // diagonal apart (short hops say little about a route planner).
  double min_pair_distance_fraction = 0.1;
  // Random draws allowed per wanted pair before giving up (charts that are
  // mostly land need more).
  int draws_per_pair = 2000;

  absl::Status Validate() const;
};

struct PairOutcome {
  EastNorth from;
  EastNorth to;
  bool level1_connected = false;
  bool routed = false;  // Plan succeeded and chose a route
  std::string error;    // Level-1 or Plan error message
  double level1_wall_s = 0.0;
  double route_wall_s = 0.0;
  // Chosen route's clearance from the unbuffered obstacles, metres
  // (+infinity when not routed or the chart has no obstacle).
  double clearance_m = std::numeric_limits<double>::infinity();
  EastNorth closest_route_point;
  int waypoints = 0;
  std::vector<EastNorth> route;  // the chosen route's waypoints (local frame); empty if not routed
  int filleted_turns = 0;        // of the chosen route
  int tightened_turns = 0;       // of those, on a circle under the fillet radius
  std::vector<std::string> warnings;  // the chosen route's (corners it cannot make sailable)
};

struct SweepResult {
  std::vector<PairOutcome> pairs;
  int connected = 0;            // Level 1 connects
  int routed = 0;               // of the connected pairs
  int within_margin = 0;        // routed with clearance < margin_m
  int with_warnings = 0;        // routed with a warning (a corner left unsailable)
  double margin_m = 0.0;        // the chart's safety buffer
  bool clearance_exact = true;  // false: the map has no unbuffered obstacles
};

// Errors: InvalidArgument for bad options; FailedPrecondition when too few
// navigable pairs can be drawn.
StatusOr<SweepResult> RunRouteSweep(const RoutePlanner& planner, const chart::ObstacleMap& map,
                                    const Environment& env, const SweepOptions& options);

// Median and 95th percentile (nearest rank) of `values`; 0 when empty.
double Percentile(std::vector<double> values, double fraction);

}  // namespace seaplan::route
