#include "seaplan/risk/grounding_test.h"

#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"

namespace seaplan::risk {
namespace {

using Vec = Eigen::Vector2d;

double Cross(const Vec& a, const Vec& b, const Vec& c) {
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

bool OnSegment(const Vec& a, const Vec& b, const Vec& p) {
  return std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
         std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]);
}

// Closed segments [a,b] and [c,d] share a point (touching counts).
bool SegmentsIntersect(const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
  const double d1 = Cross(c, d, a), d2 = Cross(c, d, b);
  const double d3 = Cross(a, b, c), d4 = Cross(a, b, d);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  if (d1 == 0 && OnSegment(c, d, a)) return true;
  if (d2 == 0 && OnSegment(c, d, b)) return true;
  if (d3 == 0 && OnSegment(a, b, c)) return true;
  if (d4 == 0 && OnSegment(a, b, d)) return true;
  return false;
}

double PointSegmentDistance(const Vec& p, const Vec& a, const Vec& b) {
  const Vec ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double SegmentDistance(const Vec& a, const Vec& b, const Vec& c, const Vec& d) {
  if (SegmentsIntersect(a, b, c, d)) return 0.0;
  return std::min({PointSegmentDistance(a, c, d), PointSegmentDistance(b, c, d),
                   PointSegmentDistance(c, a, b), PointSegmentDistance(d, a, b)});
}

// Crossing-number point-in-polygon (boundary cases are caught by the edge test).
bool PointInPolygon(const Vec& p, const std::vector<Vec>& v) {
  bool inside = false;
  const size_t n = v.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    if ((v[i][1] > p[1]) != (v[j][1] > p[1])) {
      const double x = v[j][0] + (p[1] - v[j][1]) * (v[i][0] - v[j][0]) / (v[i][1] - v[j][1]);
      if (p[0] < x) inside = !inside;
    }
  }
  return inside;
}

// Point strictly inside the convex hull rectangle (corners in order).
bool PointInConvexQuad(const Vec& p, const std::array<Vec, 4>& q) {
  bool pos = false, neg = false;
  for (int i = 0; i < 4; ++i) {
    const double c = Cross(q[i], q[(i + 1) % 4], p);
    pos |= c > 0;
    neg |= c < 0;
  }
  return !(pos && neg);
}

}  // namespace

HullPolygon HullPolygon::Rectangle(double north, double east, double psi, double length,
                                   double beam) {
  return Rectangle(north, east, std::cos(psi), std::sin(psi), length, beam);
}

HullPolygon HullPolygon::Rectangle(double north, double east, double c, double s, double length,
                                   double beam) {
  const double hl = 0.5 * length, hb = 0.5 * beam;
  // Body (x fwd, y stbd) -> NE: N = x c - y s, E = x s + y c.
  const std::array<std::pair<double, double>, 4> body = {
      {{hl, -hb}, {hl, hb}, {-hl, hb}, {-hl, -hb}}};
  HullPolygon h;
  for (int i = 0; i < 4; ++i) {
    const auto [x, y] = body[i];
    h.corners_ne[i] = {north + x * c - y * s, east + x * s + y * c};
    h.bounds.Extend(h.corners_ne[i]);
  }
  return h;
}

StatusOr<PolygonObstacles> PolygonObstacles::Create(std::vector<std::vector<Vec>> polygons) {
  std::vector<Polygon> out;
  out.reserve(polygons.size());
  for (size_t i = 0; i < polygons.size(); ++i) {
    std::vector<Vec>& v = polygons[i];
    if (v.size() >= 2 && v.front() == v.back()) v.pop_back();
    if (v.size() < 3) {
      return absl::InvalidArgumentError(absl::StrCat("PolygonObstacles: polygon ", i, " has ",
                                                     v.size(), " distinct vertices (< 3)"));
    }
    Polygon p;
    for (size_t k = 0; k < v.size(); ++k) {
      if (!v[k].allFinite()) {
        return absl::InvalidArgumentError(
            absl::StrCat("PolygonObstacles: polygon ", i, " vertex ", k, " is not finite"));
      }
      p.bounds.Extend(v[k]);
    }
    p.vertices = std::move(v);
    out.push_back(std::move(p));
  }
  return PolygonObstacles(std::move(out));
}

bool PolygonObstacles::Intersects(const Polygon& poly, const HullPolygon& hull) const {
  const std::vector<Vec>& v = poly.vertices;
  const size_t n = v.size();
  for (size_t i = 0, j = n - 1; i < n; j = i++) {
    // Edge bounding box against the hull's box first: most edges of a long
    // coastline are far from the hull.
    BoxNE eb;
    eb.Extend(v[j]);
    eb.Extend(v[i]);
    if (!eb.Overlaps(hull.bounds)) continue;
    for (int k = 0; k < 4; ++k) {
      if (SegmentsIntersect(hull.corners_ne[k], hull.corners_ne[(k + 1) % 4], v[j], v[i]))
        return true;
    }
  }
  // No edge crossing: either disjoint or one contains the other.
  return PointInPolygon(hull.corners_ne[0], v) || PointInConvexQuad(v[0], hull.corners_ne);
}

bool PolygonObstacles::HullIntersects(const HullPolygon& hull) const {
  for (const Polygon& p : polygons_) {
    if (p.bounds.Overlaps(hull.bounds) && Intersects(p, hull)) return true;
  }
  return false;
}

double PolygonObstacles::Clearance(const HullPolygon& hull) const {
  double best = HUGE_VAL;
  for (const Polygon& p : polygons_) {
    if (p.bounds.Overlaps(hull.bounds) && Intersects(p, hull)) return 0.0;
    const std::vector<Vec>& v = p.vertices;
    for (size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
      for (int k = 0; k < 4; ++k) {
        best = std::min(
            best, SegmentDistance(hull.corners_ne[k], hull.corners_ne[(k + 1) % 4], v[j], v[i]));
      }
    }
  }
  return best;
}

}  // namespace seaplan::risk
