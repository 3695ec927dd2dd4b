#include "seaplan/chart/obstacle_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <utility>

#include "absl/strings/str_cat.h"
#include "obstacle_map_internal.h"
#include "seaplan/common/log.h"

namespace seaplan::chart {

using internal::GeomPtr;
using internal::GeosContext;
using internal::Own;

absl::Status ChartOptions::Validate() const {
  auto finite_nonneg = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!std::isfinite(min_depth_m) || min_depth_m < 0.0 || min_depth_m > 1000.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("min_depth_m must be in [0, 1000], got ", min_depth_m));
  }
  if (!finite_nonneg(safety_buffer_m) || safety_buffer_m > 10000.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("safety_buffer_m must be in [0, 10000], got ", safety_buffer_m));
  }
  if (!std::isfinite(point_hazard_radius_m) || point_hazard_radius_m <= 0.0 ||
      point_hazard_radius_m > 10000.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("point_hazard_radius_m must be in (0, 10000], got ", point_hazard_radius_m));
  }
  if (!finite_nonneg(simplify_tolerance_m) || simplify_tolerance_m > 1000.0) {
    return absl::InvalidArgumentError(
        absl::StrCat("simplify_tolerance_m must be in [0, 1000], got ", simplify_tolerance_m));
  }
  if (frame_epsg != 0) {
    SEAPLAN_RETURN_IF_ERROR(LocalFrame::FromEpsg(frame_epsg).status());
  }
  return absl::OkStatus();
}

namespace {
// Half the angle of one buffer chord (8 per quarter circle).
constexpr double kChordHalfAngle = M_PI / 32.0;
}  // namespace

double ObstacleGrowthM(const ChartOptions& options) {
  return (options.safety_buffer_m + options.simplify_tolerance_m) / std::cos(kChordHalfAngle);
}

ObstacleMap::ObstacleMap(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
ObstacleMap::ObstacleMap(ObstacleMap&&) noexcept = default;
ObstacleMap& ObstacleMap::operator=(ObstacleMap&&) noexcept = default;
ObstacleMap::~ObstacleMap() = default;

const LocalFrame& ObstacleMap::frame() const {
  return impl_->frame;
}
const ObstacleSummary& ObstacleMap::summary() const {
  return impl_->summary;
}
const std::vector<Polygon>& ObstacleMap::polygons() const {
  return impl_->polygons;
}
LocalBox ObstacleMap::bounds() const {
  return impl_->bounds;
}
const std::string& ObstacleMap::wkb() const {
  return impl_->wkb;
}
bool ObstacleMap::has_unbuffered_obstacles() const {
  return !impl_->unbuffered_wkb.empty();
}

namespace internal {

std::string WriteWkb(const GeosContext& c, const GEOSGeometry* g) {
  GEOSWKBWriter* writer = GEOSWKBWriter_create_r(c.get());
  size_t size = 0;
  unsigned char* buf = GEOSWKBWriter_write_r(c.get(), writer, g, &size);
  GEOSWKBWriter_destroy_r(c.get(), writer);
  if (buf == nullptr) return "";
  std::string out(reinterpret_cast<const char*>(buf), size);
  GEOSFree_r(c.get(), buf);
  return out;
}

StatusOr<ObstacleMap> FinishObstacleMap(GeosContext& c, GeomPtr obstacles, LocalFrame frame,
                                        ObstacleSummary summary, std::string unbuffered_wkb) {
  auto impl = std::make_unique<ObstacleMap::Impl>();
  impl->frame = frame;
  impl->unbuffered_wkb = std::move(unbuffered_wkb);
  if (obstacles) ExportPolygons(c, obstacles.get(), &impl->polygons);
  // WKB of a MultiPolygon of exactly the exported polygons.
  {
    std::vector<GeomPtr> parts;
    parts.reserve(impl->polygons.size());
    for (const Polygon& p : impl->polygons) parts.push_back(MakePolygon(c, p));
    GeomPtr multi = MakeCollection(c, GEOS_MULTIPOLYGON, std::move(parts));
    if (!multi)
      return absl::InternalError(
          absl::StrCat("GEOS: cannot build obstacle multipolygon: ", c.TakeError()));
    impl->wkb = WriteWkb(c, multi.get());
    if (impl->wkb.empty())
      return absl::InternalError(absl::StrCat("GEOS: cannot write WKB: ", c.TakeError()));
  }
  const double inf = std::numeric_limits<double>::infinity();
  LocalBox all{{inf, inf}, {-inf, -inf}};
  double lat_min = inf, lat_max = -inf, lon_min = inf, lon_max = -inf;
  int vertices = 0;
  double area = 0.0;
  impl->polygon_boxes.reserve(impl->polygons.size());
  for (const Polygon& p : impl->polygons) {
    LocalBox b{{inf, inf}, {-inf, -inf}};
    for (const EastNorth& q : p.outer) {
      b.min.east_m = std::min(b.min.east_m, q.east_m);
      b.min.north_m = std::min(b.min.north_m, q.north_m);
      b.max.east_m = std::max(b.max.east_m, q.east_m);
      b.max.north_m = std::max(b.max.north_m, q.north_m);
      const LatLon ll = frame.ToLatLon(q);
      lat_min = std::min(lat_min, ll.lat_deg);
      lat_max = std::max(lat_max, ll.lat_deg);
      lon_min = std::min(lon_min, ll.lon_deg);
      lon_max = std::max(lon_max, ll.lon_deg);
    }
    vertices += static_cast<int>(p.outer.size());
    for (const Ring& h : p.holes) vertices += static_cast<int>(h.size());
    area += PolygonArea(p);
    impl->polygon_boxes.push_back(b);
    all.min.east_m = std::min(all.min.east_m, b.min.east_m);
    all.min.north_m = std::min(all.min.north_m, b.min.north_m);
    all.max.east_m = std::max(all.max.east_m, b.max.east_m);
    all.max.north_m = std::max(all.max.north_m, b.max.north_m);
  }
  if (impl->polygons.empty()) {
    all = summary.coverage;
    const LatLon a = frame.ToLatLon(all.min), b = frame.ToLatLon(all.max);
    lat_min = a.lat_deg, lon_min = a.lon_deg, lat_max = b.lat_deg, lon_max = b.lon_deg;
  }
  impl->bounds = all;
  summary.polygon_count = static_cast<int>(impl->polygons.size());
  summary.vertex_count = vertices;
  summary.total_area_m2 = area;
  summary.bbox_min = {lat_min, lon_min};
  summary.bbox_max = {lat_max, lon_max};
  summary.frame_epsg = frame.epsg();
  impl->summary = std::move(summary);
  return ObstacleMap(std::move(impl));
}

StatusOr<ObstacleMap> BuildObstacleMap(GeosContext& c, std::vector<GeomPtr> areas,
                                       std::vector<int> tiled_group, LocalFrame frame,
                                       const ChartOptions& options, ObstacleSummary summary) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  tiled_group.resize(areas.size(), -1);
  int repaired = 0;
  // Tiled layers (S-57 skin of the earth: LNDARE/DEPARE/DRGARE/UNSARE;
  // Kartverket dybdeareal, landareal, ...) share their edges exactly, so
  // GEOSCoverageUnion merges a group in near-linear time; OverlayNG's union
  // of the same polygons takes ~3 s on US4MD81M. A group that is not a clean
  // coverage gives an invalid result and goes through the general union.
  std::map<int, std::vector<GeomPtr>> groups;
  for (size_t i = 0; i < areas.size(); ++i) {
    GeomPtr& g = areas[i];
    if (!g || GEOSisEmpty_r(c.get(), g.get()) == 1) continue;
    bool was_repaired = false;
    GeomPtr v = MakeValidPolygonal(c, std::move(g), &was_repaired);
    if (was_repaired) ++repaired;
    if (!v || GEOSisEmpty_r(c.get(), v.get()) == 1) continue;
    std::vector<GeomPtr>& group = groups[tiled_group[i]];
    if (tiled_group[i] >= 0) {
      for (GeomPtr& part : PolygonParts(c, v.get())) group.push_back(std::move(part));
    } else {
      group.push_back(std::move(v));
    }
  }
  if (repaired > 0) {
    summary.warnings.push_back(absl::StrCat(
        repaired, " invalid (e.g. self-intersecting) polygon(s) repaired with GEOSMakeValid"));
    log::Warn("chart: {} invalid polygon(s) repaired", repaired);
  }
  const auto t0 = std::chrono::steady_clock::now();
  auto ms = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
  };
  std::vector<GeomPtr> rest;
  int clean_groups = 0, dirty_groups = 0;
  for (auto& [id, members] : groups) {
    if (id < 0 || members.size() < 2) {
      for (GeomPtr& m : members) rest.push_back(std::move(m));
      continue;
    }
    if (id >= kPreSimplifyGroup) {
      // Dense coastlines (Kartverket: ~10 cm vertex spacing) make the
      // overlay slow; the final outline is simplified anyway, so thin each
      // member first with half the tolerance (Douglas-Peucker, linear time)
      // and keep the total deviation within simplify_tolerance_m.
      const double pre = 0.5 * options.simplify_tolerance_m;
      for (GeomPtr& m : members) {
        if (pre > 0.0) {
          GeomPtr thin = Own(c, GEOSSimplify_r(c.get(), m.get(), pre));
          if (thin) {
            bool fixed = false;
            thin = MakeValidPolygonal(c, std::move(thin), &fixed);
            if (thin && GEOSisEmpty_r(c.get(), thin.get()) == 0) m = std::move(thin);
          }
        }
        rest.push_back(std::move(m));
      }
      continue;
    }
    std::vector<GeomPtr> backup;
    backup.reserve(members.size());
    for (GeomPtr& m : members) backup.push_back(Own(c, GEOSGeom_clone_r(c.get(), m.get())));
    GeomPtr multi = MakeCollection(c, GEOS_MULTIPOLYGON, std::move(members));
    auto tg = std::chrono::steady_clock::now();
    GeomPtr merged = multi ? Own(c, GEOSCoverageUnion_r(c.get(), multi.get())) : nullptr;
    const double cu_ms = ms(tg);
    tg = std::chrono::steady_clock::now();
    const bool valid_merge = merged && GEOSisValid_r(c.get(), merged.get()) == 1;
    log::Debug("group {}: {} members, coverage union {:.0f} ms, isValid {:.0f} ms", id,
               backup.size(), cu_ms, ms(tg));
    if (valid_merge) {
      ++clean_groups;
      rest.push_back(std::move(merged));
    } else {
      ++dirty_groups;
      c.TakeError();
      for (GeomPtr& m : backup) rest.push_back(std::move(m));
    }
  }
  const double coverage_ms = ms(t0);
  const auto t1 = std::chrono::steady_clock::now();
  GeomPtr result;
  std::string unbuffered_wkb;
  double union_ms = 0, buffer_ms = 0;
  if (!rest.empty()) {
    GeomPtr collection = MakeCollection(c, GEOS_GEOMETRYCOLLECTION, std::move(rest));
    GeomPtr unioned = Own(c, GEOSUnaryUnion_r(c.get(), collection.get()));
    if (!unioned)
      return absl::InvalidArgumentError(
          absl::StrCat("chart: union of obstacles failed: ", c.TakeError()));
    union_ms = ms(t1);
    unbuffered_wkb = WriteWkb(c, unioned.get());
    const auto t2 = std::chrono::steady_clock::now();
    const double simplify_final =
        groups.rbegin() != groups.rend() && groups.rbegin()->first >= kPreSimplifyGroup
            ? 0.5 * options.simplify_tolerance_m
            : options.simplify_tolerance_m;
    if (options.safety_buffer_m + simplify_final > 0.0) {
      // The outline is simplified below (it may cut in by up to the
      // tolerance) and the buffer's arcs are chords (8 per quarter circle,
      // cutting in by r (1 - cos(pi/32))): grow the buffer by both so that
      // every point outside the final obstacles keeps safety_buffer_m from
      // the unbuffered ones.
      const double buffer_m =
          (options.safety_buffer_m + simplify_final) / std::cos(kChordHalfAngle);
      result = Own(c, GEOSBuffer_r(c.get(), unioned.get(), buffer_m, 8));
      if (!result)
        return absl::InvalidArgumentError(
            absl::StrCat("chart: safety buffer failed: ", c.TakeError()));
    } else {
      result = std::move(unioned);
    }
    if (simplify_final > 0.0) {
      GeomPtr simple =
          Own(c, GEOSTopologyPreserveSimplify_r(c.get(), result.get(), simplify_final));
      if (simple) {
        bool fixed = false;
        simple = MakeValidPolygonal(c, std::move(simple), &fixed);
        if (simple) result = std::move(simple);
      }
    }
    buffer_ms = ms(t2);
  }
  log::Debug(
      "chart build: coverage union {:.0f} ms ({} clean, {} not), union {:.0f} ms, buffer+simplify "
      "{:.0f} ms",
      coverage_ms, clean_groups, dirty_groups, union_ms, buffer_ms);
  return FinishObstacleMap(c, std::move(result), frame, std::move(summary),
                           std::move(unbuffered_wkb));
}

}  // namespace internal

StatusOr<ObstacleMap> ObstacleMap::FromPolygons(std::vector<Polygon> obstacles, LocalFrame frame,
                                                const ChartOptions& options, std::string layer_name,
                                                std::optional<LocalBox> coverage) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  GeosContext c;
  std::vector<GeomPtr> areas;
  const double inf = std::numeric_limits<double>::infinity();
  LocalBox box{{inf, inf}, {-inf, -inf}};
  for (size_t i = 0; i < obstacles.size(); ++i) {
    const Polygon& p = obstacles[i];
    for (const EastNorth& q : p.outer) {
      if (!std::isfinite(q.east_m) || !std::isfinite(q.north_m)) {
        return absl::InvalidArgumentError(
            absl::StrCat("obstacle polygon ", i, " has a non-finite coordinate"));
      }
      box.min.east_m = std::min(box.min.east_m, q.east_m);
      box.min.north_m = std::min(box.min.north_m, q.north_m);
      box.max.east_m = std::max(box.max.east_m, q.east_m);
      box.max.north_m = std::max(box.max.north_m, q.north_m);
    }
    GeomPtr g = internal::MakePolygon(c, p);
    if (!g)
      return absl::InvalidArgumentError(
          absl::StrCat("obstacle polygon ", i, " has fewer than 3 distinct points"));
    areas.push_back(std::move(g));
  }
  ObstacleSummary summary;
  summary.source_format = "polygons";
  summary.features_per_layer[std::move(layer_name)] = static_cast<int>(obstacles.size());
  summary.options = options;
  if (coverage) {
    summary.coverage = *coverage;
  } else if (obstacles.empty()) {
    return absl::InvalidArgumentError("FromPolygons: no obstacles and no coverage box");
  } else {
    const double grow = 1000.0 + options.safety_buffer_m;
    summary.coverage = {{box.min.east_m - grow, box.min.north_m - grow},
                        {box.max.east_m + grow, box.max.north_m + grow}};
  }
  return internal::BuildObstacleMap(c, std::move(areas), {}, frame, options, std::move(summary));
}

// ---------------------------------------------------------------------------
// ObstacleQuery

struct ObstacleQuery::State {
  GeosContext ctx;
  const ObstacleMap* map = nullptr;
  // Pieces of the obstacle polygons (large polygons are subdivided, like
  // PostGIS ST_Subdivide, so the STR-tree prunes well and each prepared
  // geometry is small); owner[piece] = index into map->polygons().
  std::vector<GeomPtr> parts;
  std::vector<int> owner;
  std::vector<GeomPtr> originals;  // per polygon, for boundaries
  std::vector<const GEOSPreparedGeometry*> prepared;
  std::vector<GeomPtr> boundaries;
  std::vector<const GEOSPreparedGeometry*> prepared_boundaries;
  GEOSSTRtree* tree = nullptr;
  std::vector<int> ids;   // tree items point into this (stable after build)
  std::vector<int> hits;  // scratch for tree queries
  int query_sentinel = -1;
  const GEOSGeometry* query_geom = nullptr;
  // The unbuffered obstacles, read from the map's WKB on first use.
  bool unbuffered_read = false;
  GeomPtr unbuffered;
  const GEOSPreparedGeometry* prepared_unbuffered = nullptr;

  ~State() {
    if (prepared_unbuffered != nullptr) GEOSPreparedGeom_destroy_r(ctx.get(), prepared_unbuffered);
    unbuffered.reset();
    for (const GEOSPreparedGeometry* p : prepared) {
      if (p != nullptr) GEOSPreparedGeom_destroy_r(ctx.get(), p);
    }
    for (const GEOSPreparedGeometry* p : prepared_boundaries) {
      if (p != nullptr) GEOSPreparedGeom_destroy_r(ctx.get(), p);
    }
    if (tree != nullptr) GEOSSTRtree_destroy_r(ctx.get(), tree);
    parts.clear();
    boundaries.clear();
    originals.clear();
  }

  const GEOSPreparedGeometry* Prepared(int i) {
    if (prepared[i] == nullptr) prepared[i] = GEOSPrepare_r(ctx.get(), parts[i].get());
    return prepared[i];
  }
  const GEOSPreparedGeometry* PreparedBoundary(int i) {
    if (prepared_boundaries[i] == nullptr) {
      boundaries[i] = Own(ctx, GEOSBoundary_r(ctx.get(), originals[i].get()));
      prepared_boundaries[i] = GEOSPrepare_r(ctx.get(), boundaries[i].get());
    }
    return prepared_boundaries[i];
  }

  static void Collect(void* item, void* userdata) {
    static_cast<State*>(userdata)->hits.push_back(*static_cast<int*>(item));
  }
  // Candidate polygons whose envelope meets g's envelope.
  void Candidates(const GEOSGeometry* g) {
    hits.clear();
    GEOSSTRtree_query_r(ctx.get(), tree, g, &State::Collect, this);
  }
  bool Hits(const GEOSGeometry* g) {
    if (g == nullptr) return false;
    Candidates(g);
    for (int i : hits) {
      if (GEOSPreparedIntersects_r(ctx.get(), Prepared(i), g) == 1) return true;
    }
    return false;
  }
  static int Distance(const void* item1, const void* item2, double* distance, void* userdata) {
    auto* self = static_cast<State*>(userdata);
    const int a = *static_cast<const int*>(item1);
    const int b = *static_cast<const int*>(item2);
    const int poly = a >= 0 ? a : b;
    if (poly < 0) {
      *distance = 0.0;
      return 1;
    }
    return GEOSPreparedDistance_r(self->ctx.get(), self->Prepared(poly), self->query_geom,
                                  distance);
  }
};

namespace {

// Splits g in halves along its longer side until each piece has at most
// kMaxPieceVertices vertices (or the depth limit is reached).
constexpr int kMaxPieceVertices = 64;
void Subdivide(const GeosContext& c, GeomPtr g, int owner, int depth, std::vector<GeomPtr>* out,
               std::vector<int>* owners) {
  if (!g || GEOSisEmpty_r(c.get(), g.get()) == 1) return;
  if (GEOSGetNumCoordinates_r(c.get(), g.get()) <= kMaxPieceVertices || depth >= 12) {
    out->push_back(std::move(g));
    owners->push_back(owner);
    return;
  }
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  GEOSGeom_getXMin_r(c.get(), g.get(), &x0);
  GEOSGeom_getYMin_r(c.get(), g.get(), &y0);
  GEOSGeom_getXMax_r(c.get(), g.get(), &x1);
  GEOSGeom_getYMax_r(c.get(), g.get(), &y1);
  const bool split_x = (x1 - x0) >= (y1 - y0);
  const double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
  const double boxes[2][4] = {{x0, y0, split_x ? xm : x1, split_x ? y1 : ym},
                              {split_x ? xm : x0, split_x ? y0 : ym, x1, y1}};
  for (const auto& b : boxes) {
    GeomPtr half = Own(c, GEOSClipByRect_r(c.get(), g.get(), b[0], b[1], b[2], b[3]));
    if (!half) {  // clipping failed: keep the piece whole rather than lose it
      out->push_back(Own(c, GEOSGeom_clone_r(c.get(), g.get())));
      owners->push_back(owner);
      return;
    }
    for (GeomPtr& part : internal::PolygonParts(c, half.get())) {
      Subdivide(c, std::move(part), owner, depth + 1, out, owners);
    }
  }
}

}  // namespace

ObstacleQuery::ObstacleQuery(const ObstacleMap& map) : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.map = &map;
  const auto& polygons = map.polygons();
  const size_t n = polygons.size();
  s.originals.reserve(n);
  for (size_t i = 0; i < n; ++i) {
    s.originals.push_back(internal::MakePolygon(s.ctx, polygons[i]));
    GeomPtr copy = s.originals.back()
                       ? Own(s.ctx, GEOSGeom_clone_r(s.ctx.get(), s.originals.back().get()))
                       : nullptr;
    Subdivide(s.ctx, std::move(copy), static_cast<int>(i), 0, &s.parts, &s.owner);
  }
  const size_t pieces = s.parts.size();
  s.ids.resize(pieces);
  s.prepared.assign(pieces, nullptr);
  s.boundaries.resize(n);
  s.prepared_boundaries.assign(n, nullptr);
  s.tree = GEOSSTRtree_create_r(s.ctx.get(), 10);
  for (size_t i = 0; i < pieces; ++i) {
    s.ids[i] = static_cast<int>(i);
    GEOSSTRtree_insert_r(s.ctx.get(), s.tree, s.parts[i].get(), &s.ids[i]);
  }
  // The tree builds itself on its first query; do it now so the cost is paid
  // at construction, not in the first (timed) query.
  if (pieces > 0) {
    GeomPtr probe = internal::MakePoint(s.ctx, polygons[0].outer[0]);
    s.Candidates(probe.get());
  }
}

ObstacleQuery::ObstacleQuery(ObstacleQuery&&) noexcept = default;
ObstacleQuery& ObstacleQuery::operator=(ObstacleQuery&&) noexcept = default;
ObstacleQuery::~ObstacleQuery() = default;

double ObstacleQuery::PolygonDistanceM(std::span<const EastNorth> ring) {
  State& s = *state_;
  if (s.parts.empty() || ring.empty()) return std::numeric_limits<double>::infinity();
  GeomPtr g = ring.size() >= 3 ? internal::MakeRingPolygon(s.ctx, ring.data(), ring.size())
                               : internal::MakeLine(s.ctx, ring.data(), ring.size());
  if (!g) g = internal::MakePoint(s.ctx, ring[0]);
  s.query_geom = g.get();
  const void* found = GEOSSTRtree_nearest_generic_r(s.ctx.get(), s.tree, &s.query_sentinel, g.get(),
                                                    &State::Distance, &s);
  s.query_geom = nullptr;
  if (found == nullptr) return std::numeric_limits<double>::infinity();
  double d = 0.0;
  GEOSPreparedDistance_r(s.ctx.get(), s.Prepared(*static_cast<const int*>(found)), g.get(), &d);
  return d;
}

NearestObstacle ObstacleQuery::Nearest(EastNorth p) {
  State& s = *state_;
  NearestObstacle out;
  if (s.parts.empty()) return out;
  GeomPtr pt = internal::MakePoint(s.ctx, p);
  s.query_geom = pt.get();
  const void* found = GEOSSTRtree_nearest_generic_r(s.ctx.get(), s.tree, &s.query_sentinel,
                                                    pt.get(), &State::Distance, &s);
  s.query_geom = nullptr;
  if (found == nullptr) return out;
  const int i = *static_cast<const int*>(found);
  double d = 0.0;
  GEOSPreparedDistance_r(s.ctx.get(), s.Prepared(i), pt.get(), &d);
  out.distance_m = d;
  out.polygon_index = s.owner[i];
  out.nearest = p;
  if (d > 0.0) {
    GEOSCoordSequence* seq = GEOSPreparedNearestPoints_r(s.ctx.get(), s.Prepared(i), pt.get());
    if (seq != nullptr) {
      GEOSCoordSeq_getXY_r(s.ctx.get(), seq, 0, &out.nearest.east_m, &out.nearest.north_m);
      GEOSCoordSeq_destroy_r(s.ctx.get(), seq);
    }
  }
  return out;
}

double ObstacleQuery::DistanceM(EastNorth p) {
  return Nearest(p).distance_m;
}

bool ObstacleQuery::Inside(EastNorth p) {
  State& s = *state_;
  GeomPtr pt = internal::MakePoint(s.ctx, p);
  return s.Hits(pt.get());
}

double ObstacleQuery::SignedDistanceM(EastNorth p) {
  State& s = *state_;
  GeomPtr pt = internal::MakePoint(s.ctx, p);
  s.Candidates(pt.get());
  for (int i : s.hits) {
    if (GEOSPreparedIntersects_r(s.ctx.get(), s.Prepared(i), pt.get()) == 1) {
      double d = 0.0;
      GEOSPreparedDistance_r(s.ctx.get(), s.PreparedBoundary(s.owner[i]), pt.get(), &d);
      return -d;
    }
  }
  return Nearest(p).distance_m;
}

bool ObstacleQuery::SegmentHits(EastNorth a, EastNorth b) {
  State& s = *state_;
  const EastNorth pts[2] = {a, b};
  GeomPtr line = a == b ? internal::MakePoint(s.ctx, a) : internal::MakeLine(s.ctx, pts, 2);
  return s.Hits(line.get());
}

bool ObstacleQuery::PolylineHits(std::span<const EastNorth> polyline) {
  State& s = *state_;
  if (polyline.empty()) return false;
  if (polyline.size() == 1) return Inside(polyline[0]);
  GeomPtr line = internal::MakeLine(s.ctx, polyline.data(), polyline.size());
  return s.Hits(line.get());
}

bool ObstacleQuery::PolygonHits(std::span<const EastNorth> ring) {
  State& s = *state_;
  if (ring.size() < 3) return PolylineHits(ring);
  GeomPtr poly = internal::MakeRingPolygon(s.ctx, ring.data(), ring.size());
  if (!poly) return PolylineHits(ring);
  return s.Hits(poly.get());
}

std::optional<Clearance> ObstacleQuery::UnbufferedClearance(std::span<const EastNorth> polyline) {
  State& s = *state_;
  const std::string& wkb = s.map->impl().unbuffered_wkb;
  if (wkb.empty()) return std::nullopt;
  if (!s.unbuffered_read) {
    s.unbuffered_read = true;
    GEOSWKBReader* reader = GEOSWKBReader_create_r(s.ctx.get());
    s.unbuffered = Own(s.ctx, GEOSWKBReader_read_r(
                                  s.ctx.get(), reader,
                                  reinterpret_cast<const unsigned char*>(wkb.data()), wkb.size()));
    GEOSWKBReader_destroy_r(s.ctx.get(), reader);
    if (s.unbuffered) s.prepared_unbuffered = GEOSPrepare_r(s.ctx.get(), s.unbuffered.get());
  }
  if (s.prepared_unbuffered == nullptr) return std::nullopt;
  Clearance out;
  if (polyline.empty() || GEOSisEmpty_r(s.ctx.get(), s.unbuffered.get()) == 1) return out;
  GeomPtr g = polyline.size() == 1 ? internal::MakePoint(s.ctx, polyline[0])
                                   : internal::MakeLine(s.ctx, polyline.data(), polyline.size());
  if (!g) g = internal::MakePoint(s.ctx, polyline[0]);
  out.route_point = polyline[0];
  out.obstacle_point = polyline[0];
  if (GEOSPreparedIntersects_r(s.ctx.get(), s.prepared_unbuffered, g.get()) == 1) {
    out.distance_m = 0.0;
  } else if (GEOSPreparedDistance_r(s.ctx.get(), s.prepared_unbuffered, g.get(), &out.distance_m) !=
             1) {
    return std::nullopt;
  }
  // Nearest points: [0] on the prepared geometry, [1] on the route.
  if (GEOSCoordSequence* seq =
          GEOSPreparedNearestPoints_r(s.ctx.get(), s.prepared_unbuffered, g.get())) {
    GEOSCoordSeq_getXY_r(s.ctx.get(), seq, 0, &out.obstacle_point.east_m,
                         &out.obstacle_point.north_m);
    GEOSCoordSeq_getXY_r(s.ctx.get(), seq, 1, &out.route_point.east_m, &out.route_point.north_m);
    GEOSCoordSeq_destroy_r(s.ctx.get(), seq);
  }
  return out;
}

std::optional<EastNorth> ObstacleQuery::NearestNavigable(EastNorth p, double step_out_m) {
  State& s = *state_;
  if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) return std::nullopt;
  const LocalBox box = s.map->summary().coverage;
  auto navigable = [&](EastNorth q) { return box.Contains(q) && !Inside(q); };
  if (navigable(p)) return p;
  // The navigable water: the coverage box (inset by the step, so a point
  // stepped towards it stays inside) minus the obstacles. Built per call:
  // this answers error messages, not a hot loop.
  const double inset = std::max(0.0, std::min({step_out_m, 0.25 * (box.max.east_m - box.min.east_m),
                                               0.25 * (box.max.north_m - box.min.north_m)}));
  GeomPtr water = internal::MakeBox(s.ctx, {{box.min.east_m + inset, box.min.north_m + inset},
                                            {box.max.east_m - inset, box.max.north_m - inset}});
  for (const GeomPtr& obstacle : s.originals) {
    if (!water || !obstacle) continue;
    water = Own(s.ctx, GEOSDifference_r(s.ctx.get(), water.get(), obstacle.get()));
  }
  if (!water || GEOSisEmpty_r(s.ctx.get(), water.get()) == 1) return std::nullopt;
  GeomPtr pt = internal::MakePoint(s.ctx, p);
  GEOSCoordSequence* seq = GEOSNearestPoints_r(s.ctx.get(), water.get(), pt.get());
  if (seq == nullptr) return std::nullopt;
  EastNorth q = p;
  GEOSCoordSeq_getXY_r(s.ctx.get(), seq, 0, &q.east_m, &q.north_m);
  GEOSCoordSeq_destroy_r(s.ctx.get(), seq);
  // q is on the water's edge (which counts as obstacle): step on into the
  // water, as far as step_out_m when it is that wide.
  const double dx = q.east_m - p.east_m, dy = q.north_m - p.north_m;
  const double len = std::hypot(dx, dy);
  if (len > 0.0) {
    for (double step = step_out_m; step > 1e-3; step *= 0.25) {
      const EastNorth r{q.east_m + dx / len * step, q.north_m + dy / len * step};
      if (navigable(r)) return r;
    }
  }
  return navigable(q) ? std::optional<EastNorth>(q) : std::nullopt;
}

// ---------------------------------------------------------------------------
// Serialization: "SPCHART" 0x01, then little-endian fields, then an FNV-1a
// 64-bit checksum of everything before it.

namespace {

constexpr char kMagic[8] = {'S', 'P', 'C', 'H', 'A', 'R', 'T', 1};

class Writer {
 public:
  void U32(uint32_t v) { Raw(&v, 4); }
  void I32(int32_t v) { Raw(&v, 4); }
  void F64(double v) { Raw(&v, 8); }
  void Str(std::string_view s) {
    U32(static_cast<uint32_t>(s.size()));
    out_.append(s.data(), s.size());
  }
  void Raw(const void* p, size_t n) { out_.append(static_cast<const char*>(p), n); }
  std::string& out() { return out_; }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  bool U32(uint32_t* v) { return Raw(v, 4); }
  bool I32(int32_t* v) { return Raw(v, 4); }
  bool F64(double* v) { return Raw(v, 8); }
  bool Str(std::string* s) {
    uint32_t n = 0;
    if (!U32(&n) || n > in_.size() - pos_) return false;
    s->assign(in_.data() + pos_, n);
    pos_ += n;
    return true;
  }
  bool AtEnd() const { return pos_ == in_.size(); }
  bool Raw(void* p, size_t n) {
    if (n > in_.size() - pos_) return false;
    std::memcpy(p, in_.data() + pos_, n);
    pos_ += n;
    return true;
  }

 private:
  std::string_view in_;
  size_t pos_ = 0;
};

uint64_t Fnv1a(std::string_view s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : s) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

}  // namespace

std::string SerializeObstacleMap(const ObstacleMap& map) {
  static_assert(sizeof(double) == 8);
  Writer w;
  w.Raw(kMagic, sizeof(kMagic));
  const ObstacleSummary& s = map.summary();
  w.I32(map.frame().epsg());
  w.Str(s.source_format);
  w.U32(static_cast<uint32_t>(s.features_per_layer.size()));
  for (const auto& [name, count] : s.features_per_layer) {
    w.Str(name);
    w.I32(count);
  }
  w.U32(static_cast<uint32_t>(s.warnings.size()));
  for (const std::string& warning : s.warnings) w.Str(warning);
  for (double v : {s.coverage.min.east_m, s.coverage.min.north_m, s.coverage.max.east_m,
                   s.coverage.max.north_m})
    w.F64(v);
  const ChartOptions& o = s.options;
  for (double v :
       {o.min_depth_m, o.safety_buffer_m, o.point_hazard_radius_m, o.simplify_tolerance_m})
    w.F64(v);
  w.I32(o.frame_epsg);
  w.I32(o.unknown_depth_is_obstacle ? 1 : 0);
  w.Str(map.wkb());
  // Appended field: blobs written before it end here and still load.
  w.Str(map.impl().unbuffered_wkb);
  const uint64_t sum = Fnv1a(w.out());
  w.Raw(&sum, 8);
  return std::move(w.out());
}

StatusOr<ObstacleMap> DeserializeObstacleMap(std::string_view bytes) {
  auto corrupt = [](const std::string& what) {
    return absl::InvalidArgumentError(
        absl::StrCat("stored chart blob is corrupt or not a seaplan chart: ", what));
  };
  if (bytes.size() < sizeof(kMagic) + 8 || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    return corrupt("bad magic/version");
  }
  uint64_t sum = 0;
  std::memcpy(&sum, bytes.data() + bytes.size() - 8, 8);
  if (Fnv1a(bytes.substr(0, bytes.size() - 8)) != sum) return corrupt("checksum mismatch");
  Reader r(bytes.substr(sizeof(kMagic), bytes.size() - 8 - sizeof(kMagic)));
  ObstacleSummary s;
  int32_t epsg = 0;
  if (!r.I32(&epsg)) return corrupt("frame");
  auto frame = LocalFrame::FromEpsg(epsg);
  if (!frame.ok()) return corrupt(std::string(frame.status().message()));
  uint32_t n = 0;
  if (!r.Str(&s.source_format) || !r.U32(&n)) return corrupt("header");
  for (uint32_t i = 0; i < n; ++i) {
    std::string name;
    int32_t count = 0;
    if (!r.Str(&name) || !r.I32(&count)) return corrupt("layer counts");
    s.features_per_layer[name] = count;
  }
  if (!r.U32(&n)) return corrupt("warnings");
  for (uint32_t i = 0; i < n; ++i) {
    std::string warning;
    if (!r.Str(&warning)) return corrupt("warnings");
    s.warnings.push_back(std::move(warning));
  }
  int32_t frame_epsg = 0, unknown = 0;
  if (!r.F64(&s.coverage.min.east_m) || !r.F64(&s.coverage.min.north_m) ||
      !r.F64(&s.coverage.max.east_m) || !r.F64(&s.coverage.max.north_m) ||
      !r.F64(&s.options.min_depth_m) || !r.F64(&s.options.safety_buffer_m) ||
      !r.F64(&s.options.point_hazard_radius_m) || !r.F64(&s.options.simplify_tolerance_m) ||
      !r.I32(&frame_epsg) || !r.I32(&unknown)) {
    return corrupt("coverage/options");
  }
  s.options.frame_epsg = frame_epsg;
  s.options.unknown_depth_is_obstacle = unknown != 0;
  std::string wkb;
  if (!r.Str(&wkb)) return corrupt("geometry");
  GeosContext c;
  GEOSWKBReader* reader = GEOSWKBReader_create_r(c.get());
  GeomPtr g =
      Own(c, GEOSWKBReader_read_r(c.get(), reader,
                                  reinterpret_cast<const unsigned char*>(wkb.data()), wkb.size()));
  GEOSWKBReader_destroy_r(c.get(), reader);
  if (!g) return corrupt(absl::StrCat("WKB: ", c.TakeError()));
  std::string unbuffered_wkb;
  if (!r.AtEnd() && !r.Str(&unbuffered_wkb)) return corrupt("unbuffered geometry");
  return internal::FinishObstacleMap(c, std::move(g), *frame, std::move(s),
                                     std::move(unbuffered_wkb));
}

}  // namespace seaplan::chart
