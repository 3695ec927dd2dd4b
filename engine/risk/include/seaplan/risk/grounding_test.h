// The obstacle test of the drifting-grounding model, kept abstract so that
// seaplan_risk does not depend on GEOS: engine/chart implements GroundingTest
// over GEOS prepared geometries; PolygonObstacles below is a dependency-free
// implementation over plain polygons, used by the tests and benchmarks.
//
// Coordinates: the local metric NED frame of seaplan::ship (x = north,
// y = east, metres). Note that GEOS/Shapely code usually stores (east, north).
//
// Thread-safety: implementations must make both methods safe to call
// concurrently on a const object (the route optimiser evaluates particles in
// parallel); PolygonObstacles is immutable after construction.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "Eigen/Core"
#include "seaplan/common/status.h"

namespace seaplan::risk {

// Axis-aligned box in (N, E).
struct BoxNE {
  Eigen::Vector2d min = Eigen::Vector2d::Constant(HUGE_VAL);
  Eigen::Vector2d max = Eigen::Vector2d::Constant(-HUGE_VAL);
  void Extend(const Eigen::Vector2d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  bool Overlaps(const BoxNE& o) const {
    return min[0] <= o.max[0] && o.min[0] <= max[0] && min[1] <= o.max[1] && o.min[1] <= max[1];
  }
};

// The hull outline: a rectangle L x B centred on the ship's reference point
// (midship, as SITS) and rotated by the heading psi. Corners are in order
// around the rectangle (bow-port, bow-starboard, stern-starboard, stern-port).
struct HullPolygon {
  std::array<Eigen::Vector2d, 4> corners_ne;
  BoxNE bounds;

  static HullPolygon Rectangle(double north_m, double east_m, double heading_rad, double length_m,
                               double beam_m);
  // Same with cos/sin of the heading precomputed (hot loops).
  static HullPolygon Rectangle(double north_m, double east_m, double cos_heading,
                               double sin_heading, double length_m, double beam_m);
};

class GroundingTest {
 public:
  virtual ~GroundingTest() = default;
  // True if any part of the hull touches or overlaps an obstacle.
  virtual bool HullIntersects(const HullPolygon& hull) const = 0;
  // Distance [m] from the hull to the nearest obstacle; 0 when intersecting.
  // May return +inf when there is no obstacle within the implementation's
  // search radius.
  virtual double Clearance(const HullPolygon& hull) const = 0;
};

// Simple polygons (outer rings only, no holes), each a list of (N, E)
// vertices; the closing edge is implicit (a repeated first vertex is
// accepted and dropped). Per-polygon and per-edge bounding boxes prune the
// exact tests, so a hull far from a long coastline costs one box test.
class PolygonObstacles final : public GroundingTest {
 public:
  static StatusOr<PolygonObstacles> Create(std::vector<std::vector<Eigen::Vector2d>> polygons_ne);

  bool HullIntersects(const HullPolygon& hull) const override;
  double Clearance(const HullPolygon& hull) const override;
  size_t size() const { return polygons_.size(); }

 private:
  struct Polygon {
    std::vector<Eigen::Vector2d> vertices;
    BoxNE bounds;
  };
  explicit PolygonObstacles(std::vector<Polygon> p) : polygons_(std::move(p)) {}
  bool Intersects(const Polygon& poly, const HullPolygon& hull) const;
  std::vector<Polygon> polygons_;
};

}  // namespace seaplan::risk
