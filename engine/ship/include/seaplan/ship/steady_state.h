// Steady-state operating points and route sailing costs.
//
// The route optimiser needs "the route's sailing time at the ship's speed in
// the chosen modes" and the fuel that costs. Two ways are offered:
//  * CalmWaterSteadySpeed: closed form of the SITS surge balance in calm
//    water (no wind, no current, straight course):
//        F = (m/T_surge) u + (k_u - 1/2 rho_a c_x A_F) u^2,
//    the second term because SITS' wind model pushes a ship forward through
//    still air (relative wind from ahead, gamma = -pi, c_x cos(gamma) < 0):
//    this is what makes SITS settle at 9.153 m/s rather than 9.115 m/s in PTO
//    at throttle 0.8. Microseconds; use it in optimiser inner loops.
//  * SimulateSteadyState: runs the full 3-DOF model with constant throttle and
//    a heading-hold autopilot until the surge acceleration is below a
//    tolerance (or a time limit), in any wind/current.
#pragma once

#include <span>

#include "Eigen/Core"
#include "seaplan/common/status.h"
#include "seaplan/ship/machinery.h"
#include "seaplan/ship/ship_params.h"

namespace seaplan::ship {

struct OperatingPoint {
  MsoMode mode = MsoMode::kPto;
  double throttle = 0.0;
  double speed_mps = 0.0;  // surge speed through the water
  double thrust_n = 0.0;
  LoadOnPowerSources load;
  FuelRate fuel_rate;
  double simulated_time_s = 0.0;  // 0 for the closed form
};

// Closed-form calm-water steady surge speed at `throttle`. Pure; no checks
// beyond CHECK-style assumptions (valid params, throttle >= 0).
double CalmWaterSteadySpeed(const ShipParams& ship, const MachineryParams& machinery, MsoMode mode,
                            double throttle);
// Full operating point from the closed form.
OperatingPoint CalmWaterOperatingPoint(const ShipParams& ship, const MachineryParams& machinery,
                                       MsoMode mode, double throttle);

// Throttle that holds `speed_mps` in calm water. OutOfRange if that needs more
// than `max_throttle` (the mode's top speed is below speed_mps).
StatusOr<double> ThrottleForSpeed(const ShipParams& ship, const MachineryParams& machinery,
                                  MsoMode mode, double speed_mps, double max_throttle = 1.0);
// Calm-water speed at `max_throttle`.
double TopSpeed(const ShipParams& ship, const MachineryParams& machinery, MsoMode mode,
                double max_throttle = 1.0);

struct SteadyStateOptions {
  double dt_s = 0.5;
  double max_time_s = 3000.0;
  // Stop once |u_dot| < this for a whole `settle_time_s`.
  double surge_acceleration_tolerance_mps2 = 1e-6;
  double settle_time_s = 60.0;
  double initial_speed_mps = 0.0;
  double heading_rad = 0.0;  // held by a PID autopilot
  Status Validate() const;
};

StatusOr<OperatingPoint> SimulateSteadyState(const ShipParams& ship,
                                             const MachineryParams& machinery, MsoMode mode,
                                             double throttle, const Environment& env = {},
                                             const SteadyStateOptions& options = {});

// Sailing time and fuel along a polyline of (N, E) points at a calm-water
// speed in one mode.
struct SailingCost {
  double length_m = 0.0;
  double time_s = 0.0;
  double fuel_kg = 0.0;
  double throttle = 0.0;
};
// At a given speed (throttle found by ThrottleForSpeed).
StatusOr<SailingCost> SailingCostAtSpeed(const ShipParams& ship, const MachineryParams& machinery,
                                         std::span<const Eigen::Vector2d> polyline_ne, MsoMode mode,
                                         double speed_mps);
// At a given throttle (speed = CalmWaterSteadySpeed).
StatusOr<SailingCost> SailingCostAtThrottle(const ShipParams& ship,
                                            const MachineryParams& machinery,
                                            std::span<const Eigen::Vector2d> polyline_ne,
                                            MsoMode mode, double throttle);

}  // namespace seaplan::ship
