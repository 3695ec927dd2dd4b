// A position or displacement in a local metric frame: metres east and north.
//
// Every library that works in a flat frame uses this one type: the chart's
// UTM frame (seaplan::chart::LocalFrame), the Level-2 route optimiser's
// obstacle queries, the mission's locations and routes, the simulation
// client's encounters. Which frame (which UTM zone, or a caller's own flat
// frame) is the owner's to say; the axes are always east then north.
//
// The ship model (seaplan::ship, seaplan::risk) keeps Eigen vectors in the
// marine-dynamics order (north, east) because its matrices act on them; the
// code that crosses over names the swap (waypoints_ne, corners_ne).
#pragma once

#include <cmath>

namespace seaplan {

struct EastNorth {
  double east_m = 0.0;
  double north_m = 0.0;

  friend bool operator==(const EastNorth&, const EastNorth&) = default;
  EastNorth operator+(EastNorth o) const { return {east_m + o.east_m, north_m + o.north_m}; }
  EastNorth operator-(EastNorth o) const { return {east_m - o.east_m, north_m - o.north_m}; }
  EastNorth operator*(double s) const { return {east_m * s, north_m * s}; }
  double Dot(EastNorth o) const { return east_m * o.east_m + north_m * o.north_m; }
  // z of the 3-D cross product: positive when `o` is counter-clockwise of this.
  double Cross(EastNorth o) const { return east_m * o.north_m - north_m * o.east_m; }
  double Norm() const { return std::hypot(east_m, north_m); }
};

// Straight-line distance, metres.
inline double Distance(EastNorth a, EastNorth b) {
  return std::hypot(a.east_m - b.east_m, a.north_m - b.north_m);
}

}  // namespace seaplan
