// Level-1 route planning (MISSION.md 3.2, Algorithm A1; SHIP_MODEL.md 9):
// alternative routes start -> goal around the obstacles of an ObstacleMap.
//
// A1 as in the paper: H = convex hulls of the obstacle components, I = H
// dilated by margin_m, J = unions of overlapping members of I, K = their
// convex hulls (repeated until no two overlap). The straight segment is split
// around the largest hull it crosses: the hull vertices visible from the
// segment start, split into left and right of the segment, the farthest from
// it on each side becomes a waypoint; recursion on every new segment that
// still crosses a hull (depth limit max_depth, at most max_alternatives).
//
// When A1 cannot answer (our additions, in this order):
//  1. A1 on the whole chart (the paper). On real charts the hull of a large
//     concave land polygon (a fjord, a bay) often swallows start or goal, or
//     hulls merge into one that covers the chart; then
//  2. A1 on the obstacles clipped to a corridor box around start-goal
//     (grown by 0.15, then 0.35 x the distance): the hulls of the local pieces
//     of a coast rarely contain start/goal. Routes are then verified against
//     the real obstacles (the clipped-away parts too) and dropped if they hit.
//  3. A shortest path in the reduced (bitangent) visibility graph of the
//     obstacles dilated by margin_m (nodes: convex vertices within a corridor
//     box grown until a path exists), which avoids every obstacle exactly.
//     A second alternative in A1's spirit: a thin wall from inside the
//     obstacle that blocks the straight line most, across the first route's
//     side, to beyond the chart; the shortest path that remains passes that
//     obstacle on the other side (kept if at most 3x the first route's
//     length). `used_fallback` and `note` say so.
// Every returned route is checked against the obstacles (ObstacleQuery) and
// must stay inside the chart coverage.
#pragma once

#include <string>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"

namespace seaplan::chart {

struct AlternativesOptions {
  // Margin on top of the chart's safety buffer, metres (paper: 50 m).
  double margin_m = 50.0;
  // Recursion depth limit of A1 (each level adds one waypoint per branch).
  int max_depth = 12;
  // Stop after this many finished alternatives.
  int max_alternatives = 16;
  // Use the visibility-graph fallback when A1 cannot answer.
  bool allow_fallback = true;
  // Visibility-graph size limit (nodes); exceeding it is ResourceExhausted.
  int max_graph_nodes = 4000;
  // Deadline / cancellation, polled in the A1 recursion and the graph
  // search (default: never stops). Stopping gives DeadlineExceeded or
  // Cancelled.
  StopToken stop;

  absl::Status Validate() const;
};

struct Alternative {
  std::vector<EastNorth> waypoints;  // start .. goal
  double length_m = 0.0;
};

struct AlternativesResult {
  // Free of hull crossings (A1) or of obstacle crossings (fallback); sorted
  // by length, shortest first; duplicates removed.
  std::vector<Alternative> alternatives;
  bool used_fallback = false;
  std::string note;  // why the fallback was used, limits hit, ...
};

// Errors: InvalidArgument when start or goal lies inside an obstacle (the
// message names which, and the obstacle index) or outside chart coverage;
// NotFound when no obstacle-free route exists; ResourceExhausted on limits;
// DeadlineExceeded / Cancelled when options.stop fires.
StatusOr<AlternativesResult> PlanAlternatives(const ObstacleMap& map, EastNorth start,
                                              EastNorth goal,
                                              const AlternativesOptions& options = {});

}  // namespace seaplan::chart
