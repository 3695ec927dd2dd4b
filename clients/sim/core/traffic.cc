#include "traffic.h"

namespace seaplan::sim {

Kinematics TrafficVessel::At(double t) const {
  if (track.empty()) return {};
  if (track.size() == 1) return {track[0].position, {}};
  if (t <= track.front().time_s) return {track.front().position, {}};
  for (size_t i = 0; i + 1 < track.size(); ++i) {
    const TrackPoint& a = track[i];
    const TrackPoint& b = track[i + 1];
    if (t <= b.time_s) {
      double dt = b.time_s - a.time_s;
      EastNorth v = dt > 0 ? (b.position - a.position) * (1.0 / dt) : EastNorth{};
      return {a.position + v * (t - a.time_s), v};
    }
  }
  const TrackPoint& a = track[track.size() - 2];
  const TrackPoint& b = track.back();
  double dt = b.time_s - a.time_s;
  EastNorth v = dt > 0 ? (b.position - a.position) * (1.0 / dt) : EastNorth{};
  return {b.position + v * (t - b.time_s), v};
}

}  // namespace seaplan::sim
