#include "geos_internal.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace seaplan::chart::internal {
namespace {

void RecordError(const char* message, void* userdata) {
  auto* error = static_cast<std::string*>(userdata);
  *error = message != nullptr ? message : "unknown GEOS error";
}
void IgnoreNotice(const char*, void*) {}

}  // namespace

GeosContext::GeosContext() : handle_(GEOS_init_r()) {
  GEOSContext_setErrorMessageHandler_r(handle_, &RecordError, &error_);
  GEOSContext_setNoticeMessageHandler_r(handle_, &IgnoreNotice, nullptr);
}

GeosContext::~GeosContext() {
  GEOS_finish_r(handle_);
}

std::string GeosContext::TakeError() const {
  std::string e;
  e.swap(error_);
  return e;
}

GeomPtr MakePoint(const GeosContext& c, EastNorth p) {
  return Own(c, GEOSGeom_createPointFromXY_r(c.get(), p.east_m, p.north_m));
}

GeomPtr MakeLine(const GeosContext& c, const EastNorth* pts, size_t n) {
  if (n < 2) return Own(c, nullptr);
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(c.get(), static_cast<unsigned>(n), 2);
  for (size_t i = 0; i < n; ++i)
    GEOSCoordSeq_setXY_r(c.get(), seq, static_cast<unsigned>(i), pts[i].east_m, pts[i].north_m);
  return Own(c, GEOSGeom_createLineString_r(c.get(), seq));
}

namespace {
GEOSGeometry* RawRing(const GeosContext& c, const EastNorth* pts, size_t n) {
  // Drop a repeated closing point if the caller gave one.
  if (n >= 2 && pts[0] == pts[n - 1]) --n;
  if (n < 3) return nullptr;
  GEOSCoordSequence* seq = GEOSCoordSeq_create_r(c.get(), static_cast<unsigned>(n + 1), 2);
  for (size_t i = 0; i < n; ++i)
    GEOSCoordSeq_setXY_r(c.get(), seq, static_cast<unsigned>(i), pts[i].east_m, pts[i].north_m);
  GEOSCoordSeq_setXY_r(c.get(), seq, static_cast<unsigned>(n), pts[0].east_m, pts[0].north_m);
  return GEOSGeom_createLinearRing_r(c.get(), seq);
}
}  // namespace

GeomPtr MakeRing(const GeosContext& c, const Ring& ring) {
  return Own(c, RawRing(c, ring.data(), ring.size()));
}

GeomPtr MakeRingPolygon(const GeosContext& c, const EastNorth* pts, size_t n) {
  GEOSGeometry* shell = RawRing(c, pts, n);
  if (shell == nullptr) return Own(c, nullptr);
  return Own(c, GEOSGeom_createPolygon_r(c.get(), shell, nullptr, 0));
}

GeomPtr MakePolygon(const GeosContext& c, const Polygon& polygon) {
  GEOSGeometry* shell = RawRing(c, polygon.outer.data(), polygon.outer.size());
  if (shell == nullptr) return Own(c, nullptr);
  std::vector<GEOSGeometry*> holes;
  for (const Ring& h : polygon.holes) {
    GEOSGeometry* r = RawRing(c, h.data(), h.size());
    if (r != nullptr) holes.push_back(r);
  }
  return Own(c, GEOSGeom_createPolygon_r(c.get(), shell, holes.data(),
                                         static_cast<unsigned>(holes.size())));
}

GeomPtr MakeCollection(const GeosContext& c, int type, std::vector<GeomPtr> parts) {
  std::vector<GEOSGeometry*> raw;
  raw.reserve(parts.size());
  for (GeomPtr& p : parts) {
    if (p) raw.push_back(p.release());
  }
  return Own(
      c, GEOSGeom_createCollection_r(c.get(), type, raw.data(), static_cast<unsigned>(raw.size())));
}

GeomPtr MakeBox(const GeosContext& c, const LocalBox& box) {
  return Own(c, GEOSGeom_createRectangle_r(c.get(), box.min.east_m, box.min.north_m, box.max.east_m,
                                           box.max.north_m));
}

Ring ExportRing(const GeosContext& c, const GEOSGeometry* ring) {
  Ring out;
  const GEOSCoordSequence* seq = GEOSGeom_getCoordSeq_r(c.get(), ring);
  unsigned n = 0;
  if (seq == nullptr || GEOSCoordSeq_getSize_r(c.get(), seq, &n) == 0 || n == 0) return out;
  out.reserve(n);
  for (unsigned i = 0; i + 1 < n; ++i) {  // skip the closing point
    double x = 0, y = 0;
    GEOSCoordSeq_getXY_r(c.get(), seq, i, &x, &y);
    out.push_back({x, y});
  }
  return out;
}

void ExportPolygons(const GeosContext& c, const GEOSGeometry* g, std::vector<Polygon>* out) {
  if (g == nullptr) return;
  const int type = GEOSGeomTypeId_r(c.get(), g);
  if (type == GEOS_POLYGON) {
    if (GEOSisEmpty_r(c.get(), g) == 1) return;
    Polygon p;
    p.outer = ExportRing(c, GEOSGetExteriorRing_r(c.get(), g));
    const int holes = GEOSGetNumInteriorRings_r(c.get(), g);
    for (int i = 0; i < holes; ++i)
      p.holes.push_back(ExportRing(c, GEOSGetInteriorRingN_r(c.get(), g, i)));
    if (p.outer.size() >= 3) out->push_back(std::move(p));
    return;
  }
  if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
    const int n = GEOSGetNumGeometries_r(c.get(), g);
    for (int i = 0; i < n; ++i) ExportPolygons(c, GEOSGetGeometryN_r(c.get(), g, i), out);
  }
}

namespace {
void CollectPolygonParts(const GeosContext& c, const GEOSGeometry* g, std::vector<GeomPtr>* out) {
  const int type = GEOSGeomTypeId_r(c.get(), g);
  if (type == GEOS_POLYGON) {
    if (GEOSisEmpty_r(c.get(), g) == 0) out->push_back(Own(c, GEOSGeom_clone_r(c.get(), g)));
  } else if (type == GEOS_MULTIPOLYGON || type == GEOS_GEOMETRYCOLLECTION) {
    const int n = GEOSGetNumGeometries_r(c.get(), g);
    for (int i = 0; i < n; ++i) CollectPolygonParts(c, GEOSGetGeometryN_r(c.get(), g, i), out);
  }
}
}  // namespace

std::vector<GeomPtr> PolygonParts(const GeosContext& c, const GEOSGeometry* g) {
  std::vector<GeomPtr> out;
  if (g != nullptr) CollectPolygonParts(c, g, &out);
  return out;
}

GeomPtr MakeValidPolygonal(const GeosContext& c, GeomPtr g, bool* repaired) {
  *repaired = false;
  if (!g) return g;
  if (GEOSisValid_r(c.get(), g.get()) == 1) return g;
  *repaired = true;
  GeomPtr fixed = Own(c, GEOSMakeValid_r(c.get(), g.get()));
  if (!fixed) return fixed;
  // MakeValid may return lines/points besides the areas (collapsed parts).
  std::vector<GeomPtr> parts = PolygonParts(c, fixed.get());
  if (parts.size() == 1) return std::move(parts[0]);
  return MakeCollection(c, GEOS_MULTIPOLYGON, std::move(parts));
}

double RingSignedArea(const Ring& ring) {
  double a = 0.0;
  const size_t n = ring.size();
  for (size_t i = 0; i < n; ++i) {
    const EastNorth& p = ring[i];
    const EastNorth& q = ring[(i + 1) % n];
    // Relative to the first point to keep precision with UTM magnitudes.
    a += (p.east_m - ring[0].east_m) * (q.north_m - ring[0].north_m) -
         (q.east_m - ring[0].east_m) * (p.north_m - ring[0].north_m);
  }
  return 0.5 * a;
}

double PolygonArea(const Polygon& p) {
  double a = std::abs(RingSignedArea(p.outer));
  for (const Ring& h : p.holes) a -= std::abs(RingSignedArea(h));
  return a;
}

}  // namespace seaplan::chart::internal
