// The life cycle of a mission (paper 000 fig. 5 seen from the service):
//
//   ACTIVE --replan started--> REPLANNING --new version / replan ended--> ACTIVE
//   ACTIVE or REPLANNING --every task done / the goal holds--> COMPLETED
//   ACTIVE or REPLANNING --failed--> FAILED
//   ACTIVE or REPLANNING --cancelled--> CANCELLED
//
// COMPLETED, FAILED and CANCELLED are final: nothing leaves them. The
// server stores the state and serialises its changes per mission; the rules
// of which change is allowed live here.
#pragma once

#include <string_view>

#include "seaplan/common/status.h"

namespace seaplan::mission {

enum class MissionState { kActive, kReplanning, kCompleted, kFailed, kCancelled };

// "ACTIVE", "REPLANNING", "COMPLETED", "FAILED", "CANCELLED".
std::string_view MissionStateName(MissionState state);
bool IsFinal(MissionState state);

enum class MissionEvent {
  kReplanStarted,  // a trigger or an operator asked for a new version
  kNewVersion,     // a new plan version was stored
  kReplanEnded,    // a replan ended without a new version (failed, stopped, refused)
  kCompleted,      // every task of the current version done, or the goal holds
  kFailed,
  kCancelled,
};

// The state after `event`. FailedPrecondition when the mission is in a
// final state (nothing leaves it). A replan that ends while the mission is
// ACTIVE (it was never marked REPLANNING) leaves it ACTIVE.
StatusOr<MissionState> NextState(MissionState state, MissionEvent event);

}  // namespace seaplan::mission
