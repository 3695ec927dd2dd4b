#include "seaplan/colav/velocity_obstacle.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/container/inlined_vector.h"

namespace seaplan::colav {
namespace {

// Metres of safety-circle violation one unit of candidate cost (m^2/s^2 of
// deviation from the desired velocity) is worth in the least-bad choice.
constexpr double kViolationPerCost = 0.01;

// Does relative motion (p_rel of the other from us, v_rel = ours - theirs)
// bring us within `r` of it within the horizon?
bool Collides(EastNorth p_rel, EastNorth v_rel, double r, double horizon) {
  double c = p_rel.Dot(p_rel) - r * r;
  if (c <= 0) return v_rel.Dot(p_rel) > 0;  // inside already: only closing velocities collide
  double a = v_rel.Dot(v_rel);
  if (a < 1e-12) return false;
  double t = p_rel.Dot(v_rel) / a;  // time of closest approach
  if (t <= 0) return false;
  double tc = std::min(t, horizon);
  EastNorth closest = p_rel - v_rel * tc;
  return closest.Dot(closest) < r * r;
}

// Time before `v` is actually sailed when the ship now has `current`.
double ManoeuvreDelay(EastNorth current, EastNorth v, const AvoidanceOptions& o) {
  if (o.turn_rate_rad_s <= 0) return 0.0;
  double cs = current.Norm(), vs = v.Norm();
  double turn =
      (cs > 0.3 && vs > 1e-6) ? std::abs(WrapAngle(CourseOf(v) - CourseOf(current))) : 0.0;
  double delay = turn / o.turn_rate_rad_s +
                 (o.acceleration_mps2 > 0 ? std::abs(vs - cs) / o.acceleration_mps2 : 0.0);
  return delay > 1e-3 ? delay + o.manoeuvre_lag_s : 0.0;
}

// Smallest distance of relative motion p_rel - v_rel * t over t in [0, horizon].
double MinDistance(EastNorth p_rel, EastNorth v_rel, double horizon) {
  const double a = v_rel.Dot(v_rel);
  const double t = a < 1e-12 ? 0.0 : std::clamp(p_rel.Dot(v_rel) / a, 0.0, std::max(horizon, 0.0));
  return (p_rel - v_rel * t).Norm();
}

// The own ship keeps its present velocity for `delay` (a ManoeuvreDelay,
// at most `horizon`), then sails `v`. Smallest distance to `other` within
// the horizon: how deep a candidate cuts into the safety circle (the
// measure of "least bad" when every candidate does).
double MinDistanceDelayed(const Kinematics& own, EastNorth v, double delay, const Kinematics& other,
                          double horizon) {
  EastNorth p_rel = other.position - own.position;
  double best = std::numeric_limits<double>::infinity();
  if (delay > 0) {
    const EastNorth v_now = own.velocity - other.velocity;
    best = MinDistance(p_rel, v_now, delay);
    p_rel = p_rel - v_now * delay;
  }
  return std::min(best, MinDistance(p_rel, v - other.velocity, horizon - delay));
}

// Same motion: does it bring the own ship within `r` of `other` within the
// horizon? (Not MinDistanceDelayed < r: inside the circle already, only a
// closing velocity collides.)
bool CollidesDelayed(const Kinematics& own, EastNorth v, double delay, const Kinematics& other,
                     double r, double horizon) {
  EastNorth p_rel = other.position - own.position;
  if (delay > 0) {
    EastNorth v_now = own.velocity - other.velocity;
    if (Collides(p_rel, v_now, r, delay)) return true;
    p_rel = p_rel - v_now * delay;
  }
  return Collides(p_rel, v - other.velocity, r, horizon - delay);
}

}  // namespace

AvoidanceDecision ChooseVelocity(const Kinematics& own, EastNorth desired,
                                 const std::vector<Obstacle>& others,
                                 const AvoidanceOptions& options) {
  AvoidanceDecision decision;
  decision.velocity = desired;
  const double r = options.safety_distance_m;
  struct Active {
    const Obstacle* o;
    Role role;
    double tcpa;
  };
  std::vector<Active> active;
  Kinematics own_desired{own.position, desired};
  for (const Obstacle& o : others) {
    Cpa cpa = ComputeCpa(own_desired, o.kinematics);
    Cpa now = ComputeCpa(own, o.kinematics);
    bool dangerous = (cpa.dcpa_m < r && cpa.tcpa_s < options.horizon_s) ||
                     (now.dcpa_m < r && now.tcpa_s < options.horizon_s) ||
                     (options.turn_rate_rad_s > 0 &&
                      CollidesDelayed(own, desired,
                                      std::min(ManoeuvreDelay(own.velocity, desired, options),
                                               options.horizon_s),
                                      o.kinematics, r, options.horizon_s));
    if (!dangerous) continue;
    Role role = ClassifyEncounter(own, o.kinematics, options.colreg);
    bool must_act =
        IsGiveWay(role) || std::min(cpa.tcpa_s, now.tcpa_s) < options.stand_on_action_tcpa_s;
    if (!must_act) {
      if (decision.role == Role::kNone) {
        decision.role = role;
        decision.vessel_id = o.id;
      }
      continue;  // stand-on: keep course and speed (rule 17 a i)
    }
    active.push_back({&o, role, cpa.tcpa_s});
  }
  if (active.empty()) return decision;

  const double desired_speed = desired.Norm();
  const double desired_course = desired_speed > 1e-6 ? CourseOf(desired) : CourseOf(own.velocity);
  double best_cost = std::numeric_limits<double>::infinity();
  EastNorth best = desired;
  bool found = false;
  double least_violation = std::numeric_limits<double>::infinity();
  EastNorth least_bad = desired;
  const int steps =
      static_cast<int>(std::round(options.max_course_change_rad / options.course_step_rad));
  absl::InlinedVector<double, 8> speeds;
  for (double f : options.speed_factors) speeds.push_back(desired_speed * f);
  if (options.max_speed_mps > desired_speed * 1.05) {
    for (double f : {1.25, 1.5})
      speeds.push_back(std::min(desired_speed * f, options.max_speed_mps));
  }
  for (double speed : speeds) {
    const double f = desired_speed > 1e-9 ? speed / desired_speed : 1.0;
    for (int k = -steps; k <= steps; ++k) {
      double course = desired_course + k * options.course_step_rad;
      EastNorth v = VelocityOf(course, speed);
      const double delay = std::min(ManoeuvreDelay(own.velocity, v, options), options.horizon_s);
      bool ok = true;
      double violation = 0;
      for (const Active& a : active) {
        EastNorth p_rel = a.o->kinematics.position - own.position;
        EastNorth v_rel = v - a.o->kinematics.velocity;
        if (CollidesDelayed(own, v, delay, a.o->kinematics, r, options.horizon_s)) {
          ok = false;
          // Depth of the cut under the modelled delay, less a tenth of the
          // clearance the velocity would give if taken at once (bounded by
          // r, so one vessel's wide berth cannot hide a cut into another's
          // circle): the delay is an estimate, and of candidates it makes
          // equal, the one that turns away more decisively is the safer bet.
          const double at_once = MinDistance(p_rel, v_rel, options.horizon_s);
          violation += std::max(0.0, r - MinDistanceDelayed(own, v, delay, a.o->kinematics,
                                                            options.horizon_s)) +
                       0.1 * std::clamp(r - at_once, -r, r);
        }
        // COLREG: give way to starboard (rules 14, 15): the relative
        // velocity must pass the other with it on our port side.
        if ((a.role == Role::kHeadOn || a.role == Role::kCrossingGiveWay) &&
            p_rel.Cross(v_rel) > 0) {
          ok = false;
          violation += 1.0;
        }
      }
      // Prefer small deviations, starboard turns over port, course changes
      // over speed changes (speeding up costs more: fuel, and a slower
      // ship's intentions are easier for others to read).
      double dev = v.east_m - desired.east_m, dev_y = v.north_m - desired.north_m;
      double cost = dev * dev + dev_y * dev_y +
                    (k < 0 ? 0.5 : 0.0) * desired_speed * desired_speed * 0.01 +
                    (f <= 1.0 ? (1.0 - f) * 0.5 : (f - 1.0)) * desired_speed * desired_speed;
      // Among candidates that all cut into the circle by about as much (a
      // slow-turning hull: the delay dominates), the one nearest the desired
      // velocity, so the choice does not swing between far-apart courses.
      violation += ok ? 0.0 : kViolationPerCost * cost;
      // Land, checked only for a candidate that could be chosen (the check
      // is the costly part: the land's edges against the track).
      if (options.land != nullptr && (ok ? cost < best_cost : violation < least_violation)) {
        const double clear = options.land->Clearance(
            own.position, own.position + v * options.land_lookahead_s, options.land_clearance_m);
        if (clear < options.land_clearance_m) {
          ok = false;
          // Worse than any CPA shortfall; when every candidate is short of
          // the clearance, the one nearest to clear.
          violation += 1e6 + 1e3 * (options.land_clearance_m - clear);
        }
      }
      if (ok && cost < best_cost) {
        best_cost = cost;
        best = v;
        found = true;
      }
      if (!ok && violation < least_violation) {
        least_violation = violation;
        least_bad = v;
      }
    }
  }
  const Active* main = &active.front();
  for (const Active& a : active) {
    if (a.tcpa < main->tcpa) main = &a;
  }
  decision.vessel_id = main->o->id;
  decision.role = main->role;
  decision.feasible = found;
  decision.velocity = found ? best : least_bad;
  decision.manoeuvring = (decision.velocity - desired).Norm() > 1e-6;
  return decision;
}

}  // namespace seaplan::colav
