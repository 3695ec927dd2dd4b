// Geodesy for seaplan: the only place with great-circle maths (STYLE.md) and
// the local metric frame every other library works in.
//
// The local frame is a UTM projection (WGS84 / ETRS89, which agree to well
// under a millimetre for our purposes): x = easting (m, east), y = northing
// (m, north), in the zone's own false-easting/northing, so coordinates match
// what GIS tools show for that EPSG code (e.g. the Alesund route1.csv, UTM33).
// Conversions use Karney's 6th-order Krueger series (accurate to < 1 mm
// within a few zones' width of the central meridian): they are pure functions,
// allocation-free and thread-safe, unlike an OGRCoordinateTransformation (PROJ
// contexts are per thread), which is why we do not call PROJ per point.
#pragma once

#include <string>

#include "seaplan/common/east_north.h"
#include "seaplan/common/status.h"

namespace seaplan::chart {

// Geographic position, degrees (WGS84).
struct LatLon {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
};

// "38.98000,-76.38000": latitude, longitude in degrees (5 decimals, ~1 m),
// the form the command line and the API take positions in.
std::string FormatLatLon(LatLon p);

// Mean Earth radius used by the great-circle formulas (IUGG), metres.
inline constexpr double kEarthRadiusM = 6371008.8;

// Great-circle (haversine) distance between two positions, metres.
double HaversineDistanceM(LatLon a, LatLon b);
// Initial great-circle bearing from a to b, degrees clockwise from north in [0, 360).
double InitialBearingDeg(LatLon a, LatLon b);

// A UTM frame. Copyable value; every method is const and thread-safe.
class LocalFrame {
 public:
  // The WGS84 UTM frame (EPSG 326zz north / 327zz south) of the zone that
  // contains `centre` (standard zones; no Norway/Svalbard exceptions).
  static LocalFrame ForCentre(LatLon centre);
  // A frame from an EPSG code: 326zz, 327zz (WGS84 UTM) or 258zz (ETRS89 UTM,
  // zones 28-38). Anything else is InvalidArgument.
  static StatusOr<LocalFrame> FromEpsg(int epsg);

  LocalFrame() = default;  // WGS84 UTM zone 33N (EPSG:32633).

  EastNorth ToLocal(LatLon p) const;
  LatLon ToLatLon(EastNorth p) const;

  int epsg() const { return epsg_; }
  int zone() const { return zone_; }
  bool north() const { return north_; }
  // Central meridian, degrees.
  double central_meridian_deg() const;

 private:
  LocalFrame(int epsg, int zone, bool north) : epsg_(epsg), zone_(zone), north_(north) {}
  int epsg_ = 32633;
  int zone_ = 33;
  bool north_ = true;
};

}  // namespace seaplan::chart
