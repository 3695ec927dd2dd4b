// The MissionEngine backed by engine/mission (plan -> refine -> parse,
// update problem -> replan) with engine/search as the temporal planner and,
// for missions with a chart, engine/route as the router.
//
// Frames: positions of the spec's named locations are WGS84; the engine
// works in a local metric frame: the chart's frame when the mission names a
// chart, else the UTM zone of the first location. Without a chart a move's
// route is the straight line sailed at ship.service_speed_mps (default
// kDefaultServiceSpeedMps).
//
// Engine state stored with each version: the location table (a replan may
// add a location such as "port-s"), one "name x_m y_m" line per location.
#pragma once

#include <memory>

#include "seaplan/storage/repositories.h"
#include "server/core/mission_engine.h"

namespace seaplan::server {

inline constexpr double kDefaultServiceSpeedMps = 5.0;

// Null when this server is built without engine/mission, engine/search or
// engine/chart.
std::shared_ptr<MissionEngine> MakeMissionEngine(storage::ChartRepository& charts);

}  // namespace seaplan::server
