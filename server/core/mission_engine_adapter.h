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
// Routing over a chart: a route::RoutePlanner per (chart, ship, route
// options, environment), built once and cached, plans every move between
// the locations' positions; the chosen route's sailing time becomes the
// move's duration and the task carries the route and its mode schedule.
// Routes are cached per (from, to) position (a replan asks again for most
// legs). A leg with no safe route (or an end inside an obstacle or off the
// chart) fails with FailedPrecondition naming the leg; an unknown chart_id
// is FailedPrecondition.
//
// Feedback: a ShipState in a report is a full state, so fuel_fraction 0 is
// an empty tank; a report without a state carries no fuel reading.
//
// Replans use the spec's planner options but, with anytime search, stop at
// the first plan plus a short improvement run (10-40 ms): the ship waits.
//
// Engine state stored with each version: the location table (a replan may
// add a location such as "port-s"), mission::EncodeEngineState.
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
