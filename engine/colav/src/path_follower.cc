#include "seaplan/colav/path_follower.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_format.h"

namespace seaplan::colav {

Status PathFollowerOptions::Validate() const {
  if (!(lookahead_m > 0) || !(switch_distance_m >= 0) || !(search_distance_m >= 0) ||
      !(turn_radius_m >= 0) || !(chord_s >= 0)) {
    return absl::InvalidArgumentError(
        absl::StrFormat("path follower: lookahead_m (%g) must be > 0, switch_distance_m (%g), "
                        "search_distance_m (%g), turn_radius_m (%g) and chord_s (%g) >= 0",
                        lookahead_m, switch_distance_m, search_distance_m, turn_radius_m, chord_s));
  }
  return absl::OkStatus();
}

StatusOr<PathFollower> PathFollower::Create(std::vector<EastNorth> path,
                                            const PathFollowerOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  if (path.size() < 2) {
    return absl::InvalidArgumentError(
        absl::StrFormat("path follower: %d points, need >= 2", static_cast<int>(path.size())));
  }
  for (size_t i = 0; i < path.size(); ++i) {
    if (!std::isfinite(path[i].east_m) || !std::isfinite(path[i].north_m)) {
      return absl::InvalidArgumentError(
          absl::StrFormat("path follower: point %d is not finite", static_cast<int>(i)));
    }
    if (i > 0 && (path[i] - path[i - 1]).Norm() < 1e-6) {
      return absl::InvalidArgumentError(absl::StrFormat("path follower: points %d and %d coincide",
                                                        static_cast<int>(i - 1),
                                                        static_cast<int>(i)));
    }
  }
  return PathFollower(std::move(path), options);
}

PathFollower::PathFollower(std::vector<EastNorth> path, const PathFollowerOptions& o)
    : path_(std::move(path)), options_(o) {
  start_distance_.resize(path_.size(), 0.0);
  for (size_t i = 1; i < path_.size(); ++i) {
    start_distance_[i] = start_distance_[i - 1] + (path_[i] - path_[i - 1]).Norm();
  }
  wheel_over_m_.assign(path_.size() - 1, options_.switch_distance_m);
  for (size_t i = 0; i + 2 < path_.size(); ++i) {
    const double turn = std::abs(std::remainder(
        CourseOf(path_[i + 2] - path_[i + 1]) - CourseOf(path_[i + 1] - path_[i]), 2.0 * M_PI));
    // Capped below a right angle's tangent (a sharper corner is sailed
    // round anyway).
    const double w = options_.turn_radius_m * std::tan(std::min(turn, 0.45 * M_PI) / 2.0);
    wheel_over_m_[i] = std::max(w, options_.switch_distance_m);
  }
  for (double w : wheel_over_m_) max_wheel_over_m_ = std::max(max_wheel_over_m_, w);
}

double PathFollower::Along(int leg, EastNorth p) const {
  EastNorth d = path_[leg + 1] - path_[leg];
  return (p - path_[leg]).Dot(d) / d.Norm();
}

double PathFollower::DistanceTo(int leg, EastNorth p) const {
  EastNorth d = path_[leg + 1] - path_[leg];
  double len = d.Norm();
  double s = std::clamp(Along(leg, p), 0.0, len);
  return (p - (path_[leg] + d * (s / len))).Norm();
}

EastNorth PathFollower::PointAt(double s) const {
  const int last = static_cast<int>(path_.size()) - 2;
  const int leg = std::min<int>(
      last, static_cast<int>(std::upper_bound(start_distance_.begin(), start_distance_.end(), s) -
                             start_distance_.begin()) -
                1);
  const EastNorth d = path_[leg + 1] - path_[leg];
  return path_[leg] + d * ((s - start_distance_[leg]) / d.Norm());
}

double PathFollower::Update(EastNorth here, double speed_mps) {
  const int last = static_cast<int>(path_.size()) - 2;
  // Re-choose the leg: the nearest of the legs ahead within the search
  // distance (ties go to the later leg: it is further along).
  const double limit = start_distance_[leg_ + 1] + options_.search_distance_m;
  int best = leg_;
  double best_d = DistanceTo(leg_, here);
  for (int j = leg_ + 1; j <= last && start_distance_[j] < limit; ++j) {
    double d = DistanceTo(j, here);
    if (d <= best_d) {
      best = j;
      best_d = d;
    }
  }
  leg_ = best;
  // Where the ship is abeam of the path, and how far off it, before the
  // wheel-over moves on to a leg ahead (the chord leads the corner itself).
  const double abeam_len = start_distance_[leg_ + 1] - start_distance_[leg_];
  const double s_abeam = start_distance_[leg_] + std::clamp(Along(leg_, here), 0.0, abeam_len);
  const EastNorth abeam_dir = (path_[leg_ + 1] - path_[leg_]) * (1.0 / abeam_len);
  const double off_path_m = (here - path_[leg_]).Dot({abeam_dir.north_m, -abeam_dir.east_m});
  // Past (or nearly past) the leg's end along track: the next leg.
  // The wheel-over distance may exceed a short leg (waypoints every 100 m):
  // measured along the path from where the ship is abeam of its leg.
  const double s_here = start_distance_[leg_] + Along(leg_, here);
  int next = leg_;
  for (int j = leg_; j < last && start_distance_[j + 1] - s_here <= max_wheel_over_m_; ++j) {
    if (s_here > start_distance_[j + 1] - wheel_over_m_[j]) next = j + 1;
  }
  leg_ = next;
  const EastNorth a = path_[leg_], b = path_[leg_ + 1];
  const EastNorth d = b - a;
  const double len = d.Norm();
  const double alpha = CourseOf(d);
  // Starboard normal of the leg direction (x east, y north): (dy, -dx).
  cross_track_m_ = (here - a).Dot({d.north_m / len, -d.east_m / len});
  leg_remaining_m_ = len - Along(leg_, here);
  const double chord_m = options_.chord_s * std::max(speed_mps, 0.0);
  double c = chord_m > 0 ? CourseOf(PointAt(s_abeam + chord_m) - PointAt(s_abeam)) -
                               std::atan(off_path_m / options_.lookahead_m)
                         : alpha - std::atan(cross_track_m_ / options_.lookahead_m);
  c = std::fmod(c, 2.0 * M_PI);
  return c < 0 ? c + 2.0 * M_PI : c;
}

}  // namespace seaplan::colav
