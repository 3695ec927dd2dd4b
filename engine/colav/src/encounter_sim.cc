#include "seaplan/colav/encounter_sim.h"

#include <algorithm>
#include <cmath>

#include "absl/strings/str_format.h"
#include "seaplan/ship/steady_state.h"

namespace seaplan::colav {
namespace {

constexpr double kLandSampleS = 2.0;

double PathDistance(const std::vector<EastNorth>& path, EastNorth p) {
  double best = 1e18;
  for (size_t i = 0; i + 1 < path.size(); ++i) {
    best = std::min(best, PointSegmentDistance(p, path[i], path[i + 1]));
  }
  return best;
}

std::string_view KindName(EventKind k) {
  switch (k) {
    case EventKind::kPotentialCollision:
      return "potential collision";
    case EventKind::kManoeuvreStarted:
      return "manoeuvre started";
    case EventKind::kManoeuvreEnded:
      return "manoeuvre ended";
    case EventKind::kSpeedReduced:
      return "speed reduced";
  }
  return "";
}

double ThrottleForSpeedOrTop(double speed_mps) {
  auto t = ship::ThrottleForSpeed(ship::ShipParams{}, ship::MachineryParams{}, ship::MsoMode::kPto,
                                  speed_mps);
  return t.ok() ? *t : 1.0;
}

}  // namespace

Kinematics EncounterVessel::At(double time_s) const {
  if (time_s < still_until_s) return {position, {0.0, 0.0}};
  return {position + velocity * (time_s - still_until_s), velocity};
}

StatusOr<UnderWay> ShipUnderWay(EastNorth position, double heading_rad, double speed_mps,
                                const ship::Environment& environment,
                                const AutopilotOptions& autopilot_options) {
  SEAPLAN_RETURN_IF_ERROR(autopilot_options.Validate());
  const ship::OperatingPoint op =
      ship::CalmWaterOperatingPoint(ship::ShipParams{}, ship::MachineryParams{},
                                    ship::MsoMode::kPto, ThrottleForSpeedOrTop(speed_mps));
  SEAPLAN_ASSIGN_OR_RETURN(
      ship::ShipModel model,
      ship::ShipModel::Create(
          ship::ShipParams{}, ship::MachineryParams{}, environment,
          ship::ShipState::At(position.north_m, position.east_m, heading_rad, op.speed_mps),
          ship::MsoMode::kPto, op.thrust_n));
  Autopilot autopilot(autopilot_options);
  autopilot.HoldThrottle(op.throttle);
  return UnderWay{std::move(model), autopilot};
}

StatusOr<EncounterOutcome> SimulateEncounter(const EncounterSetup& setup) {
  if (setup.path.size() < 2) return absl::InvalidArgumentError("encounter: path needs 2 points");
  if (!(setup.dt_s > 0) || !(setup.cruise_speed_mps > 0)) {
    return absl::InvalidArgumentError("encounter: dt_s and cruise_speed_mps must be > 0");
  }
  SEAPLAN_RETURN_IF_ERROR(setup.autopilot.Validate());
  SEAPLAN_ASSIGN_OR_RETURN(PathFollower follower, PathFollower::Create(setup.path, setup.follower));
  SEAPLAN_ASSIGN_OR_RETURN(CollisionAvoidance avoidance,
                           CollisionAvoidance::Create(setup.avoidance));
  const LandIndex land(setup.land);
  if (!land.empty()) avoidance.set_land(&land);
  const EastNorth start = setup.path.front();
  const double heading = CourseOf(setup.path[1] - setup.path[0]);
  SEAPLAN_ASSIGN_OR_RETURN(UnderWay ship, ShipUnderWay(start, heading, setup.cruise_speed_mps,
                                                       setup.environment, setup.autopilot));
  if (setup.start_at_rest) {
    SEAPLAN_ASSIGN_OR_RETURN(
        ship.model,
        ship::ShipModel::Create(ship::ShipParams{}, ship::MachineryParams{}, setup.environment,
                                ship::ShipState::At(start.north_m, start.east_m, heading, 0.0),
                                ship::MsoMode::kPto));
    ship.autopilot = Autopilot(setup.autopilot);
  }
  ship::ShipModel& model = ship.model;
  Autopilot& autopilot = ship.autopilot;

  EncounterOutcome out;
  for (const EncounterVessel& v : setup.traffic) out.vessels.push_back({.id = v.id});
  std::vector<Obstacle> traffic(setup.traffic.size());
  const EastNorth goal = setup.path.back();
  const CollisionAvoidanceOptions& o = setup.avoidance;
  double last_land_sample = -1e9;
  bool was_manoeuvring = false;
  double t = 0.0;
  for (; t <= setup.max_time_s; t += setup.dt_s) {
    const ship::ShipState& s = model.state();
    const EastNorth here{s.east_m(), s.north_m()};
    const Kinematics own{here, VelocityOf(s.heading_rad(), s.surge_mps())};
    for (size_t i = 0; i < setup.traffic.size(); ++i) {
      const EncounterVessel& v = setup.traffic[i];
      traffic[i] = {v.At(t), v.id};
      const EastNorth rel = traffic[i].kinematics.position - here;
      VesselOutcome& vo = out.vessels[i];
      if (rel.Norm() < vo.min_distance_m) {
        vo.min_distance_m = rel.Norm();
        vo.time_s = t;
        vo.bearing_rad = WrapAngle(std::atan2(rel.east_m, rel.north_m) - s.heading_rad());
      }
    }
    out.max_path_deviation_m = std::max(out.max_path_deviation_m, PathDistance(setup.path, here));
    if (t - last_land_sample >= kLandSampleS) {
      last_land_sample = t;
      out.track.push_back(here);
    }
    if (!land.empty() && last_land_sample == t) {
      const double c = land.SignedClearance(here, 1000.0);
      out.min_land_clearance_m = std::min(out.min_land_clearance_m, c);
      if (c < 0) out.aground_s += kLandSampleS;
    }
    const double course = follower.Update(here, s.surge_mps());
    const double to_goal = (goal - here).Norm();
    if (to_goal < o.arrival_radius_m ||
        (follower.on_last_leg() && follower.leg_remaining_m() <= 0 &&
         std::abs(follower.cross_track_m()) < 3 * o.arrival_radius_m)) {
      out.arrived = true;
      break;
    }
    double speed = setup.cruise_speed_mps;
    if (to_goal < o.slow_down_distance_m) {
      speed = std::max(o.min_approach_speed_mps, speed * to_goal / o.slow_down_distance_m);
    }
    const Command cmd = avoidance.Step({t, &model, &autopilot},
                                       {course, speed, setup.cruise_speed_mps}, follower, traffic);
    for (const Event& e : cmd.events) {
      out.log.push_back(absl::StrFormat("%.0f s: %s, vessel %d (%s)%s%s", t, KindName(e.kind),
                                        e.vessel_id, RoleName(e.role), e.detail.empty() ? "" : ": ",
                                        e.detail));
      if (e.kind == EventKind::kManoeuvreStarted) ++out.manoeuvres;
    }
    for (size_t i = 0; i < setup.traffic.size(); ++i) {
      VesselOutcome& vo = out.vessels[i];
      const Role r = avoidance.RoleOf(setup.traffic[i].id);
      if (vo.role == Role::kNone && r != Role::kNone) vo.role = r;
      if (cmd.manoeuvring && vo.first_manoeuvre_s < 0 && cmd.vessel_id == setup.traffic[i].id) {
        vo.first_manoeuvre_s = t;
        vo.tcpa_at_first_manoeuvre_s = ComputeCpa(own, traffic[i].kinematics).tcpa_s;
      }
    }
    if (cmd.manoeuvring) {
      const double offset = WrapAngle(cmd.course_rad - course);
      out.max_starboard_offset_rad = std::max(out.max_starboard_offset_rad, offset);
      out.max_port_offset_rad = std::max(out.max_port_offset_rad, -offset);
      const double factor = speed > 1e-6 ? cmd.speed_mps / speed : 1.0;
      out.min_speed_factor = std::min(out.min_speed_factor, factor);
      if (!was_manoeuvring) out.manoeuvre_extents.push_back({.start_s = t});
      EncounterOutcome::Manoeuvre& m = out.manoeuvre_extents.back();
      m.max_offset_rad = std::max(m.max_offset_rad, std::abs(offset));
      m.min_speed_factor = std::min(m.min_speed_factor, factor);
    }
    was_manoeuvring = cmd.manoeuvring;
    const ActuatorCommand a = autopilot.Update(cmd.course_rad, cmd.speed_mps, s.heading_rad(),
                                               s.yaw_rate_radps(), s.surge_mps(), setup.dt_s);
    model.Step(a.throttle, a.rudder_rad, setup.dt_s);
  }
  out.arrival_time_s = t;
  const ship::ShipState& end = model.state();
  out.track.push_back({end.east_m(), end.north_m()});
  return out;
}

}  // namespace seaplan::colav
