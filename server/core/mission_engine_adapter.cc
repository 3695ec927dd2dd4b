#include "server/core/mission_engine_adapter.h"

#include <cmath>
#include <utility>

#include "absl/strings/str_cat.h"
#include "server/core/convert.h"
#include "server/core/route_convert.h"
#include "server/core/status_details.h"

namespace seaplan::server {
namespace {

v1::Task::Kind KindToProto(mission::TaskKind k) {
  switch (k) {
    case mission::TaskKind::kMove:
      return v1::Task::KIND_MOVE;
    case mission::TaskKind::kLoad:
      return v1::Task::KIND_LOAD;
    case mission::TaskKind::kUnload:
      return v1::Task::KIND_UNLOAD;
    case mission::TaskKind::kRepair:
      return v1::Task::KIND_REPAIR;
    case mission::TaskKind::kRefuel:
      return v1::Task::KIND_REFUEL;
    case mission::TaskKind::kOther:
      return v1::Task::KIND_OTHER;
  }
  return v1::Task::KIND_OTHER;
}

mission::TaskKind KindFromProto(v1::Task::Kind k) {
  switch (k) {
    case v1::Task::KIND_MOVE:
      return mission::TaskKind::kMove;
    case v1::Task::KIND_LOAD:
      return mission::TaskKind::kLoad;
    case v1::Task::KIND_UNLOAD:
      return mission::TaskKind::kUnload;
    case v1::Task::KIND_REPAIR:
      return mission::TaskKind::kRepair;
    case v1::Task::KIND_REFUEL:
      return mission::TaskKind::kRefuel;
    default:
      return mission::TaskKind::kOther;
  }
}

mission::MsoMode ModeFromProto(v1::MsoMode m) {
  switch (m) {
    case v1::MSO_MODE_PTO:
      return mission::MsoMode::kPto;
    case v1::MSO_MODE_MEC:
      return mission::MsoMode::kMec;
    case v1::MSO_MODE_PTI:
      return mission::MsoMode::kPti;
    default:
      return mission::MsoMode::kUnspecified;
  }
}

v1::TimedAction StepToProto(const validate::PlanStep& s) {
  v1::TimedAction a;
  a.set_start_s(s.start_s);
  a.set_duration_s(s.duration_s);
  a.set_name(s.name);
  for (const auto& arg : s.args) a.add_arguments(arg);
  return a;
}

validate::PlanStep StepFromProto(const v1::TimedAction& a) {
  validate::PlanStep s;
  s.start_s = a.start_s();
  s.duration_s = a.duration_s();
  s.name = a.name();
  s.args.assign(a.arguments().begin(), a.arguments().end());
  return s;
}

EastNorth ToLocal(const chart::LocalFrame& frame, const v1::LatLon& p) {
  const EastNorth local = frame.ToLocal({p.latitude_deg(), p.longitude_deg()});
  return {local.east_m, local.north_m};
}

mission::FeedbackKind FeedbackKindFromProto(v1::Feedback::Kind kind) {
  switch (kind) {
    case v1::Feedback::KIND_TASK_STARTED:
      return mission::FeedbackKind::kTaskStarted;
    case v1::Feedback::KIND_TASK_COMPLETED:
      return mission::FeedbackKind::kTaskCompleted;
    case v1::Feedback::KIND_TASK_FAILED:
      return mission::FeedbackKind::kTaskFailed;
    case v1::Feedback::KIND_GNSS_FAULT:
      return mission::FeedbackKind::kGnssFault;
    case v1::Feedback::KIND_MACHINERY_FAULT:
      return mission::FeedbackKind::kMachineryFault;
    case v1::Feedback::KIND_OPERATOR_CHANGE:
      return mission::FeedbackKind::kOperatorChange;
    case v1::Feedback::KIND_COLLISION_AVOIDANCE:
      return mission::FeedbackKind::kCollisionAvoidance;
    default:
      return mission::FeedbackKind::kPosition;
  }
}

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
  const v1::PlannerOptions& o = spec.planner_options();
  if (o.has_time_limit()) {
    SEAPLAN_ASSIGN_OR_RETURN(double s,
                             DurationSeconds(o.time_limit(), "spec.planner_options.time_limit"));
    if (s > 0) out.planner.time_limit_s = s;
  }
  if (o.memory_limit_mb() > 0) out.planner.memory_limit_mb = o.memory_limit_mb();
  if (o.max_concurrent_actions() > 0)
    out.planner.max_concurrent_actions = o.max_concurrent_actions();
  if (o.has_anytime()) out.planner.anytime = o.anytime();
  if (o.random_seed() != 0) out.planner.random_seed = o.random_seed();
  if (o.epsilon_s() > 0) out.planner.epsilon_s = o.epsilon_s();
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

v1::PlanVersion PlanVersionToProto(const mission::PlanVersion& v, const chart::LocalFrame& frame) {
  v1::PlanVersion p;
  p.set_version(v.version);
  p.set_reason(v.reason);
  p.set_makespan_s(v.makespan_s);
  p.set_problem(v.problem);
  p.set_mission_time_origin_s(v.mission_time_origin_s);
  p.set_planner_status(v.quality == mission::PlanQuality::kOptimal ? v1::SOLVED_OPTIMALLY
                                                                   : v1::SOLVED_SATISFICING);
  for (const auto& s : v.plan.steps) *p.add_plan() = StepToProto(s);
  for (const auto& t : v.tasks) {
    v1::Task* task = p.add_tasks();
    task->set_task_id(t.id);
    task->set_kind(KindToProto(t.kind));
    task->set_start_s(t.start_s);
    task->set_duration_s(t.duration_s);
    *task->mutable_action() = StepToProto(t.action);
    task->set_from_location(t.from_location);
    task->set_to_location(t.to_location);
    if (!t.route) continue;
    v1::RouteAlternative* r = task->mutable_route();
    r->set_index(t.route->alternative_index);
    r->set_length_m(t.route->length_m);
    r->set_sailing_time_s(t.route->sailing_time_s);
    r->set_fuel_kg(t.route->fuel_kg);
    r->set_expected_grounding_cost(t.route->expected_grounding_cost);
    r->set_max_grounding_probability(t.route->max_grounding_probability);
    for (const auto& w : t.route->waypoints) {
      v1::RouteWaypoint* rw = r->add_waypoints();
      const chart::LatLon ll = frame.ToLatLon({w.position.east_m, w.position.north_m});
      rw->mutable_position()->set_latitude_deg(ll.lat_deg);
      rw->mutable_position()->set_longitude_deg(ll.lon_deg);
      rw->set_mode(MsoModeToProto(w.mode));
      rw->set_eta_s(w.eta_s);
      rw->set_distance_from_start_m(w.distance_from_start_m);
      rw->set_time_to_grounding_s(w.time_to_grounding_s);
      rw->set_grounding_probability(w.grounding_probability);
      rw->set_expected_grounding_cost(w.expected_grounding_cost);
      rw->set_fuel_kg(w.fuel_kg);
    }
    AddModeSchedule(*t.route, task->mutable_mode_schedule());
  }
  return p;
}

mission::PlanVersion PlanVersionFromProto(const v1::PlanVersion& p,
                                          const chart::LocalFrame& frame) {
  mission::PlanVersion v;
  v.version = p.version();
  v.reason = p.reason();
  v.mission_time_origin_s = p.mission_time_origin_s();
  v.makespan_s = p.makespan_s();
  v.problem = p.problem();
  v.quality = p.planner_status() == v1::SOLVED_OPTIMALLY ? mission::PlanQuality::kOptimal
                                                         : mission::PlanQuality::kSatisficing;
  for (const auto& a : p.plan()) v.plan.steps.push_back(StepFromProto(a));
  for (const auto& t : p.tasks()) {
    mission::Task task;
    task.id = t.task_id();
    task.kind = KindFromProto(t.kind());
    task.start_s = t.start_s();
    task.duration_s = t.duration_s();
    task.action = StepFromProto(t.action());
    task.from_location = t.from_location();
    task.to_location = t.to_location();
    if (t.has_route()) {
      const v1::RouteAlternative& r = t.route();
      mission::Route route;
      route.alternative_index = r.index();
      route.length_m = r.length_m();
      route.sailing_time_s = r.sailing_time_s();
      route.fuel_kg = r.fuel_kg();
      route.expected_grounding_cost = r.expected_grounding_cost();
      route.max_grounding_probability = r.max_grounding_probability();
      for (const auto& w : r.waypoints()) {
        mission::RouteWaypoint m;
        m.position = ToLocal(frame, w.position());
        m.mode = ModeFromProto(w.mode());
        m.eta_s = w.eta_s();
        m.distance_from_start_m = w.distance_from_start_m();
        m.time_to_grounding_s = w.time_to_grounding_s();
        m.grounding_probability = w.grounding_probability();
        m.expected_grounding_cost = w.expected_grounding_cost();
        m.fuel_kg = w.fuel_kg();
        route.waypoints.push_back(m);
      }
      task.route = std::move(route);
    }
    v.tasks.push_back(std::move(task));
  }
  return v;
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
