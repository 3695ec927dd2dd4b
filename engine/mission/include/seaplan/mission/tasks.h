// Plan parsing (paper 000, fig. 5 block 3): a refined temporal plan becomes
// the list of executable tasks the onboard executor runs (moves -> path
// planning and following along the refined route, port operations -> timed
// tasks).
#pragma once

#include <optional>
#include <vector>

#include "seaplan/mission/refine.h"
#include "seaplan/mission/types.h"

namespace seaplan::mission {

// One task per step of `refined.plan`, in its order, ids "v<version>-t<i>"
// (i from 1). Moves carry their route; the other tasks name the location
// they happen at (first argument that is a known location) in to_location.
std::vector<Task> ParseTasks(const RefinedPlan& refined, const LocationTable& locations,
                             const MoveRecognition& recognition, int version);

// Distance from `p` to the polyline of `route`, metres (infinity when empty).
double CrossTrackDistance(const Route& route, EastNorth p);

}  // namespace seaplan::mission
