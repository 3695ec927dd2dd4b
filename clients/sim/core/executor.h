// The onboard side of a mission, simulated (paper 000 fig. 5, the GNC block):
// executes the tasks of the current plan version on the 3-DOF ship model
// (seaplan::ship, SITS) with LOS path following along each move's refined
// route in the route's MSO modes, runs port operations as timed tasks,
// avoids the scripted traffic under COLREG (engine/colav),
// tracks fuel, injects scripted events (GNSS jump) and produces the feedback
// the client posts to the server. No networking here: the seaplan-sim binary
// moves feedback and plan versions between this class and the server.
//
// Scheduling: a task starts when the mission time has reached its planned
// start and every task of the version planned to end before that start has
// completed (so a late arrival delays what depends on it, an early one waits).
// A new plan version replaces the remaining tasks; a move under way is
// abandoned (the new plan starts where the ship is), a port operation under
// way is let finish (and reported under its old id).
//
// Thread-compatible; one per simulated ship.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "fuel.h"
#include "report.h"
#include "seaplan/colav/autopilot.h"
#include "seaplan/colav/colav.h"
#include "seaplan/colav/path_follower.h"
#include "seaplan/common/status.h"
#include "seaplan/mission/navigation_log.h"
#include "seaplan/mission/replan_policy.h"
#include "seaplan/mission/types.h"
#include "seaplan/ship/control.h"
#include "seaplan/ship/ship_model.h"
#include "traffic.h"

namespace seaplan::sim {

using colav::PathFollower;
using colav::PathFollowerOptions;
using colav::PointSegmentDistance;
using colav::VelocityOf;

// A grid over the local frame for scripted events: cell (i, j) is at
// origin + (i * cell_m east, j * cell_m north).
struct Grid {
  EastNorth origin;
  double cell_m = 25.0;
  EastNorth Cell(double i, double j) const {
    return {origin.east_m + i * cell_m, origin.north_m + j * cell_m};
  }
};

// GNSS jump (paper case B): at start_s the ship's navigated position jumps
// to cell `to` (the simulated ship is where its navigation says it is, as in
// the paper's simulation); the fault is cleared at end_s (logged). `from` is
// where the scenario expects the ship to be (logged with the actual
// distance, for checking the scenario).
struct GnssJump {
  double start_s = 0.0;
  double end_s = 0.0;
  EastNorth from_cell;  // (i, j)
  EastNorth to_cell;
};

struct ExecutorConfig {
  std::string vessel_id = "mass-1";
  EastNorth start;                 // local frame
  double start_heading_rad = 0.0;  // clockwise from north
  double service_speed_mps = 4.0;  // when a route has no sailing time
  double dt_s = 0.5;
  double arrival_radius_m = 60.0;
  double slow_down_distance_m = 400.0;
  double min_approach_speed_mps = 1.0;
  double position_report_interval_s = 30.0;
  double deviation_limit_m = 200.0;  // a move fails when the ship is further off its route
  ship::LosOptions los{150.0, 400.0, 0.0, 0.5};  // validated; path following uses `path` below
  // LOS path following (leg by along-track progress, no integral term);
  // after an avoidance manoeuvre the ship rejoins the leg it has reached.
  // search 0: legs advance by along-track progress only (a nearer later leg
  // may lie across a headland: jumping to it cut corners over land).
  // turn_radius 450 m: the wheel-over for this hull under its autopilot.
  // This hull's wheel-over and chord (colav::ShipPathFollowerOptions says why).
  PathFollowerOptions path = colav::ShipPathFollowerOptions();
  // Heading and speed control (engine/colav's autopilot: the same law the
  // collision avoidance predicts with). SITS' gains (kp 4, kd 90, ki 0.01)
  // make this hull circle under LOS when a leg starts far off its heading.
  colav::AutopilotOptions autopilot;
  // A position change this large within one step is a jump (GNSS fault):
  // the move fails at once. A slower drift off the route fails the move
  // only beyond 3 x deviation_limit_m (collision avoidance may legitimately
  // take the ship off its route).
  double jump_threshold_m = 100.0;
  ship::Environment environment;
  // Collision avoidance (policy, safety distance, horizon, weights); its
  // arrival parameters are taken from this config.
  colav::CollisionAvoidanceOptions avoidance;
  // Land (outer rings, local frame) the avoidance keeps clear of; empty =
  // none known.
  std::vector<std::vector<EastNorth>> land;
  FuelOptions fuel;
  double initial_fuel_fraction = 1.0;
  double fuel_threshold_fraction = 0.3;  // logged when crossed (the server decides replans)
  Grid grid;
  std::vector<GnssJump> gnss_jumps;
  std::vector<TrafficVessel> traffic;
};

struct FeedbackOut {
  mission::FeedbackKind kind = mission::FeedbackKind::kPosition;
  std::string task_id;
  int plan_version = 0;
  double mission_time_s = 0.0;
  EastNorth position;
  double heading_rad = 0.0;
  double speed_mps = 0.0;
  double fuel_fraction = 1.0;
  mission::MsoMode mode = mission::MsoMode::kUnspecified;
  bool collision_avoidance_active = false;  // manoeuvring for traffic or rejoining the route
  std::string detail;
};

class Executor {
 public:
  static StatusOr<Executor> Create(const ExecutorConfig& config);

  // Installs a new plan version (its tasks replace the remaining ones).
  void SetPlan(const mission::PlanVersion& version);
  // Advances one time step; appends what to report to `out`.
  void Step(std::vector<FeedbackOut>* out);

  // Every task of the current version completed and nothing is running.
  bool Finished() const;
  // A task failed: the executor holds until SetPlan.
  bool WaitingForPlan() const { return waiting_; }
  double time_s() const { return time_s_; }
  EastNorth position() const;
  double fuel_fraction() const { return tank_.fraction(); }
  int plan_version() const { return version_.version; }
  const std::set<std::string>& completed_task_ids() const { return completed_; }
  // The ship now, as a position report would carry it (for live updates).
  FeedbackOut CurrentState() const {
    return MakeFeedback(mission::FeedbackKind::kPosition, "", version_.version);
  }
  const std::vector<TrafficVessel>& traffic() const { return config_.traffic; }

  const MissionReport& report() const { return report_; }
  MissionReport& mutable_report() { return report_; }
  void Log(std::string_view message) { report_.log.Add(time_s_, message, config_.vessel_id); }

 private:
  struct Running {
    mission::Task task;
    int version = 0;
    double started_s = 0.0;
  };
  Executor(const ExecutorConfig& config, ship::ShipModel model,
           colav::CollisionAvoidance avoidance);
  FeedbackOut MakeFeedback(mission::FeedbackKind kind, const std::string& task_id, int version,
                           std::string detail = "") const;
  void StartTasks(std::vector<FeedbackOut>* out);
  void StartMove(const mission::Task& task);
  void StepMove(std::vector<FeedbackOut>* out);
  // Logs the avoidance's events (and reports manoeuvres as feedback).
  void LogAvoidance(const colav::Command& c, const Running& move, std::vector<FeedbackOut>* out);
  void Complete(const Running& r, std::vector<FeedbackOut>* out);
  // A port operation whose time is up still waits for the tasks of its
  // version planned to start before it ends (definition: executor.cc).
  bool WaitsForPlannedStarts(const Running& r) const;
  void NoteFuel();  // logs crossing the fuel threshold (the server decides replans)
  void InjectEvents(std::vector<FeedbackOut>* out);
  void TrackTraffic();

  ExecutorConfig config_;
  ship::ShipModel model_;
  colav::LandIndex land_;  // config_.land, indexed for the avoidance
  colav::CollisionAvoidance avoidance_;
  std::vector<colav::Obstacle> others_;  // per-step scratch
  colav::Autopilot autopilot_;
  std::optional<PathFollower> los_;
  std::vector<mission::RouteWaypoint> route_;  // of the move under way
  std::vector<mission::MsoMode> path_modes_;   // MSO mode of each leg of los_'s path
  double move_speed_mps_ = 0.0;
  FuelTank tank_;
  mission::PlanVersion version_;
  std::vector<mission::Task> pending_;
  std::vector<Running> running_;
  std::set<std::string> completed_;
  bool waiting_ = false;
  double time_s_ = 0.0;
  double last_position_report_s_ = -1e9;
  double last_fuel_sample_s_ = -1e9;
  double last_track_sample_s_ = -1e9;
  double last_land_sample_s_ = -1e9;
  EastNorth last_position_;
  bool jumped_ = false;
  bool avoidance_active_ = false;  // the move under way is off its route for traffic
  bool fuel_low_logged_ = false;
  std::set<size_t> jumps_done_, jumps_cleared_;
  MissionReport report_;
};

}  // namespace seaplan::sim
