#include "seaplan/colav/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace seaplan::colav {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Relative bearing of `to` seen from `from` with heading `course`, (-pi, pi], starboard positive.
double RelativeBearing(EastNorth from, double course, EastNorth to) {
  EastNorth d = to - from;
  return WrapAngle(std::atan2(d.east_m, d.north_m) - course);
}

}  // namespace

double WrapAngle(double a) {
  a = std::fmod(a + M_PI, kTwoPi);
  if (a < 0) a += kTwoPi;
  return a - M_PI;
}

EastNorth VelocityOf(double course_rad, double speed_mps) {
  return {std::sin(course_rad) * speed_mps, std::cos(course_rad) * speed_mps};
}

double CourseOf(EastNorth v) {
  double c = std::atan2(v.east_m, v.north_m);
  return c < 0 ? c + kTwoPi : c;
}

Cpa ComputeCpa(const Kinematics& own, const Kinematics& other) {
  EastNorth p = other.position - own.position;
  EastNorth v = other.velocity - own.velocity;
  double vv = v.Dot(v);
  if (vv < 1e-12) return {0.0, p.Norm()};
  double t = -p.Dot(v) / vv;
  if (t <= 0) return {0.0, p.Norm()};
  return {t, (p + v * t).Norm()};
}

std::string_view RoleName(Role role) {
  switch (role) {
    case Role::kNone:
      return "none";
    case Role::kHeadOn:
      return "head-on";
    case Role::kCrossingGiveWay:
      return "crossing give-way";
    case Role::kCrossingStandOn:
      return "crossing stand-on";
    case Role::kOvertaking:
      return "overtaking";
    case Role::kOvertaken:
      return "overtaken";
  }
  return "none";
}

bool IsGiveWay(Role role) {
  return role == Role::kHeadOn || role == Role::kCrossingGiveWay || role == Role::kOvertaking;
}

Role ClassifyEncounter(const Kinematics& own, const Kinematics& other, const ColregOptions& o) {
  double own_speed = own.velocity.Norm(), other_speed = other.velocity.Norm();
  double own_course = own_speed > 1e-6 ? CourseOf(own.velocity) : 0.0;
  double other_course = other_speed > 1e-6 ? CourseOf(other.velocity) : 0.0;
  double bearing_to_other = RelativeBearing(own.position, own_course, other.position);
  double bearing_to_own = RelativeBearing(other.position, other_course, own.position);
  // Rule 13: a vessel coming up from more than 22.5 deg abaft the beam of
  // the other, and faster along that course.
  if (std::abs(bearing_to_own) > o.overtaking_sector_rad && own_speed > other_speed) {
    return Role::kOvertaking;
  }
  if (std::abs(bearing_to_other) > o.overtaking_sector_rad && other_speed > own_speed) {
    return Role::kOvertaken;
  }
  // Rule 14: nearly reciprocal courses, each ahead of the other.
  if (std::abs(bearing_to_other) < o.head_on_sector_rad &&
      std::abs(bearing_to_own) < o.head_on_sector_rad) {
    return Role::kHeadOn;
  }
  // Rule 15: the vessel with the other on its starboard side gives way.
  return bearing_to_other > 0 ? Role::kCrossingGiveWay : Role::kCrossingStandOn;
}

namespace {

bool SegmentsCross(EastNorth a, EastNorth b, EastNorth c, EastNorth d) {
  const double d1 = (b - a).Cross(c - a), d2 = (b - a).Cross(d - a);
  const double d3 = (d - c).Cross(a - c), d4 = (d - c).Cross(b - c);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0));
}

bool InsideRing(const std::vector<EastNorth>& ring, EastNorth p) {
  bool in = false;
  for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
    if ((ring[i].north_m > p.north_m) != (ring[j].north_m > p.north_m) &&
        p.east_m < (ring[j].east_m - ring[i].east_m) * (p.north_m - ring[i].north_m) /
                           (ring[j].north_m - ring[i].north_m) +
                       ring[i].east_m) {
      in = !in;
    }
  }
  return in;
}

}  // namespace

double PointSegmentDistance(EastNorth p, EastNorth a, EastNorth b) {
  const EastNorth d = b - a;
  const double len2 = d.Dot(d);
  const double t = len2 > 0 ? std::clamp((p - a).Dot(d) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + d * t)).Norm();
}

double LandClearance(const std::vector<std::vector<EastNorth>>& rings, EastNorth a, EastNorth b) {
  double best = std::numeric_limits<double>::infinity();
  for (const std::vector<EastNorth>& ring : rings) {
    if (ring.size() < 3) continue;
    if (InsideRing(ring, a)) return 0.0;
    for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const EastNorth c = ring[j], d = ring[i];
      if (SegmentsCross(a, b, c, d)) return 0.0;
      best = std::min({best, PointSegmentDistance(a, c, d), PointSegmentDistance(b, c, d),
                       PointSegmentDistance(c, a, b), PointSegmentDistance(d, a, b)});
    }
  }
  return best;
}

LandIndex::LandIndex(const std::vector<std::vector<EastNorth>>& rings, double cell_m)
    : cell_m_(cell_m) {
  for (const std::vector<EastNorth>& ring : rings) {
    if (ring.size() < 2) continue;
    for (size_t i = 0, j = ring.size() - 1; i < ring.size(); j = i++) {
      const EastNorth c = ring[j], d = ring[i];
      const int32_t id = static_cast<int32_t>(edges_.size());
      edges_.push_back({c, d});
      const int64_t i0 = static_cast<int64_t>(std::floor(std::min(c.east_m, d.east_m) / cell_m_));
      const int64_t i1 = static_cast<int64_t>(std::floor(std::max(c.east_m, d.east_m) / cell_m_));
      const int64_t j0 = static_cast<int64_t>(std::floor(std::min(c.north_m, d.north_m) / cell_m_));
      const int64_t j1 = static_cast<int64_t>(std::floor(std::max(c.north_m, d.north_m) / cell_m_));
      for (int64_t x = i0; x <= i1; ++x) {
        for (int64_t y = j0; y <= j1; ++y) cells_[Key(x, y)].push_back(id);
      }
      max_i_ = edges_.size() == 1 ? i1 : std::max(max_i_, i1);
    }
  }
  seen_.assign(edges_.size(), -1);
}

double LandIndex::Clearance(EastNorth a, EastNorth b, double limit_m) const {
  double best = limit_m;
  if (edges_.empty()) return best;
  ++query_;
  const int64_t i0 =
      static_cast<int64_t>(std::floor((std::min(a.east_m, b.east_m) - limit_m) / cell_m_));
  const int64_t i1 =
      static_cast<int64_t>(std::floor((std::max(a.east_m, b.east_m) + limit_m) / cell_m_));
  const int64_t j0 =
      static_cast<int64_t>(std::floor((std::min(a.north_m, b.north_m) - limit_m) / cell_m_));
  const int64_t j1 =
      static_cast<int64_t>(std::floor((std::max(a.north_m, b.north_m) + limit_m) / cell_m_));
  for (int64_t x = i0; x <= i1; ++x) {
    for (int64_t y = j0; y <= j1; ++y) {
      auto it = cells_.find(Key(x, y));
      if (it == cells_.end()) continue;
      for (int32_t id : it->second) {
        if (seen_[static_cast<size_t>(id)] == query_) continue;
        seen_[static_cast<size_t>(id)] = query_;
        const auto& [c, d] = edges_[static_cast<size_t>(id)];
        if (SegmentsCross(a, b, c, d)) return 0.0;
        best = std::min({best, PointSegmentDistance(a, c, d), PointSegmentDistance(b, c, d),
                         PointSegmentDistance(c, a, b), PointSegmentDistance(d, a, b)});
      }
    }
  }
  return best;
}

PathApproach PathAheadClosestApproach(const std::vector<EastNorth>& path, size_t next,
                                      EastNorth position, double speed_mps, const Kinematics& other,
                                      double horizon_s, double step_s, double start_speed_mps,
                                      double acceleration_mps2) {
  PathApproach best{(other.position - position).Norm(), 0.0};
  if (!(speed_mps > 0) || !(step_s > 0)) return best;
  EastNorth at = position;
  size_t target = next;
  const bool ramp = start_speed_mps >= 0 && acceleration_mps2 > 0;
  double speed = ramp ? start_speed_mps : speed_mps;
  for (double t = step_s; t <= horizon_s + 1e-9; t += step_s) {
    double next_speed = speed;
    if (ramp) {
      const double dv =
          std::clamp(speed_mps - speed, -acceleration_mps2 * step_s, acceleration_mps2 * step_s);
      next_speed = speed + dv;
    }
    double left = 0.5 * (speed + next_speed) * step_s;  // walk along the path, past its points
    speed = next_speed;
    while (left > 0 && target < path.size()) {
      const EastNorth d = path[target] - at;
      const double len = d.Norm();
      if (len <= left) {
        at = path[target];
        left -= len;
        ++target;
      } else {
        at = at + d * (left / len);
        left = 0;
      }
    }
    const double dist = (other.position + other.velocity * t - at).Norm();
    if (dist < best.distance_m) best = {dist, t};
  }
  return best;
}

bool LandIndex::Inside(EastNorth p) const {
  if (edges_.empty()) return false;
  ++query_;
  bool in = false;
  const int64_t j = static_cast<int64_t>(std::floor(p.north_m / cell_m_));
  for (int64_t i = static_cast<int64_t>(std::floor(p.east_m / cell_m_)); i <= max_i_; ++i) {
    auto it = cells_.find(Key(i, j));
    if (it == cells_.end()) continue;
    for (int32_t id : it->second) {
      if (seen_[static_cast<size_t>(id)] == query_) continue;
      seen_[static_cast<size_t>(id)] = query_;
      const auto& [c, d] = edges_[static_cast<size_t>(id)];
      if ((c.north_m > p.north_m) != (d.north_m > p.north_m) &&
          p.east_m <
              (d.east_m - c.east_m) * (p.north_m - c.north_m) / (d.north_m - c.north_m) + c.east_m)
        in = !in;
    }
  }
  return in;
}

double LandIndex::SignedClearance(EastNorth p, double limit_m) const {
  const double d = Clearance(p, p, limit_m);
  return Inside(p) ? -d : d;
}

}  // namespace seaplan::colav
