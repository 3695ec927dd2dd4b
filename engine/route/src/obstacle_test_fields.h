// Small obstacle fields for the route library's unit tests.
#pragma once

#include <gtest/gtest.h>

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

}  // namespace seaplan::route::test_fields
