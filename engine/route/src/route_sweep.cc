#include "seaplan/route/route_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "absl/strings/str_cat.h"
#include "seaplan/chart/alternatives.h"

namespace seaplan::route {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// SplitMix64: a fixed generator, so a seed gives the same pairs everywhere
// (std:: distributions are implementation-defined).
class PairRng {
 public:
  explicit PairRng(uint64_t seed) : state_(seed) {}
  double Uniform() { return static_cast<double>(Next() >> 11) * 0x1.0p-53; }

 private:
  uint64_t Next() {
    uint64_t x = (state_ += 0x9E3779B97F4A7C15ull);
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
    return x ^ (x >> 31);
  }
  uint64_t state_;
};

}  // namespace

absl::Status SweepOptions::Validate() const {
  if (pairs < 1 || pairs > 100000) {
    return absl::InvalidArgumentError(absl::StrCat("pairs must be in [1, 100000], got ", pairs));
  }
  if (!(min_pair_distance_fraction >= 0.0 && min_pair_distance_fraction < 1.0)) {
    return absl::InvalidArgumentError("min_pair_distance_fraction must be in [0, 1)");
  }
  if (draws_per_pair < 1) return absl::InvalidArgumentError("draws_per_pair must be >= 1");
  return absl::OkStatus();
}

double Percentile(std::vector<double> values, double fraction) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t rank = static_cast<size_t>(std::ceil(fraction * static_cast<double>(values.size())));
  return values[std::clamp<size_t>(rank, 1, values.size()) - 1];
}

StatusOr<SweepResult> RunRouteSweep(const RoutePlanner& planner, const chart::ObstacleMap& map,
                                    const Environment& env, const SweepOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  const chart::LocalBox box = map.summary().coverage;
  const double width = box.max.east_m - box.min.east_m, height = box.max.north_m - box.min.north_m;
  const double min_distance = options.min_pair_distance_fraction * std::hypot(width, height);
  PairRng rng(options.seed);
  auto draw = [&]() -> EastNorth {
    return {box.min.east_m + rng.Uniform() * width, box.min.north_m + rng.Uniform() * height};
  };
  auto navigable = [&](EastNorth p) {
    return map.Covers(p) && !planner.field().Inside({p.east_m, p.north_m});
  };

  SweepResult out;
  out.margin_m = map.summary().options.safety_buffer_m;
  chart::ObstacleQuery query(map);
  const int64_t max_draws = static_cast<int64_t>(options.pairs) * options.draws_per_pair;
  int64_t draws = 0;
  while (static_cast<int>(out.pairs.size()) < options.pairs) {
    PairOutcome pair;
    bool found = false;
    while (!found && draws < max_draws) {
      ++draws;
      pair.from = draw();
      pair.to = draw();
      found = navigable(pair.from) && navigable(pair.to) &&
              std::hypot(pair.to.east_m - pair.from.east_m, pair.to.north_m - pair.from.north_m) >=
                  min_distance;
    }
    if (!found) {
      return absl::FailedPreconditionError(
          absl::StrCat("only ", out.pairs.size(), " navigable pairs in ", draws, " draws"));
    }
    Clock::time_point t = Clock::now();
    auto level1 = chart::PlanAlternatives(map, pair.from, pair.to, planner.options().alternatives);
    pair.level1_wall_s = Since(t);
    pair.level1_connected = level1.ok() && !level1->alternatives.empty();
    if (!pair.level1_connected) {
      pair.error = level1.ok() ? "Level 1 found none" : std::string(level1.status().message());
      out.pairs.push_back(std::move(pair));
      continue;
    }
    ++out.connected;
    t = Clock::now();
    auto routed = planner.Plan(pair.from, pair.to, env);
    pair.route_wall_s = Since(t);
    if (!routed.ok() || routed->chosen < 0) {
      pair.error = routed.ok() ? "no route chosen" : std::string(routed.status().message());
      out.pairs.push_back(std::move(pair));
      continue;
    }
    pair.routed = true;
    ++out.routed;
    std::vector<EastNorth> line;
    for (const RouteWaypoint& w : routed->alternatives[routed->chosen].waypoints) {
      line.push_back(w.local);
    }
    pair.filleted_turns = routed->alternatives[routed->chosen].filleted_turns;
    pair.tightened_turns = routed->alternatives[routed->chosen].tightened_turns;
    pair.warnings = routed->alternatives[routed->chosen].warnings;
    if (!pair.warnings.empty()) ++out.with_warnings;
    pair.waypoints = static_cast<int>(line.size());
    pair.route = line;
    const std::optional<chart::Clearance> clearance = query.UnbufferedClearance(line);
    if (clearance) {
      pair.clearance_m = clearance->distance_m;
      pair.closest_route_point = clearance->route_point;
    } else {
      // No unbuffered geometry: the buffered obstacles are the only truth.
      out.clearance_exact = false;
      pair.clearance_m = query.PolylineHits(line) ? 0.0 : out.margin_m;
    }
    // 1 mm of slack for floating-point rounding of the GEOS distance.
    if (pair.clearance_m < out.margin_m - 1e-3) ++out.within_margin;
    out.pairs.push_back(std::move(pair));
  }
  return out;
}

}  // namespace seaplan::route
