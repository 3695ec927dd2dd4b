#include "seaplan/route/sail_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "absl/strings/str_cat.h"
#include "seaplan/colav/encounter_sim.h"

namespace seaplan::route {

StatusOr<SailedTrack> SailRoute(const std::vector<EastNorth>& route, double speed_mps,
                                const ObstacleField* field,
                                const colav::PathFollowerOptions* follower) {
  if (!(speed_mps > 0.0) || !std::isfinite(speed_mps)) {
    return absl::InvalidArgumentError(absl::StrCat("sail speed must be > 0, got ", speed_mps));
  }
  colav::EncounterSetup setup;
  for (const EastNorth& p : route) {
    if (!std::isfinite(p.east_m) || !std::isfinite(p.north_m)) {
      return absl::InvalidArgumentError("a route to sail has a non-finite point");
    }
    if (setup.path.empty() || (p - setup.path.back()).Norm() >= 1.0) setup.path.push_back(p);
  }
  if (setup.path.size() < 2) {
    return absl::InvalidArgumentError("a route to sail needs 2 points at least 1 m apart");
  }
  double length_m = 0.0;
  for (size_t i = 1; i < setup.path.size(); ++i) {
    length_m += (setup.path[i] - setup.path[i - 1]).Norm();
  }
  setup.cruise_speed_mps = speed_mps;
  setup.start_at_rest = true;
  if (follower != nullptr) setup.follower = *follower;
  // Twice the time at speed plus the acceleration and the slow approach.
  setup.max_time_s = 2.0 * length_m / speed_mps + 900.0;
  SEAPLAN_ASSIGN_OR_RETURN(colav::EncounterOutcome out, colav::SimulateEncounter(setup));
  SailedTrack sailed;
  sailed.arrived = out.arrived;
  sailed.track = std::move(out.track);
  sailed.clearance_m = std::numeric_limits<double>::infinity();
  if (field == nullptr) return sailed;
  double prev_d = 0.0;
  for (size_t i = 0; i < sailed.track.size(); ++i) {
    const double d = field->SignedDistance(sailed.track[i]);
    if (d < sailed.clearance_m) {
      sailed.clearance_m = d;
      sailed.closest = sailed.track[i];
    }
    if (d <= 0.0) sailed.touches = true;
    // A segment that crosses an obstacle has its ends within its length of
    // the crossing: only then the (brute-force) segment test.
    if (i > 0 && !sailed.touches && prev_d + d <= Distance(sailed.track[i - 1], sailed.track[i]) &&
        field->SegmentHits(sailed.track[i - 1], sailed.track[i])) {
      sailed.touches = true;
    }
    prev_d = d;
  }
  // Consecutive points are ~18 m apart: a segment can dip in between two
  // points that are not inside.
  if (sailed.touches) sailed.clearance_m = std::min(sailed.clearance_m, 0.0);
  return sailed;
}

absl::Status SailRepairOptions::Validate() const {
  if (max_sails < 0 || max_sails > 1000) {
    return absl::InvalidArgumentError(
        absl::StrCat("sail repair max_sails must be in [0, 1000], got ", max_sails));
  }
  if (!(target_clearance_m >= 0.0 && target_clearance_m < 1e4)) {
    return absl::InvalidArgumentError("sail repair target_clearance_m must be in [0, 1e4)");
  }
  if (!(window_m > 0.0 && window_m < 1e5)) {
    return absl::InvalidArgumentError("sail repair window_m must be in (0, 1e5)");
  }
  return absl::OkStatus();
}

namespace {

// Clear beats not; then arriving; then the larger clearance.
bool Better(const SailedTrack& a, const SailedTrack& b) {
  if (a.Clear() != b.Clear()) return a.Clear();
  if (a.arrived != b.arrived) return a.arrived;
  return a.clearance_m > b.clearance_m;
}

// The point of the route `pts` nearest `at`, and its arc length.
std::pair<EastNorth, double> NearestOnRoute(const std::vector<FilletPoint>& pts, EastNorth at) {
  double best_d = std::numeric_limits<double>::infinity(), s = 0.0, best_s = 0.0;
  EastNorth best;
  for (size_t i = 1; i < pts.size(); ++i) {
    const EastNorth a = pts[i - 1].position, ab = pts[i].position - a;
    const double len2 = ab.Dot(ab);
    const double t = len2 > 0.0 ? std::clamp((at - a).Dot(ab) / len2, 0.0, 1.0) : 0.0;
    const EastNorth q = a + ab * t;
    if (Distance(at, q) < best_d) {
      best_d = Distance(at, q);
      best = q;
      best_s = s + t * std::sqrt(len2);
    }
    s += std::sqrt(len2);
  }
  return {best, best_s};
}

// `pts` bent by `shift` at its point nearest `at`, tapered by a cosine to
// nothing `window_m` along the route either side (new vertices every
// window / 4 carry the bend; start and goal stay). Nullopt when a moved or
// new point leaves the field's area or a segment of one touches an obstacle.
std::optional<std::vector<FilletPoint>> Bend(const ObstacleField& field,
                                             const std::vector<FilletPoint>& pts, EastNorth at,
                                             EastNorth shift, double window_m) {
  const size_t n = pts.size();
  std::vector<double> cum(n, 0.0);
  for (size_t i = 1; i < n; ++i)
    cum[i] = cum[i - 1] + Distance(pts[i - 1].position, pts[i].position);
  const double s_at = NearestOnRoute(pts, at).second;
  const double total = cum[n - 1];
  auto weight = [&](double s) {
    if (s <= 0.0 || s >= total) return 0.0;  // start and goal stay
    const double x = (s - s_at) / window_m;
    return std::abs(x) < 1.0 ? 0.5 * (1.0 + std::cos(M_PI * x)) : 0.0;
  };
  std::vector<FilletPoint> out;
  out.reserve(n + 9);
  auto add_samples = [&](size_t seg, double s0, double s1) {  // in (s0, s1) of segment seg
    for (int k = 1; k <= 7; ++k) {  // k = 0 and 8: the window's ends, not bent
      const double s = s_at - window_m + k * window_m / 4.0;
      if (s <= s0 + 1.0 || s >= s1 - 1.0) continue;
      const double t = (s - cum[seg - 1]) / (cum[seg] - cum[seg - 1]);
      const EastNorth p = pts[seg - 1].position + (pts[seg].position - pts[seg - 1].position) * t;
      out.push_back({p + shift * weight(s), -1});
    }
  };
  for (size_t i = 0; i < n; ++i) {
    if (i > 0) add_samples(i, cum[i - 1], cum[i]);
    const double wgt = weight(cum[i]);
    out.push_back(wgt > 0.0 ? FilletPoint{pts[i].position + shift * wgt, -1} : pts[i]);
  }
  for (size_t i = 0; i < out.size(); ++i) {
    if (out[i].source >= 0) continue;  // an input point, its segments as they were
    const EastNorth p = out[i].position;
    if (!field.InArea(p) || field.Inside(p)) return std::nullopt;
    if (i > 0 && field.SegmentHits(out[i - 1].position, p)) return std::nullopt;
    if (i + 1 < out.size() && field.SegmentHits(p, out[i + 1].position)) return std::nullopt;
  }
  return out;
}

// `pts` with its interior vertex nearest `at` moved `push_m` outwards
// along the corner's bisector. Nullopt when the vertex is (nearly) straight
// or the moved vertex or its segments leave the area or touch an obstacle.
std::optional<std::vector<FilletPoint>> PushCorner(const ObstacleField& field,
                                                   const std::vector<FilletPoint>& pts,
                                                   EastNorth at, double push_m) {
  size_t k = 0;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i = 1; i + 1 < pts.size(); ++i) {
    if (Distance(pts[i].position, at) < best) {
      best = Distance(pts[i].position, at);
      k = i;
    }
  }
  if (k == 0) return std::nullopt;
  const EastNorth a = pts[k - 1].position, b = pts[k].position, c = pts[k + 1].position;
  const EastNorth ab = b - a, bc = c - b;
  if (!(ab.Norm() > 1e-6 && bc.Norm() > 1e-6)) return std::nullopt;
  const EastNorth out = ab * (1.0 / ab.Norm()) - bc * (1.0 / bc.Norm());
  if (!(out.Norm() > 0.1)) return std::nullopt;  // under ~6 deg of turn
  const EastNorth p = b + out * (push_m / out.Norm());
  if (!field.InArea(p) || field.Inside(p) || field.SegmentHits(a, p) || field.SegmentHits(p, c)) {
    return std::nullopt;
  }
  std::vector<FilletPoint> moved = pts;
  moved[k] = {p, -1};
  return moved;
}

}  // namespace

StatusOr<SailRepair> RepairSailedRoute(const ObstacleField& field,
                                       const std::vector<EastNorth>& route,
                                       const SailedTrack& sailed, double speed_mps,
                                       const SailRepairOptions& options, const StopToken* stop) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  SailRepair repair;
  for (size_t i = 0; i < route.size(); ++i) {
    repair.points.push_back({route[i], static_cast<int>(i)});
  }
  repair.track = sailed;
  // Widths and shifts tried in turn while a bend does not improve the track.
  constexpr double kWindowScale[] = {1.0, 2.0, 1.0, 2.0};
  constexpr double kShiftScale[] = {1.0, 1.0, 2.0, 2.0};
  bool improved = true;
  while (improved && !repair.track.Clear() && repair.track.arrived &&
         repair.sails < options.max_sails && (stop == nullptr || !stop->StopRequested())) {
    improved = false;
    const EastNorth at = repair.track.closest;
    // Away from the obstacle: the signed distance's gradient (central
    // differences over 5 m).
    const double h = 5.0;
    const EastNorth gradient{
        field.SignedDistance(at + EastNorth{h, 0}) - field.SignedDistance(at - EastNorth{h, 0}),
        field.SignedDistance(at + EastNorth{0, h}) - field.SignedDistance(at - EastNorth{0, h})};
    // Where it has none (the middle of a small obstacle, or beyond the
    // field's reach): from the track's point towards the route.
    EastNorth away = gradient;
    if (!(gradient.Norm() > 0.2 * 2.0 * h)) away = NearestOnRoute(repair.points, at).first - at;
    if (!(away.Norm() > 1e-6)) break;  // on the route itself: no side to go
    away = away * (1.0 / away.Norm());
    const double shift_m = std::max(0.0, -field.SignedDistance(at)) + options.target_clearance_m;
    // Sails a moved route; kept when its track is better.
    auto sail = [&](std::vector<FilletPoint> moved) -> absl::Status {
      if (stop != nullptr && stop->StopRequested()) return absl::OkStatus();
      std::vector<EastNorth> line;
      line.reserve(moved.size());
      for (const FilletPoint& p : moved) line.push_back(p.position);
      SEAPLAN_ASSIGN_OR_RETURN(SailedTrack track, SailRoute(line, speed_mps, &field));
      ++repair.sails;
      if (Better(track, repair.track)) {
        repair.points = std::move(moved);
        repair.track = std::move(track);
        ++repair.bends;
        improved = true;
      }
      return absl::OkStatus();
    };
    for (size_t v = 0; v < std::size(kWindowScale) && !improved; ++v) {
      for (double part = 1.0; part >= 0.25 && repair.sails < options.max_sails; part /= 2.0) {
        std::optional<std::vector<FilletPoint>> bent =
            Bend(field, repair.points, at, away * (shift_m * kShiftScale[v] * part),
                 options.window_m * kWindowScale[v]);
        if (!bent) continue;  // the bend touches an obstacle: a smaller one
        SEAPLAN_RETURN_IF_ERROR(sail(std::move(*bent)));
        break;  // sailed: the next width or shift, or the next round
      }
    }
    // No bend helps (the water beside the route is too narrow, e.g. a
    // hairpin round a shoal's tip): the corner nearest the point pushed
    // outwards along its bisector, the turn made further on.
    for (double push : {0.25, 0.5, 1.0}) {
      if (improved || repair.sails >= options.max_sails) break;
      std::optional<std::vector<FilletPoint>> pushed =
          PushCorner(field, repair.points, at, push * options.window_m);
      if (pushed) SEAPLAN_RETURN_IF_ERROR(sail(std::move(*pushed)));
    }
  }
  return repair;
}

}  // namespace seaplan::route
