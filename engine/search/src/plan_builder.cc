#include "plan_builder.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "plan_lifting.h"
#include "seaplan/common/log.h"

namespace seaplan::search {

PlanValidator::PlanValidator(const task::GroundTask& task, double epsilon_s) : task_(task) {
  options_.epsilon_s = epsilon_s;
  // Non-owning: the planner's task outlives the run (aliasing constructor).
  std::shared_ptr<const task::GroundTask> view(std::shared_ptr<void>(), &task);
  auto created = validate::Validator::Create(std::move(view), options_);
  if (created.ok()) validator_.emplace(std::move(*created));
}

validate::ValidationResult PlanValidator::Validate(const validate::Plan& plan) const {
  if (validator_) return validator_->Validate(plan);
  return validate::ValidatePlan(task_, plan, options_);
}

namespace {

// Pairs start/end events into printed steps at `times`, prints, parses back
// and validates; nullopt (and `error`) when anything fails.
std::optional<BuiltPlan> PlanAtTimes(const SnapTask& task, std::span<const Event> events,
                                     std::span<const double> times, const PlanValidator& validator,
                                     std::string* error) {
  std::vector<std::pair<double, validate::PlanStep>> steps;
  std::vector<std::int32_t> open(static_cast<std::size_t>(task.num_actions()), -1);
  for (std::size_t i = 0; i < events.size(); ++i) {
    const Event& e = events[i];
    if (e.is_til()) continue;
    const SnapAction& snap = task.snap(e.snap);
    const task::Action& action = task.task().actions[snap.action];
    if (!snap.is_end) {
      if (!action.is_durative) {
        validate::PlanStep step;
        step.start_s = times[i];
        step.name = action.name;
        step.args = action.args;
        step.duration_s = 0;
        steps.emplace_back(step.start_s, std::move(step));
      } else {
        open[snap.action] = static_cast<std::int32_t>(i);
      }
      continue;
    }
    const std::int32_t start = open[snap.action];
    if (start < 0) {
      *error = "end event without start";
      return std::nullopt;
    }
    open[snap.action] = -1;
    validate::PlanStep step;
    step.start_s = times[static_cast<std::size_t>(start)];
    double duration = times[i] - step.start_s;
    const Event& se = events[static_cast<std::size_t>(start)];
    // Keep fixed durations exact (the STN sums may differ in the last bit).
    if (se.min_duration_s == se.max_duration_s || std::abs(duration - se.min_duration_s) < 1e-7) {
      duration = se.min_duration_s;
    } else if (std::abs(duration - se.max_duration_s) < 1e-7) {
      duration = se.max_duration_s;
    }
    step.duration_s = duration;
    step.name = action.name;
    step.args = action.args;
    steps.emplace_back(step.start_s, std::move(step));
  }
  std::stable_sort(steps.begin(), steps.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  validate::Plan plan;
  for (auto& [t, step] : steps) plan.steps.push_back(std::move(step));

  const std::string text = validate::FormatPlan(plan);
  auto parsed = validate::ParsePlan(text);
  if (!parsed.ok()) {
    *error = "printed plan does not parse: " + std::string(parsed.status().message());
    return std::nullopt;
  }
  const validate::ValidationResult result = validator.Validate(*parsed);
  if (!result.valid) {
    *error = result.ToString() + "\n" + text;
    return std::nullopt;
  }
  BuiltPlan built;
  built.plan = std::move(*parsed);
  built.makespan_s = result.makespan_s;
  built.metric_value = result.metric_value;
  return built;
}

}  // namespace

std::optional<BuiltPlan> BuildValidatedPlan(const SnapTask& task, std::span<const Event> events,
                                            Timeline& timeline, const PlanValidator& validator,
                                            std::string* error) {
  if (!timeline.Build(events)) {
    *error = "schedule of the plan is inconsistent";
    return std::nullopt;
  }
  std::vector<double> times(events.size());
  for (std::size_t i = 0; i < events.size(); ++i) times[i] = timeline.EventTime(i);
  auto built = PlanAtTimes(task, events, times, validator, error);
  if (!built) return std::nullopt;
  // Post-processing: the partial-order lift, kept only when it validates as
  // printed and is not longer (see plan_lifting.h).
  if (auto lifted_times = LiftAndReschedule(task, events, times, validator.epsilon_s(),
                                            timeline.bound_concurrency())) {
    std::string lift_error;
    auto lifted = PlanAtTimes(task, events, *lifted_times, validator, &lift_error);
    if (lifted && lifted->makespan_s <= built->makespan_s) return lifted;
    if (!lifted) log::Debug("planner: lifted schedule rejected: {}", lift_error);
  }
  return built;
}

}  // namespace seaplan::search
