#include "executor.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "absl/strings/str_format.h"
#include "seaplan/mission/tasks.h"

namespace seaplan::sim {
namespace {

using mission::FeedbackKind;
using mission::TaskKind;

ship::MsoMode ToShipMode(mission::MsoMode m) {
  switch (m) {
    case mission::MsoMode::kMec:
      return ship::MsoMode::kMec;
    case mission::MsoMode::kPti:
      return ship::MsoMode::kPti;
    default:
      return ship::MsoMode::kPto;
  }
}

mission::MsoMode FromShipMode(ship::MsoMode m) {
  switch (m) {
    case ship::MsoMode::kMec:
      return mission::MsoMode::kMec;
    case ship::MsoMode::kPti:
      return mission::MsoMode::kPti;
    case ship::MsoMode::kPto:
      return mission::MsoMode::kPto;
  }
  return mission::MsoMode::kUnspecified;
}

}  // namespace

StatusOr<Executor> Executor::Create(const ExecutorConfig& config) {
  if (!(config.dt_s > 0)) return absl::InvalidArgumentError("executor: dt_s must be > 0");
  if (!(config.service_speed_mps > 0)) {
    return absl::InvalidArgumentError("executor: service_speed_mps must be > 0");
  }
  SEAPLAN_RETURN_IF_ERROR(config.los.Validate());
  SEAPLAN_RETURN_IF_ERROR(config.autopilot.Validate());
  // The avoidance predicts the moves as the executor sails them.
  colav::CollisionAvoidanceOptions avoidance = config.avoidance;
  avoidance.slow_down_distance_m = config.slow_down_distance_m;
  avoidance.min_approach_speed_mps = config.min_approach_speed_mps;
  avoidance.arrival_radius_m = config.arrival_radius_m;
  SEAPLAN_ASSIGN_OR_RETURN(auto collision_avoidance, colav::CollisionAvoidance::Create(avoidance));
  ship::ShipState s =
      ship::ShipState::At(config.start.north_m, config.start.east_m, config.start_heading_rad);
  SEAPLAN_ASSIGN_OR_RETURN(auto model,
                           ship::ShipModel::Create(ship::ShipParams{}, ship::MachineryParams{},
                                                   config.environment, s, ship::MsoMode::kPto));
  return Executor(config, std::move(model), std::move(collision_avoidance));
}

Executor::Executor(const ExecutorConfig& config, ship::ShipModel model,
                   colav::CollisionAvoidance avoidance)
    : config_(config),
      model_(std::move(model)),
      land_(config.land),
      avoidance_(std::move(avoidance)),
      autopilot_(config.autopilot),
      tank_(config.fuel, config.initial_fuel_fraction) {
  report_.safety_distance_m = config.avoidance.safety_distance_m;
  report_.land_known = !land_.empty();
  for (const TrafficVessel& v : config.traffic) report_.cpa[v.id].vessel = v.name;
  report_.min_fuel_fraction = config.initial_fuel_fraction;
}

EastNorth Executor::position() const {
  return {model_.state().east_m(), model_.state().north_m()};
}

FeedbackOut Executor::MakeFeedback(FeedbackKind kind, const std::string& task_id, int version,
                                   std::string detail) const {
  FeedbackOut f;
  f.kind = kind;
  f.task_id = task_id;
  f.plan_version = version;
  f.mission_time_s = time_s_;
  f.position = position();
  f.heading_rad = model_.state().heading_rad();
  f.speed_mps = std::hypot(model_.state().surge_mps(), model_.state().sway_mps());
  f.fuel_fraction = tank_.fraction();
  f.mode = model_.mode() == ship::MsoMode::kMec   ? mission::MsoMode::kMec
           : model_.mode() == ship::MsoMode::kPti ? mission::MsoMode::kPti
                                                  : mission::MsoMode::kPto;
  f.collision_avoidance_active = avoidance_active_;
  f.detail = std::move(detail);
  return f;
}

void Executor::SetPlan(const mission::PlanVersion& version) {
  version_ = version;
  report_.versions.push_back(version);
  pending_ = version.tasks;
  std::sort(pending_.begin(), pending_.end(),
            [](const mission::Task& a, const mission::Task& b) { return a.start_s < b.start_s; });
  // A move under way is abandoned; port operations are let finish.
  running_.erase(std::remove_if(running_.begin(), running_.end(),
                                [](const Running& r) { return r.task.kind == TaskKind::kMove; }),
                 running_.end());
  los_.reset();
  route_.clear();
  avoidance_active_ = false;
  waiting_ = false;
  Log(absl::StrFormat("plan version %d received (%s): %d tasks", version.version, version.reason,
                      static_cast<int>(version.tasks.size())));
}

bool Executor::Finished() const {
  return pending_.empty() && running_.empty() && !waiting_;
}

void Executor::StartTasks(std::vector<FeedbackOut>* out) {
  bool moving = std::any_of(running_.begin(), running_.end(),
                            [](const Running& r) { return r.task.kind == TaskKind::kMove; });
  for (auto it = pending_.begin(); it != pending_.end();) {
    const mission::Task& t = *it;
    bool ready = time_s_ + 1e-9 >= t.start_s;
    // Everything planned to end before this starts must be done.
    for (const mission::Task& other : version_.tasks) {
      if (!ready) break;
      if (other.id == t.id || other.end_s() > t.start_s + 1e-6) continue;
      if (!completed_.contains(other.id)) ready = false;
    }
    if (ready && t.kind == TaskKind::kMove) {
      bool port_op_running = !running_.empty();
      if (moving || port_op_running) ready = false;
    }
    if (!ready) {
      ++it;
      continue;
    }
    Running r{t, version_.version, time_s_};
    tank_.OnTaskStarted(t.kind);
    Log(mission::TaskStartedMessage(t.kind));
    NoteFuel();
    out->push_back(
        MakeFeedback(FeedbackKind::kTaskStarted, t.id, version_.version, t.action.DisplayName()));
    if (t.kind == TaskKind::kMove) {
      StartMove(t);
      moving = true;
    }
    running_.push_back(std::move(r));
    it = pending_.erase(it);
  }
}

void Executor::StartMove(const mission::Task& task) {
  route_.clear();
  if (task.route) route_ = task.route->waypoints;
  const EastNorth here = position();
  // The path is the route itself, joined where the ship is. The ship usually
  // lies some way off the route's start: it stopped abeam of the previous
  // route's end, or the server snapped it to a named location up to
  // RegenerationOptions::snap_distance_m away. A first leg from the ship to
  // the route's start would point anywhere (often back along the route or
  // towards the shore): a hull at 9 m/s that turns ~1 deg/s cannot follow a
  // leg of 100 m, and looping around it ran the ship 400 m into the land
  // (case A). So: drop the legs the ship is already abeam of or
  // past, and let the LOS law converge on the leg it has reached.
  std::vector<EastNorth> path;
  path_modes_.clear();
  for (size_t i = 0; i < route_.size(); ++i) {
    const EastNorth p{route_[i].position.east_m, route_[i].position.north_m};
    if (!path.empty() && (p - path.back()).Norm() < 1.0) continue;
    // The leg ending here is sailed in the mode of the waypoint it starts from.
    if (!path.empty()) path_modes_.push_back(route_[i - 1].mode);
    path.push_back(p);
  }
  if (path.size() >= 2) {
    // The leg to join: the nearest to the ship among the legs whose start is
    // within the look-ahead distance of the route's start; legs before it
    // are behind the ship.
    size_t join = 0;
    double best = std::numeric_limits<double>::infinity(), along_start = 0.0;
    for (size_t i = 0; i + 1 < path.size() && along_start <= config_.path.lookahead_m; ++i) {
      const double len = (path[i + 1] - path[i]).Norm();
      const double dist = PointSegmentDistance(here, path[i], path[i + 1]);
      if (dist < best) {
        best = dist;
        join = i;
      }
      along_start += len;
    }
    path.erase(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(join));
    path_modes_.erase(path_modes_.begin(), path_modes_.begin() + static_cast<std::ptrdiff_t>(join));
  }
  if (path.size() < 2) {
    // No route (or a single point): head for it, or hold the heading.
    const EastNorth to = path.empty() || (path.back() - here).Norm() < 1.0
                             ? here + VelocityOf(model_.state().heading_rad(), 1.0)
                             : path.back();
    path = {here, to};
    path_modes_.assign(1, route_.empty() ? mission::MsoMode::kPto : route_.front().mode);
  }
  auto los = PathFollower::Create(std::move(path), config_.path);
  if (los.ok()) {
    los_.emplace(std::move(*los));
  } else {
    Log(absl::StrFormat("cannot follow the route: %s", los.status().ToString()));
  }
  // Unberthing is not modelled: a ship at rest leaves its berth on the
  // course the path follower asks for (tugs / thrusters), as the paper's
  // simulation does.
  if (los_ && std::hypot(model_.state().surge_mps(), model_.state().sway_mps()) < 0.5) {
    ship::ShipState s = model_.state();
    s.eta[2] = los_->Update(here);
    s.nu.setZero();
    model_.set_state(s);
  }
  double length = task.route ? task.route->length_m : 0.0;
  double time = task.route ? task.route->sailing_time_s : 0.0;
  move_speed_mps_ = (length > 0 && time > 0) ? length / time : config_.service_speed_mps;
}

void Executor::StepMove(std::vector<FeedbackOut>* out) {
  auto it = std::find_if(running_.begin(), running_.end(),
                         [](const Running& r) { return r.task.kind == TaskKind::kMove; });
  if (it == running_.end() || !los_) return;
  const ship::ShipState& s = model_.state();
  EastNorth here = position();
  const EastNorth goal = los_->path().back();
  double to_goal = (goal - here).Norm();
  // Arrived: inside the arrival circle, or abeam of / past the end of the
  // route close to its line (a slow-turning hull that misses the circle
  // must not orbit the berth).
  los_->Update(here);
  const bool passed_end = los_->on_last_leg() && los_->leg_remaining_m() <= 0 &&
                          std::abs(los_->cross_track_m()) < 3 * config_.arrival_radius_m;
  if (to_goal < config_.arrival_radius_m || passed_end) {
    // Berthing is not modelled: the ship stops at the berth.
    ship::ShipState moored = s;
    moored.nu.setZero();
    model_.set_state(moored);
    Running done = *it;
    running_.erase(it);
    los_.reset();
    Complete(done, out);
    return;
  }
  // Deviation from the route (e.g. after a GNSS jump): the move fails.
  if (!route_.empty()) {
    mission::Route r;
    r.waypoints = route_;
    double off = mission::CrossTrackDistance(r, {here.east_m, here.north_m});
    if ((jumped_ && off > config_.deviation_limit_m) || off > 3 * config_.deviation_limit_m) {
      Log(mission::TaskFailedMessage(TaskKind::kMove));
      out->push_back(MakeFeedback(
          FeedbackKind::kTaskFailed, it->task.id, it->version,
          absl::StrFormat("%.0f m off the route (limit %.0f m)", off, config_.deviation_limit_m)));
      ship::ShipState hold = s;
      hold.nu.setZero();
      model_.set_state(hold);
      running_.erase(it);
      los_.reset();
      avoidance_active_ = false;
      waiting_ = true;
      return;
    }
  }
  double psi_d = los_->Update(here, s.surge_mps());
  double speed = move_speed_mps_;
  if (to_goal < config_.slow_down_distance_m) {
    speed =
        std::max(config_.min_approach_speed_mps, speed * to_goal / config_.slow_down_distance_m);
  }
  // MSO mode of the segment steered along.
  if (!path_modes_.empty()) {
    model_.set_mode(ToShipMode(path_modes_[std::min<size_t>(los_->leg(), path_modes_.size() - 1)]));
  }

  // Collision avoidance.
  others_.clear();
  for (const TrafficVessel& v : config_.traffic) others_.push_back({v.At(time_s_), v.id});
  avoidance_.set_land(land_.empty() ? nullptr : &land_);  // not in the constructor: executors move
  const colav::Command cmd = avoidance_.Step({time_s_, &model_, &autopilot_},
                                             {psi_d, speed, move_speed_mps_}, *los_, others_);
  avoidance_active_ = cmd.collision_avoidance_active;
  LogAvoidance(cmd, *it, out);
  const colav::ActuatorCommand act =
      autopilot_.Update(cmd.course_rad, cmd.speed_mps, s.heading_rad(), s.yaw_rate_radps(),
                        s.surge_mps(), config_.dt_s);
  ship::StepReport rep = model_.Step(act.throttle, act.rudder_rad, config_.dt_s);
  tank_.Burn(rep.fuel_rate.total_kgps() * config_.dt_s);

  if (time_s_ - last_position_report_s_ >= config_.position_report_interval_s) {
    last_position_report_s_ = time_s_;
    out->push_back(MakeFeedback(FeedbackKind::kPosition, it->task.id, it->version));
  }
}

void Executor::LogAvoidance(const colav::Command& c, const Running& move,
                            std::vector<FeedbackOut>* out) {
  for (const colav::Event& e : c.events) {
    const std::string name = e.vessel_id >= 0 ? report_.cpa[e.vessel_id].vessel : "traffic";
    const std::string role(colav::RoleName(e.role));
    std::string what;
    switch (e.kind) {
      case colav::EventKind::kPotentialCollision:
        Log(absl::StrFormat("%s with %s (%s)", std::string(mission::messages::kPotentialCollision),
                            name, e.role == colav::Role::kNone ? "keep clear" : role));
        break;
      case colav::EventKind::kSpeedReduced:
        Log(absl::StrFormat("%s with %s ahead on the route: %s",
                            std::string(mission::messages::kPotentialCollision), name, e.detail));
        break;
      case colav::EventKind::kManoeuvreStarted:
        what = absl::StrFormat("collision avoidance manoeuvre started (%s, %s%s%s)", name, role,
                               e.detail.empty() ? "" : ": ", e.detail);
        break;
      case colav::EventKind::kManoeuvreEnded:
        what = absl::StrFormat("collision avoidance manoeuvre ended (%s)", name);
        break;
    }
    if (what.empty()) continue;
    Log(what);
    out->push_back(
        MakeFeedback(FeedbackKind::kCollisionAvoidance, move.task.id, move.version, what));
  }
}

void Executor::Complete(const Running& r, std::vector<FeedbackOut>* out) {
  if (r.task.kind == TaskKind::kMove) avoidance_active_ = false;
  completed_.insert(r.task.id);
  tank_.OnTaskCompleted(r.task.kind);
  Log(mission::TaskCompletedMessage(r.task.kind));
  NoteFuel();
  out->push_back(MakeFeedback(FeedbackKind::kTaskCompleted, r.task.id, r.version,
                              r.task.action.DisplayName()));
}

// StartTasks keeps the plan's order of an end before a start; this keeps
// the order of a start before an end. A ship running late starts the tasks
// that waited for it together, so without it a refuel planned to end 1 ms
// after a load starts ended first, and the load was charged after the refill
// the plan had charged it before: 10 % short, the tank ran dry (case C
// numeric). Port operations of the ship only: a move planned to start before
// the operation ends (not in a valid plan: it needs the ship) does not hold
// it, as the move could never start while it runs.
bool Executor::WaitsForPlannedStarts(const Running& r) const {
  if (r.version != version_.version) return false;
  const double end_s = r.task.end_s() - 1e-6;
  bool holds = false;
  for (const mission::Task& t : pending_) {
    if (t.start_s >= end_s) continue;
    if (t.kind == TaskKind::kMove) return false;
    holds = true;
  }
  return holds;
}

void Executor::NoteFuel() {
  const bool low = mission::FuelAtOrBelow(tank_.fraction(), config_.fuel_threshold_fraction);
  if (low && !fuel_low_logged_) {
    Log(absl::StrFormat("fuel %.0f%% <= %.0f%%", tank_.fraction() * 100,
                        config_.fuel_threshold_fraction * 100));
  }
  fuel_low_logged_ = low;
}

void Executor::InjectEvents(std::vector<FeedbackOut>* out) {
  (void)out;
  for (size_t i = 0; i < config_.gnss_jumps.size(); ++i) {
    const GnssJump& j = config_.gnss_jumps[i];
    if (!jumps_done_.contains(i) && time_s_ >= j.start_s) {
      jumps_done_.insert(i);
      EastNorth expected = config_.grid.Cell(j.from_cell.east_m, j.from_cell.north_m);
      EastNorth to = config_.grid.Cell(j.to_cell.east_m, j.to_cell.north_m);
      EastNorth here = position();
      Log(
          absl::StrFormat("GNSS fault: position jumps from grid (%g, %g) to (%g, %g) (%.0f m; ship "
                          "was %.0f m from the first cell)",
                          j.from_cell.east_m, j.from_cell.north_m, j.to_cell.east_m,
                          j.to_cell.north_m, (to - here).Norm(), (expected - here).Norm()));
      ship::ShipState s = model_.state();
      s.eta[0] = to.north_m;
      s.eta[1] = to.east_m;
      model_.set_state(s);
    }
    if (jumps_done_.contains(i) && !jumps_cleared_.contains(i) && time_s_ >= j.end_s) {
      jumps_cleared_.insert(i);
      Log("GNSS fault cleared");
    }
  }
}

namespace {
constexpr double kLandSampleS = 2.0;  // the report's land clearance, every this many seconds
}  // namespace

void Executor::TrackTraffic() {
  EastNorth here = position();
  for (const TrafficVessel& v : config_.traffic) {
    Kinematics k = v.At(time_s_);
    double d = (k.position - here).Norm();
    CpaRecord& rec = report_.cpa[v.id];
    if (d < rec.min_distance_m) {
      rec.min_distance_m = d;
      rec.time_s = time_s_;
    }
  }
  if (!land_.empty() && time_s_ - last_land_sample_s_ >= kLandSampleS) {
    last_land_sample_s_ = time_s_;
    const double clearance = land_.SignedClearance(here, 1000.0);
    if (clearance < report_.min_land_clearance_m) {
      report_.min_land_clearance_m = clearance;
      report_.min_land_clearance_time_s = time_s_;
    }
    if (clearance < 0) report_.aground_s += kLandSampleS;
  }
  if (time_s_ - last_track_sample_s_ >= 10.0) {
    last_track_sample_s_ = time_s_;
    report_.trajectory.push_back({time_s_, here, FromShipMode(model_.mode())});
    for (const TrafficVessel& v : config_.traffic) {
      report_.traffic_tracks[v.name].push_back({time_s_, v.At(time_s_).position});
    }
  }
  if (time_s_ - last_fuel_sample_s_ >= 10.0) {
    last_fuel_sample_s_ = time_s_;
    report_.fuel.emplace_back(time_s_, tank_.fraction());
  }
  report_.min_fuel_fraction = std::min(report_.min_fuel_fraction, tank_.fraction());
  report_.tank_ran_dry = report_.tank_ran_dry || tank_.ran_dry();
}

void Executor::Step(std::vector<FeedbackOut>* out) {
  if (waiting_) return;
  last_position_ = position();
  InjectEvents(out);
  jumped_ = (position() - last_position_).Norm() > config_.jump_threshold_m;
  StartTasks(out);
  // Port operations complete by time, in the plan's order of events.
  for (auto it = running_.begin(); it != running_.end();) {
    if (it->task.kind != TaskKind::kMove && time_s_ + 1e-9 >= it->started_s + it->task.duration_s &&
        !WaitsForPlannedStarts(*it)) {
      Running done = *it;
      it = running_.erase(it);
      Complete(done, out);
    } else {
      ++it;
    }
  }
  StepMove(out);
  TrackTraffic();
  report_.end_time_s = time_s_;
  if (!waiting_) time_s_ += config_.dt_s;
}

}  // namespace seaplan::sim
