// seaplan.v1 <-> engine/route conversions shared by the RouteService
// handlers and the mission engine adapter (routing moves over a chart).
#pragma once

#include <memory>
#include <string>

#include "google/protobuf/repeated_ptr_field.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/status.h"
#include "seaplan/mission/types.h"
#include "seaplan/route/route_planner.h"
#include "seaplan/storage/repositories.h"
#include "seaplan/v1/common.pb.h"
#include "seaplan/v1/mission.pb.h"
#include "seaplan/v1/route.pb.h"

namespace seaplan::server {

route::ShipParticulars ShipToEngine(const v1::ShipParticulars& p);
// The API gives both directions as "from"; the engine wants the current's "toward".
route::Environment EnvironmentToEngine(const v1::Environment& e);
route::RouteOptions OptionsToEngine(const v1::OptimizerOptions& o);
// The stored obstacles of chart `id` (NotFound; DataLoss when unreadable).
absl::StatusOr<std::shared_ptr<const chart::ObstacleMap>> LoadMap(storage::ChartRepository& charts,
                                                                  const std::string& id);

}  // namespace seaplan::server
