// The narrow interface between the mission service and the mission loop
// engine (engine/mission: plan -> refine -> parse, update problem ->
// replan).
//
// The MissionCoordinator (mission_coordinator.h) owns the flow: it stores
// missions, versions, feedback and log events, serialises replans per
// mission and notifies watchers. A MissionEngine only computes: it never
// touches storage, streams or threads. An adapter in the server translates
// seaplan.v1 messages to engine/mission values and back (the engine itself
// never sees protobuf).
//
// Without a registered engine, CreateMission and RequestReplan answer
// UNIMPLEMENTED and store nothing.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/v1/mission.pb.h"

namespace seaplan::server {

// What the coordinator knows about a running mission.
struct MissionRuntimeState {
  v1::Mission mission;  // as stored: state, current_version, last_state, completed_tasks
  v1::PlanVersion current_version;            // the version the vessel executes (empty when none)
  std::string engine_state;                   // what the engine returned with that version
  std::vector<v1::Feedback> recent_feedback;  // the latest reports, oldest first (bounded)
};

// A computed plan version. The coordinator sets mission_id, version and
// created_at; everything else comes from the engine.
struct PlannedVersion {
  v1::PlanVersion version;
  std::string engine_state;  // opaque, stored with the version
  std::vector<std::string>
      log_messages;  // navigation-log lines ("computing the temporal plan", ...)
};

// The engine's answer to one feedback report.
struct FeedbackDecision {
  bool replan = false;        // the plan no longer holds: replan (asynchronously)
  std::string replan_reason;  // e.g. "fuel 28% <= 30%", "task v1-t2 move-ship failed"
  std::optional<v1::MissionState> new_state;                // e.g. COMPLETED after the last task
  std::optional<std::vector<std::string>> completed_tasks;  // the full list when it changed
  std::string failure_reason;                               // with new_state FAILED
  std::vector<std::string> log_messages;                    // navigation-log lines for this report
};

class MissionEngine {
 public:
  virtual ~MissionEngine() = default;

  // Cheap checks of a spec before anything is stored (InvalidArgument with
  // what and where, e.g. PDDL diagnostics attached via status_details.h).
  virtual absl::Status CheckSpec(const v1::MissionSpec& spec) = 0;

  // Plans, refines and parses version 1. Errors: InvalidArgument (bad
  // input), FailedPrecondition (no plan: unsolvable, timeout), or what
  // `stop` caused.
  virtual absl::StatusOr<PlannedVersion> PlanInitial(const v1::MissionSpec& spec,
                                                     const StopToken& stop) = 0;

  // Regenerates the problem from `state` and replans. nullopt when the
  // goal already holds (the mission is complete).
  virtual absl::StatusOr<std::optional<PlannedVersion>> Replan(const v1::MissionSpec& spec,
                                                               const MissionRuntimeState& state,
                                                               std::string_view reason,
                                                               const StopToken& stop) = 0;

  // Decides what a feedback report means (fast: no planning here). Called
  // before the report is stored; `state` does not include `feedback` yet.
  virtual FeedbackDecision OnFeedback(const v1::MissionSpec& spec, const MissionRuntimeState& state,
                                      const v1::Feedback& feedback) = 0;
};

}  // namespace seaplan::server
