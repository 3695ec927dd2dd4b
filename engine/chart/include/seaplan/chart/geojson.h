// GeoJSON (RFC 7946, WGS84 lon/lat) export of obstacles and routes, for the
// CLI's --geojson and for looking at results in any GIS viewer.
#pragma once

#include <string>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"

namespace seaplan::chart {

struct NamedRoute {
  std::string name;
  std::vector<EastNorth> waypoints;  // local frame of the map
};

// A FeatureCollection: one Polygon feature per obstacle polygon
// (properties: kind "obstacle", index) and one LineString per route
// (properties: kind "route", name). Coordinates rounded to 1e-7 degrees.
std::string ToGeoJson(const ObstacleMap& map, const std::vector<NamedRoute>& routes = {});

}  // namespace seaplan::chart
