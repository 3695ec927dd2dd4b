#include "seaplan/mission/mission_state.h"

#include <string>

#include "absl/strings/str_cat.h"

namespace seaplan::mission {

std::string_view MissionStateName(MissionState state) {
  switch (state) {
    case MissionState::kActive:
      return "ACTIVE";
    case MissionState::kReplanning:
      return "REPLANNING";
    case MissionState::kCompleted:
      return "COMPLETED";
    case MissionState::kFailed:
      return "FAILED";
    case MissionState::kCancelled:
      return "CANCELLED";
  }
  return "UNKNOWN";
}

bool IsFinal(MissionState state) {
  return state == MissionState::kCompleted || state == MissionState::kFailed ||
         state == MissionState::kCancelled;
}

StatusOr<MissionState> NextState(MissionState state, MissionEvent event) {
  if (IsFinal(state)) {
    return absl::FailedPreconditionError(
        absl::StrCat("the mission is ", std::string(MissionStateName(state)), " (a final state)"));
  }
  switch (event) {
    case MissionEvent::kReplanStarted:
      return MissionState::kReplanning;
    case MissionEvent::kNewVersion:
    case MissionEvent::kReplanEnded:
      return MissionState::kActive;
    case MissionEvent::kCompleted:
      return MissionState::kCompleted;
    case MissionEvent::kFailed:
      return MissionState::kFailed;
    case MissionEvent::kCancelled:
      return MissionState::kCancelled;
  }
  return absl::InvalidArgumentError("unknown mission event");
}

}  // namespace seaplan::mission
