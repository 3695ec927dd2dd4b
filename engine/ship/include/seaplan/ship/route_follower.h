// Closed-loop execution of a planned route on the ship model: LOS guidance
// (SITS NavigationSystem) -> heading PID -> rudder, speed PI -> throttle, MSO
// mode and speed set per leg, fuel tracked by the ship model. This is what a
// simulation client steps to "sail" a plan.
//
// Leg i runs from waypoint i to waypoint i + 1 and uses leg_modes[i] and
// leg_speeds_mps[i]; the active leg is LOS's target index - 1. A speed above
// the mode's top speed simply saturates the throttle (1.1 by default).
//
// Thread-safety: one instance per simulated ship. Step() allocates nothing.
#pragma once

#include <vector>

#include "Eigen/Core"
#include "seaplan/common/status.h"
#include "seaplan/ship/control.h"
#include "seaplan/ship/machinery.h"
#include "seaplan/ship/ship_model.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::ship {

struct PlannedRoute {
  std::vector<Eigen::Vector2d> waypoints_ne;  // >= 2, (N, E) metres
  std::vector<MsoMode> leg_modes;             // waypoints - 1 entries
  std::vector<double> leg_speeds_mps;         // waypoints - 1 entries, > 0
};

struct RouteFollowerOptions {
  double dt_s = 0.5;
  LosOptions los;
  HeadingControllerOptions heading;
  SpeedControllerOptions speed;
  Status Validate() const;
};

class RouteFollower {
 public:
  // Starts at the first waypoint heading along the first leg at its speed,
  // with the thrust that holds that speed in calm water, unless `initial` is
  // given.
  static StatusOr<RouteFollower> Create(const ShipParams& ship, const MachineryParams& machinery,
                                        const Environment& env, PlannedRoute route,
                                        const RouteFollowerOptions& options = {},
                                        const ShipState* initial = nullptr);

  // One control + integration step of dt_s. No-op once finished().
  void Step();
  // Steps until finished() or `max_time_s` of simulated time; returns whether
  // the route was completed.
  bool RunUntilFinished(double max_time_s);

  bool finished() const { return los_.finished(); }
  int current_leg() const { return los_.target_index() - 1; }
  const ShipModel& ship() const { return ship_; }
  double time_s() const { return ship_.time_s(); }
  double last_throttle() const { return throttle_; }
  double last_rudder_rad() const { return rudder_; }
  double cross_track_error_m() const { return los_.cross_track_error_m(); }
  void set_environment(const Environment& env) { ship_.set_environment(env); }

 private:
  RouteFollower(ShipModel ship, LosGuidance los, PlannedRoute route, const RouteFollowerOptions& o)
      : ship_(std::move(ship)),
        los_(std::move(los)),
        route_(std::move(route)),
        options_(o),
        heading_(o.heading, o.dt_s),
        speed_(o.speed, o.dt_s) {}
  ShipModel ship_;
  LosGuidance los_;
  PlannedRoute route_;
  RouteFollowerOptions options_;
  HeadingController heading_;
  SpeedController speed_;
  double throttle_ = 0.0;
  double rudder_ = 0.0;
};

}  // namespace seaplan::ship
