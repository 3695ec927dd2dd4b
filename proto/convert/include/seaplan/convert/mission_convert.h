// seaplan.v1 <-> engine/mission translations shared by the server and the
// simulation client: field by field, WGS84 positions through the mission's
// local frame (chart::LocalFrame), unknown enum values to the engine's
// "unspecified"/"other".
#pragma once

#include "google/protobuf/repeated_ptr_field.h"
#include "seaplan/chart/geodesy.h"
#include "seaplan/mission/replan_policy.h"
#include "seaplan/mission/types.h"
#include "seaplan/v1/mission.pb.h"
#include "seaplan/v1/route.pb.h"
#include "seaplan/validate/plan.h"

namespace seaplan::convert {

v1::MsoMode MsoModeToProto(mission::MsoMode mode);
mission::MsoMode MsoModeFromProto(v1::MsoMode mode);
v1::Task::Kind TaskKindToProto(mission::TaskKind kind);
mission::TaskKind TaskKindFromProto(v1::Task::Kind kind);
v1::Feedback::Kind FeedbackKindToProto(mission::FeedbackKind kind);
// Unknown kinds are position reports.
mission::FeedbackKind FeedbackKindFromProto(v1::Feedback::Kind kind);

v1::TimedAction PlanStepToProto(const validate::PlanStep& step);
validate::PlanStep PlanStepFromProto(const v1::TimedAction& action);

EastNorth ToLocal(const chart::LocalFrame& frame, const v1::LatLon& position);

// Appends the route's mode schedule (mission::ModeSchedule: runs of equal
// modes over its segments).
void AddModeSchedule(const mission::Route& route,
                     google::protobuf::RepeatedPtrField<v1::ModeScheduleEntry>* out);

// Plan versions with their tasks' routes (and their mode schedules);
// waypoints through `frame`.
v1::PlanVersion PlanVersionToProto(const mission::PlanVersion& version,
                                   const chart::LocalFrame& frame);
mission::PlanVersion PlanVersionFromProto(const v1::PlanVersion& version,
                                          const chart::LocalFrame& frame);

}  // namespace seaplan::convert
