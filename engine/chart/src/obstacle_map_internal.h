// Internals shared by the chart loader, the map and the A1 planner.
#pragma once

#include <string>
#include <vector>

#include "geos_internal.h"
#include "seaplan/chart/obstacle_map.h"

namespace seaplan::chart {

struct ObstacleMap::Impl {
  LocalFrame frame;
  ObstacleSummary summary;
  std::vector<Polygon> polygons;
  std::vector<LocalBox> polygon_boxes;
  LocalBox bounds;
  std::string wkb;
  // The obstacles as selected from the chart, unioned, before the safety
  // buffer (ISO WKB, local frame); empty for blobs stored before it was kept.
  std::string unbuffered_wkb;
};

namespace internal {

// Buffers (safety_buffer_m), unions, simplifies and repairs `areas` (already
// in the local frame; point hazards already grown to areas) and builds the
// map. tiled_group[i] >= 0 marks areas[i] as a member of a tiled layer group
// (edge-matched, non-overlapping: S-57 skin of the earth, one Kartverket
// layer) merged with GEOSCoverageUnion; -1 (or a short vector) = general. `summary` carries source
// format, per-layer counts, coverage and warnings; the rest is filled here. Groups numbered from
// kPreSimplifyGroup on are not unioned as a coverage but thinned (Douglas-Peucker, half the
// tolerance) and overlaid.
inline constexpr int kPreSimplifyGroup = 1000;
StatusOr<ObstacleMap> BuildObstacleMap(GeosContext& c, std::vector<GeomPtr> areas,
                                       std::vector<int> tiled_group, LocalFrame frame,
                                       const ChartOptions& options, ObstacleSummary summary);

// Builds the map from the final (already buffered) obstacle geometry and the
// WKB of the unbuffered one ("" = unknown).
StatusOr<ObstacleMap> FinishObstacleMap(GeosContext& c, GeomPtr obstacles, LocalFrame frame,
                                        ObstacleSummary summary, std::string unbuffered_wkb);

// ISO WKB of g ("" on failure).
std::string WriteWkb(const GeosContext& c, const GEOSGeometry* g);

}  // namespace internal
}  // namespace seaplan::chart
