// Helpers for the server's MissionEngine adapter (server/core/mission_engine.h):
// everything the adapter needs besides translating seaplan.v1 messages, so
// that the adapter stays a thin edge.
//
//   OnFeedback   -> FeedbackDecision (replan? completed? which tasks done?)
//   MakeReplanInput -> what Replan needs, from the stored runtime state
//   Encode/DecodeEngineState -> the opaque engine_state stored with a version
//                   (the location table, which a replan may extend by port-s)
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
FeedbackOutcome OnFeedback(const MissionDefinition& mission, const PlanVersion& current,
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

// "name x y" per line, exact round trip.
std::string EncodeEngineState(const LocationTable& locations);
StatusOr<LocationTable> DecodeEngineState(std::string_view text);

}  // namespace seaplan::mission
