#include "seaplan/ship/route_follower.h"

#include <cmath>
#include <string>
#include <utility>

#include "absl/strings/str_cat.h"
#include "seaplan/ship/steady_state.h"

namespace seaplan::ship {

Status RouteFollowerOptions::Validate() const {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    return absl::InvalidArgumentError(
        absl::StrCat("RouteFollowerOptions.dt_s ", dt_s, " must be > 0"));
  }
  SEAPLAN_RETURN_IF_ERROR(los.Validate());
  SEAPLAN_RETURN_IF_ERROR(heading.Validate());
  return speed.Validate();
}

StatusOr<RouteFollower> RouteFollower::Create(const ShipParams& ship,
                                              const MachineryParams& machinery,
                                              const Environment& env, PlannedRoute route,
                                              const RouteFollowerOptions& options,
                                              const ShipState* initial) {
  SEAPLAN_RETURN_IF_ERROR(options.Validate());
  const size_t legs = route.waypoints_ne.size() < 2 ? 0 : route.waypoints_ne.size() - 1;
  if (legs == 0 || route.leg_modes.size() != legs || route.leg_speeds_mps.size() != legs) {
    return absl::InvalidArgumentError(absl::StrCat(
        "PlannedRoute: ", route.waypoints_ne.size(),
        " waypoints need >= 2 waypoints and one mode and "
        "speed per leg; got ",
        route.leg_modes.size(), " modes and ", route.leg_speeds_mps.size(), " speeds"));
  }
  for (size_t i = 0; i < legs; ++i) {
    if (!(route.leg_speeds_mps[i] > 0.0) || !std::isfinite(route.leg_speeds_mps[i])) {
      return absl::InvalidArgumentError(absl::StrCat("PlannedRoute: leg ", i, " speed ",
                                                     route.leg_speeds_mps[i], " must be > 0"));
    }
  }
  SEAPLAN_ASSIGN_OR_RETURN(LosGuidance los, LosGuidance::Create(route.waypoints_ne, options.los));
  ShipState start;
  double thrust = 0.0;
  if (initial != nullptr) {
    start = *initial;
  } else {
    const Eigen::Vector2d d = route.waypoints_ne[1] - route.waypoints_ne[0];
    const MsoMode mode = route.leg_modes[0];
    const double speed = std::min(route.leg_speeds_mps[0], TopSpeed(ship, machinery, mode));
    start = ShipState::At(route.waypoints_ne[0][0], route.waypoints_ne[0][1],
                          std::atan2(d[1], d[0]), speed);
    auto throttle = ThrottleForSpeed(ship, machinery, mode, speed);
    if (throttle.ok()) thrust = SteadyThrust(machinery, mode, *throttle);
  }
  SEAPLAN_ASSIGN_OR_RETURN(
      ShipModel model, ShipModel::Create(ship, machinery, env, start, route.leg_modes[0], thrust));
  return RouteFollower(std::move(model), std::move(los), std::move(route), options);
}

void RouteFollower::Step() {
  if (finished()) return;
  const ShipState& s = ship_.state();
  const double psi_d = los_.Update(s.eta[0], s.eta[1]);
  const int leg = current_leg();
  ship_.set_mode(route_.leg_modes[leg]);
  throttle_ = speed_.Throttle(route_.leg_speeds_mps[leg], s.nu[0]);
  rudder_ = heading_.RudderAngle(psi_d, s.eta[2]);
  ship_.Step(throttle_, rudder_, options_.dt_s);
}

bool RouteFollower::RunUntilFinished(double max_time_s) {
  while (!finished() && ship_.time_s() < max_time_s) Step();
  return finished();
}

}  // namespace seaplan::ship
