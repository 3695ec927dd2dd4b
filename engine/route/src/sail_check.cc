#include "seaplan/route/sail_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

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

}  // namespace seaplan::route
