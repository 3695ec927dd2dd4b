#include "seaplan/convert/mission_convert.h"

#include <utility>

namespace seaplan::convert {

v1::MsoMode MsoModeToProto(mission::MsoMode mode) {
  switch (mode) {
    case mission::MsoMode::kPto:
      return v1::MSO_MODE_PTO;
    case mission::MsoMode::kMec:
      return v1::MSO_MODE_MEC;
    case mission::MsoMode::kPti:
      return v1::MSO_MODE_PTI;
    case mission::MsoMode::kUnspecified:
      break;
  }
  return v1::MSO_MODE_UNSPECIFIED;
}

mission::MsoMode MsoModeFromProto(v1::MsoMode mode) {
  switch (mode) {
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

v1::Task::Kind TaskKindToProto(mission::TaskKind kind) {
  switch (kind) {
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

mission::TaskKind TaskKindFromProto(v1::Task::Kind kind) {
  switch (kind) {
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

v1::Feedback::Kind FeedbackKindToProto(mission::FeedbackKind kind) {
  switch (kind) {
    case mission::FeedbackKind::kTaskStarted:
      return v1::Feedback::KIND_TASK_STARTED;
    case mission::FeedbackKind::kTaskCompleted:
      return v1::Feedback::KIND_TASK_COMPLETED;
    case mission::FeedbackKind::kTaskFailed:
      return v1::Feedback::KIND_TASK_FAILED;
    case mission::FeedbackKind::kPosition:
      return v1::Feedback::KIND_POSITION;
    case mission::FeedbackKind::kGnssFault:
      return v1::Feedback::KIND_GNSS_FAULT;
    case mission::FeedbackKind::kMachineryFault:
      return v1::Feedback::KIND_MACHINERY_FAULT;
    case mission::FeedbackKind::kOperatorChange:
      return v1::Feedback::KIND_OPERATOR_CHANGE;
    case mission::FeedbackKind::kCollisionAvoidance:
      return v1::Feedback::KIND_COLLISION_AVOIDANCE;
  }
  return v1::Feedback::KIND_UNSPECIFIED;
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

v1::TimedAction PlanStepToProto(const validate::PlanStep& step) {
  v1::TimedAction a;
  a.set_start_s(step.start_s);
  a.set_duration_s(step.duration_s);
  a.set_name(step.name);
  for (const auto& arg : step.args) a.add_arguments(arg);
  return a;
}

validate::PlanStep PlanStepFromProto(const v1::TimedAction& action) {
  validate::PlanStep s;
  s.start_s = action.start_s();
  s.duration_s = action.duration_s();
  s.name = action.name();
  s.args.assign(action.arguments().begin(), action.arguments().end());
  return s;
}

EastNorth ToLocal(const chart::LocalFrame& frame, const v1::LatLon& position) {
  return frame.ToLocal({position.latitude_deg(), position.longitude_deg()});
}

void AddModeSchedule(const mission::Route& route,
                     google::protobuf::RepeatedPtrField<v1::ModeScheduleEntry>* out) {
  for (const mission::ModeScheduleEntry& e : mission::ModeSchedule(route)) {
    v1::ModeScheduleEntry* m = out->Add();
    m->set_from_waypoint(e.from_waypoint);
    m->set_to_waypoint(e.to_waypoint);
    m->set_mode(MsoModeToProto(e.mode));
    m->set_start_s(e.start_s);
    m->set_duration_s(e.duration_s);
  }
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
  for (const auto& s : v.plan.steps) *p.add_plan() = PlanStepToProto(s);
  for (const auto& t : v.tasks) {
    v1::Task* task = p.add_tasks();
    task->set_task_id(t.id);
    task->set_kind(TaskKindToProto(t.kind));
    task->set_start_s(t.start_s);
    task->set_duration_s(t.duration_s);
    *task->mutable_action() = PlanStepToProto(t.action);
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
      const chart::LatLon ll = frame.ToLatLon(w.position);
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
  for (const auto& a : p.plan()) v.plan.steps.push_back(PlanStepFromProto(a));
  for (const auto& t : p.tasks()) {
    mission::Task task;
    task.id = t.task_id();
    task.kind = TaskKindFromProto(t.kind());
    task.start_s = t.start_s();
    task.duration_s = t.duration_s();
    task.action = PlanStepFromProto(t.action());
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
        m.mode = MsoModeFromProto(w.mode());
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

}  // namespace seaplan::convert
