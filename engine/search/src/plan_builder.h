// From a search path to a printed, validated plan.
//
// The path's events are scheduled at their earliest STN times (Timeline),
// start/end events are paired into steps (start time, duration), and the
// plan goes through validate::FormatPlan -> ParsePlan -> ValidatePlan, so
// what is returned is exactly what was validated. The schedule is then lifted
// to a partial order and rescheduled (plan_lifting.h); that plan replaces the
// first when it validates as printed and is not longer.
#pragma once

#include <optional>
#include <span>
#include <string>

#include "seaplan/validate/plan.h"
#include "seaplan/validate/validator.h"
#include "snap_task.h"
#include "timeline.h"

namespace seaplan::search {

struct BuiltPlan {
  validate::Plan plan;
  double makespan_s = 0;
  std::optional<double> metric_value;
};

// One validate::Validator per task (the action index is built once, not per
// plan). Falls back to one-shot ValidatePlan if the validator cannot be made.
class PlanValidator {
 public:
  // `task` must outlive this object.
  PlanValidator(const task::GroundTask& task, double epsilon_s);
  validate::ValidationResult Validate(const validate::Plan& plan) const;
  double epsilon_s() const { return options_.epsilon_s; }

 private:
  const task::GroundTask& task_;
  validate::ValidationOptions options_;
  std::optional<validate::Validator> validator_;
};

// Schedules `events` and validates the printed plan; nullopt (and `error`
// set) when the plan does not validate, which is a planner bug.
std::optional<BuiltPlan> BuildValidatedPlan(const SnapTask& task, std::span<const Event> events,
                                            Timeline& timeline, const PlanValidator& validator,
                                            std::string* error);

}  // namespace seaplan::search
