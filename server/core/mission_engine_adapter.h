// Translation between seaplan.v1 mission messages and the mission engine
// (engine/mission/include/seaplan/mission/mission_engine.h), which decides
// everything about a mission. This file only converts: field by field, WGS84
// positions through the local frame the engine chose (MissionEngine::Frame),
// Protobuf defaults (0 = "not given") to the engine's defaults, and the
// engine's PDDL diagnostics into the status details.
//
// Feedback: a ShipState in a report is a full state (fuel_fraction 0 is an
// empty tank); a report without a state carries neither position nor fuel.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/convert/mission_convert.h"
#include "seaplan/mission/mission_engine.h"
#include "seaplan/mission/mission_state.h"
#include "seaplan/v1/mission.pb.h"

namespace seaplan::server {

// What the service has stored about a running mission.
struct MissionRuntimeState {
  v1::Mission mission;  // as stored: state, current_version, last_state, completed_tasks
  v1::PlanVersion current_version;            // the version the vessel executes (empty when none)
  std::string engine_state;                   // stored with that version
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

class MissionAdapter {
 public:
  explicit MissionAdapter(std::shared_ptr<mission::MissionEngine> engine)
      : engine_(std::move(engine)) {}

  // InvalidArgument with what and where (PDDL diagnostics in the details).
  absl::Status CheckSpec(const v1::MissionSpec& spec);
  absl::StatusOr<PlannedVersion> PlanInitial(const v1::MissionSpec& spec, const StopToken& stop);
  // nullopt when the goal already holds.
  absl::StatusOr<std::optional<PlannedVersion>> Replan(const v1::MissionSpec& spec,
                                                       const MissionRuntimeState& state,
                                                       std::string_view reason,
                                                       const StopToken& stop);
  // `state` does not include `feedback` yet.
  mission::FeedbackOutcome OnFeedback(const v1::MissionSpec& spec, const MissionRuntimeState& state,
                                      const v1::Feedback& feedback);
  // The chart was deleted: the engine drops what it keeps of it.
  void ForgetChart(const std::string& chart_id) { engine_->ForgetChart(chart_id); }

 private:
  std::shared_ptr<mission::MissionEngine> engine_;
};

// ---- translations (exposed for their tests) ----

absl::StatusOr<mission::MissionSpec> SpecFromProto(const v1::MissionSpec& spec);
// Plan versions with their routes (proto/convert, shared with the simulation
// client); waypoints through `frame`.
using convert::PlanVersionFromProto;
using convert::PlanVersionToProto;
// Position through `frame` (none without a frame or a state).
mission::Feedback FeedbackFromProto(const v1::Feedback& feedback, const chart::LocalFrame* frame);
// Stored mission states are v1::MissionState numbers.
v1::MissionState MissionStateToProto(mission::MissionState state);
mission::MissionState MissionStateFromProto(int state);

}  // namespace seaplan::server
