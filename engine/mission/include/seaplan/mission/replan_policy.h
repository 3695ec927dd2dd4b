// When does feedback from the ship require a new plan (paper 000 fig. 5,
// "plan still valid?"): a failed task, a position off the route by more than
// a threshold, fuel under a threshold with no refuelling left in the plan,
// a task finishing much later than planned, or an explicit request (the
// RequestReplan RPC, which needs no decision).
#pragma once

#include <optional>
#include <set>
#include <string>

#include "seaplan/common/status.h"
#include "seaplan/mission/types.h"

namespace seaplan::mission {

struct ReplanPolicy {
  double fuel_threshold_fraction = 0.3;  // replan when fuel <= this
  double position_deviation_m = 200.0;   // off the current move's route by more
  // While the ship reports collision avoidance active (manoeuvring for
  // traffic or returning to its route after it) it is off its route on
  // purpose and its own path follower is taking it back; a route replanned
  // then would start where a ship under way can no longer follow it (behind
  // it, round an obstacle it is already passing). The position trigger then
  // waits until the deviation exceeds this factor times position_deviation_m.
  double avoidance_deviation_factor = 3.0;
  double delay_tolerance_s = 120.0;  // a task completes later than planned by more
  // The domain tracks fuel itself (a numeric fuel fluent, DomainPlansFuel):
  // the plan already schedules the refuelling stops, so low fuel triggers a
  // replan only when the tank is empty before a task that needs fuel (the
  // plan did not hold; DecideReplan).
  bool fuel_planned = false;
  Status Validate() const;
};

enum class FeedbackKind {
  kTaskStarted,
  kTaskCompleted,
  kTaskFailed,
  kPosition,
  kGnssFault,
  kMachineryFault,
  kOperatorChange,
  kCollisionAvoidance,
};

struct Feedback {
  FeedbackKind kind = FeedbackKind::kPosition;
  std::string task_id;
  int plan_version = 0;
  double mission_time_s = 0.0;
  std::optional<EastNorth> position;
  std::optional<double> fuel_fraction;
  std::string detail;
  // The ship is manoeuvring for traffic or rejoining its route after a
  // manoeuvre (its collision avoidance says so with each report).
  bool collision_avoidance_active = false;
};

// Fuel at or below the threshold, with a tolerance of 1e-6 of the tank: a
// percentage model that sums 10 % and 15 % steps in binary floating point
// reports 0.30000000000000004 for 30 %, which must count as "at 30 %". The
// replan decision and the problem regeneration (RegenerationOptions) both use
// this, so a replan for low fuel always plans with (no_fuel ?v).
bool FuelAtOrBelow(double fuel_fraction, double threshold_fraction);

// Returns the reason for a replan, or nullopt when the current version still
// holds. `active_task` is the task the feedback is about or the task under
// way (may be null). Fuel: only when no refuel task remains and a move does
// (otherwise the plan already handles it, or nothing is left to burn fuel
// on); this is what keeps a plan with fuel planned up front (numeric
// fluents) from being replanned for fuel. With fuel planned, only an empty
// tank that a remaining task is to draw on before the next refuel ends (a
// port operation not yet started by the plan's time of the report, a move
// not yet arrived): the domain lets a plan take the last of the fuel and
// refuel next. A task "remains" when it is not in
// `completed_task_ids` (with a list given; the task this feedback completes
// counts as completed), or, without a list, when its planned end is not
// before the feedback time (a late ship makes that guess wrong: prefer the
// list).
// Feedback about an older plan version never triggers a replan.
std::optional<std::string> DecideReplan(const Feedback& feedback, const PlanVersion& current,
                                        const Task* active_task, const ReplanPolicy& policy,
                                        const std::set<std::string>* completed_task_ids = nullptr);

}  // namespace seaplan::mission
