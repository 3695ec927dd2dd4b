// Small obstacle fields for the route library's unit tests, and a measure
// of how far a sailed track strays from its route.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "seaplan/route/obstacle_field.h"

namespace seaplan::route::test_fields {

// A field over the 6 km square centred on the origin, 50 m cells.
inline ObstacleField Field(std::vector<ObstaclePolygon> obstacles) {
  ObstacleFieldOptions fo;
  fo.cell_m = 50.0;
  auto field = ObstacleField::Build(std::move(obstacles), {-3000, -3000}, {3000, 3000}, fo);
  EXPECT_TRUE(field.ok()) << field.status();
  return std::move(field).value();
}

// The axis-aligned rectangle [x0, x1] x [y0, y1].
inline ObstaclePolygon Rect(double x0, double y0, double x1, double y1) {
  return ObstaclePolygon{{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}};
}

// The point of `track` farthest from the polyline `route`, and how far.
inline std::pair<EastNorth, double> WidestSwing(const std::vector<EastNorth>& route,
                                                const std::vector<EastNorth>& track) {
  EastNorth widest;
  double widest_m = 0.0;
  for (const EastNorth& p : track) {
    double d = 1e300;
    for (size_t k = 1; k < route.size(); ++k) {
      const EastNorth a = route[k - 1], ab = route[k] - a;
      const double t = std::clamp((p - a).Dot(ab) / ab.Dot(ab), 0.0, 1.0);
      d = std::min(d, Distance(p, a + ab * t));
    }
    if (d > widest_m) {
      widest_m = d;
      widest = p;
    }
  }
  return {widest, widest_m};
}

}  // namespace seaplan::route::test_fields
