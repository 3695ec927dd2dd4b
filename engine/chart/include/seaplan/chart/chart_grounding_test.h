// risk::GroundingTest (engine/risk/grounding_test.h) over a chart's
// ObstacleMap, for the drifting-grounding model: hull footprint vs the
// buffered GEOS obstacles. Library seaplan_chart_risk (built when engine/risk
// exists), so seaplan_chart itself does not depend on seaplan_risk.
//
// Frames: the risk model works in NED (x north, y east); the chart in
// EastNorth (east, north). A NED point (n, e) is the chart point
// (origin.east_m + e, origin.north_m + n). With the default origin {0, 0} NED
// coordinates are simply the chart frame's northing/easting.
//
// Thread-safety: both methods are const and safe to call concurrently: each
// thread lazily gets its own ObstacleQuery (a small thread_local cache, at
// most 8 maps per thread, oldest evicted), since GEOS query state is not
// shareable between threads.
#pragma once

#include <cstdint>
#include <memory>

#include "seaplan/chart/obstacle_map.h"
#include "seaplan/risk/grounding_test.h"

namespace seaplan::chart {

class ChartGroundingTest final : public risk::GroundingTest {
 public:
  explicit ChartGroundingTest(std::shared_ptr<const ObstacleMap> map, EastNorth origin = {});

  bool HullIntersects(const risk::HullPolygon& hull) const override;
  // Exact distance from the hull to the nearest obstacle; +inf without obstacles.
  double Clearance(const risk::HullPolygon& hull) const override;

 private:
  ObstacleQuery& Query() const;
  std::shared_ptr<const ObstacleMap> map_;
  EastNorth origin_;
  uint64_t id_;
};

}  // namespace seaplan::chart
