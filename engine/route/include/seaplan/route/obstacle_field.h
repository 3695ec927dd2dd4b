// Exact, allocation-free obstacle queries for the Level-2 route optimiser.
//
// Why our own and not the chart's GEOS ObstacleQuery: the optimiser asks
// ~10^5-10^6 questions per route (every particle evaluation sums a term over
// every obstacle and tests the drifting hull at every TTG step). A GEOS call
// costs a few microseconds plus context/prepared-geometry bookkeeping; these
// questions cost tens of nanoseconds on a precomputed uniform grid, and the
// answers are EXACT (no rasterisation): each grid cell stores, per obstacle,
// the only edges that can be nearest to any point of the cell (a Lipschitz
// bound on the distance), plus the edges that can touch a ship hull centred
// in the cell. Points outside the grid fall back to a brute-force scan, which
// is also offered as the reference (`*BruteForce`) for tests and the exact
// baseline of bench/route.
//
// Frame: local metric frame, seaplan::EastNorth (metres east, north).
// Thread-safety: immutable after Build; every const method is thread-safe.
#pragma once

#include <cstdint>
#include <vector>

#include "seaplan/common/east_north.h"
#include "seaplan/common/status.h"

namespace seaplan::route {

// One obstacle: rings (outer boundary and holes, any orientation, no repeated
// closing point). Inside = even-odd rule over all rings.
struct ObstaclePolygon {
  std::vector<std::vector<EastNorth>> rings;
};

// Ship footprint used for the grounding test: a convex pentagon, stern
// corners at -L/2, parallel sides up to L/2 - B/2, bow point at +L/2
// (the seacharts `Ship` outline the public code intersects with the shore).
struct HullShape {
  double length_m = 80.0;
  double beam_m = 16.0;
};

struct ObstacleFieldOptions {
  // Grid cell size, metres. Smaller cells -> shorter candidate lists but more
  // memory and build time; 50 m suits harbour/coastal charts and ~80 m ships.
  double cell_m = 50.0;
  // Distance beyond which an obstacle's exp(-zeta d) term is not tracked by the
  // grid (the optimiser sets it to 30/zeta: exp(-30) ~ 1e-13 of a touching
  // obstacle's term). Queries stay exact below it.
  double far_cutoff_m = 750.0;
  // Grid extent = `area` grown by this margin (a drifting ship may leave the
  // chart); outside the grid queries are brute force (exact, slower).
  double margin_m = 1000.0;
  HullShape hull;

  absl::Status Validate() const;
};

class ObstacleField {
 public:
  // `area_min`/`area_max`: the box the queries concentrate in (chart coverage).
  static StatusOr<ObstacleField> Build(std::vector<ObstaclePolygon> obstacles, EastNorth area_min,
                                       EastNorth area_max, const ObstacleFieldOptions& options);

  ObstacleField(ObstacleField&&) noexcept = default;
  ObstacleField& operator=(ObstacleField&&) noexcept = default;
  ObstacleField(const ObstacleField&) = delete;
  ObstacleField& operator=(const ObstacleField&) = delete;

  int obstacle_count() const { return static_cast<int>(obstacle_edge_begin_.size()) - 1; }
  const ObstacleFieldOptions& options() const { return options_; }
  EastNorth area_min() const { return area_min_; }
  EastNorth area_max() const { return area_max_; }
  bool InArea(EastNorth p) const {
    return p.east_m >= area_min_.east_m && p.east_m <= area_max_.east_m &&
           p.north_m >= area_min_.north_m && p.north_m <= area_max_.north_m;
  }

  // Sum over obstacles of exp(-zeta * d_i(p)), d_i the signed distance to
  // obstacle i (negative inside; the exponent is capped at +50). Obstacles
  // farther than far_cutoff_m are left out (their terms are < exp(-zeta*cutoff));
  // deeper inside an obstacle than the cutoff, d_i is clipped to -cutoff.
  double SumExpDistance(EastNorth p, double zeta) const;
  double SumExpDistanceBruteForce(EastNorth p, double zeta) const;

  // Signed distance to the nearest obstacle (negative inside). Beyond
  // far_cutoff_m outside the result is a lower bound; deeper inside than the
  // cutoff it is clipped to -cutoff (the sign is always exact).
  double SignedDistance(EastNorth p) const;
  double SignedDistanceBruteForce(EastNorth p) const;
  bool Inside(EastNorth p) const;

  // True when the hull (options().hull) centred at `centre` with heading
  // `heading_rad` (from north, clockwise) touches or overlaps an obstacle.
  bool HullHits(EastNorth centre, double heading_rad) const;
  bool HullHitsBruteForce(EastNorth centre, double heading_rad) const;

  // True when segment a-b touches an obstacle (brute force; for final checks).
  bool SegmentHits(EastNorth a, EastNorth b) const;

 private:
  ObstacleField() = default;

  struct Edge {
    EastNorth a;
    EastNorth d;      // b - a
    double inv_len2;  // 1 / |d|^2 (0 for a degenerate edge)
  };
  struct CellObstacle {
    int32_t obstacle;
    int32_t cand_begin;  // into candidates_
    int32_t cand_end;
    // 0 outside, 1 inside, -1 boundary crosses the cell: test; 2 deeper
    // inside than the cutoff (no candidates; distance clipped to -cutoff).
    int8_t inside;
  };
  struct Cell {
    int32_t entries_begin, entries_end;  // into entries_
    int32_t hull_begin, hull_end;        // into hull_candidates_
    // Lower bound of the signed distance to any obstacle over the cell
    // (negative when the cell may lie inside one).
    float clear_lb_m;
  };

  bool PointInObstacle(int obstacle, EastNorth p) const;
  // The same answer for p in grid row `row`, from the obstacle's edges that
  // can straddle that row (row_edges_).
  bool PointInObstacleInRow(int obstacle, int row, EastNorth p) const;
  double EdgeDistance2(const Edge& e, EastNorth p) const;
  double ObstacleDistanceBruteForce(int obstacle, EastNorth p) const;  // unsigned
  // Signed distance from p (inside the entry's cell) to the entry's obstacle:
  // nearest candidate edge, negative inside, -deep_inside_m_ for a cell deeper
  // inside than the cutoff.
  double EntrySignedDistance(const CellObstacle& entry, EastNorth p) const;
  const Cell* CellAt(EastNorth p) const;
  void HullVertices(EastNorth centre, double heading_rad, EastNorth out[5]) const;
  bool HullHitsEdges(const EastNorth hull[5], const int32_t* edges, int n) const;

  ObstacleFieldOptions options_;
  EastNorth area_min_, area_max_;
  std::vector<Edge> edges_;
  std::vector<int32_t> obstacle_edge_begin_;  // size obstacles + 1
  std::vector<EastNorth> obstacle_box_min_, obstacle_box_max_;
  // Grid.
  EastNorth grid_origin_;
  int nx_ = 0, ny_ = 0;
  double cell_ = 50.0, inv_cell_ = 0.02;
  std::vector<Cell> cells_;
  std::vector<CellObstacle> entries_;
  std::vector<int32_t> candidates_;
  std::vector<int32_t> hull_candidates_;
  std::vector<int32_t> all_edges_;  // 0..edges-1 (brute-force hull test)
  // Per obstacle and grid row of the rows its edges reach (key
  // obstacle_row_key_[i] + row - obstacle_row_lo_[i], into row_edges_): the
  // obstacle's edges whose north extent reaches the row (with 1 m to
  // spare), the only ones a ray east from a point of the row can cross.
  std::vector<int32_t> obstacle_row_lo_;   // size obstacles
  std::vector<int32_t> obstacle_row_key_;  // size obstacles + 1
  std::vector<int32_t> row_edge_begin_;
  std::vector<int32_t> row_edges_;
  double hull_outer_radius_ = 0.0, hull_inner_radius_ = 0.0;
  double deep_inside_m_ = 0.0;
};

}  // namespace seaplan::route
