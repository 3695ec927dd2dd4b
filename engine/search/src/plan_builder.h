// From a search path to a printed, validated plan.
//
// The path's events are scheduled at their earliest STN times (Timeline),
// start/end events are paired into steps (start time, duration), and the
// plan goes through validate::FormatPlan -> ParsePlan -> ValidatePlan, so
// what is returned is exactly what was validated.
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

// Schedules `events` and validates the printed plan; nullopt (and `error`
// set) when the plan does not validate, which is a planner bug.
std::optional<BuiltPlan> BuildValidatedPlan(const SnapTask& task, std::span<const Event> events,
                                            Timeline& timeline, double epsilon_s,
                                            std::string* error);

}  // namespace seaplan::search
