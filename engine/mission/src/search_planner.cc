#include "seaplan/mission/search_planner.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace seaplan::mission {
namespace {

bool Solved(search::PlanStatus s) {
  return s == search::PlanStatus::kSolvedSatisficing || s == search::PlanStatus::kSolvedOptimally;
}

}  // namespace

TemporalPlanner SearchPlanner(const search::PlannerOptions& options, PlanningPhase phase) {
  return [options, phase](std::string_view domain, std::string_view problem,
                          const StopToken& stop) -> StatusOr<PlannerOutcome> {
    search::PlanResult r;
    if (phase == PlanningPhase::kReplan && options.anytime) {
      search::PlannerOptions first = options;
      first.anytime = false;
      r = search::Solve(domain, problem, first, stop);
      if (r.status == search::PlanStatus::kSolvedSatisficing && !stop.StopRequested()) {
        search::PlannerOptions improve = options;
        if (options.max_expansions > 0) {
          // Effort instead of time, so that the replan is the same on any
          // machine; the time limit stays the safety net.
          improve.max_expansions = std::min<std::uint64_t>(
              options.max_expansions, std::max<std::uint64_t>(1, 2 * r.stats.expanded));
        } else {
          improve.time_limit_s = std::min(
              options.time_limit_s,
              std::clamp(2.0 * r.stats.search_time_s, kReplanImproveMinS, kReplanImproveMaxS));
        }
        search::PlanResult better = search::Solve(domain, problem, improve, stop);
        if (Solved(better.status) && better.makespan_s < r.makespan_s - 1e-9) r = std::move(better);
      }
    } else {
      r = search::Solve(domain, problem, options, stop);
    }
    if (r.status == search::PlanStatus::kError) return absl::InvalidArgumentError(r.message);
    PlannerOutcome out;
    out.solved = Solved(r.status);
    out.plan = std::move(r.plan);
    out.status = search::ToString(r.status);
    out.quality = r.status == search::PlanStatus::kSolvedOptimally ? PlanQuality::kOptimal
                                                                   : PlanQuality::kSatisficing;
    return out;
  };
}

}  // namespace seaplan::mission
