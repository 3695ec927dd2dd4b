#include "seaplan/mission/replan_policy.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "seaplan/mission/tasks.h"

namespace seaplan::mission {

Status ReplanPolicy::Validate() const {
  if (!(fuel_threshold_fraction >= 0 && fuel_threshold_fraction <= 1)) {
    return absl::InvalidArgumentError("replan policy: fuel_threshold_fraction must be in [0, 1]");
  }
  if (!(position_deviation_m > 0)) {
    return absl::InvalidArgumentError("replan policy: position_deviation_m must be > 0");
  }
  if (!(avoidance_deviation_factor >= 1)) {
    return absl::InvalidArgumentError("replan policy: avoidance_deviation_factor must be >= 1");
  }
  if (!(delay_tolerance_s > 0)) {
    return absl::InvalidArgumentError("replan policy: delay_tolerance_s must be > 0");
  }
  return absl::OkStatus();
}

bool FuelAtOrBelow(double fuel_fraction, double threshold_fraction) {
  return fuel_fraction <= threshold_fraction + 1e-6;
}

std::optional<std::string> DecideReplan(const Feedback& feedback, const PlanVersion& current,
                                        const Task* active_task, const ReplanPolicy& policy,
                                        const std::set<std::string>* completed_task_ids) {
  if (feedback.plan_version != 0 && feedback.plan_version != current.version) return std::nullopt;
  if (feedback.kind == FeedbackKind::kTaskFailed) {
    std::string what = active_task ? absl::StrCat(active_task->id, " ", active_task->action.name)
                                   : feedback.task_id;
    std::string reason = absl::StrCat("task ", what, " failed");
    if (!feedback.detail.empty()) absl::StrAppend(&reason, ": ", feedback.detail);
    return reason;
  }
  if (feedback.kind == FeedbackKind::kGnssFault || feedback.kind == FeedbackKind::kMachineryFault ||
      feedback.kind == FeedbackKind::kOperatorChange) {
    // Reported on their own these are information; the executor reports the
    // task failure (or the deviation) that makes the plan invalid.
  }
  if (feedback.position && active_task && active_task->kind == TaskKind::kMove &&
      active_task->route && feedback.kind != FeedbackKind::kTaskCompleted) {
    const double off = CrossTrackDistance(*active_task->route, *feedback.position);
    const double limit_m = feedback.collision_avoidance_active
                               ? policy.position_deviation_m * policy.avoidance_deviation_factor
                               : policy.position_deviation_m;
    if (off > limit_m) {
      return absl::StrFormat(
          "position %.0f m off the route of %s (limit %.0f m%s)", off, active_task->id, limit_m,
          feedback.collision_avoidance_active ? " during collision avoidance" : "");
    }
  }
  // Whether a task of the current version is still to do (header).
  const auto remains = [&](const Task& t) {
    if (completed_task_ids != nullptr) {
      if (completed_task_ids->contains(t.id)) return false;
    } else if (t.end_s() < feedback.mission_time_s - 1e-6) {
      return false;
    }
    if (feedback.kind == FeedbackKind::kTaskCompleted &&
        (t.id == feedback.task_id || (active_task && t.id == active_task->id))) {
      return false;
    }
    return true;
  };
  if (policy.fuel_planned && feedback.fuel_fraction &&
      FuelAtOrBelow(*feedback.fuel_fraction, 0.0)) {
    // The domain lets an action take the last of the fuel, so a plan may
    // empty the tank on purpose and refuel next: the plan did not hold only
    // when fuel is spent before the next refill. A port operation pays when
    // it starts (those started by the plan's time of this report have paid),
    // a move when it arrives, as the executor charges them (fuel.h); a
    // refuel fills the tank when it ends.
    double plan_now_s = feedback.mission_time_s;
    if (active_task != nullptr) {
      plan_now_s = feedback.kind == FeedbackKind::kTaskCompleted ? active_task->end_s()
                                                                 : active_task->start_s;
    }
    double refill_s = std::numeric_limits<double>::infinity();
    double next_use_s = std::numeric_limits<double>::infinity();
    for (const Task& t : current.tasks) {
      if (!remains(t)) continue;
      if (t.kind == TaskKind::kRefuel) {
        refill_s = std::min(refill_s, t.end_s());
      } else if (t.kind == TaskKind::kMove) {
        next_use_s = std::min(next_use_s, t.end_s());
      } else if (t.kind != TaskKind::kOther && t.start_s > plan_now_s + 1e-6) {
        next_use_s = std::min(next_use_s, t.start_s);
      }
    }
    if (next_use_s < refill_s - 1e-6) {
      return std::string("fuel tank empty although fuel was planned");
    }
  }
  if (!policy.fuel_planned && feedback.fuel_fraction &&
      FuelAtOrBelow(*feedback.fuel_fraction, policy.fuel_threshold_fraction)) {
    bool refuel_left = false, move_left = false;
    for (const Task& t : current.tasks) {
      if (!remains(t)) continue;
      refuel_left |= t.kind == TaskKind::kRefuel;
      move_left |= t.kind == TaskKind::kMove;
    }
    if (!refuel_left && move_left) {
      return absl::StrFormat("fuel %.0f%% <= %.0f%%", *feedback.fuel_fraction * 100,
                             policy.fuel_threshold_fraction * 100);
    }
  }
  if (feedback.kind == FeedbackKind::kTaskCompleted && active_task &&
      feedback.mission_time_s > active_task->end_s() + policy.delay_tolerance_s) {
    return absl::StrFormat("task %s completed %.0f s late (tolerance %.0f s)", active_task->id,
                           feedback.mission_time_s - active_task->end_s(),
                           policy.delay_tolerance_s);
  }
  return std::nullopt;
}

}  // namespace seaplan::mission
