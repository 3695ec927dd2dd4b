#include "seaplan/route/obstacle_field.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "absl/strings/str_cat.h"

namespace seaplan::route {
namespace {

constexpr double kMaxExponent = 50.0;

double Cross(EastNorth a, EastNorth b) {
  return a.east_m * b.north_m - a.north_m * b.east_m;
}
EastNorth Sub(EastNorth a, EastNorth b) {
  return {a.east_m - b.east_m, a.north_m - b.north_m};
}

int Orientation(EastNorth a, EastNorth b, EastNorth c) {
  const double v = Cross(Sub(b, a), Sub(c, a));
  return (v > 0) - (v < 0);
}
bool OnSegment(EastNorth a, EastNorth b, EastNorth p) {
  return std::min(a.east_m, b.east_m) <= p.east_m && p.east_m <= std::max(a.east_m, b.east_m) &&
         std::min(a.north_m, b.north_m) <= p.north_m && p.north_m <= std::max(a.north_m, b.north_m);
}
// Closed segments a-b and c-d share a point.
bool SegmentsIntersect(EastNorth a, EastNorth b, EastNorth c, EastNorth d) {
  const int o1 = Orientation(a, b, c), o2 = Orientation(a, b, d);
  const int o3 = Orientation(c, d, a), o4 = Orientation(c, d, b);
  if (o1 != o2 && o3 != o4) return true;
  if (o1 == 0 && OnSegment(a, b, c)) return true;
  if (o2 == 0 && OnSegment(a, b, d)) return true;
  if (o3 == 0 && OnSegment(c, d, a)) return true;
  if (o4 == 0 && OnSegment(c, d, b)) return true;
  return false;
}
// p inside or on the convex polygon v[0..n).
bool InConvex(const EastNorth* v, int n, EastNorth p) {
  bool pos = false, neg = false;
  for (int i = 0; i < n; ++i) {
    const double c = Cross(Sub(v[(i + 1) % n], v[i]), Sub(p, v[i]));
    pos |= c > 0;
    neg |= c < 0;
  }
  return !(pos && neg);
}
double BoxDistance(EastNorth p, EastNorth lo, EastNorth hi) {
  const double dx = std::max({lo.east_m - p.east_m, 0.0, p.east_m - hi.east_m});
  const double dy = std::max({lo.north_m - p.north_m, 0.0, p.north_m - hi.north_m});
  return std::sqrt(dx * dx + dy * dy);
}

}  // namespace

absl::Status ObstacleFieldOptions::Validate() const {
  if (!(cell_m >= 1.0 && cell_m <= 10000.0)) {
    return absl::InvalidArgumentError(absl::StrCat("cell_m must be in [1, 10000], got ", cell_m));
  }
  if (!(far_cutoff_m > 0.0 && far_cutoff_m <= 1e5)) {
    return absl::InvalidArgumentError(
        absl::StrCat("far_cutoff_m must be in (0, 1e5], got ", far_cutoff_m));
  }
  if (!(margin_m >= 0.0 && margin_m <= 1e5)) {
    return absl::InvalidArgumentError(absl::StrCat("margin_m must be in [0, 1e5], got ", margin_m));
  }
  if (!(hull.length_m > 0.0 && hull.beam_m > 0.0 && hull.beam_m <= hull.length_m &&
        hull.length_m < 1000.0)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "hull must have 0 < beam <= length < 1000 m, got ", hull.length_m, " x ", hull.beam_m));
  }
  return absl::OkStatus();
}

StatusOr<ObstacleField> ObstacleField::Build(std::vector<ObstaclePolygon> obstacles,
                                             EastNorth area_min, EastNorth area_max,
                                             const ObstacleFieldOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (!(area_max.east_m > area_min.east_m && area_max.north_m > area_min.north_m) ||
      !std::isfinite(area_min.east_m + area_min.north_m + area_max.east_m + area_max.north_m)) {
    return absl::InvalidArgumentError("obstacle field area must be a non-empty finite box");
  }
  const double width = area_max.east_m - area_min.east_m + 2 * options.margin_m;
  const double height = area_max.north_m - area_min.north_m + 2 * options.margin_m;
  const double cells = (width / options.cell_m + 1) * (height / options.cell_m + 1);
  if (cells > 4e6) {
    return absl::ResourceExhaustedError(absl::StrCat(
        "obstacle field grid would need ", cells, " cells (area ", width, " x ", height, " m at ",
        options.cell_m, " m); use a larger cell_m or a smaller area"));
  }

  ObstacleField f;
  f.options_ = options;
  f.area_min_ = area_min;
  f.area_max_ = area_max;
  const double half_l = options.hull.length_m / 2, half_b = options.hull.beam_m / 2;
  f.hull_outer_radius_ = std::hypot(half_l, half_b);
  f.hull_inner_radius_ = std::min(half_b, half_l / std::sqrt(2.0));
  f.obstacle_edge_begin_.push_back(0);
  for (size_t i = 0; i < obstacles.size(); ++i) {
    EastNorth lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    EastNorth hi{-lo.east_m, -lo.north_m};
    for (const auto& ring : obstacles[i].rings) {
      const size_t n = ring.size();
      if (n < 3) {
        return absl::InvalidArgumentError(
            absl::StrCat("obstacle ", i, " has a ring with ", n, " points (need >= 3)"));
      }
      for (size_t k = 0; k < n; ++k) {
        const EastNorth a = ring[k], b = ring[(k + 1) % n];
        if (!std::isfinite(a.east_m) || !std::isfinite(a.north_m)) {
          return absl::InvalidArgumentError(
              absl::StrCat("obstacle ", i, " has a non-finite vertex"));
        }
        const EastNorth d = Sub(b, a);
        const double len2 = d.east_m * d.east_m + d.north_m * d.north_m;
        f.edges_.push_back({a, d, len2 > 0 ? 1.0 / len2 : 0.0});
        lo = {std::min(lo.east_m, a.east_m), std::min(lo.north_m, a.north_m)};
        hi = {std::max(hi.east_m, a.east_m), std::max(hi.north_m, a.north_m)};
      }
    }
    if (f.edges_.size() == static_cast<size_t>(f.obstacle_edge_begin_.back())) {
      return absl::InvalidArgumentError(absl::StrCat("obstacle ", i, " has no ring"));
    }
    f.obstacle_edge_begin_.push_back(static_cast<int32_t>(f.edges_.size()));
    f.obstacle_box_min_.push_back(lo);
    f.obstacle_box_max_.push_back(hi);
  }
  f.all_edges_.resize(f.edges_.size());
  for (size_t e = 0; e < f.edges_.size(); ++e) f.all_edges_[e] = static_cast<int32_t>(e);

  // The grid. Every cell keeps, per obstacle near enough to matter, the edges
  // that can be the nearest for some point of the cell: for p in the cell,
  // |d_e(p) - d_e(c)| <= hd (hd = half diagonal), so only edges with
  // d_e(c) <= min_e d_e(c) + 2 hd can win. Likewise the edges that a hull
  // centred in the cell can touch have d_e(c) <= R_outer + hd.
  //
  // Build cost: a first pass over blocks of kBlock x kBlock cells (centre C,
  // half diagonal H) keeps per obstacle only the edges that can matter to any
  // cell of the block (the same Lipschitz argument one level up), and
  // inside/outside of every cell centre comes from one scanline per grid row;
  // so a chart-sized coastline polygon costs O(blocks x edges + cells x local
  // edges), not O(cells x edges).
  f.cell_ = options.cell_m;
  f.inv_cell_ = 1.0 / options.cell_m;
  f.grid_origin_ = {area_min.east_m - options.margin_m, area_min.north_m - options.margin_m};
  f.nx_ = static_cast<int>(std::ceil(width / options.cell_m));
  f.ny_ = static_cast<int>(std::ceil(height / options.cell_m));
  const double hd = options.cell_m * std::sqrt(0.5);
  // Every obstacle a hull may touch must have an entry (HullHits relies on it).
  const double cutoff = std::max(options.far_cutoff_m, f.hull_outer_radius_ + 2 * hd);
  const double hull_reach = f.hull_outer_radius_ + hd;
  constexpr int kBlock = 4;
  const double big_h = kBlock * options.cell_m * std::sqrt(0.5);
  const size_t cell_count = static_cast<size_t>(f.nx_) * f.ny_;
  struct TmpEntry {
    CellObstacle entry;
    std::vector<int32_t> cand, hull;
  };
  // Edges by grid row for the even-odd test of points in boundary cells:
  // an edge counts for p only when p.north_m lies between its ends, so the
  // edges whose extent misses p's row cannot change the parity. The row
  // range is widened by 1 m against rounding of a point's row.
  {
    const int polygon_count = f.obstacle_count();
    auto rows_of = [&](const Edge& e) {
      const double y0 = std::min(e.a.north_m, e.a.north_m + e.d.north_m) - 1.0;
      const double y1 = std::max(e.a.north_m, e.a.north_m + e.d.north_m) + 1.0;
      const double r0 = std::floor((y0 - f.grid_origin_.north_m) * f.inv_cell_);
      const double r1 = std::floor((y1 - f.grid_origin_.north_m) * f.inv_cell_);
      return std::pair<int, int>{static_cast<int>(std::clamp(r0, 0.0, f.ny_ - 1.0)),
                                 static_cast<int>(std::clamp(r1, 0.0, f.ny_ - 1.0))};
    };
    // Each obstacle's rows run from the lowest to the highest its edges
    // reach, so the index grows with the obstacles' extents, not with
    // rows x obstacles (many islets on a large chart).
    f.obstacle_row_lo_.assign(polygon_count, 0);
    f.obstacle_row_key_.assign(polygon_count + 1, 0);
    for (int i = 0; i < polygon_count; ++i) {
      int lo = f.ny_, hi = -1;
      for (int k = f.obstacle_edge_begin_[i]; k < f.obstacle_edge_begin_[i + 1]; ++k) {
        const auto [r0, r1] = rows_of(f.edges_[k]);
        lo = std::min(lo, r0);
        hi = std::max(hi, r1);
      }
      if (hi < lo) {  // no edges: no rows
        lo = 0;
        hi = -1;
      }
      f.obstacle_row_lo_[i] = lo;
      f.obstacle_row_key_[i + 1] = f.obstacle_row_key_[i] + (hi - lo + 1);
    }
    const size_t keys = static_cast<size_t>(f.obstacle_row_key_[polygon_count]);
    auto key_of = [&](int i, int row) {
      return static_cast<size_t>(f.obstacle_row_key_[i] + row - f.obstacle_row_lo_[i]);
    };
    f.row_edge_begin_.assign(keys + 1, 0);
    for (int i = 0; i < polygon_count; ++i) {
      for (int k = f.obstacle_edge_begin_[i]; k < f.obstacle_edge_begin_[i + 1]; ++k) {
        const auto [r0, r1] = rows_of(f.edges_[k]);
        for (int r = r0; r <= r1; ++r) ++f.row_edge_begin_[key_of(i, r) + 1];
      }
    }
    for (size_t key = 0; key < keys; ++key) f.row_edge_begin_[key + 1] += f.row_edge_begin_[key];
    f.row_edges_.resize(f.row_edge_begin_[keys]);
    std::vector<int32_t> fill(f.row_edge_begin_.begin(), f.row_edge_begin_.end() - 1);
    for (int i = 0; i < polygon_count; ++i) {
      for (int k = f.obstacle_edge_begin_[i]; k < f.obstacle_edge_begin_[i + 1]; ++k) {
        const auto [r0, r1] = rows_of(f.edges_[k]);
        for (int r = r0; r <= r1; ++r) f.row_edges_[fill[key_of(i, r)]++] = k;
      }
    }
  }
  std::vector<std::vector<TmpEntry>> tmp(cell_count);
  std::vector<float> clear(cell_count, std::numeric_limits<float>::max());
  std::vector<uint8_t> inside_flag(cell_count);
  std::vector<double> crossings, d2, dc2;
  std::vector<int32_t> block_edges;
  auto centre = [&](int ix, int iy) {
    return EastNorth{f.grid_origin_.east_m + (ix + 0.5) * f.cell_,
                     f.grid_origin_.north_m + (iy + 0.5) * f.cell_};
  };
  for (int i = 0; i < f.obstacle_count(); ++i) {
    const int eb = f.obstacle_edge_begin_[i], ee = f.obstacle_edge_begin_[i + 1];
    const EastNorth lo = f.obstacle_box_min_[i], hi = f.obstacle_box_max_[i];
    // Even-odd inside flags of the cell centres, one scanline per row.
    std::fill(inside_flag.begin(), inside_flag.end(), 0);
    for (int iy = 0; iy < f.ny_; ++iy) {
      const double y = centre(0, iy).north_m;
      if (y < lo.north_m || y > hi.north_m) continue;
      crossings.clear();
      for (int k = eb; k < ee; ++k) {
        const Edge& e = f.edges_[k];
        const double by = e.a.north_m + e.d.north_m;
        if ((e.a.north_m > y) != (by > y))
          crossings.push_back(e.a.east_m + (y - e.a.north_m) * e.d.east_m / e.d.north_m);
      }
      std::sort(crossings.begin(), crossings.end());
      // Centre x is inside when an odd number of crossings lie to its right
      // (PointInObstacle's rule: p.east_m < crossing).
      size_t next = 0;
      for (int ix = 0; ix < f.nx_; ++ix) {
        const double x = centre(ix, 0).east_m;
        while (next < crossings.size() && crossings[next] <= x) ++next;
        inside_flag[static_cast<size_t>(iy) * f.nx_ + ix] = ((crossings.size() - next) % 2) == 1;
      }
    }
    for (int by0 = 0; by0 < f.ny_; by0 += kBlock) {
      for (int bx0 = 0; bx0 < f.nx_; bx0 += kBlock) {
        const int bx1 = std::min(bx0 + kBlock, f.nx_), by1 = std::min(by0 + kBlock, f.ny_);
        const EastNorth bc{f.grid_origin_.east_m + (bx0 + kBlock * 0.5) * f.cell_,
                           f.grid_origin_.north_m + (by0 + kBlock * 0.5) * f.cell_};
        const double bd = BoxDistance(bc, lo, hi);
        if (bd - big_h - hd >= cutoff) {  // centres outside the box: outside
          for (int iy = by0; iy < by1; ++iy) {
            for (int ix = bx0; ix < bx1; ++ix) {
              float& c = clear[static_cast<size_t>(iy) * f.nx_ + ix];
              c = std::min<float>(c, static_cast<float>(bd - big_h - hd));
            }
          }
          continue;
        }
        dc2.resize(ee - eb);
        double min2 = std::numeric_limits<double>::infinity();
        for (int k = eb; k < ee; ++k) {
          dc2[k - eb] = f.EdgeDistance2(f.edges_[k], bc);
          min2 = std::min(min2, dc2[k - eb]);
        }
        const double dmin_b = std::sqrt(min2);
        const bool far = dmin_b - big_h - hd >= cutoff;
        block_edges.clear();
        if (!far) {
          const double keep = std::max(dmin_b + 2 * big_h + 2 * hd, hull_reach + big_h);
          for (int k = eb; k < ee; ++k) {
            if (dc2[k - eb] <= keep * keep) block_edges.push_back(k);
          }
        }
        for (int iy = by0; iy < by1; ++iy) {
          for (int ix = bx0; ix < bx1; ++ix) {
            const size_t ci = static_cast<size_t>(iy) * f.nx_ + ix;
            const bool centre_inside = inside_flag[ci] != 0;
            if (far) {
              // Deep inside (clipped distance) or far outside (no entry).
              if (centre_inside) {
                clear[ci] = -std::numeric_limits<float>::max();
                TmpEntry t;
                t.entry = {i, 0, 0, 2};
                tmp[ci].push_back(std::move(t));
              } else {
                clear[ci] = std::min<float>(clear[ci], static_cast<float>(dmin_b - big_h - hd));
              }
              continue;
            }
            const EastNorth c = centre(ix, iy);
            d2.resize(block_edges.size());
            double cmin2 = std::numeric_limits<double>::infinity();
            for (size_t j = 0; j < block_edges.size(); ++j) {
              d2[j] = f.EdgeDistance2(f.edges_[block_edges[j]], c);
              cmin2 = std::min(cmin2, d2[j]);
            }
            const double dmin = std::sqrt(cmin2);
            const int8_t inside = dmin > hd ? (centre_inside ? 1 : 0) : -1;
            clear[ci] = std::min<float>(clear[ci], inside == 1 ? -std::numeric_limits<float>::max()
                                                               : static_cast<float>(dmin - hd));
            if (dmin - hd >= cutoff) {
              if (inside == 1) {
                TmpEntry t;
                t.entry = {i, 0, 0, 2};
                tmp[ci].push_back(std::move(t));
              }
              continue;
            }
            TmpEntry t;
            t.entry = {i, 0, 0, inside};
            const double keep = (dmin + 2 * hd) * (dmin + 2 * hd);
            const double hull_keep = hull_reach * hull_reach;
            for (size_t j = 0; j < block_edges.size(); ++j) {
              if (d2[j] <= keep) t.cand.push_back(block_edges[j]);
              if (d2[j] <= hull_keep) t.hull.push_back(block_edges[j]);
            }
            tmp[ci].push_back(std::move(t));
          }
        }
      }
    }
  }
  f.cells_.resize(cell_count);
  for (size_t ci = 0; ci < cell_count; ++ci) {
    Cell& cell = f.cells_[ci];
    cell.entries_begin = static_cast<int32_t>(f.entries_.size());
    cell.hull_begin = static_cast<int32_t>(f.hull_candidates_.size());
    for (TmpEntry& t : tmp[ci]) {
      t.entry.cand_begin = static_cast<int32_t>(f.candidates_.size());
      f.candidates_.insert(f.candidates_.end(), t.cand.begin(), t.cand.end());
      t.entry.cand_end = static_cast<int32_t>(f.candidates_.size());
      f.hull_candidates_.insert(f.hull_candidates_.end(), t.hull.begin(), t.hull.end());
      f.entries_.push_back(t.entry);
    }
    cell.entries_end = static_cast<int32_t>(f.entries_.size());
    cell.hull_end = static_cast<int32_t>(f.hull_candidates_.size());
    cell.clear_lb_m = clear[ci];
    std::vector<TmpEntry>().swap(tmp[ci]);
  }
  f.deep_inside_m_ = cutoff;
  return f;
}

double ObstacleField::EdgeDistance2(const Edge& e, EastNorth p) const {
  const double px = p.east_m - e.a.east_m, py = p.north_m - e.a.north_m;
  double t = (px * e.d.east_m + py * e.d.north_m) * e.inv_len2;
  t = std::clamp(t, 0.0, 1.0);
  const double dx = px - t * e.d.east_m, dy = py - t * e.d.north_m;
  return dx * dx + dy * dy;
}

bool ObstacleField::PointInObstacle(int obstacle, EastNorth p) const {
  bool inside = false;
  for (int k = obstacle_edge_begin_[obstacle]; k < obstacle_edge_begin_[obstacle + 1]; ++k) {
    const Edge& e = edges_[k];
    const double by = e.a.north_m + e.d.north_m;
    if ((e.a.north_m > p.north_m) != (by > p.north_m)) {
      const double x = e.a.east_m + (p.north_m - e.a.north_m) * e.d.east_m / e.d.north_m;
      if (p.east_m < x) inside = !inside;
    }
  }
  return inside;
}

bool ObstacleField::PointInObstacleInRow(int obstacle, int row, EastNorth p) const {
  // Outside the rows the obstacle's edges reach no edge straddles p's
  // northing: the parity is even.
  const int offset = row - obstacle_row_lo_[obstacle];
  if (offset < 0 || offset >= obstacle_row_key_[obstacle + 1] - obstacle_row_key_[obstacle])
    return false;
  const size_t key = static_cast<size_t>(obstacle_row_key_[obstacle] + offset);
  bool inside = false;
  for (int32_t j = row_edge_begin_[key]; j < row_edge_begin_[key + 1]; ++j) {
    const Edge& e = edges_[row_edges_[j]];
    const double by = e.a.north_m + e.d.north_m;
    if ((e.a.north_m > p.north_m) != (by > p.north_m)) {
      const double x = e.a.east_m + (p.north_m - e.a.north_m) * e.d.east_m / e.d.north_m;
      if (p.east_m < x) inside = !inside;
    }
  }
  return inside;
}

double ObstacleField::ObstacleDistanceBruteForce(int obstacle, EastNorth p) const {
  double min2 = std::numeric_limits<double>::infinity();
  for (int k = obstacle_edge_begin_[obstacle]; k < obstacle_edge_begin_[obstacle + 1]; ++k) {
    min2 = std::min(min2, EdgeDistance2(edges_[k], p));
  }
  return std::sqrt(min2);
}

const ObstacleField::Cell* ObstacleField::CellAt(EastNorth p) const {
  const double fx = (p.east_m - grid_origin_.east_m) * inv_cell_,
               fy = (p.north_m - grid_origin_.north_m) * inv_cell_;
  if (!(fx >= 0 && fy >= 0 && fx < nx_ && fy < ny_)) return nullptr;
  return &cells_[static_cast<size_t>(static_cast<int>(fy)) * nx_ + static_cast<int>(fx)];
}

// Defined here, before its two hot callers, so it is inlined into both.
double ObstacleField::EntrySignedDistance(const CellObstacle& entry, EastNorth p) const {
  if (entry.inside == 2) return -deep_inside_m_;
  double min2 = std::numeric_limits<double>::infinity();
  for (int32_t k = entry.cand_begin; k < entry.cand_end; ++k) {
    min2 = std::min(min2, EdgeDistance2(edges_[candidates_[k]], p));
  }
  const double d = std::sqrt(min2);
  // p lies in the grid (the callers found its cell): its row as CellAt has it.
  const bool inside =
      entry.inside < 0
          ? PointInObstacleInRow(
                entry.obstacle, static_cast<int>((p.north_m - grid_origin_.north_m) * inv_cell_), p)
          : entry.inside == 1;
  return inside ? -d : d;
}

double ObstacleField::SumExpDistance(EastNorth p, double zeta) const {
  const Cell* cell = CellAt(p);
  if (cell == nullptr) return SumExpDistanceBruteForce(p, zeta);
  double sum = 0.0;
  for (int32_t j = cell->entries_begin; j < cell->entries_end; ++j) {
    sum += std::exp(std::min(kMaxExponent, -zeta * EntrySignedDistance(entries_[j], p)));
  }
  return sum;
}

double ObstacleField::SumExpDistanceBruteForce(EastNorth p, double zeta) const {
  double sum = 0.0;
  for (int i = 0; i < obstacle_count(); ++i) {
    double d = ObstacleDistanceBruteForce(i, p);
    if (PointInObstacle(i, p)) d = -d;
    sum += std::exp(std::min(kMaxExponent, -zeta * d));
  }
  return sum;
}

double ObstacleField::SignedDistance(EastNorth p) const {
  const Cell* cell = CellAt(p);
  if (cell == nullptr) return SignedDistanceBruteForce(p);
  double best = std::numeric_limits<double>::infinity();
  for (int32_t j = cell->entries_begin; j < cell->entries_end; ++j) {
    best = std::min(best, EntrySignedDistance(entries_[j], p));
  }
  if (cell->entries_begin == cell->entries_end) return std::max<double>(cell->clear_lb_m, 0.0);
  return best;
}

double ObstacleField::SignedDistanceBruteForce(EastNorth p) const {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < obstacle_count(); ++i) {
    double d = ObstacleDistanceBruteForce(i, p);
    if (PointInObstacle(i, p)) d = -d;
    best = std::min(best, d);
  }
  return best;
}

bool ObstacleField::Inside(EastNorth p) const {
  return SignedDistance(p) <= 0.0;
}

void ObstacleField::HullVertices(EastNorth c, double heading_rad, EastNorth out[5]) const {
  const double half_l = options_.hull.length_m / 2, half_b = options_.hull.beam_m / 2;
  const double fx = std::sin(heading_rad), fy = std::cos(heading_rad);  // forward
  const double sx = fy, sy = -fx;                                       // starboard
  const double pts[5][2] = {{-half_l, -half_b},
                            {half_l - half_b, -half_b},
                            {half_l, 0.0},
                            {half_l - half_b, half_b},
                            {-half_l, half_b}};
  for (int i = 0; i < 5; ++i) {
    out[i] = {c.east_m + pts[i][0] * fx + pts[i][1] * sx,
              c.north_m + pts[i][0] * fy + pts[i][1] * sy};
  }
}

bool ObstacleField::HullHitsEdges(const EastNorth hull[5], const int32_t* edges, int n) const {
  for (int j = 0; j < n; ++j) {
    const Edge& e = edges_[edges[j]];
    const EastNorth b{e.a.east_m + e.d.east_m, e.a.north_m + e.d.north_m};
    // An obstacle ring lying wholly inside the hull has its vertices inside.
    if (InConvex(hull, 5, e.a)) return true;
    for (int i = 0; i < 5; ++i) {
      if (SegmentsIntersect(hull[i], hull[(i + 1) % 5], e.a, b)) return true;
    }
  }
  return false;
}

bool ObstacleField::HullHits(EastNorth centre, double heading_rad) const {
  const Cell* cell = CellAt(centre);
  if (cell == nullptr) return HullHitsBruteForce(centre, heading_rad);
  if (cell->clear_lb_m > hull_outer_radius_) return false;
  const double sd = SignedDistance(centre);
  if (sd <= hull_inner_radius_) return true;  // centre inside, or the inscribed disc touches
  if (sd > hull_outer_radius_) return false;
  EastNorth hull[5];
  HullVertices(centre, heading_rad, hull);
  return HullHitsEdges(hull, hull_candidates_.data() + cell->hull_begin,
                       cell->hull_end - cell->hull_begin);
}

bool ObstacleField::HullHitsBruteForce(EastNorth centre, double heading_rad) const {
  for (int i = 0; i < obstacle_count(); ++i) {
    if (PointInObstacle(i, centre)) return true;
  }
  EastNorth hull[5];
  HullVertices(centre, heading_rad, hull);
  return HullHitsEdges(hull, all_edges_.data(), static_cast<int>(all_edges_.size()));
}

bool ObstacleField::SegmentHits(EastNorth a, EastNorth b) const {
  for (int i = 0; i < obstacle_count(); ++i) {
    if (PointInObstacle(i, a)) return true;
  }
  for (const Edge& e : edges_) {
    if (SegmentsIntersect(a, b, e.a, {e.a.east_m + e.d.east_m, e.a.north_m + e.d.north_m}))
      return true;
  }
  return false;
}

}  // namespace seaplan::route
