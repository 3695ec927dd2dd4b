#include "seaplan/colav/colav.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_format.h"
#include "seaplan/ship/steady_state.h"

namespace seaplan::colav {
namespace {

constexpr double kDegToRad = M_PI / 180.0;
constexpr double kQuarterTurnRad = M_PI / 2.0;
// Steps between the land checks of a predicted track (one segment each).
constexpr int kLandCheckEvery = 5;
// A give-way vessel passed closer than this many safety distances counts
// for the side it is passed on (further off, the side does not matter).
constexpr double kSideCheckFactor = 4.0;
// Below this speed a vessel is taken as lying still: no COLREG role, keep clear of it.
constexpr double kStillMps = 0.5;
// Without a non-zero course offset in the options, a parallel track is
// turned onto by this much (rule 8: readily apparent).
constexpr double kDefaultTurnRad = 30.0 * kDegToRad;

bool IsStandOn(Role r) {
  return r == Role::kCrossingStandOn || r == Role::kOvertaken;
}

Kinematics OwnKinematics(const ship::ShipModel& m) {
  const ship::ShipState& s = m.state();
  return {{s.east_m(), s.north_m()}, VelocityOf(s.heading_rad(), s.surge_mps())};
}

// The other vessel is getting further away and is beyond `distance_m`.
bool Passed(const Kinematics& own, const Kinematics& other, double distance_m) {
  const EastNorth p = other.position - own.position;
  return p.Norm() > distance_m && p.Dot(other.velocity - own.velocity) >= 0;
}

std::string BehaviourText(double offset_rad, double factor, double track_offset_m) {
  const double deg = std::round(std::abs(offset_rad) / kDegToRad);
  const std::string course =
      track_offset_m != 0 ? absl::StrFormat("track %.0f m to %s", std::abs(track_offset_m),
                                            track_offset_m > 0 ? "starboard" : "port")
      : deg < 0.5         ? std::string("course kept")
                  : absl::StrFormat("%s %.0f deg", offset_rad > 0 ? "starboard" : "port", deg);
  return absl::StrFormat("%s, speed %.0f %%", course, factor * 100.0);
}

}  // namespace

std::string_view PolicyName(Policy p) {
  return p == Policy::kScenarioMpc ? "sbmpc" : "vo";
}

Status CollisionAvoidanceOptions::Validate() const {
  if (!(safety_distance_m > 0) || !(margin_factor >= 1.0) || !(horizon_s > 0) ||
      !(prediction_step_s > 0) || prediction_step_s > horizon_s || !(decision_interval_s >= 0) ||
      !(rule17_time_s >= 0) || !(land_clearance_m >= 0) || !(min_land_clearance_m >= 0) ||
      !(land_step_m > 0) || !(margin_land_clearance_m >= 0) || !(rejoined_cross_track_m > 0) ||
      !(uncertain_speed_mps >= 0) || !(uncertain_margin_factor >= 0)) {
    return absl::InvalidArgumentError(absl::StrFormat(
        "collision avoidance: safety_distance_m (%g), horizon_s (%g), prediction_step_s (%g, "
        "at most the horizon) and rejoined_cross_track_m (%g) must be > 0, margin_factor (%g) "
        ">= 1, decision_interval_s (%g), rule17_time_s (%g), land_clearance_m (%g), "
        "min_land_clearance_m (%g), uncertain_speed_mps (%g), uncertain_margin_factor (%g) and "
        "margin_land_clearance_m (%g) >= 0, land_step_m (%g) > 0",
        safety_distance_m, horizon_s, prediction_step_s, rejoined_cross_track_m, margin_factor,
        decision_interval_s, rule17_time_s, land_clearance_m, min_land_clearance_m,
        uncertain_speed_mps, uncertain_margin_factor, margin_land_clearance_m, land_step_m));
  }
  if (course_offsets_deg.empty() || speed_factors.empty()) {
    return absl::InvalidArgumentError(
        "collision avoidance: course_offsets_deg and speed_factors must not be empty");
  }
  for (double f : speed_factors) {
    if (!(f >= 0) || f > 2.0) {
      return absl::InvalidArgumentError(
          absl::StrFormat("collision avoidance: speed factor %g is not in [0, 2]", f));
    }
  }
  for (double o : course_offsets_deg) {
    if (!(std::abs(o) <= 180.0)) {
      return absl::InvalidArgumentError(
          absl::StrFormat("collision avoidance: course offset %g deg is not in [-180, 180]", o));
    }
  }
  for (double o : track_offsets_m) {
    if (!std::isfinite(o) || o == 0) {
      return absl::InvalidArgumentError(
          absl::StrFormat("collision avoidance: track offset %g m must be finite and non-zero", o));
    }
  }
  return absl::OkStatus();
}

StatusOr<CollisionAvoidance> CollisionAvoidance::Create(const CollisionAvoidanceOptions& options) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  return CollisionAvoidance(options);
}

CollisionAvoidance::CollisionAvoidance(const CollisionAvoidanceOptions& options)
    : options_(options) {
  vo_.safety_distance_m = options.safety_distance_m * options.margin_factor;
  vo_.colreg = options.colreg;
  vo_.turn_rate_rad_s = options.turn_rate_rad_s;
  vo_.manoeuvre_lag_s = options.manoeuvre_lag_s;
  vo_.land_clearance_m = options.land_clearance_m;
  min_turn_rad_ = std::numeric_limits<double>::infinity();
  for (double o : options.course_offsets_deg) {
    if (std::abs(o) > 1e-9) min_turn_rad_ = std::min(min_turn_rad_, std::abs(o) * kDegToRad);
  }
  if (!std::isfinite(min_turn_rad_) || min_turn_rad_ >= kQuarterTurnRad) {
    min_turn_rad_ = kDefaultTurnRad;
  }
}

double CollisionAvoidance::TrackCourse(const PathFollower& follower, double track_offset_m) const {
  const std::vector<EastNorth>& pts = follower.path();
  const size_t leg = static_cast<size_t>(follower.leg());
  // Line of sight to the parallel track with the look-ahead that starts the
  // turn at min_turn_rad_ from the leg's course: smaller alterations would
  // not be readily apparent, and the path follower's own look-ahead (sized
  // for rejoining the route) would turn by only a few degrees.
  const double lookahead = std::abs(track_offset_m) / std::tan(min_turn_rad_);
  return CourseOf(pts[leg + 1] - pts[leg]) -
         std::atan((follower.cross_track_m() - track_offset_m) / lookahead);
}

double CollisionAvoidance::CommandedCourse(double path_course_rad, const PathFollower& path,
                                           Behaviour b) const {
  return b.track_offset_m != 0 ? TrackCourse(path, b.track_offset_m)
                               : path_course_rad + b.offset_rad;
}

std::vector<double> CollisionAvoidance::UncertainGrowth(
    const std::vector<Obstacle>& traffic) const {
  std::vector<double> growth(traffic.size(), 0.0);
  for (size_t i = 0; i < traffic.size(); ++i) {
    if (traffic[i].kinematics.velocity.Norm() < kStillMps) {
      growth[i] = options_.uncertain_speed_mps;
    }
  }
  return growth;
}

double CollisionAvoidance::PathLandClearance(const PathFollower& path, double reach_m,
                                             double limit_m) const {
  const std::vector<EastNorth>& pts = path.path();
  double clear = limit_m, along = 0.0;
  for (size_t j = static_cast<size_t>(path.leg()); j + 1 < pts.size() && along < reach_m; ++j) {
    clear = std::min(clear, options_.land->Clearance(pts[j], pts[j + 1], limit_m));
    along += (pts[j + 1] - pts[j]).Norm();
  }
  return clear;
}

Role CollisionAvoidance::RoleOf(int vessel_id) const {
  auto it = roles_.find(vessel_id);
  return it == roles_.end() ? Role::kNone : it->second;
}

Command CollisionAvoidance::Step(const OwnShip& own, const DesiredMotion& desired,
                                 const PathFollower& path, const std::vector<Obstacle>& traffic) {
  if (own.model == nullptr || own.autopilot == nullptr) return Hold(desired);
  Command out = options_.policy == Policy::kScenarioMpc
                    ? StepScenarioMpc(own, desired, path, traffic)
                    : StepVelocityObstacle(own, desired, path, traffic);
  if (out.manoeuvring) {
    rejoining_ = true;
  } else if (std::abs(path.cross_track_m()) <= options_.rejoined_cross_track_m) {
    rejoining_ = false;
  }
  out.collision_avoidance_active = out.manoeuvring || rejoining_;
  return out;
}

Command CollisionAvoidance::Hold(const DesiredMotion& desired) const {
  Command c;
  c.course_rad = desired.course_rad;
  c.speed_mps = desired.speed_mps;
  return c;
}

void CollisionAvoidance::NoteEncounters(const std::set<int>& now, Command* out) {
  for (int id : now) {
    if (dangerous_.contains(id)) continue;
    Event e;
    e.kind = EventKind::kPotentialCollision;
    e.vessel_id = id;
    e.role = RoleOf(id);
    out->events.push_back(std::move(e));
  }
  dangerous_ = now;
}

double CollisionAvoidance::PenaltyAt(double d) const {
  const double safe = options_.safety_distance_m;
  const double plan = safe * options_.margin_factor;
  if (d >= plan) return 0.0;
  const ScenarioMpcWeights& w = options_.weights;
  if (d >= safe) {
    const double x = plan > safe ? (plan - d) / (plan - safe) : 1.0;
    return w.collision * x * x;
  }
  return w.collision + w.inside_safety + w.inside_safety_per_m * (safe - d);
}

CollisionAvoidance::Prediction CollisionAvoidance::Predict(
    const OwnShip& own, const DesiredMotion& desired, const PathFollower& path,
    const std::vector<Obstacle>& traffic, Behaviour b, const std::vector<bool>& release) const {
  ship::ShipModel model = *own.model;
  Autopilot autopilot = *own.autopilot;
  PathFollower follower = path;
  const double dt = options_.prediction_step_s;
  const double plan = options_.safety_distance_m * options_.margin_factor;
  const size_t n = traffic.size();
  Prediction p;
  constexpr double kFar = std::numeric_limits<double>::infinity();
  p.vessels.assign(n, {kFar, kFar, 0.0, 0.0});
  const double max_margin = options_.uncertain_margin_factor * options_.safety_distance_m;
  std::vector<double> worst(n, 0.0), worst_certain(n, 0.0), last_distance(n, 0.0);
  const bool releasable = std::find(release.begin(), release.end(), true) != release.end();
  bool active = !(b == Behaviour{});
  bool arrived = false;
  const EastNorth goal = follower.path().back();
  const double cruise = desired.cruise_speed_mps > 0 ? desired.cruise_speed_mps : desired.speed_mps;
  EastNorth here{model.state().east_m(), model.state().north_m()};
  EastNorth land_from = here;
  for (size_t i = 0; i < n; ++i) last_distance[i] = (traffic[i].kinematics.position - here).Norm();
  const int steps = static_cast<int>(std::floor(options_.horizon_s / dt + 1e-9));
  const double land_limit = std::max(
      {options_.land_clearance_m, options_.min_land_clearance_m, options_.margin_land_clearance_m});
  if (options_.land != nullptr) p.min_land_m = land_limit;
  for (int k = 1; k <= steps; ++k) {
    const double t = k * dt;
    const EastNorth before = here;
    if (!arrived) {
      const ship::ShipState& s = model.state();
      double course = follower.Update(here, s.surge_mps());
      const double to_goal = (goal - here).Norm();
      if (to_goal < options_.arrival_radius_m ||
          (follower.on_last_leg() && follower.leg_remaining_m() <= 0)) {
        arrived = true;  // stops at the berth, as the executor does
      } else {
        double speed = cruise;
        if (to_goal < options_.slow_down_distance_m) {
          speed = std::max(options_.min_approach_speed_mps,
                           cruise * to_goal / options_.slow_down_distance_m);
        }
        if (active) {
          course = CommandedCourse(course, follower, b);
          speed *= b.speed_factor;
        }
        const ActuatorCommand c =
            autopilot.Update(course, speed, s.heading_rad(), s.yaw_rate_radps(), s.surge_mps(), dt);
        model.Step(c.throttle, c.rudder_rad, dt);
        here = {model.state().east_m(), model.state().north_m()};
      }
    }
    const EastNorth moved = here - before;
    const double course_over_ground =
        moved.Norm() > 1e-6 ? CourseOf(moved) : model.state().heading_rad();
    // Near-term risk is certain, far-term risk may go away (the traffic
    // changes its mind, a later decision acts): weigh it down linearly.
    const double weight = 1.0 - 0.5 * t / options_.horizon_s;
    bool all_passed = true;
    double own_land_m = -1.0;  // the ship's distance to the land, once a margin needs it
    for (size_t i = 0; i < n; ++i) {
      const EastNorth other = traffic[i].kinematics.position + traffic[i].kinematics.velocity * t;
      const EastNorth rel = other - here;
      const double d = rel.Norm();
      VesselPrediction& v = p.vessels[i];
      if (d < v.min_distance_m) {
        v.min_distance_m = d;
        v.time_s = t;
        v.bearing_rad = WrapAngle(std::atan2(rel.east_m, rel.north_m) - course_over_ground);
      }
      const double growth = i < growth_.size() ? growth_[i] : 0.0;
      double margin = std::min(growth * t, max_margin);
      if (margin > 0 && options_.land != nullptr) {
        // No more room from the vessel than the ship has from the land
        // beyond margin_land_clearance_m.
        if (own_land_m < 0) {
          own_land_m =
              options_.land->Clearance(here, here, options_.margin_land_clearance_m + max_margin);
        }
        margin = std::min(margin, std::max(0.0, own_land_m - options_.margin_land_clearance_m));
      }
      v.min_margin_m = std::min(v.min_margin_m, d - margin);
      worst[i] = std::max(worst[i], weight * PenaltyAt(d - margin));
      worst_certain[i] = std::max(worst_certain[i], weight * PenaltyAt(d));
      if (release[i] && !(d - margin > plan && d >= last_distance[i])) all_passed = false;
      last_distance[i] = d;
    }
    if (active && releasable && all_passed) active = false;  // rejoin the path
    if (options_.land != nullptr && (k % kLandCheckEvery == 0 || k == steps)) {
      const double clear = options_.land->Clearance(land_from, here, land_limit);
      land_from = here;
      p.min_land_m = std::min(p.min_land_m, clear);
      if (clear < options_.land_clearance_m) {
        const double x = (options_.land_clearance_m - clear) / options_.land_clearance_m;
        const double cost = clear <= 0 ? options_.weights.aground : options_.weights.land * x * x;
        p.land_cost = std::max(p.land_cost, weight * cost);
      }
    }
  }
  for (double w : worst) p.collision_cost += w;
  for (double w : worst_certain) p.certain_collision_cost += w;
  return p;
}

Command CollisionAvoidance::StepScenarioMpc(const OwnShip& own, const DesiredMotion& desired,
                                            const PathFollower& path,
                                            const std::vector<Obstacle>& traffic) {
  Command out = Hold(desired);
  if (own.time_s + 1e-9 < next_decision_s_) {
    out.course_rad = CommandedCourse(desired.course_rad, path, behaviour_);
    out.speed_mps = desired.speed_mps * behaviour_.speed_factor;
    out.manoeuvring = manoeuvring_;
    out.vessel_id = manoeuvre_vessel_;
    out.role = manoeuvre_role_;
    return out;
  }
  next_decision_s_ = own.time_s + options_.decision_interval_s;
  const double plan = options_.safety_distance_m * options_.margin_factor;
  const Kinematics self = OwnKinematics(*own.model);
  const size_t n = traffic.size();
  const std::vector<bool> none(n, false);
  growth_ = UncertainGrowth(traffic);
  // The nominal prediction is read for the vessels and for the return to
  // the path after a manoeuvre. With neither (no traffic and no manoeuvre
  // under way or ending, as when a planned route is sailed alone) nothing
  // below reads it, the decision is the nominal behaviour, and the
  // prediction (a simulation over the whole horizon) is not made.
  const bool nominal_read = n > 0 || manoeuvring_ || rejoining_;
  const Prediction nominal =
      nominal_read ? Predict(own, desired, path, traffic, Behaviour{}, none) : Prediction{};

  // The encounters: vessels the nominal behaviour brings within the planning
  // distance, and those a manoeuvre under way is for until they are passed.
  std::vector<bool> release(n, false);
  std::set<int> conflict;
  for (size_t i = 0; i < n; ++i) {
    const Obstacle& o = traffic[i];
    const bool in_conflict = nominal.vessels[i].min_margin_m < plan;
    const bool held = manoeuvring_ && roles_.contains(o.id) && !Passed(self, o.kinematics, plan);
    if (in_conflict) conflict.insert(o.id);
    if (!in_conflict && !held) {
      if (Passed(self, o.kinematics, plan)) {
        roles_.erase(o.id);
        rule17_.erase(o.id);
      }
      continue;
    }
    release[i] = true;
    // A vessel that lay still when its encounter started and has got under
    // way since has a role now.
    const bool moving = o.kinematics.velocity.Norm() >= kStillMps;
    if (!roles_.contains(o.id) || (roles_[o.id] == Role::kNone && moving)) {
      // Judged on the course of the path's leg, not on the heading of a
      // manoeuvre under way for another vessel or of the return to the path
      // (a temporary heading makes a head-on vessel look like one crossing).
      const std::vector<EastNorth>& pts = path.path();
      const size_t leg = static_cast<size_t>(path.leg());
      const Kinematics steering{
          self.position, VelocityOf(CourseOf(pts[leg + 1] - pts[leg]), self.velocity.Norm())};
      roles_[o.id] =
          moving ? ClassifyEncounter(steering, o.kinematics, options_.colreg) : Role::kNone;
    }
    const Role role = roles_[o.id];
    if (IsStandOn(role) && in_conflict && nominal.vessels[i].time_s < options_.rule17_time_s) {
      rule17_.insert(o.id);
    }
  }
  NoteEncounters(conflict, &out);

  // Must the ship act? Not while every encounter leaves it stand-on (rule 17 a i).
  bool act = false;
  int main_vessel = -1;
  double main_time = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < n; ++i) {
    if (!release[i]) continue;
    const int id = traffic[i].id;
    if (!IsStandOn(roles_[id]) || rule17_.contains(id)) {
      act = true;
      if (nominal.vessels[i].time_s < main_time) {
        main_time = nominal.vessels[i].time_s;
        main_vessel = id;
      }
    }
  }

  // The land comes first: a behaviour that takes the ship closer to it
  // than the hard minimum (or than the path ahead does) loses against any
  // that does not; of those that all do, the one that stays furthest off.
  double land_floor = options_.min_land_clearance_m;
  if (options_.land != nullptr) {
    const double cruise =
        desired.cruise_speed_mps > 0 ? desired.cruise_speed_mps : desired.speed_mps;
    land_floor = std::min(land_floor, PathLandClearance(path, cruise * options_.horizon_s,
                                                        options_.min_land_clearance_m));
  }
  // The return to the path after a manoeuvre is the avoidance's doing too:
  // where it would take the ship closer to the land than that (this hull,
  // turning back at full speed, sweeps wide), the behaviours are compared
  // for the land alone until the return is clear.
  if (!act && (manoeuvring_ || rejoining_) && nominal.min_land_m < land_floor - 1e-6) {
    act = true;
    main_vessel = manoeuvre_vessel_;
  }

  Behaviour chosen;
  if (act) {
    const ScenarioMpcWeights& w = options_.weights;
    double best = std::numeric_limits<double>::infinity();
    double best_short = std::numeric_limits<double>::infinity();
    const double margin_land = std::min(nominal.min_land_m, options_.margin_land_clearance_m);
    const double nominal_uncertain = nominal.collision_cost - nominal.certain_collision_cost;
    std::vector<Behaviour> behaviours;
    for (double factor : options_.speed_factors) {
      for (double offset_deg : options_.course_offsets_deg) {
        behaviours.push_back({offset_deg * kDegToRad, factor, 0.0});
      }
      for (double track_m : options_.track_offsets_m) behaviours.push_back({0.0, factor, track_m});
    }
    const double safe = options_.safety_distance_m;
    for (const Behaviour& b : behaviours) {
      const double factor = b.speed_factor;
      const Prediction p =
          b == Behaviour{} ? nominal : Predict(own, desired, path, traffic, b, release);
      // Room from a vessel lying still (its growing margin) is not worth
      // coming closer to the land than the nominal behaviour does: such a
      // behaviour is charged at least the nominal's cost of that margin.
      double collision = p.collision_cost;
      if (p.min_land_m < margin_land - options_.land_step_m) {
        collision = p.certain_collision_cost +
                    std::max(p.collision_cost - p.certain_collision_cost, nominal_uncertain);
      }
      double cost = collision + p.land_cost;
      for (size_t i = 0; i < n; ++i) {
        if (!release[i]) continue;
        const Role role = roles_[traffic[i].id];
        const bool starboard_rule = role == Role::kHeadOn || role == Role::kCrossingGiveWay;
        // Rules 14, 15: the other passed on our port side (port to port,
        // astern of a crossing vessel).
        if (starboard_rule && p.vessels[i].bearing_rad > 0 &&
            p.vessels[i].min_distance_m < kSideCheckFactor * options_.safety_distance_m) {
          cost += w.colreg_side;
        }
        // Rules 14, 15 and 17 c: no turn to port.
        const bool no_port =
            starboard_rule || (role == Role::kCrossingStandOn && rule17_.contains(traffic[i].id));
        if (no_port && b.offset_rad < 0) {
          cost += w.colreg_port_turn * (0.5 + 0.5 * std::abs(b.offset_rad) / kQuarterTurnRad);
        }
        if (no_port && b.track_offset_m < 0) {
          cost += w.colreg_port_turn * (0.5 + 0.5 * min_turn_rad_ / kQuarterTurnRad);
        }
      }
      const double x = b.offset_rad / kQuarterTurnRad;
      const double y = b.track_offset_m / safe;
      const double side = b.offset_rad < 0 || b.track_offset_m < 0 ? w.port_factor : 1.0;
      cost += (w.course_offset * x * x + w.track_offset * y * y) * side +
              w.speed_reduction * (1.0 - std::min(factor, 1.0));
      // Hysteresis on ending a manoeuvre: back to the nominal behaviour
      // only once it is predicted clear (else the ship alternates between
      // a manoeuvre and the nominal behaviour every decision, each undoing
      // the other's prediction).
      if (manoeuvring_ && b == Behaviour{} && nominal.collision_cost > 0) cost += w.collision;
      if (manoeuvring_) {
        cost +=
            w.change_course * (std::abs(b.offset_rad - behaviour_.offset_rad) / kQuarterTurnRad +
                               std::abs(b.track_offset_m - behaviour_.track_offset_m) / safe) +
            w.change_speed * std::abs(b.speed_factor - behaviour_.speed_factor);
      }
      // The shortfall from the floor in steps of land_step_m (0: none).
      const double short_m = land_floor - p.min_land_m;
      const double land_short = short_m > 1e-6 ? std::ceil(short_m / options_.land_step_m) : 0.0;
      if (land_short < best_short || (land_short == best_short && cost < best - 1e-9)) {
        best = cost;
        best_short = land_short;
        chosen = b;
      }
    }
  }
  const bool manoeuvre = !(chosen == Behaviour{});
  if (manoeuvre && (!manoeuvring_ || !(chosen == behaviour_))) {
    Event e;
    e.kind = EventKind::kManoeuvreStarted;
    e.vessel_id = main_vessel;
    e.role = RoleOf(main_vessel);
    e.detail = BehaviourText(chosen.offset_rad, chosen.speed_factor, chosen.track_offset_m);
    if (manoeuvring_) e.detail = "changed: " + e.detail;
    out.events.push_back(std::move(e));
  } else if (!manoeuvre && manoeuvring_) {
    Event e;
    e.kind = EventKind::kManoeuvreEnded;
    e.vessel_id = manoeuvre_vessel_;
    e.role = manoeuvre_role_;
    out.events.push_back(std::move(e));
  }
  behaviour_ = chosen;
  manoeuvring_ = manoeuvre;
  if (manoeuvre) {
    manoeuvre_vessel_ = main_vessel;
    manoeuvre_role_ = RoleOf(main_vessel);
  }
  out.course_rad = CommandedCourse(desired.course_rad, path, chosen);
  out.speed_mps = desired.speed_mps * chosen.speed_factor;
  out.manoeuvring = manoeuvre;
  out.vessel_id = manoeuvre ? manoeuvre_vessel_ : -1;
  out.role = manoeuvre ? manoeuvre_role_ : Role::kNone;
  return out;
}

Command CollisionAvoidance::StepVelocityObstacle(const OwnShip& own, const DesiredMotion& desired,
                                                 const PathFollower& path,
                                                 const std::vector<Obstacle>& traffic) {
  Command out = Hold(desired);
  const Kinematics self = OwnKinematics(*own.model);
  const EastNorth here = self.position;
  const size_t next = static_cast<size_t>(path.leg()) + 1;
  const double plan = vo_.safety_distance_m;
  double speed = desired.speed_mps;
  // Path-ahead check: the highest of these speeds at which no vessel comes
  // within the planning distance of the route ahead; when none clears them
  // all (a vessel from astern, or one already close), full speed, left to
  // the velocity obstacles.
  if (options_.path_lookahead_s > 0 && !traffic.empty()) {
    int blocking_at_full = -1;
    double chosen = speed;
    for (double f : {1.0, 0.75, 0.5, 0.3}) {
      int blocking = -1;
      for (const Obstacle& o : traffic) {
        const PathApproach a = PathAheadClosestApproach(path.path(), next, here, speed * f,
                                                        o.kinematics, options_.path_lookahead_s);
        if (a.distance_m < plan) {
          blocking = o.id;
          break;
        }
      }
      if (f == 1.0) blocking_at_full = blocking;
      if (blocking < 0) {
        chosen = speed * f;
        break;
      }
    }
    const bool slowed = chosen < speed - 1e-9;
    if (slowed && !path_slowed_) {
      out.events.push_back({EventKind::kSpeedReduced, blocking_at_full, Role::kNone,
                            absl::StrFormat("speed reduced to %.1f m/s", chosen)});
    }
    path_slowed_ = slowed;
    speed = chosen;
  }
  vo_.land = options_.land;
  const ship::MsoMode mode = own.model->mode();
  vo_.max_speed_mps = ship::TopSpeed(ship::ShipParams{}, own.model->machinery(), mode);
  // A vessel the ship clears along its route (the path ahead at the speed it
  // is ramping to) and that is not closing in on its present motion is no
  // encounter: the straight-line models would call a ship leaving its berth
  // "in danger" of a vessel it will pass well ahead of.
  scratch_.clear();
  std::set<int> dangerous_now;
  for (const Obstacle& o : traffic) {
    const Cpa now = ComputeCpa(self, o.kinematics);
    const bool closing_now = now.dcpa_m < options_.safety_distance_m && now.tcpa_s < vo_.horizon_s;
    if (closing_now) dangerous_now.insert(o.id);
    const PathApproach along = PathAheadClosestApproach(
        path.path(), next, here, speed, o.kinematics, options_.path_lookahead_s, 5.0,
        self.velocity.Norm(), vo_.acceleration_mps2);
    if (along.distance_m >= plan && !closing_now) continue;
    scratch_.push_back(o);
  }
  const AvoidanceDecision d =
      ChooseVelocity(self, VelocityOf(desired.course_rad, speed), scratch_, vo_);
  if (d.role != Role::kNone) dangerous_now.insert(d.vessel_id);
  roles_.clear();
  for (const Obstacle& o : traffic) {
    if (dangerous_now.contains(o.id)) roles_[o.id] = ClassifyEncounter(self, o.kinematics);
  }
  NoteEncounters(dangerous_now, &out);
  if (d.manoeuvring && !manoeuvring_) {
    out.events.push_back({EventKind::kManoeuvreStarted, d.vessel_id, d.role, ""});
    manoeuvre_vessel_ = d.vessel_id;
    manoeuvre_role_ = d.role;
  } else if (!d.manoeuvring && manoeuvring_) {
    out.events.push_back({EventKind::kManoeuvreEnded, manoeuvre_vessel_, manoeuvre_role_, ""});
  }
  manoeuvring_ = d.manoeuvring;
  out.manoeuvring = d.manoeuvring;
  out.vessel_id = d.manoeuvring ? d.vessel_id : -1;
  out.role = d.manoeuvring ? d.role : Role::kNone;
  out.course_rad = d.manoeuvring ? CourseOf(d.velocity) : desired.course_rad;
  out.speed_mps = d.manoeuvring ? d.velocity.Norm() : speed;
  return out;
}

}  // namespace seaplan::colav
