#include "seaplan/chart/geojson.h"

#include <cstdio>
#include <string>

#include "absl/strings/str_cat.h"
#include "seaplan/common/json.h"

namespace seaplan::chart {
namespace {

void AppendCoord(const LocalFrame& frame, EastNorth p, std::string* out) {
  const LatLon ll = frame.ToLatLon(p);
  char buf[64];
  std::snprintf(buf, sizeof(buf), "[%.7f,%.7f]", ll.lon_deg, ll.lat_deg);
  out->append(buf);
}

// RFC 7946: exterior rings counter-clockwise, holes clockwise, closed.
void AppendRing(const LocalFrame& frame, const Ring& ring, bool ccw, std::string* out) {
  double area2 = 0.0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const EastNorth& a = ring[i];
    const EastNorth& b = ring[(i + 1) % ring.size()];
    area2 += (a.east_m - ring[0].east_m) * (b.north_m - ring[0].north_m) -
             (b.east_m - ring[0].east_m) * (a.north_m - ring[0].north_m);
  }
  const bool reverse = (area2 > 0) != ccw;
  out->push_back('[');
  for (size_t k = 0; k <= ring.size(); ++k) {
    const size_t i = k % ring.size();
    const size_t j = reverse ? (ring.size() - i) % ring.size() : i;
    if (k > 0) out->push_back(',');
    AppendCoord(frame, ring[j], out);
  }
  out->push_back(']');
}

}  // namespace

std::string ToGeoJson(const ObstacleMap& map, const std::vector<NamedRoute>& routes) {
  const LocalFrame& frame = map.frame();
  std::string out = "{\"type\":\"FeatureCollection\",\"features\":[";
  bool first = true;
  const auto& polygons = map.polygons();
  for (size_t i = 0; i < polygons.size(); ++i) {
    if (!first) out.push_back(',');
    first = false;
    absl::StrAppend(&out,
                    "{\"type\":\"Feature\",\"properties\":{\"kind\":\"obstacle\",\"index\":", i,
                    "},\"geometry\":{\"type\":\"Polygon\",\"coordinates\":[");
    AppendRing(frame, polygons[i].outer, true, &out);
    for (const Ring& h : polygons[i].holes) {
      out.push_back(',');
      AppendRing(frame, h, false, &out);
    }
    out += "]}}";
  }
  for (const NamedRoute& r : routes) {
    if (!first) out.push_back(',');
    first = false;
    absl::StrAppend(&out, "{\"type\":\"Feature\",\"properties\":{\"kind\":\"route\",\"name\":",
                    JsonString(r.name),
                    "},\"geometry\":{\"type\":\"LineString\",\"coordinates\":[");
    for (size_t i = 0; i < r.waypoints.size(); ++i) {
      if (i > 0) out.push_back(',');
      AppendCoord(frame, r.waypoints[i], &out);
    }
    out += "]}}";
  }
  out += "]}";
  return out;
}

}  // namespace seaplan::chart
