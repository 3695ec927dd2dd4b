// The mission loop between two plans: what a feedback report means, what a
// replan starts from, and the engine state stored with each plan version.
// MissionEngine (mission_engine.h) calls these; they are pure functions over
// values so that each rule is tested on its own.
//
//   OnFeedback      -> FeedbackOutcome (replan? completed? which tasks done?)
//   MakeReplanInput -> what Replan needs, from the stored runtime state
//   Encode/DecodeEngineState -> the opaque engine_state stored with a version
//                   (the location table, which a replan may extend by port-s,
//                   and the tank fluent decided when the mission was created)
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/mission/mission_planner.h"
#include "seaplan/mission/replan_policy.h"
#include "seaplan/mission/tasks.h"
#include "seaplan/mission/types.h"

namespace seaplan::mission {

struct FeedbackOutcome {
  std::optional<std::string> replan_reason;
  bool mission_completed = false;               // every task of the current version completed
  std::vector<std::string> completed_task_ids;  // updated list (current version's ids)
  bool completed_changed = false;
  std::vector<std::string> log_messages;  // navigation-log lines, paper wording
};

// What a feedback report means for `current`, given the tasks already
// completed (ids of any version; only the current version's count for
// completion). Pure and fast (no planning).
//  * A report is about the task it names; one that names no task of
//    `current` (a position report without a task id) is about the move under
//    way: the latest move of `current` that has started by the report's time
//    and is not completed. That task's route is what the position-deviation
//    trigger measures against.
//  * A report without a task id completes nothing.
//  * Completion comes first: when the report completes the last task of
//    `current`, the mission is completed and no replan is decided (a last
//    task finishing late has nothing left to replan).
//  * A collision-avoidance report logs the paper's "potential collision
//    situation" (the report itself, with its detail, is logged by the caller).
FeedbackOutcome OnFeedback(const ReplanPolicy& policy, const PlanVersion& current,
                           const std::vector<std::string>& completed_task_ids,
                           const Feedback& feedback);

// The replan input from the runtime state: completed ids of `current`; the
// move under way (started, not completed; or the failed task in
// `recent_feedback`) is interrupted; port operations under way are counted
// as completed (they are let finish) and the new version starts at the
// latest of `mission_time_s` and their planned end.
ReplanInput MakeReplanInput(const PlanVersion& current,
                            const std::vector<std::string>& completed_task_ids,
                            const std::vector<Feedback>& recent_feedback, std::string reason,
                            const ShipObservation& ship, double mission_time_s);

// What the engine carries from one plan version to the next.
struct EngineState {
  LocationTable locations;
  // The numeric fluent that is the ship's tank when the domain plans fuel
  // up front ("" when it does not), decided once when the mission is
  // created (PlannedFuelFunction); nullopt in states stored before it was
  // recorded.
  std::optional<std::string> fuel_function;
  friend bool operator==(const EngineState&, const EngineState&) = default;
};

// "name x y" per location line, then "@fuel-function NAME" ("@fuel-function"
// alone when there is none); exact round trip. A text of location lines only
// (stored before the fuel line existed) decodes with fuel_function nullopt.
std::string EncodeEngineState(const EngineState& state);
StatusOr<EngineState> DecodeEngineState(std::string_view text);

}  // namespace seaplan::mission
