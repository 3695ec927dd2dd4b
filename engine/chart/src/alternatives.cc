// Algorithm A1 (Level-1 alternatives) and its visibility-graph fallback.
#include "seaplan/chart/alternatives.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <queue>
#include <utility>
#include <vector>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "absl/strings/str_join.h"
#include "geos_internal.h"
#include "seaplan/chart/geodesy.h"
#include "seaplan/common/log.h"

namespace seaplan::chart {
namespace {

using internal::GeomPtr;
using internal::GeosContext;
using internal::Own;

double Dist(EastNorth a, EastNorth b) {
  return std::hypot(b.east_m - a.east_m, b.north_m - a.north_m);
}
double Cross(EastNorth o, EastNorth a, EastNorth b) {
  return (a.east_m - o.east_m) * (b.north_m - o.north_m) -
         (a.north_m - o.north_m) * (b.east_m - o.east_m);
}
double PolylineLength(const std::vector<EastNorth>& pts) {
  double len = 0.0;
  for (size_t i = 1; i < pts.size(); ++i) len += Dist(pts[i - 1], pts[i]);
  return len;
}
// Positions in messages: latitude and longitude, as the user gave them
// (the local frame is internal).
std::string Where(const ObstacleMap& map, EastNorth p) {
  return FormatLatLon(map.frame().ToLatLon(p));
}

struct PreparedDeleter {
  GEOSContextHandle_t ctx;
  void operator()(const GEOSPreparedGeometry* p) const {
    if (p != nullptr) GEOSPreparedGeom_destroy_r(ctx, p);
  }
};
using PreparedPtr = std::unique_ptr<const GEOSPreparedGeometry, PreparedDeleter>;

PreparedPtr Prepare(const GeosContext& c, const GEOSGeometry* g) {
  return PreparedPtr(g != nullptr ? GEOSPrepare_r(c.get(), g) : nullptr, PreparedDeleter{c.get()});
}

bool SegmentHitsPrepared(const GeosContext& c, const GEOSPreparedGeometry* p, EastNorth a,
                         EastNorth b) {
  if (p == nullptr) return false;
  const EastNorth pts[2] = {a, b};
  GeomPtr line = a == b ? internal::MakePoint(c, a) : internal::MakeLine(c, pts, 2);
  return GEOSPreparedIntersects_r(c.get(), p, line.get()) == 1;
}

bool PointInPrepared(const GeosContext& c, const GEOSPreparedGeometry* p, EastNorth a) {
  if (p == nullptr) return false;
  GeomPtr pt = internal::MakePoint(c, a);
  return GEOSPreparedIntersects_r(c.get(), p, pt.get()) == 1;
}

// One hull of K with what A1 needs about it.
struct Hull {
  GeomPtr shape;   // the dilated convex hull
  GeomPtr shrunk;  // shape shrunk by a hair: touching its boundary is not a crossing
  PreparedPtr prepared_shrunk;
  std::vector<EastNorth> vertices;
  double area = 0.0;
};

// K <- convex hulls of the unions of overlapping dilated hulls, until no two overlap.
StatusOr<std::vector<Hull>> BuildHulls(const GeosContext& c, const std::vector<GeomPtr>& obstacles,
                                       double margin_m) {
  std::vector<GeomPtr> dilated;
  dilated.reserve(obstacles.size());
  for (const GeomPtr& o : obstacles) {
    GeomPtr hull = Own(c, GEOSConvexHull_r(c.get(), o.get()));
    if (!hull) continue;
    // Mitred joins: a dilated convex hull keeps one vertex per corner, so
    // A1's waypoints are real corners, not steps along a rounded arc (the
    // mitre limit 2 bevels very sharp corners).
    GeomPtr d = margin_m > 0
                    ? Own(c, GEOSBufferWithStyle_r(c.get(), hull.get(), margin_m, 4,
                                                   GEOSBUF_CAP_ROUND, GEOSBUF_JOIN_MITRE, 2.0))
                    : std::move(hull);
    if (d) dilated.push_back(std::move(d));
  }
  std::vector<GeomPtr> current = std::move(dilated);
  for (int iter = 0; iter < 64; ++iter) {
    const size_t before = current.size();
    GeomPtr all = internal::MakeCollection(c, GEOS_GEOMETRYCOLLECTION, std::move(current));
    GeomPtr unioned = Own(c, GEOSUnaryUnion_r(c.get(), all.get()));
    if (!unioned)
      return absl::InternalError(absl::StrCat("A1: union of hulls failed: ", c.TakeError()));
    std::vector<GeomPtr> parts = internal::PolygonParts(c, unioned.get());
    current.clear();
    for (GeomPtr& p : parts) {
      GeomPtr h = Own(c, GEOSConvexHull_r(c.get(), p.get()));
      if (h) current.push_back(std::move(h));
    }
    if (current.size() == before && iter > 0) break;
  }
  std::vector<Hull> hulls;
  for (GeomPtr& g : current) {
    Hull h;
    std::vector<Polygon> plain;
    internal::ExportPolygons(c, g.get(), &plain);
    if (plain.empty()) continue;
    h.vertices = plain[0].outer;
    h.area = internal::PolygonArea(plain[0]);
    const double eps = std::max(0.01, 1e-4 * std::sqrt(h.area));
    h.shrunk = Own(c, GEOSBuffer_r(c.get(), g.get(), -eps, 2));
    h.shape = std::move(g);
    h.prepared_shrunk = Prepare(c, h.shrunk.get());
    hulls.push_back(std::move(h));
  }
  return hulls;
}

struct Partial {
  std::vector<EastNorth> pts;
  std::vector<std::pair<int, int>> sides;  // (hull, +1 left / -1 right) already chosen
  int depth = 0;
};

struct A1Outcome {
  std::vector<std::vector<EastNorth>> routes;
  std::string failure;  // non-empty when A1 is not applicable
  bool limit_hit = false;
  bool stopped = false;
};

A1Outcome RunA1(const GeosContext& c, const std::vector<Hull>& hulls, EastNorth start,
                EastNorth goal, const AlternativesOptions& options) {
  A1Outcome out;
  for (size_t i = 0; i < hulls.size(); ++i) {
    if (PointInPrepared(c, hulls[i].prepared_shrunk.get(), start)) {
      out.failure = absl::StrCat("the start lies inside obstacle hull ", i);
      return out;
    }
    if (PointInPrepared(c, hulls[i].prepared_shrunk.get(), goal)) {
      out.failure = absl::StrCat("the goal lies inside obstacle hull ", i);
      return out;
    }
  }
  std::vector<Partial> stack;
  stack.push_back({{start, goal}, {}, 0});
  int expansions = 0;
  constexpr int kMaxExpansions = 4000;
  while (!stack.empty()) {
    if (options.stop.StopRequested()) {
      out.stopped = true;
      break;
    }
    if (static_cast<int>(out.routes.size()) >= options.max_alternatives ||
        ++expansions > kMaxExpansions) {
      out.limit_hit = true;
      break;
    }
    Partial p = std::move(stack.back());
    stack.pop_back();
    // First segment that crosses a hull; the largest crossing hull.
    int seg = -1, hull = -1;
    for (size_t k = 0; k + 1 < p.pts.size() && seg < 0; ++k) {
      for (size_t i = 0; i < hulls.size(); ++i) {
        if (SegmentHitsPrepared(c, hulls[i].prepared_shrunk.get(), p.pts[k], p.pts[k + 1]) &&
            (hull < 0 || hulls[i].area > hulls[hull].area)) {
          hull = static_cast<int>(i);
          seg = static_cast<int>(k);
        }
      }
    }
    if (seg < 0) {
      out.routes.push_back(std::move(p.pts));
      continue;
    }
    if (p.depth >= options.max_depth) {
      out.limit_hit = true;
      continue;
    }
    const EastNorth from = p.pts[seg];
    const EastNorth to = p.pts[seg + 1];
    const double len = std::max(Dist(from, to), 1e-9);
    EastNorth best[2];
    double best_d[2] = {-1.0, -1.0};
    for (const EastNorth& v : hulls[hull].vertices) {
      if (Dist(v, from) < 1.0) continue;
      if (SegmentHitsPrepared(c, hulls[hull].prepared_shrunk.get(), from, v))
        continue;  // not visible
      const double cr = Cross(from, to, v);
      const int side = cr > 0 ? 0 : 1;
      const double d = std::abs(cr) / len;
      if (d > best_d[side]) {
        best_d[side] = d;
        best[side] = v;
      }
    }
    int forced = 0;
    for (const auto& [h, s] : p.sides) {
      if (h == hull) forced = s;
    }
    for (int side = 1; side >= 0; --side) {  // push right first: left pops first
      const int sign = side == 0 ? +1 : -1;
      if (best_d[side] < 0 || (forced != 0 && forced != sign)) continue;
      if (std::find(p.pts.begin(), p.pts.end(), best[side]) != p.pts.end()) continue;  // would loop
      Partial next;
      next.pts = p.pts;
      next.pts.insert(next.pts.begin() + seg + 1, best[side]);
      next.sides = p.sides;
      if (forced == 0) next.sides.emplace_back(hull, sign);
      next.depth = p.depth + 1;
      stack.push_back(std::move(next));
    }
  }
  return out;
}

// Obstacle polygons of the map as GEOS geometries, optionally clipped to a box.
std::vector<GeomPtr> MapGeometries(const GeosContext& c, const ObstacleMap& map,
                                   const LocalBox* clip) {
  std::vector<GeomPtr> out;
  const auto& polygons = map.polygons();
  for (const Polygon& p : polygons) {
    GeomPtr g = internal::MakePolygon(c, p);
    if (!g) continue;
    if (clip != nullptr) {
      double minx = 0, miny = 0, maxx = 0, maxy = 0;
      GEOSGeom_getXMin_r(c.get(), g.get(), &minx);
      GEOSGeom_getYMin_r(c.get(), g.get(), &miny);
      GEOSGeom_getXMax_r(c.get(), g.get(), &maxx);
      GEOSGeom_getYMax_r(c.get(), g.get(), &maxy);
      if (maxx < clip->min.east_m || minx > clip->max.east_m || maxy < clip->min.north_m ||
          miny > clip->max.north_m)
        continue;
      if (minx < clip->min.east_m || miny < clip->min.north_m || maxx > clip->max.east_m ||
          maxy > clip->max.north_m) {
        g = Own(c, GEOSClipByRect_r(c.get(), g.get(), clip->min.east_m, clip->min.north_m,
                                    clip->max.east_m, clip->max.north_m));
        if (!g || GEOSisEmpty_r(c.get(), g.get()) == 1) continue;
      }
    }
    for (GeomPtr& part : internal::PolygonParts(c, g.get())) out.push_back(std::move(part));
  }
  return out;
}

LocalBox Corridor(EastNorth a, EastNorth b, double grow) {
  return {{std::min(a.east_m, b.east_m) - grow, std::min(a.north_m, b.north_m) - grow},
          {std::max(a.east_m, b.east_m) + grow, std::max(a.north_m, b.north_m) + grow}};
}

// Shortest path in the visibility graph of the obstacles dilated by the
// margin, restricted to `box`. Returns an empty path when none exists in box.
absl::Status StopStatus(const StopToken& stop, const char* where) {
  return stop.Reason() == StopReason::kCancelled
             ? absl::CancelledError(absl::StrCat("route alternatives cancelled during ", where))
             : absl::DeadlineExceededError(
                   absl::StrCat("route alternatives: deadline reached during ", where));
}

StatusOr<std::vector<EastNorth>> VisibilityPath(const GeosContext& c, const ObstacleMap& map,
                                                EastNorth start, EastNorth goal, double margin_m,
                                                const LocalBox& box, int max_nodes,
                                                const StopToken& stop,
                                                const GEOSGeometry* extra_obstacle = nullptr) {
  const auto t_build = std::chrono::steady_clock::now();
  const double tol = 0.2 * margin_m;
  // Obstacles near the box (a margin wider, so dilation near the edge is right).
  const LocalBox wide{{box.min.east_m - 2 * margin_m, box.min.north_m - 2 * margin_m},
                      {box.max.east_m + 2 * margin_m, box.max.north_m + 2 * margin_m}};
  std::vector<GeomPtr> raw = MapGeometries(c, map, &wide);
  if (extra_obstacle != nullptr) raw.push_back(Own(c, GEOSGeom_clone_r(c.get(), extra_obstacle)));
  GeomPtr raw_all = internal::MakeCollection(c, GEOS_GEOMETRYCOLLECTION, std::move(raw));
  // Test geometry: a segment is visible when it misses the obstacles dilated by
  // slightly less than the margin the nodes sit at (see below).
  GeomPtr test = Own(c, GEOSBuffer_r(c.get(), raw_all.get(), 0.98 * (margin_m - tol), 4));
  GeomPtr dilated = Own(c, GEOSBuffer_r(c.get(), raw_all.get(), margin_m, 4));
  if (!test || !dilated)
    return absl::InternalError(absl::StrCat("visibility graph: buffer failed: ", c.TakeError()));
  // Douglas-Peucker keeps original vertices (on the dilated outline, margin_m
  // from the obstacles); edges between them stay within tol of the outline.
  GeomPtr simple = Own(c, GEOSTopologyPreserveSimplify_r(c.get(), dilated.get(), tol));
  if (simple) dilated = std::move(simple);
  PreparedPtr test_prepared = Prepare(c, test.get());
  PreparedPtr raw_prepared = Prepare(c, raw_all.get());

  const auto t_nodes = std::chrono::steady_clock::now();
  std::vector<EastNorth> nodes = {start, goal};
  // Ring neighbours of each obstacle vertex node (start/goal: none).
  std::vector<std::pair<EastNorth, EastNorth>> around = {{start, start}, {goal, goal}};
  std::vector<Polygon> plain;
  internal::ExportPolygons(c, dilated.get(), &plain);
  for (const Polygon& p : plain) {
    auto add_ring = [&](const Ring& ring, bool outer) {
      const double area = internal::RingSignedArea(ring);
      // Orient so the obstacle lies on the left: outer CCW, holes CW.
      const bool reversed = outer ? area < 0 : area > 0;
      const size_t n = ring.size();
      for (size_t i = 0; i < n; ++i) {
        EastNorth prev = ring[(i + n - 1) % n], cur = ring[i], next = ring[(i + 1) % n];
        if (reversed) std::swap(prev, next);
        if (Cross(prev, cur, next) <= 0) continue;  // reflex: never on a shortest path
        if (!box.Contains(cur)) continue;
        nodes.push_back(cur);
        around.emplace_back(prev, next);
      }
    };
    add_ring(p.outer, true);
    for (const Ring& h : p.holes) add_ring(h, false);
  }
  if (static_cast<int>(nodes.size()) > max_nodes) {
    return absl::ResourceExhaustedError(
        absl::StrCat("visibility graph needs ", nodes.size(), " nodes (limit ", max_nodes, ")"));
  }
  // Nodes inside the test geometry (clipping artefacts) are dropped.
  std::vector<char> usable(nodes.size(), 1);
  for (size_t i = 2; i < nodes.size(); ++i)
    usable[i] = !PointInPrepared(c, test_prepared.get(), nodes[i]);
  // Start/goal closer than the margin to an obstacle: their own segments are
  // checked against the obstacles themselves (they already carry the chart's
  // safety buffer) instead of the dilated ones.
  const bool start_close = PointInPrepared(c, test_prepared.get(), start);
  const bool goal_close = PointInPrepared(c, test_prepared.get(), goal);
  // Reduced visibility graph (Lozano-Perez & Wesley): a shortest path only
  // uses edges tangent to the obstacle at both ends, i.e. both ring
  // neighbours of a vertex lie on one side of the edge's line. This O(1)
  // filter removes most candidate edges before the GEOS test.
  auto tangent = [&](size_t u, size_t v) {
    if (u < 2) return true;
    const double s1 = Cross(nodes[u], nodes[v], around[u].first);
    const double s2 = Cross(nodes[u], nodes[v], around[u].second);
    return s1 * s2 >= 0.0;
  };
  long tests = 0;
  auto visible = [&](size_t u, size_t v) {
    if (!tangent(u, v) || !tangent(v, u)) return false;
    ++tests;
    const bool endpoint_close =
        ((u == 0 || v == 0) && start_close) || ((u == 1 || v == 1) && goal_close);
    return !SegmentHitsPrepared(c, endpoint_close ? raw_prepared.get() : test_prepared.get(),
                                nodes[u], nodes[v]);
  };
  // A* with lazy visibility: an edge is tested only when it would improve.
  const size_t n = nodes.size();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> g(n, inf);
  std::vector<int> parent(n, -1);
  std::vector<char> closed(n, 0);
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> open;
  g[0] = 0.0;
  open.push({Dist(start, goal), 0});
  while (!open.empty()) {
    const auto [f, u] = open.top();
    open.pop();
    if (closed[u]) continue;
    if (stop.StopRequested()) return StopStatus(stop, "the visibility-graph search");
    closed[u] = 1;
    if (u == 1) break;
    for (size_t v = 1; v < n; ++v) {
      if (closed[v] || !usable[v]) continue;
      const double nd = g[u] + Dist(nodes[u], nodes[v]);
      if (nd >= g[v] || nd + Dist(nodes[v], goal) >= g[1]) continue;
      if (!visible(static_cast<size_t>(u), v)) continue;
      g[v] = nd;
      parent[v] = u;
      open.push({nd + Dist(nodes[v], goal), static_cast<int>(v)});
    }
  }
  log::Debug("visibility graph: {} nodes, {} visibility tests; build {:.0f} ms, search {:.0f} ms",
             n, tests, std::chrono::duration<double, std::milli>(t_nodes - t_build).count(),
             std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t_nodes)
                 .count());
  std::vector<EastNorth> path;
  if (!std::isfinite(g[1])) return path;
  for (int v = 1; v >= 0; v = parent[v]) path.push_back(nodes[v]);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace

absl::Status AlternativesOptions::Validate() const {
  if (!std::isfinite(margin_m) || margin_m < 0 || margin_m > 10000) {
    return absl::InvalidArgumentError(
        absl::StrCat("margin_m must be in [0, 10000], got ", margin_m));
  }
  if (max_depth < 1 || max_depth > 64) {
    return absl::InvalidArgumentError(
        absl::StrCat("max_depth must be in [1, 64], got ", max_depth));
  }
  if (max_alternatives < 1 || max_alternatives > 1024) {
    return absl::InvalidArgumentError(
        absl::StrCat("max_alternatives must be in [1, 1024], got ", max_alternatives));
  }
  if (max_graph_nodes < 16) {
    return absl::InvalidArgumentError(
        absl::StrCat("max_graph_nodes must be >= 16, got ", max_graph_nodes));
  }
  return absl::OkStatus();
}

StatusOr<AlternativesResult> PlanAlternatives(const ObstacleMap& map, EastNorth start,
                                              EastNorth goal, const AlternativesOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  for (const auto& [name, p] : {std::pair{"start", start}, std::pair{"goal", goal}}) {
    if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) {
      return absl::InvalidArgumentError(absl::StrCat(name, " has a non-finite coordinate"));
    }
    if (!map.Covers(p)) {
      const LocalBox& b = map.summary().coverage;
      return absl::InvalidArgumentError(absl::StrCat(name, " ", Where(map, p),
                                                     " lies outside the chart coverage ",
                                                     Where(map, b.min), " to ", Where(map, b.max)));
    }
  }
  ObstacleQuery query(map);
  for (const auto& [name, p] : {std::pair{"start", start}, std::pair{"goal", goal}}) {
    if (query.Inside(p)) {
      const NearestObstacle n = query.Nearest(p);
      return absl::InvalidArgumentError(
          absl::StrCat(name, " ", Where(map, p), " lies inside obstacle ", n.polygon_index,
                       " (land, shallow water or a hazard with its safety buffer; ",
                       absl::StrFormat("%.0f", -query.SignedDistanceM(p)), " m from its edge)"));
    }
  }
  AlternativesResult result;
  GeosContext c;
  auto finish = [&](std::vector<std::vector<EastNorth>> routes) {
    std::sort(routes.begin(), routes.end(),
              [](const auto& a, const auto& b) { return PolylineLength(a) < PolylineLength(b); });
    for (auto& r : routes) {
      if (query.PolylineHits(r)) continue;  // never hand out a route through an obstacle
      // Nor one that leaves the chart: beyond its coverage nothing is known.
      if (!std::all_of(r.begin(), r.end(), [&](EastNorth p) { return map.Covers(p); })) continue;
      bool dup = false;
      for (const Alternative& a : result.alternatives) dup = dup || a.waypoints == r;
      if (dup) continue;
      Alternative a;
      a.length_m = PolylineLength(r);
      a.waypoints = std::move(r);
      result.alternatives.push_back(std::move(a));
      if (static_cast<int>(result.alternatives.size()) >= options.max_alternatives) break;
    }
  };

  // 1) A1 on every obstacle of the chart (the paper's version).
  std::vector<std::string> notes;
  {
    std::vector<GeomPtr> obstacles = MapGeometries(c, map, nullptr);
    SEAPLAN_ASSIGN_OR_RETURN(std::vector<Hull> hulls, BuildHulls(c, obstacles, options.margin_m));
    A1Outcome a1 = RunA1(c, hulls, start, goal, options);
    if (a1.stopped) return StopStatus(options.stop, "A1");
    if (a1.failure.empty()) {
      finish(std::move(a1.routes));
      if (a1.limit_hit) notes.push_back("A1 recursion limit reached");
    } else {
      notes.push_back(absl::StrCat("A1 on whole-chart hulls: ", a1.failure));
    }
  }
  // 2) A1 on the obstacles clipped to a corridor around start-goal: hulls of
  //    the local pieces of a large concave coast rarely swallow start/goal.
  if (result.alternatives.empty()) {
    const double length = Dist(start, goal);
    for (double factor : {0.15, 0.35}) {
      const LocalBox box = Corridor(start, goal, std::max(4.0 * options.margin_m, factor * length));
      std::vector<GeomPtr> obstacles = MapGeometries(c, map, &box);
      SEAPLAN_ASSIGN_OR_RETURN(std::vector<Hull> hulls, BuildHulls(c, obstacles, options.margin_m));
      A1Outcome a1 = RunA1(c, hulls, start, goal, options);
      if (a1.stopped) return StopStatus(options.stop, "A1");
      if (!a1.failure.empty()) {
        notes.push_back(absl::StrCat("A1 in corridor x", factor, ": ", a1.failure));
        continue;
      }
      finish(std::move(a1.routes));
      if (!result.alternatives.empty()) {
        notes.push_back(
            absl::StrCat("A1 on obstacles clipped to a corridor (", factor, " x length)"));
        break;
      }
      notes.push_back(absl::StrCat("A1 in corridor x", factor, ": no route free of obstacles"));
    }
  }
  // 3) Visibility-graph shortest path.
  if (result.alternatives.empty() && options.allow_fallback) {
    result.used_fallback = true;
    const double margin = std::max(options.margin_m, 1.0);
    const LocalBox& cov = map.summary().coverage;
    const double cov_size =
        std::max(cov.max.east_m - cov.min.east_m, cov.max.north_m - cov.min.north_m);
    auto shortest = [&](const GEOSGeometry* wall) -> StatusOr<std::vector<EastNorth>> {
      double grow = std::max(1000.0, 0.25 * Dist(start, goal));
      std::vector<EastNorth> path;
      while (true) {
        const LocalBox box = Corridor(start, goal, grow);
        SEAPLAN_ASSIGN_OR_RETURN(path, VisibilityPath(c, map, start, goal, margin, box,
                                                      options.max_graph_nodes, options.stop, wall));
        if (!path.empty() || grow > cov_size) break;
        grow *= 2.0;
      }
      return path;
    };
    SEAPLAN_ASSIGN_OR_RETURN(std::vector<EastNorth> path, shortest(nullptr));
    if (path.empty()) {
      return absl::NotFoundError(absl::StrCat("no obstacle-free route from ", Where(map, start),
                                              " to ", Where(map, goal), " (",
                                              absl::StrJoin(notes, "; "), ")"));
    }
    std::vector<std::vector<EastNorth>> routes = {path};
    // A second alternative in A1's spirit: around the other side of the
    // obstacle that blocks the straight line most. A thin wall from inside
    // that obstacle, across the first route's side, to beyond the chart
    // closes that side; the shortest path that remains goes the other way.
    int second = 0;
    if (options.max_alternatives > 1) {
      const EastNorth line[2] = {start, goal};
      GeomPtr straight = internal::MakeLine(c, line, 2);
      double best_len = 0.0;
      EastNorth mid{};
      for (const GeomPtr& o : MapGeometries(c, map, nullptr)) {
        GeomPtr cut = Own(c, GEOSIntersection_r(c.get(), o.get(), straight.get()));
        if (!cut) continue;
        // The longest single piece of the line inside this obstacle.
        for (int k = 0; k < std::max(1, GEOSGetNumGeometries_r(c.get(), cut.get())); ++k) {
          const GEOSGeometry* piece = GEOSGetNumGeometries_r(c.get(), cut.get()) > 0
                                          ? GEOSGetGeometryN_r(c.get(), cut.get(), k)
                                          : cut.get();
          double len = 0.0;
          if (GEOSLength_r(c.get(), piece, &len) != 1 || len <= best_len) continue;
          GeomPtr centre = Own(c, GEOSInterpolateNormalized_r(c.get(), piece, 0.5));
          if (!centre) continue;
          best_len = len;
          GEOSGeomGetX_r(c.get(), centre.get(), &mid.east_m);
          GEOSGeomGetY_r(c.get(), centre.get(), &mid.north_m);
        }
      }
      double side = 0.0;
      for (const EastNorth& p : path) side += Cross(start, goal, p);
      if (best_len > 0.0 && side != 0.0) {
        const double len = std::max(Dist(start, goal), 1e-9);
        const double nx = -(goal.north_m - start.north_m) / len * (side > 0 ? 1 : -1);
        const double ny = (goal.east_m - start.east_m) / len * (side > 0 ? 1 : -1);
        const double reach = 2.0 * cov_size + Dist(start, goal);
        const double w = 1.0;            // half width, m
        const double ux = ny, uy = -nx;  // along the line
        const EastNorth far{mid.east_m + nx * reach, mid.north_m + ny * reach};
        const EastNorth wall_ring[4] = {{mid.east_m - ux * w, mid.north_m - uy * w},
                                        {mid.east_m + ux * w, mid.north_m + uy * w},
                                        {far.east_m + ux * w, far.north_m + uy * w},
                                        {far.east_m - ux * w, far.north_m - uy * w}};
        GeomPtr wall = internal::MakeRingPolygon(c, wall_ring, 4);
        auto other = shortest(wall.get());
        if (!other.ok() &&
            (absl::IsDeadlineExceeded(other.status()) || absl::IsCancelled(other.status()))) {
          return other.status();
        }
        // A detour more than kMaxDetour times the shortest route is no
        // useful alternative for Level 2 (and on charts whose layers leave
        // unmapped gaps it may run through water nobody charted).
        constexpr double kMaxDetour = 3.0;
        if (other.ok() && !other->empty() &&
            PolylineLength(*other) <= kMaxDetour * PolylineLength(path)) {
          routes.push_back(std::move(other).value());
          second = 1;
        }
      }
    }
    notes.push_back(
        second
            ? "visibility-graph fallback (shortest route + one around the other side of the main "
              "obstacle)"
            : "visibility-graph fallback (one route)");
    finish(std::move(routes));
  }
  result.note = absl::StrJoin(notes, "; ");
  if (result.alternatives.empty()) {
    return absl::NotFoundError(absl::StrCat("no obstacle-free alternative from ", Where(map, start),
                                            " to ", Where(map, goal), " (", result.note, ")"));
  }
  log::Debug("A1: {} alternative(s), fallback={}, {}", result.alternatives.size(),
             result.used_fallback, result.note);
  return result;
}

}  // namespace seaplan::chart
