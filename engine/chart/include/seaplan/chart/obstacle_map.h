// Charts -> grounding obstacles, in a local metric frame, with fast queries.
//
// Overview
//   LoadChartFile / LoadChartBytes read a chart with GDAL (IHO S-57 cells and
//   their updates, Kartverket FileGDB, shapefiles / GeoJSON / zipped sets),
//   pick every feature that grounds a ship of the operator's minimum depth,
//   project it to a UTM frame (geodesy.h), union it, grow it by the safety
//   distance (ObstacleGrowthM: enough that the simplified outline still keeps
//   the whole buffer) and simplify it with GEOS. The result is an immutable
//   ObstacleMap, which also keeps the unioned obstacles before the buffer
//   for exact clearance checks. Queries (distance, inside, segment / polygon
//   intersection, clearance, nearest navigable point) go through an
//   ObstacleQuery, one per thread.
//   Layers are recognised by the chart product's layer names (S-57 object
//   classes, Kartverket's product layers, seacharts' seabed<N>m) or by their
//   schema (depth attributes), never by the name of the file they came in.
//
// What is an obstacle (min depth D = ChartOptions::min_depth_m)
//   S-57:  LNDARE (areas; points buffered by point_hazard_radius_m),
//          DEPARE and DRGARE (dredged areas) with DRVAL1 < D, UNSARE
//          (unsurveyed: depth unknown), OBSTRN / WRECKS / UWTROC with
//          VALSOU < D, points and lines buffered by point_hazard_radius_m.
//          Unknown depth (VALSOU or DRVAL1 missing) is an obstacle while
//          unknown_depth_is_obstacle (default): a rock or wreck of unknown
//          depth is charted as dangerous (S-52 symbolises it so), and a
//          planner must not assume water it cannot see.
//          Opened with UPDATES=APPLY (the .001.. files beside the .000 are
//          applied), SPLIT_MULTIPOINT=ON, ADD_SOUNDG_DEPTH=ON,
//          RETURN_PRIMITIVES=OFF, RETURN_LINKAGES=OFF, LNAM_REFS=OFF.
//          Coverage: the extent of M_COVR when present.
//   Kartverket FileGDB (Sjokart - Dybdedata): landareal, torrfall (drying),
//          skjer (rocks, no depth), ikkekartlagtsjomaltomr (unsurveyed sea,
//          like UNSARE), dybdeareal with minimumsdybde < D,
//          grunne (shoal points) with dybde < D.
//   seacharts' processed sets (shapefile folders such as the Alesund set):
//          seabed<N>m ("sea at least N m deep"): obstacles = chart box
//          (extent of all recognised layers) minus the seabed<N>m polygon
//          with the smallest N >= D: only those layers are all deep enough,
//          and the smallest gives up the least water. No N >= D ->
//          InvalidArgument naming the deepest layer (never shallower water).
//   Any other layer (shapefiles, GeoJSON), by its schema: one with a DRVAL1 /
//          minimumsdybde / VALSOU / dybde field gives the features below D
//          (or of unknown depth); one without a depth field gives every
//          feature (plain land or obstacle polygons, coastlines, hazards).
//
// Thread-safety
//   ObstacleMap is immutable after construction: every const method may be
//   called from any thread. GEOS objects are never shared between threads:
//   an ObstacleQuery owns its own GEOS context, a private copy of the
//   geometry, its STR-tree and its prepared geometries. Create one
//   ObstacleQuery per worker thread (construction is O(vertices), ~ms for a
//   harbour cell) and reuse it; an ObstacleQuery itself is NOT thread-safe.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/common/status.h"

namespace seaplan::chart {

struct ChartOptions {
  // Operator's minimum depth (draught + under-keel clearance), metres. The
  // paper uses 10 m. Areas and hazards shallower than this are obstacles.
  double min_depth_m = 5.0;
  // Safety buffer kept around every obstacle, metres (paper: 10 m): the
  // obstacles are grown by ObstacleGrowthM, slightly more than this.
  double safety_buffer_m = 10.0;
  // Radius of the area a point (or line) hazard becomes, before the safety
  // buffer, metres.
  double point_hazard_radius_m = 20.0;
  // Douglas-Peucker tolerance applied after buffering, metres (0 = none).
  // The simplified outline may cut into the buffer by at most this much, so
  // keep it below safety_buffer_m.
  double simplify_tolerance_m = 5.0;
  // Local frame: 0 = the WGS84 UTM zone of the chart centre; otherwise an
  // EPSG code accepted by LocalFrame::FromEpsg (e.g. 25833 to keep the
  // Alesund data in its own UTM33 coordinates).
  int frame_epsg = 0;
  // Treat hazards whose depth (VALSOU, dybde) is unknown as obstacles.
  bool unknown_depth_is_obstacle = true;

  absl::Status Validate() const;
};

// How far the obstacles are grown, metres: the safety buffer plus the
// simplification tolerance (the simplified outline may cut in by that much),
// over cos(pi/32) (the buffer's arcs are 8 chords per quarter circle, whose
// midpoints lie that much closer): so every point outside the final
// obstacles keeps at least safety_buffer_m from the charted ones. Charts
// whose layers are thinned before the union (Kartverket) split the
// tolerance: half before, half after.
double ObstacleGrowthM(const ChartOptions& options);

// A ring of local points, not repeated closing point, any orientation.
using Ring = std::vector<EastNorth>;

// A polygon in the local frame: one outer ring and its holes.
struct Polygon {
  Ring outer;
  std::vector<Ring> holes;
};

// Axis-aligned box in the local frame.
struct LocalBox {
  EastNorth min;
  EastNorth max;
  bool Contains(EastNorth p) const {
    return p.east_m >= min.east_m && p.east_m <= max.east_m && p.north_m >= min.north_m &&
           p.north_m <= max.north_m;
  }
};

struct ObstacleSummary {
  // GDAL driver short name ("S57", "OpenFileGDB", "ESRI Shapefile",
  // "GeoJSON") or "polygons" for FromPolygons; kept through serialization.
  std::string source_format;
  // Number of source features taken as obstacles, per source layer name
  // (e.g. "LNDARE": 183). Synthetic layers: "chart_box-minus-seabed5m".
  std::map<std::string, int> features_per_layer;
  int polygon_count = 0;  // polygons after buffer + union
  int vertex_count = 0;   // vertices of those polygons
  double total_area_m2 = 0.0;
  // Bounding box of the obstacles (geographic, WGS84).
  LatLon bbox_min;
  LatLon bbox_max;
  // Chart coverage box in the local frame (all features' extent, or the
  // S-57 M_COVR coverage extent when present).
  LocalBox coverage;
  int frame_epsg = 0;
  ChartOptions options;
  // Non-fatal problems (repaired invalid polygons, skipped features...).
  std::vector<std::string> warnings;
};

class ObstacleQuery;

// The grounding obstacles of one chart. Move-only (heavy); share as
// std::shared_ptr<const ObstacleMap>. Immutable: all methods thread-safe.
class ObstacleMap {
 public:
  // Builds a map straight from polygons already in `frame` (tests, synthetic
  // scenarios, other libraries): buffers by options.safety_buffer_m,
  // simplifies, repairs and unions. `coverage` defaults to the obstacles'
  // box grown by 1 km when empty.
  static StatusOr<ObstacleMap> FromPolygons(std::vector<Polygon> obstacles, LocalFrame frame,
                                            const ChartOptions& options,
                                            std::string layer_name = "polygons",
                                            std::optional<LocalBox> coverage = std::nullopt);

  ObstacleMap(ObstacleMap&&) noexcept;
  ObstacleMap& operator=(ObstacleMap&&) noexcept;
  ObstacleMap(const ObstacleMap&) = delete;
  ObstacleMap& operator=(const ObstacleMap&) = delete;
  ~ObstacleMap();

  const LocalFrame& frame() const;
  const ObstacleSummary& summary() const;
  // Buffered, simplified, unioned obstacle polygons (plain data export).
  const std::vector<Polygon>& polygons() const;
  // Bounding box of all obstacles in the local frame (empty map: coverage).
  LocalBox bounds() const;
  // True when p lies inside the chart's coverage box.
  bool Covers(EastNorth p) const { return summary().coverage.Contains(p); }
  // The unioned obstacle geometry as ISO WKB (MultiPolygon, local frame).
  const std::string& wkb() const;
  // True when the map keeps the obstacles as charted, before the safety
  // buffer (every map built or loaded now; blobs stored by older versions
  // lack them).
  bool has_unbuffered_obstacles() const;

  // Internal (engine/chart/src): the GEOS side of the map.
  struct Impl;
  explicit ObstacleMap(std::unique_ptr<Impl> impl);
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// Nearest-obstacle answer.
struct NearestObstacle {
  // Distance from the query point to the obstacle, metres; 0 inside;
  // +infinity when the map has no obstacle.
  double distance_m = std::numeric_limits<double>::infinity();
  EastNorth nearest;       // closest point on that obstacle (the query point if inside)
  int polygon_index = -1;  // index into ObstacleMap::polygons()
};

// Clearance of a route from the obstacles as charted (before the buffer).
struct Clearance {
  // Exact (GEOS) distance, metres; 0 when the route touches an obstacle;
  // +infinity when the chart has none.
  double distance_m = std::numeric_limits<double>::infinity();
  EastNorth route_point;     // where the route comes closest
  EastNorth obstacle_point;  // the obstacle point nearest to it
};

// Per-thread query object over an ObstacleMap (which must outlive it).
// Not thread-safe: one per thread. Queries are O(log n) via an STR-tree and
// GEOS prepared geometries (built lazily per polygon, per query object).
class ObstacleQuery {
 public:
  explicit ObstacleQuery(const ObstacleMap& map);
  ObstacleQuery(ObstacleQuery&&) noexcept;
  ObstacleQuery& operator=(ObstacleQuery&&) noexcept;
  ObstacleQuery(const ObstacleQuery&) = delete;
  ObstacleQuery& operator=(const ObstacleQuery&) = delete;
  ~ObstacleQuery();

  // Distance to the nearest obstacle, metres; 0 inside one; +inf if none.
  double DistanceM(EastNorth p);
  // Like DistanceM outside; inside an obstacle, minus the distance to its
  // boundary (so a barrier cost can push a point out).
  double SignedDistanceM(EastNorth p);
  NearestObstacle Nearest(EastNorth p);
  // True when p lies in (or on the boundary of) an obstacle.
  bool Inside(EastNorth p);
  // True when segment a-b touches an obstacle.
  bool SegmentHits(EastNorth a, EastNorth b);
  // True when the polyline touches an obstacle.
  bool PolylineHits(std::span<const EastNorth> polyline);
  // True when the closed polygon `ring` (e.g. a drifting hull footprint)
  // overlaps or touches an obstacle.
  bool PolygonHits(std::span<const EastNorth> ring);
  // Distance from the closed polygon `ring` to the nearest obstacle, metres;
  // 0 when they touch or overlap; +inf if the map has no obstacle.
  double PolygonDistanceM(std::span<const EastNorth> ring);
  // Clearance of the polyline from the UNBUFFERED obstacles (the map's
  // obstacles are grown by safety_buffer_m plus the simplification
  // tolerance, so a polyline outside them keeps >= safety_buffer_m here).
  // nullopt when the map has no unbuffered obstacles
  // (has_unbuffered_obstacles()). The geometry is read on the first call.
  std::optional<Clearance> UnbufferedClearance(std::span<const EastNorth> polyline);
  // The navigable point (outside every obstacle, inside the coverage box)
  // nearest to p: p itself when it is navigable; otherwise the nearest point
  // of the navigable water (the coverage box inset by step_out_m, minus the
  // obstacles), stepped up to step_out_m further in. nullopt when there is
  // no navigable water. Builds that water per call (GEOS difference): meant
  // for error messages, not loops.
  std::optional<EastNorth> NearestNavigable(EastNorth p, double step_out_m = 5.0);

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// One input file given as bytes: `name` carries the extension that selects
// the reader ("US4MD81M.000", "US4MD81M.001", "land.geojson", "chart.zip",
// "x.shp" + "x.shx" + "x.dbf" + "x.prj").
struct ChartFile {
  std::string name;
  std::string bytes;
};

// Reads a chart from a path: an S-57 .000 (updates beside it are applied), a
// .gdb folder, a shapefile, a folder of shapefiles (each subfolder too, like
// the Alesund set), a GeoJSON file, or a .zip of any of these.
// Errors: NotFound (no such file), InvalidArgument (not a chart GDAL can read,
// no obstacle layer, empty chart, bad options) naming the file and problem.
StatusOr<ObstacleMap> LoadChartFile(const std::string& path, const ChartOptions& options);

// Same from bytes (server uploads). Files are written to a private /vsimem/
// folder (zips are opened through /vsizip/), never to disk. A name is a file
// name or a relative path inside an uploaded folder ("Trondheim.gdb/
// a00000009.gdbtable"), so a FileGDB or a shapefile set can be sent as its
// files; absolute paths, "." and ".." parts are InvalidArgument.
StatusOr<ObstacleMap> LoadChartBytes(const std::vector<ChartFile>& files,
                                     const ChartOptions& options);

// A compact binary blob (magic, version, frame, summary, WKB of the unioned
// obstacles) for storage; DeserializeObstacleMap rebuilds the map without
// GDAL in a few ms. Corrupt / foreign bytes -> InvalidArgument (never a crash).
std::string SerializeObstacleMap(const ObstacleMap& map);
StatusOr<ObstacleMap> DeserializeObstacleMap(std::string_view bytes);

}  // namespace seaplan::chart
