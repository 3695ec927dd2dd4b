// The mission loop's planning side as one engine facade (paper 000 fig. 5):
// plan -> refine -> parse for the first version, and update problem ->
// plan -> refine -> parse for every replan. The temporal planner and the
// route planner are callbacks, so this library depends on neither the
// search nor the route library; MissionEngine (mission_engine.h) wires the
// real ones (search_planner.h, chart_routing.h).
//
//   MissionDefinition def{domain, problem, locations};
//   NavigationLog log;
//   auto v1 = PlanInitialVersion(def, planner, router, stop, &log);
//   ... feedback ... DecideReplan(...) -> reason
//   auto v2 = Replan(def, *v1, ReplanInput{...}, planner, router, stop, &log);
//
// Thread-safety: pure functions over values; callbacks run on the caller's thread.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/mission/navigation_log.h"
#include "seaplan/mission/problem_update.h"
#include "seaplan/mission/refine.h"
#include "seaplan/mission/replan_policy.h"
#include "seaplan/mission/types.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission {

// What the temporal planner returned. solved == false with a status text
// ("unsolvable", "timeout", ...) is a result, not an error.
struct PlannerOutcome {
  bool solved = false;
  validate::Plan plan;                              // plan time (starts at 0)
  std::string status;                               // e.g. "solved", "unsolvable", "timeout"
  PlanQuality quality = PlanQuality::kSatisficing;  // when solved
};
using TemporalPlanner = std::function<StatusOr<PlannerOutcome>(
    std::string_view domain_text, std::string_view problem_text, const StopToken& stop)>;

struct MissionDefinition {
  std::string domain;
  std::string problem;
  LocationTable locations;
  RefineOptions refine;
  RegenerationOptions regeneration;
  ReplanPolicy policy;
};

// Plans, refines and parses version 1 (reason "initial plan", origin 0).
// A planner result that is not solved is FailedPrecondition with the status.
StatusOr<PlanVersion> PlanInitialVersion(const MissionDefinition& mission,
                                         const TemporalPlanner& planner, const RoutePlanner& router,
                                         const StopToken& stop, NavigationLog* log);

// A ship reported at this speed or more is under way: a replan routes its
// next move from its motion (RefineOptions::under_way), not from rest.
inline constexpr double kUnderWaySpeedMps = 1.0;

struct ReplanInput {
  std::string reason;
  double mission_time_s = 0.0;  // now; the new version starts here
  // Tasks of `current` (by id) that completed, and the one that failed or
  // was cut short (a move under way). Port operations under way must be
  // listed as completed (they are let finish), with mission_time_s set to
  // their end.
  std::vector<std::string> completed_task_ids;
  std::vector<std::string> interrupted_task_ids;
  ShipObservation ship;
};

struct ReplanResult {
  // Empty when the goal already holds (the mission is complete).
  std::optional<PlanVersion> version;
  LocationTable locations;  // including a new location the replan added
  std::string problem;      // the regenerated problem
};

// Regenerates the problem from `current` and replans from it. The new
// version is current.version + 1, its plan shifted to start at
// input.mission_time_s.
StatusOr<ReplanResult> Replan(const MissionDefinition& mission, const PlanVersion& current,
                              const LocationTable& current_locations, const ReplanInput& input,
                              const TemporalPlanner& planner, const RoutePlanner& router,
                              const StopToken& stop, NavigationLog* log);

}  // namespace seaplan::mission
