#include "seaplan/route/turn_fillet.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "absl/strings/str_cat.h"

namespace seaplan::route {
namespace {

EastNorth Unit(EastNorth v) {
  const double n = v.Norm();
  return n > 0 ? v * (1.0 / n) : EastNorth{};
}

// Counter-clockwise by `a` radians.
EastNorth Rotate(EastNorth v, double a) {
  const double c = std::cos(a), s = std::sin(a);
  return {v.east_m * c - v.north_m * s, v.east_m * s + v.north_m * c};
}

// Where the lines p + s u and q + t v meet; nullopt when (nearly) parallel.
std::optional<EastNorth> Intersect(EastNorth p, EastNorth u, EastNorth q, EastNorth v) {
  const double den = u.Cross(v);
  if (std::abs(den) < 1e-9) return std::nullopt;
  return p + u * ((q - p).Cross(v) / den);
}

// The fillet polygon of the corner prev -> corner -> next: vertices
// circumscribed about the circle of `radius_m` tangent to both legs, each
// turning by at most max_step. Empty when the legs are too short for it.
struct Fillet {
  std::vector<EastNorth> vertices;
  double tail_m = 0.0;  // straight after the last vertex that belongs to the arc
};

std::optional<Fillet> BuildFillet(EastNorth prev, EastNorth corner, EastNorth next, double radius_m,
                                  double max_step, double in_avail_m, double out_reserved_m,
                                  bool next_is_goal) {
  const EastNorth u = Unit(corner - prev), v = Unit(next - corner);
  const double theta = std::atan2(u.Cross(v), u.Dot(v));
  if (std::abs(theta) < 1e-9 || std::abs(theta) > M_PI - 1e-6) return std::nullopt;
  const double tangent_m = radius_m * std::tan(std::abs(theta) / 2.0);
  const double out_leg_m = Distance(corner, next);
  const double out_avail_m =
      next_is_goal ? out_leg_m : std::max(out_leg_m - out_reserved_m, out_leg_m / 2.0);
  if (tangent_m > in_avail_m + 1e-6 || tangent_m > out_avail_m + 1e-6) return std::nullopt;
  const int m = std::max(1, static_cast<int>(std::ceil(std::abs(theta) / max_step - 1e-9)));
  const double step = theta / m;
  const double side = theta > 0 ? 1.0 : -1.0;  // left turn: centre on the left
  const EastNorth t1 = corner - u * tangent_m;
  const EastNorth centre = t1 + Rotate(u, side * M_PI / 2.0) * radius_m;
  const EastNorth r0 = t1 - centre;
  const double scale = 1.0 / std::cos(step / 2.0);
  Fillet f;
  for (int j = 1; j <= m; ++j) {
    f.vertices.push_back(centre + Rotate(r0, (j - 0.5) * step) * scale);
  }
  f.tail_m = radius_m * std::tan(std::abs(step) / 2.0);
  return f;
}

bool InArea(const ObstacleField& field, EastNorth p) {
  const EastNorth lo = field.area_min(), hi = field.area_max();
  return p.east_m >= lo.east_m && p.east_m <= hi.east_m && p.north_m >= lo.north_m &&
         p.north_m <= hi.north_m;
}

// Smallest signed distance from the obstacles along the polyline, sampled
// every `step_m` (and at every vertex).
double SampledClearance(const ObstacleField& field, const std::vector<EastNorth>& line,
                        double step_m) {
  double c = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < line.size(); ++i) {
    c = std::min(c, field.SignedDistance(line[i]));
    if (i + 1 == line.size()) break;
    const double len = Distance(line[i], line[i + 1]);
    const int k = static_cast<int>(len / step_m);
    for (int s = 1; s <= k; ++s) {
      const double t = s * step_m / len;
      if (t >= 1.0) break;
      c = std::min(c, field.SignedDistance(line[i] + (line[i + 1] - line[i]) * t));
    }
  }
  return c;
}

// The circles a corner is tried on: radius_m, then every 10 % smaller
// down to min_radius_m (which is tried last).
std::vector<double> Radii(const TurnFilletOptions& o) {
  std::vector<double> radii = {o.radius_m};
  if (o.min_radius_m <= 0.0 || o.min_radius_m >= o.radius_m) return radii;
  for (double r = 0.9 * o.radius_m; r > o.min_radius_m + 1e-6; r -= 0.1 * o.radius_m) {
    radii.push_back(r);
  }
  radii.push_back(o.min_radius_m);
  return radii;
}

}  // namespace

double TurnAngle(EastNorth a, EastNorth b, EastNorth c) {
  const EastNorth u = b - a, v = c - b;
  if (u.Norm() < 1e-9 || v.Norm() < 1e-9) return 0.0;
  return std::atan2(u.Cross(v), u.Dot(v));
}

absl::Status TurnFilletOptions::Validate() const {
  if (!(radius_m > 0.0 && radius_m < 1e5)) {
    return absl::InvalidArgumentError(
        absl::StrCat("fillet radius_m must be in (0, 1e5), got ", radius_m));
  }
  if (!(max_step_rad > 0.01 && max_step_rad <= M_PI / 2)) {
    return absl::InvalidArgumentError("fillet max_step_rad must be in (0.01, pi/2]");
  }
  if (!(min_turn_rad >= 0.0 && min_turn_rad < M_PI)) {
    return absl::InvalidArgumentError("fillet min_turn_rad must be in [0, pi)");
  }
  if (!(clearance_m >= 0.0 && std::isfinite(clearance_m))) {
    return absl::InvalidArgumentError("fillet clearance_m must be >= 0 and finite");
  }
  if (!(max_group_turn_rad > 0.0 && max_group_turn_rad < M_PI)) {
    return absl::InvalidArgumentError("fillet max_group_turn_rad must be in (0, pi)");
  }
  if (!(min_radius_m >= 0.0 && min_radius_m <= radius_m)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "fillet min_radius_m must be in [0, radius_m = ", radius_m, "], got ", min_radius_m));
  }
  return absl::OkStatus();
}

StatusOr<FilletRoute> FilletTurns(const ObstacleField& field, const std::vector<EastNorth>& route,
                                  const TurnFilletOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (route.size() < 2) {
    return absl::InvalidArgumentError(
        absl::StrCat("a route to fillet needs >= 2 points, got ", route.size()));
  }
  for (const EastNorth& p : route) {
    if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) {
      return absl::InvalidArgumentError("a route to fillet has a non-finite point");
    }
  }
  const size_t n = route.size();
  const double r = options.radius_m;
  // What the next corner will need of the leg route[k] -> route[k + 1].
  auto need_at = [&](size_t k) {
    if (k + 1 >= n || k == 0) return 0.0;
    const double t = std::abs(TurnAngle(route[k - 1], route[k], route[k + 1]));
    return t < options.min_turn_rad ? 0.0 : r * std::tan(std::min(t, 0.49 * M_PI) / 2.0);
  };

  FilletRoute out;
  out.points.push_back({route[0], 0});
  double used_m = 0.0;  // of the straight after out.points.back(): the previous arc's tail
  size_t i = 1;
  while (i + 1 < n) {
    const EastNorth prev = out.points.back().position;
    double theta = TurnAngle(prev, route[i], route[i + 1]);
    if (std::abs(theta) < options.min_turn_rad || Distance(prev, route[i]) < 1e-6) {
      out.points.push_back({route[i], static_cast<int>(i)});
      used_m = 0.0;
      ++i;
      continue;
    }
    // The corner: route[i], or the vertices i..j that turn the same way
    // merged at the meeting point of the first and last legs' lines.
    const EastNorth u = Unit(route[i] - prev);
    size_t j = i;
    EastNorth corner = route[i];
    for (;;) {
      const bool next_is_goal = j + 2 == n;
      const double tangent_m = r * std::tan(std::abs(theta) / 2.0);
      const double out_leg_m = Distance(corner, route[j + 1]);
      const double out_avail_m =
          next_is_goal ? out_leg_m : std::max(out_leg_m - need_at(j + 1), out_leg_m / 2.0);
      if (tangent_m <= out_avail_m || next_is_goal) break;
      const double next_turn = TurnAngle(route[j], route[j + 1], route[j + 2]);
      if (next_turn * theta <= 0.0 || std::abs(theta + next_turn) > options.max_group_turn_rad) {
        break;
      }
      const EastNorth v = Unit(route[j + 2] - route[j + 1]);
      const std::optional<EastNorth> meet = Intersect(prev, u, route[j + 1], v);
      if (!meet || (*meet - prev).Dot(u) <= 0.0 || (route[j + 2] - *meet).Dot(v) <= 0.0) break;
      ++j;
      theta += next_turn;
      corner = *meet;
    }
    const EastNorth next = route[j + 1];
    const bool next_is_goal = j + 2 == n;
    const double reserved_m = need_at(j + 1);
    // Candidates: the corner moved outwards along its bisector, on the
    // circle of radius_m, then (none clear) on smaller ones.
    const EastNorth outward = Unit(u - Unit(next - corner));
    std::optional<Fillet> best;
    double best_clearance = -std::numeric_limits<double>::infinity();
    bool any_fits_the_legs = false;
    bool tightened = false;
    for (double radius : Radii(options)) {
      const double apex_m = radius * (1.0 / std::cos(std::abs(theta) / 2.0) - 1.0);
      for (double f : {1.0, 0.5, 1.5, 0.0, 2.0, 3.0}) {
        const EastNorth c = corner + outward * (f * apex_m);
        if (!InArea(field, c) && f > 0.0) continue;
        std::optional<Fillet> fillet =
            BuildFillet(prev, c, next, radius, options.max_step_rad, Distance(prev, c) - used_m,
                        reserved_m, next_is_goal);
        if (!fillet) continue;
        any_fits_the_legs = true;
        const std::vector<EastNorth>& q = fillet->vertices;
        bool clear = !field.SegmentHits(prev, q.front()) && !field.SegmentHits(q.back(), next);
        for (size_t k = 0; clear && k < q.size(); ++k) {
          clear = InArea(field, q[k]) && (k == 0 || !field.SegmentHits(q[k - 1], q[k]));
        }
        if (!clear) continue;
        const double clearance = SampledClearance(field, q, 10.0);
        if (clearance > best_clearance) {
          best_clearance = clearance;
          best = std::move(fillet);
        }
        if (clearance >= options.clearance_m) break;
      }
      if (best) {
        tightened = radius < r;
        break;
      }
    }
    if (!best) {
      out.unsailable.push_back(
          {route[i], theta, static_cast<int>(i), static_cast<int>(j), !any_fits_the_legs});
      for (size_t k = i; k <= j; ++k) out.points.push_back({route[k], static_cast<int>(k)});
      used_m = 0.0;
      i = j + 1;
      continue;
    }
    for (const EastNorth& q : best->vertices) out.points.push_back({q, -1});
    used_m = best->tail_m;
    ++out.filleted;
    if (tightened) ++out.tightened;
    out.merged_vertices += static_cast<int>(j - i);
    i = j + 1;
  }
  out.points.push_back({route[n - 1], static_cast<int>(n - 1)});
  return out;
}

}  // namespace seaplan::route
