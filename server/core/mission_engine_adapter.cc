#include "server/core/mission_engine_adapter.h"

#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "seaplan/convert/mission_convert.h"
#include "server/core/convert.h"
#include "server/core/planning_handlers.h"
#include "server/core/route_convert.h"
#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

using convert::FeedbackKindFromProto;
using convert::ToLocal;

// The engine's view of the stored runtime state; positions through `frame`.
mission::MissionRuntime RuntimeFromProto(const MissionRuntimeState& state,
                                         const chart::LocalFrame& frame) {
  mission::MissionRuntime runtime;
  runtime.current = PlanVersionFromProto(state.current_version, frame);
  runtime.engine_state = state.engine_state;
  runtime.completed_task_ids.assign(state.mission.completed_tasks().begin(),
                                    state.mission.completed_tasks().end());
  if (state.mission.has_last_state()) {
    const v1::ShipState& last = state.mission.last_state();
    mission::ShipReport report;
    if (last.has_position()) report.position = ToLocal(frame, last.position());
    report.fuel_fraction = last.fuel_fraction();
    report.motion = mission::ShipMotion{last.heading_deg() * M_PI / 180.0, last.speed_mps()};
    runtime.last_report = report;
  }
  for (const v1::Feedback& f : state.recent_feedback)
    runtime.recent_feedback.push_back(FeedbackFromProto(f, nullptr));
  return runtime;
}

}  // namespace

absl::StatusOr<mission::MissionSpec> SpecFromProto(const v1::MissionSpec& spec) {
  mission::MissionSpec out;
  out.domain = spec.domain();
  out.problem = spec.problem();
  for (const auto& l : spec.locations())
    out.locations.push_back(
        {l.name(), {l.position().latitude_deg(), l.position().longitude_deg()}});
  out.chart_id = spec.chart_id();
  out.service_speed_mps = spec.ship().service_speed_mps();
  out.routing = {ShipToEngine(spec.ship()), OptionsToEngine(spec.route_options()),
                 EnvironmentToEngine(spec.environment())};
  // The messages the routing settings come from, as bytes: equal bytes are
  // equal settings.
  for (const google::protobuf::Message* m :
       {static_cast<const google::protobuf::Message*>(&spec.ship()),
        static_cast<const google::protobuf::Message*>(&spec.route_options()),
        static_cast<const google::protobuf::Message*>(&spec.environment())}) {
    const std::string bytes = m->SerializeAsString();
    absl::StrAppend(&out.routing_key, bytes.size(), ":", bytes, "|");
  }
  SEAPLAN_ASSIGN_OR_RETURN(
      out.planner,
      PlannerOptionsToEngine(spec.planner_options(), "spec.planner_options", out.planner));
  const v1::ReplanPolicy& r = spec.replan_policy();
  if (r.fuel_threshold_fraction() > 0)
    out.policy.fuel_threshold_fraction = r.fuel_threshold_fraction();
  if (r.position_deviation_m() > 0) out.policy.position_deviation_m = r.position_deviation_m();
  if (r.delay_tolerance_s() > 0) out.policy.delay_tolerance_s = r.delay_tolerance_s();
  for (const auto& op : spec.port_operations())
    out.port_operation_durations_s[op.action()] = op.duration_s();
  out.ship_object = spec.ship_object();
  out.initial_position = {spec.initial_state().position().latitude_deg(),
                          spec.initial_state().position().longitude_deg()};
  out.initial_fuel_fraction = spec.initial_state().fuel_fraction();
  return out;
}

mission::Feedback FeedbackFromProto(const v1::Feedback& feedback, const chart::LocalFrame* frame) {
  mission::Feedback f;
  f.kind = FeedbackKindFromProto(feedback.kind());
  f.task_id = feedback.task_id();
  f.plan_version = feedback.plan_version();
  f.mission_time_s = feedback.mission_time_s();
  f.detail = feedback.detail();
  if (feedback.has_state()) {
    if (frame != nullptr && feedback.state().has_position())
      f.position = ToLocal(*frame, feedback.state().position());
    f.fuel_fraction = feedback.state().fuel_fraction();
    f.collision_avoidance_active = feedback.state().collision_avoidance_active();
  }
  return f;
}

v1::MissionState MissionStateToProto(mission::MissionState state) {
  switch (state) {
    case mission::MissionState::kActive:
      return v1::MISSION_STATE_ACTIVE;
    case mission::MissionState::kReplanning:
      return v1::MISSION_STATE_REPLANNING;
    case mission::MissionState::kCompleted:
      return v1::MISSION_STATE_COMPLETED;
    case mission::MissionState::kFailed:
      return v1::MISSION_STATE_FAILED;
    case mission::MissionState::kCancelled:
      return v1::MISSION_STATE_CANCELLED;
  }
  return v1::MISSION_STATE_UNSPECIFIED;
}

mission::MissionState MissionStateFromProto(int state) {
  switch (state) {
    case v1::MISSION_STATE_REPLANNING:
      return mission::MissionState::kReplanning;
    case v1::MISSION_STATE_COMPLETED:
      return mission::MissionState::kCompleted;
    case v1::MISSION_STATE_FAILED:
      return mission::MissionState::kFailed;
    case v1::MISSION_STATE_CANCELLED:
      return mission::MissionState::kCancelled;
    default:  // ACTIVE; PLANNING and UNSPECIFIED are never stored
      return mission::MissionState::kActive;
  }
}

absl::Status MissionAdapter::CheckSpec(const v1::MissionSpec& spec) {
  SEAPLAN_ASSIGN_OR_RETURN(mission::MissionSpec s, SpecFromProto(spec));
  std::vector<pddl::Diagnostic> diagnostics;
  absl::Status st = engine_->CheckSpec(s, &diagnostics);
  if (!st.ok() && !diagnostics.empty()) return WithDiagnostics(st, ToProto(diagnostics));
  return st;
}

absl::StatusOr<PlannedVersion> MissionAdapter::PlanInitial(const v1::MissionSpec& spec,
                                                           const StopToken& stop) {
  SEAPLAN_ASSIGN_OR_RETURN(mission::MissionSpec s, SpecFromProto(spec));
  SEAPLAN_ASSIGN_OR_RETURN(mission::PlannedVersion planned, engine_->PlanInitial(s, stop));
  SEAPLAN_ASSIGN_OR_RETURN(chart::LocalFrame frame, engine_->Frame(s));
  return PlannedVersion{PlanVersionToProto(planned.version, frame), std::move(planned.engine_state),
                        std::move(planned.log_messages)};
}

absl::StatusOr<std::optional<PlannedVersion>> MissionAdapter::Replan(
    const v1::MissionSpec& spec, const MissionRuntimeState& state, std::string_view reason,
    const StopToken& stop) {
  SEAPLAN_ASSIGN_OR_RETURN(mission::MissionSpec s, SpecFromProto(spec));
  SEAPLAN_ASSIGN_OR_RETURN(chart::LocalFrame frame, engine_->Frame(s));
  SEAPLAN_ASSIGN_OR_RETURN(std::optional<mission::PlannedVersion> planned,
                           engine_->Replan(s, RuntimeFromProto(state, frame), reason, stop));
  if (!planned) return std::optional<PlannedVersion>();
  return std::optional<PlannedVersion>(PlannedVersion{PlanVersionToProto(planned->version, frame),
                                                      std::move(planned->engine_state),
                                                      std::move(planned->log_messages)});
}

mission::FeedbackOutcome MissionAdapter::OnFeedback(const v1::MissionSpec& spec,
                                                    const MissionRuntimeState& state,
                                                    const v1::Feedback& feedback) {
  auto s = SpecFromProto(spec);
  if (!s.ok()) return {};  // a stored spec was checked when the mission was created
  auto frame = engine_->Frame(*s);
  const chart::LocalFrame runtime_frame = frame.ok() ? *frame : chart::LocalFrame();
  return engine_->OnFeedback(*s, RuntimeFromProto(state, runtime_frame),
                             FeedbackFromProto(feedback, frame.ok() ? &*frame : nullptr));
}

}  // namespace seaplan::server
