// RAII helpers over the GEOS C API (geos_c.h, re-entrant *_r functions).
// Every GEOS object here belongs to one GeosContext, and a context is used by
// one thread at a time.
#pragma once

#define GEOS_USE_ONLY_R_API
#include <geos_c.h>

#include <memory>
#include <string>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"

namespace seaplan::chart::internal {

// One GEOS context handle; records the last error message instead of
// printing it.
class GeosContext {
 public:
  GeosContext();
  ~GeosContext();
  GeosContext(const GeosContext&) = delete;
  GeosContext& operator=(const GeosContext&) = delete;

  GEOSContextHandle_t get() const { return handle_; }
  // Last error GEOS reported on this context ("" if none); cleared on read.
  std::string TakeError() const;

 private:
  GEOSContextHandle_t handle_;
  mutable std::string error_;
};

struct GeomDeleter {
  GEOSContextHandle_t ctx = nullptr;
  void operator()(GEOSGeometry* g) const {
    if (g != nullptr) GEOSGeom_destroy_r(ctx, g);
  }
};
using GeomPtr = std::unique_ptr<GEOSGeometry, GeomDeleter>;

inline GeomPtr Own(const GeosContext& c, GEOSGeometry* g) {
  return GeomPtr(g, GeomDeleter{c.get()});
}

// Builders from plain data (nullptr on degenerate input).
GeomPtr MakePoint(const GeosContext& c, EastNorth p);
GeomPtr MakeLine(const GeosContext& c, const EastNorth* pts, size_t n);
GeomPtr MakeRing(const GeosContext& c, const Ring& ring);
GeomPtr MakePolygon(const GeosContext& c, const Polygon& polygon);
GeomPtr MakeRingPolygon(const GeosContext& c, const EastNorth* pts, size_t n);
// A GeometryCollection / MultiPolygon taking ownership of `parts`.
GeomPtr MakeCollection(const GeosContext& c, int type, std::vector<GeomPtr> parts);
GeomPtr MakeBox(const GeosContext& c, const LocalBox& box);

// Plain-data export: every Polygon in g (Polygon, MultiPolygon or collection).
void ExportPolygons(const GeosContext& c, const GEOSGeometry* g, std::vector<Polygon>* out);
Ring ExportRing(const GeosContext& c, const GEOSGeometry* ring);

// Repairs an invalid geometry with GEOSMakeValid and keeps its polygonal
// part. Returns nullptr on failure. `repaired` is set when a repair happened.
GeomPtr MakeValidPolygonal(const GeosContext& c, GeomPtr g, bool* repaired);

// Polygonal parts of g (in place order), cloned.
std::vector<GeomPtr> PolygonParts(const GeosContext& c, const GEOSGeometry* g);

double RingSignedArea(const Ring& ring);
double PolygonArea(const Polygon& p);

}  // namespace seaplan::chart::internal
