#include "seaplan/mission/mission_planner.h"

#include <algorithm>
#include <map>

#include "absl/strings/str_cat.h"
#include "seaplan/common/log.h"
#include "seaplan/mission/tasks.h"

namespace seaplan::mission {
namespace {

// Plan -> refine -> parse, shared by the first version and every replan.
StatusOr<PlanVersion> PlanRefineParse(const MissionDefinition& mission, std::string_view problem,
                                      const LocationTable& locations, int version,
                                      std::string reason, double origin_s,
                                      const RefineOptions& refine, const TemporalPlanner& planner,
                                      const RoutePlanner& router, const StopToken& stop,
                                      NavigationLog* log) {
  if (!planner) return absl::InvalidArgumentError("mission: no temporal planner given");
  if (log) log->Add(origin_s, messages::kComputingPlan);
  SEAPLAN_ASSIGN_OR_RETURN(PlannerOutcome outcome, planner(mission.domain, problem, stop));
  if (!outcome.solved) {
    return absl::FailedPreconditionError(
        absl::StrCat("the temporal planner found no plan (", outcome.status, ")"));
  }
  // Mission time: the planner's plan starts at 0.
  validate::Plan shifted = outcome.plan;
  for (validate::PlanStep& s : shifted.steps) s.start_s += origin_s;
  if (log) log->Add(origin_s, messages::kRefiningPlan);
  SEAPLAN_ASSIGN_OR_RETURN(RefinedPlan refined,
                           RefinePlan(mission.domain, problem, shifted, locations, router, refine));
  if (log) log->Add(origin_s, messages::kParsingPlan);
  PlanVersion v;
  v.version = version;
  v.reason = std::move(reason);
  v.mission_time_origin_s = origin_s;
  v.makespan_s = refined.plan.steps.empty() ? origin_s : refined.makespan_s;
  v.tasks = ParseTasks(refined, locations, refine.moves, version);
  v.plan = std::move(refined.plan);
  v.problem = std::string(problem);
  v.quality = outcome.quality;
  log::Info("mission: version {} ({}): {} tasks, makespan {:.1f} s", v.version, v.reason,
            v.tasks.size(), v.makespan_s);
  return v;
}

}  // namespace

StatusOr<PlanVersion> PlanInitialVersion(const MissionDefinition& mission,
                                         const TemporalPlanner& planner, const RoutePlanner& router,
                                         const StopToken& stop, NavigationLog* log) {
  SEAPLAN_RETURN_IF_ERROR(mission.refine.Validate());
  SEAPLAN_RETURN_IF_ERROR(mission.policy.Validate());
  return PlanRefineParse(mission, mission.problem, mission.locations, 1, "initial plan", 0.0,
                         mission.refine, planner, router, stop, log);
}

StatusOr<ReplanResult> Replan(const MissionDefinition& mission, const PlanVersion& current,
                              const LocationTable& current_locations, const ReplanInput& input,
                              const TemporalPlanner& planner, const RoutePlanner& router,
                              const StopToken& stop, NavigationLog* log) {
  std::map<std::string, const Task*> by_id;
  for (const Task& t : current.tasks) by_id[t.id] = &t;
  std::vector<validate::PlanStep> completed, interrupted;
  for (const std::string& id : input.completed_task_ids) {
    auto it = by_id.find(id);
    if (it == by_id.end()) {
      return absl::InvalidArgumentError(
          absl::StrCat("replan: completed task '", id, "' is not in version ", current.version));
    }
    completed.push_back(it->second->action);
  }
  for (const std::string& id : input.interrupted_task_ids) {
    auto it = by_id.find(id);
    if (it == by_id.end()) {
      return absl::InvalidArgumentError(
          absl::StrCat("replan: interrupted task '", id, "' is not in version ", current.version));
    }
    interrupted.push_back(it->second->action);
  }
  if (log) log->Add(input.mission_time_s, messages::kUpdatingProblem);
  SEAPLAN_ASSIGN_OR_RETURN(
      RegeneratedProblem regen,
      RegenerateProblem(mission.domain, current.problem, completed, interrupted, current_locations,
                        input.ship, mission.regeneration));
  ReplanResult result;
  result.locations = regen.locations;
  result.problem = regen.problem_text;
  if (regen.goal_satisfied) {
    if (log) log->Add(input.mission_time_s, messages::kMissionCompleted);
    return result;
  }
  // A ship under way (a replan during a move) leaves where it is the way it
  // is going; one at rest (or nearly) turns where it is.
  RefineOptions refine = mission.refine;
  if (input.ship.motion && input.ship.motion->speed_mps >= kUnderWaySpeedMps) {
    refine.under_way = RefineOptions::UnderWayStart{regen.ship_location, *input.ship.motion};
  }
  SEAPLAN_ASSIGN_OR_RETURN(
      PlanVersion v,
      PlanRefineParse(mission, regen.problem_text, regen.locations, current.version + 1,
                      input.reason, input.mission_time_s, refine, planner, router, stop, log));
  if (log) log->Add(input.mission_time_s, messages::kReplanDone);
  result.version = std::move(v);
  return result;
}

}  // namespace seaplan::mission
