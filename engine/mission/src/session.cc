#include "seaplan/mission/session.h"

#include <algorithm>
#include <set>

#include "absl/strings/numbers.h"
#include "absl/strings/str_cat.h"
#include "absl/strings/str_split.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission {

FeedbackOutcome OnFeedback(const ReplanPolicy& policy, const PlanVersion& current,
                           const std::vector<std::string>& completed_task_ids,
                           const Feedback& feedback) {
  FeedbackOutcome out;
  out.completed_task_ids = completed_task_ids;
  const Task* task = nullptr;
  if (!feedback.task_id.empty()) {
    for (const Task& t : current.tasks) {
      if (t.id == feedback.task_id) task = &t;
    }
  }
  std::set<std::string> done(completed_task_ids.begin(), completed_task_ids.end());
  if (feedback.kind == FeedbackKind::kTaskCompleted && !feedback.task_id.empty() &&
      !done.contains(feedback.task_id)) {
    out.completed_task_ids.push_back(feedback.task_id);
    done.insert(feedback.task_id);
    out.completed_changed = true;
  }
  if (task) {
    if (feedback.kind == FeedbackKind::kTaskStarted)
      out.log_messages.push_back(TaskStartedMessage(task->kind));
    if (feedback.kind == FeedbackKind::kTaskCompleted)
      out.log_messages.push_back(TaskCompletedMessage(task->kind));
    if (feedback.kind == FeedbackKind::kTaskFailed)
      out.log_messages.push_back(TaskFailedMessage(task->kind));
  }
  if (feedback.kind == FeedbackKind::kCollisionAvoidance)
    out.log_messages.emplace_back(messages::kPotentialCollision);
  if (feedback.kind == FeedbackKind::kTaskCompleted && !current.tasks.empty() &&
      std::all_of(current.tasks.begin(), current.tasks.end(),
                  [&](const Task& t) { return done.contains(t.id); })) {
    out.mission_completed = true;
    out.log_messages.emplace_back(messages::kMissionCompleted);
    return out;
  }
  // The move under way when the feedback is not about a specific task.
  const Task* active = task;
  if (!active) {
    for (const Task& t : current.tasks) {
      if (t.kind == TaskKind::kMove && !done.contains(t.id) &&
          t.start_s <= feedback.mission_time_s + 1e-6) {
        active = &t;
      }
    }
  }
  // `done` holds the task this report completes: a refuel still ahead is
  // "left" whatever its planned time (a late ship is past it on paper).
  out.replan_reason = DecideReplan(feedback, current, active, policy, &done);
  return out;
}

ReplanInput MakeReplanInput(const PlanVersion& current,
                            const std::vector<std::string>& completed_task_ids,
                            const std::vector<Feedback>& recent_feedback, std::string reason,
                            const ShipObservation& ship, double mission_time_s) {
  ReplanInput in;
  in.reason = std::move(reason);
  in.ship = ship;
  in.mission_time_s = mission_time_s;
  std::set<std::string> done(completed_task_ids.begin(), completed_task_ids.end());
  std::set<std::string> started, failed;
  for (const Feedback& f : recent_feedback) {
    if (f.kind == FeedbackKind::kTaskStarted) started.insert(f.task_id);
    if (f.kind == FeedbackKind::kTaskFailed) failed.insert(f.task_id);
  }
  for (const Task& t : current.tasks) {
    if (done.contains(t.id)) {
      in.completed_task_ids.push_back(t.id);
    } else if (failed.contains(t.id) || (started.contains(t.id) && t.kind == TaskKind::kMove)) {
      in.interrupted_task_ids.push_back(t.id);
    } else if (started.contains(t.id)) {
      // A port operation under way is let finish: the new plan starts after it.
      in.completed_task_ids.push_back(t.id);
      in.mission_time_s = std::max(in.mission_time_s, t.end_s());
    }
  }
  return in;
}

namespace {
constexpr char kFuelFunctionKey[] = "@fuel-function";
}  // namespace

std::string EncodeEngineState(const EngineState& state) {
  std::string out;
  for (const auto& [name, p] : state.locations) {
    absl::StrAppend(&out, name, " ", validate::FormatTime(p.east_m), " ",
                    validate::FormatTime(p.north_m), "\n");
  }
  if (state.fuel_function) {
    absl::StrAppend(&out, kFuelFunctionKey, state.fuel_function->empty() ? "" : " ",
                    *state.fuel_function, "\n");
  }
  return out;
}

StatusOr<EngineState> DecodeEngineState(std::string_view text) {
  EngineState state;
  int line = 0;
  for (absl::string_view l :
       absl::StrSplit(absl::string_view(text.data(), text.size()), '\n', absl::SkipEmpty())) {
    ++line;
    std::vector<std::string> w = absl::StrSplit(l, ' ', absl::SkipEmpty());
    if (!w.empty() && w[0] == kFuelFunctionKey && w.size() <= 2) {
      state.fuel_function = w.size() == 2 ? w[1] : "";
      continue;
    }
    double x, y;
    if (w.size() != 3 || !absl::SimpleAtod(w[1], &x) || !absl::SimpleAtod(w[2], &y)) {
      return absl::InvalidArgumentError(absl::StrCat(
          "engine state line ", line, ": expected 'name x y' or '", kFuelFunctionKey, " [name]'"));
    }
    state.locations[w[0]] = {x, y};
  }
  return state;
}

}  // namespace seaplan::mission
