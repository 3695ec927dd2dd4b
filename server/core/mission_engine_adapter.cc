#include "server/core/mission_engine_adapter.h"

#if SEAPLAN_SERVER_HAS_MISSION && SEAPLAN_SERVER_HAS_SEARCH && SEAPLAN_SERVER_HAS_CHART

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <mutex>
#include <optional>
#include <set>

#include "absl/strings/str_cat.h"
#include "seaplan/chart/geodesy.h"
#include "seaplan/chart/obstacle_map.h"
#include "seaplan/common/log.h"
#include "seaplan/mission/mission_planner.h"
#include "seaplan/mission/problem_update.h"
#include "seaplan/mission/replan_policy.h"
#include "seaplan/mission/session.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/v1/chart.pb.h"
#include "server/core/convert.h"
#include "server/core/status_details.h"
#if SEAPLAN_SERVER_HAS_ROUTE
#include "seaplan/route/route_planner.h"
#include "server/core/route_convert.h"
#endif

namespace seaplan::server {
namespace {

v1::Task::Kind KindToProto(mission::TaskKind k) {
  switch (k) {
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

mission::TaskKind KindFromProto(v1::Task::Kind k) {
  switch (k) {
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

v1::MsoMode ModeToProto(mission::MsoMode m) {
  switch (m) {
    case mission::MsoMode::kPto:
      return v1::MSO_MODE_PTO;
    case mission::MsoMode::kMec:
      return v1::MSO_MODE_MEC;
    case mission::MsoMode::kPti:
      return v1::MSO_MODE_PTI;
    default:
      return v1::MSO_MODE_UNSPECIFIED;
  }
}

v1::TimedAction StepToProto(const validate::PlanStep& s) {
  v1::TimedAction a;
  a.set_start_s(s.start_s);
  a.set_duration_s(s.duration_s);
  a.set_name(s.name);
  for (const auto& arg : s.args) a.add_arguments(arg);
  return a;
}

validate::PlanStep StepFromProto(const v1::TimedAction& a) {
  validate::PlanStep s;
  s.start_s = a.start_s();
  s.duration_s = a.duration_s();
  s.name = a.name();
  s.args.assign(a.arguments().begin(), a.arguments().end());
  return s;
}

// The engine's view of a feedback report. A ShipState in a report is a full
// state: its fuel_fraction counts even when it is 0 (an empty tank); a report
// without a state carries neither position nor fuel.
mission::Feedback FeedbackFromProto(const v1::Feedback& feedback, int current_version,
                                    const chart::LocalFrame* frame) {
  mission::Feedback f;
  switch (feedback.kind()) {
    case v1::Feedback::KIND_TASK_STARTED:
      f.kind = mission::FeedbackKind::kTaskStarted;
      break;
    case v1::Feedback::KIND_TASK_COMPLETED:
      f.kind = mission::FeedbackKind::kTaskCompleted;
      break;
    case v1::Feedback::KIND_TASK_FAILED:
      f.kind = mission::FeedbackKind::kTaskFailed;
      break;
    case v1::Feedback::KIND_GNSS_FAULT:
      f.kind = mission::FeedbackKind::kGnssFault;
      break;
    case v1::Feedback::KIND_MACHINERY_FAULT:
      f.kind = mission::FeedbackKind::kMachineryFault;
      break;
    case v1::Feedback::KIND_OPERATOR_CHANGE:
      f.kind = mission::FeedbackKind::kOperatorChange;
      break;
    case v1::Feedback::KIND_COLLISION_AVOIDANCE:
      f.kind = mission::FeedbackKind::kCollisionAvoidance;
      break;
    default:
      f.kind = mission::FeedbackKind::kPosition;
      break;
  }
  f.task_id = feedback.task_id();
  f.plan_version = feedback.plan_version() != 0 ? feedback.plan_version() : current_version;
  f.mission_time_s = feedback.mission_time_s();
  f.detail = feedback.detail();
  if (feedback.has_state()) {
    if (frame != nullptr && feedback.state().has_position()) {
      const EastNorth p = frame->ToLocal({feedback.state().position().latitude_deg(),
                                          feedback.state().position().longitude_deg()});
      f.position = EastNorth{p.east_m, p.north_m};
    }
    f.fuel_fraction = feedback.state().fuel_fraction();
  }
  return f;
}

// Improvement budget of a replan after its first plan, seconds (see the
// planner callback in MakeContext).
inline constexpr double kReplanImproveMinS = 0.01;
inline constexpr double kReplanImproveMaxS = 0.04;

#if SEAPLAN_SERVER_HAS_ROUTE
mission::MsoMode ModeFromRoute(route::MsoMode m) {
  switch (m) {
    case route::MsoMode::kPto:
      return mission::MsoMode::kPto;
    case route::MsoMode::kMec:
      return mission::MsoMode::kMec;
    case route::MsoMode::kPti:
      return mission::MsoMode::kPti;
  }
  return mission::MsoMode::kUnspecified;
}

mission::Route RouteFromEngine(const route::RouteResult& result) {
  const route::RouteAlternative& a = result.alternatives[static_cast<size_t>(result.chosen)];
  mission::Route r;
  r.alternative_index = result.chosen;
  r.length_m = a.length_m;
  r.sailing_time_s = a.sailing_time_s;
  r.fuel_kg = a.fuel_kg;
  r.expected_grounding_cost = a.expected_grounding_cost;
  double eta = 0, distance = 0;
  for (const auto& w : a.waypoints) {
    mission::RouteWaypoint m;
    m.position = {w.local.east_m, w.local.north_m};
    m.mode = ModeFromRoute(w.mode);
    m.eta_s = eta;
    m.distance_from_start_m = distance;
    m.time_to_grounding_s = w.ttg_s;
    m.grounding_probability = w.grounding_probability;
    m.expected_grounding_cost = w.expected_grounding_cost;
    m.fuel_kg = w.segment_fuel_kg;
    r.max_grounding_probability = std::max(r.max_grounding_probability, w.grounding_probability);
    eta += w.segment_time_s;
    distance += w.segment_length_m;
    r.waypoints.push_back(m);
  }
  return r;
}

// A replan may start where the ship is, and a ship pushed off its route
// (avoidance, drift, a GNSS jump) can be inside the buffered obstacles
// (land + safety buffer) while still afloat. The route planner refuses such
// a start; a real ship leaves the buffer the shortest way out. So: the
// nearest free point within kMaxWayOutM (rings every 5 m, 64 bearings),
// 10 m further out when that is free too (clear of the buffer's edge), or
// nullopt when there is none.
inline constexpr double kMaxWayOutM = 500.0;
std::optional<EastNorth> ShortestWayOut(const route::ObstacleField& field, EastNorth p) {
  constexpr int kBearings = 64;
  for (double r = 5.0; r <= kMaxWayOutM; r += 5.0) {
    for (int k = 0; k < kBearings; ++k) {
      const double a = 2.0 * M_PI * k / kBearings;
      const EastNorth q{p.east_m + r * std::sin(a), p.north_m + r * std::cos(a)};
      if (field.Inside(q)) continue;
      const EastNorth clear{p.east_m + (r + 10.0) * std::sin(a),
                            p.north_m + (r + 10.0) * std::cos(a)};
      return field.Inside(clear) ? EastNorth{q.east_m, q.north_m}
                                 : EastNorth{clear.east_m, clear.north_m};
    }
  }
  return std::nullopt;
}

// Puts `from` in front of a route that starts at its way out of the
// obstacles: one more leg, sailed at the route's mean speed in the mode of
// its first leg.
void PrependWayOut(EastNorth from, mission::Route* r) {
  if (r->waypoints.empty()) return;
  const EastNorth first = r->waypoints.front().position;
  const double leg_m = std::hypot(first.east_m - from.east_m, first.north_m - from.north_m);
  const double speed =
      r->sailing_time_s > 0 && r->length_m > 0 ? r->length_m / r->sailing_time_s : 1.0;
  const double leg_s = leg_m / speed;
  for (mission::RouteWaypoint& w : r->waypoints) {
    w.eta_s += leg_s;
    w.distance_from_start_m += leg_m;
  }
  mission::RouteWaypoint out = r->waypoints.front();
  out.position = {from.east_m, from.north_m};
  out.eta_s = 0.0;
  out.distance_from_start_m = 0.0;
  out.fuel_kg = r->waypoints.front().fuel_kg * (r->length_m > 0 ? leg_m / r->length_m : 0.0);
  r->waypoints.insert(r->waypoints.begin(), out);
  r->length_m += leg_m;
  r->sailing_time_s += leg_s;
}

// Everything routing over one chart needs, built once per (chart, ship,
// route options, environment) and shared by every call of every mission
// using it: the RoutePlanner (its obstacle field is the expensive part) and
// the routes already planned between two positions (a replan asks again for
// most legs of the previous version).
struct ChartRouting {
  chart::LocalFrame frame;
  std::shared_ptr<const route::RoutePlanner> planner;
  route::Environment env;
  std::mutex mu;
  std::map<std::array<double, 4>, mission::Route> routes;  // (from x, y, to x, y) -> route
};
inline constexpr size_t kMaxCachedRoutings = 16;
inline constexpr size_t kMaxCachedRoutes = 4096;
#endif

class Adapter final : public MissionEngine {
 public:
  explicit Adapter(storage::ChartRepository& charts) : charts_(charts) {}

  absl::Status CheckSpec(const v1::MissionSpec& spec) override {
    task::LoadResult loaded = task::LoadTask(spec.domain(), spec.problem());
    for (const auto& d : loaded.diagnostics) {
      if (d.severity == pddl::Severity::kError) {
        return WithDiagnostics(
            absl::InvalidArgumentError(absl::StrCat("spec: malformed PDDL: ", d.ToString())),
            ToProto(loaded.diagnostics));
      }
    }
    for (int i = 0; i < spec.locations_size(); ++i) {
      if (spec.locations(i).name().empty())
        return absl::InvalidArgumentError(absl::StrCat("spec.locations[", i, "].name is empty"));
    }
    if (spec.ship().service_speed_mps() < 0)
      return absl::InvalidArgumentError("spec.ship.service_speed_mps must not be negative");
    return absl::OkStatus();
  }

  absl::StatusOr<PlannedVersion> PlanInitial(const v1::MissionSpec& spec,
                                             const StopToken& stop) override {
    SEAPLAN_ASSIGN_OR_RETURN(Context c,
                             MakeContext(spec, /*locations_state=*/"", stop, /*replan=*/false));
    mission::NavigationLog log;
    SEAPLAN_ASSIGN_OR_RETURN(
        mission::PlanVersion v,
        mission::PlanInitialVersion(c.definition, c.planner, c.router, stop, &log));
    return ToPlanned(v, c, c.definition.locations, log);
  }

  absl::StatusOr<std::optional<PlannedVersion>> Replan(const v1::MissionSpec& spec,
                                                       const MissionRuntimeState& state,
                                                       std::string_view reason,
                                                       const StopToken& stop) override {
    // The definition's locations are the engine state's (they include a
    // port-s a previous replan added), not the spec's.
    SEAPLAN_ASSIGN_OR_RETURN(Context c,
                             MakeContext(spec, state.engine_state, stop, /*replan=*/true));
    const mission::PlanVersion current = FromProto(state.current_version);
    const int current_version = state.mission.current_version();
    double now_s = state.current_version.mission_time_origin_s();
    std::vector<mission::Feedback> recent;
    for (const auto& f : state.recent_feedback) {
      if (f.plan_version() == current_version || f.plan_version() == 0) {
        now_s = std::max(now_s, f.mission_time_s());
        recent.push_back(FeedbackFromProto(f, current_version, nullptr));
      }
    }
    const std::vector<std::string> completed(state.mission.completed_tasks().begin(),
                                             state.mission.completed_tasks().end());
    mission::ShipObservation ship;
    const v1::ShipState& last =
        state.mission.has_last_state() ? state.mission.last_state() : spec.initial_state();
    const EastNorth p =
        c.frame.ToLocal({last.position().latitude_deg(), last.position().longitude_deg()});
    ship.position = {p.east_m, p.north_m};
    // A reported state is a full state: fuel 0 is an empty tank. The spec's
    // initial state counts only when it names a fuel level.
    if (state.mission.has_last_state() || last.fuel_fraction() > 0)
      ship.fuel_fraction = last.fuel_fraction();
    const mission::ReplanInput input =
        mission::MakeReplanInput(current, completed, recent, std::string(reason), ship, now_s);
    mission::NavigationLog log;
    SEAPLAN_ASSIGN_OR_RETURN(mission::ReplanResult r,
                             mission::Replan(c.definition, current, c.definition.locations, input,
                                             c.planner, c.router, stop, &log));
    if (!r.version) return std::optional<PlannedVersion>();
    return std::optional<PlannedVersion>(ToPlanned(*r.version, c, r.locations, log));
  }

  FeedbackDecision OnFeedback(const v1::MissionSpec& spec, const MissionRuntimeState& state,
                              const v1::Feedback& feedback) override {
    FeedbackDecision d;
    const mission::PlanVersion current = FromProto(state.current_version);
    const mission::Task* task = nullptr;
    for (const auto& t : current.tasks) {
      if (t.id == feedback.task_id()) task = &t;
    }
    switch (feedback.kind()) {
      case v1::Feedback::KIND_TASK_STARTED:
        if (task) d.log_messages.push_back(mission::TaskStartedMessage(task->kind));
        break;
      case v1::Feedback::KIND_TASK_COMPLETED: {
        std::vector<std::string> done(state.mission.completed_tasks().begin(),
                                      state.mission.completed_tasks().end());
        if (std::find(done.begin(), done.end(), feedback.task_id()) == done.end())
          done.push_back(feedback.task_id());
        if (task) d.log_messages.push_back(mission::TaskCompletedMessage(task->kind));
        bool all = !current.tasks.empty();
        for (const auto& t : current.tasks)
          all &= std::find(done.begin(), done.end(), t.id) != done.end();
        d.completed_tasks = std::move(done);
        if (all) {
          d.new_state = v1::MISSION_STATE_COMPLETED;
          d.log_messages.emplace_back(mission::messages::kMissionCompleted);
          return d;
        }
        break;
      }
      case v1::Feedback::KIND_TASK_FAILED:
        if (task) d.log_messages.push_back(mission::TaskFailedMessage(task->kind));
        break;
      case v1::Feedback::KIND_COLLISION_AVOIDANCE:
        d.log_messages.emplace_back(mission::messages::kPotentialCollision);
        break;
      default:
        break;
    }
    auto frame = FrameFor(spec);
    const mission::Feedback f = FeedbackFromProto(feedback, state.mission.current_version(),
                                                  frame.ok() ? &*frame : nullptr);
    // Tasks done so far (DecideReplan counts the one this report completes):
    // a refuel still ahead is "left" whatever its planned time (a late ship
    // is past it on paper).
    const std::set<std::string> done(state.mission.completed_tasks().begin(),
                                     state.mission.completed_tasks().end());
    if (auto reason = mission::DecideReplan(f, current, task, Policy(spec), &done)) {
      d.replan = true;
      d.replan_reason = *reason;
    }
    return d;
  }

 private:
  struct Context {
    mission::MissionDefinition definition;
    mission::TemporalPlanner planner;
    mission::RoutePlanner router;
    chart::LocalFrame frame;
  };

  static mission::ReplanPolicy Policy(const v1::MissionSpec& spec) {
    mission::ReplanPolicy p;
    const v1::ReplanPolicy& r = spec.replan_policy();
    if (r.fuel_threshold_fraction() > 0) p.fuel_threshold_fraction = r.fuel_threshold_fraction();
    if (r.position_deviation_m() > 0) p.position_deviation_m = r.position_deviation_m();
    if (r.delay_tolerance_s() > 0) p.delay_tolerance_s = r.delay_tolerance_s();
    p.fuel_planned = mission::DomainPlansFuel(spec.domain());
    return p;
  }

  absl::StatusOr<chart::LocalFrame> FrameFor(const v1::MissionSpec& spec) {
#if SEAPLAN_SERVER_HAS_ROUTE
    if (!spec.chart_id().empty()) {
      SEAPLAN_ASSIGN_OR_RETURN(std::shared_ptr<ChartRouting> routing, RoutingFor(spec));
      return routing->frame;
    }
#else
    if (!spec.chart_id().empty()) {
      SEAPLAN_ASSIGN_OR_RETURN(storage::ChartRecord record,
                               charts_.Get(spec.chart_id(), /*with_blobs=*/false));
      v1::ObstacleSummary summary;
      summary.ParseFromString(record.summary);
      int epsg = 0;
      if (std::sscanf(summary.frame().c_str(), "EPSG:%d", &epsg) == 1)
        return chart::LocalFrame::FromEpsg(epsg);
    }
#endif
    if (spec.locations_size() > 0) {
      const auto& p = spec.locations(0).position();
      return chart::LocalFrame::ForCentre({p.latitude_deg(), p.longitude_deg()});
    }
    return chart::LocalFrame();
  }

#if SEAPLAN_SERVER_HAS_ROUTE
  // The routing of a chart mission, built once per (chart, ship, route
  // options, environment) and cached.
  absl::StatusOr<std::shared_ptr<ChartRouting>> RoutingFor(const v1::MissionSpec& spec) {
    std::string key = spec.chart_id();
    for (const auto* m : {static_cast<const google::protobuf::Message*>(&spec.ship()),
                          static_cast<const google::protobuf::Message*>(&spec.route_options()),
                          static_cast<const google::protobuf::Message*>(&spec.environment())}) {
      std::string bytes;
      m->SerializeToString(&bytes);
      absl::StrAppend(&key, "|", bytes.size(), ":", bytes);
    }
    {
      std::lock_guard lock(routings_mu_);
      if (auto it = routings_.find(key); it != routings_.end()) return it->second;
    }
    // Built outside the lock: loading a chart and its field takes a while and
    // must not hold up missions on other charts. Two first calls may both
    // build; the first stored wins.
    auto map = LoadMap(charts_, spec.chart_id());
    if (!map.ok()) {
      if (absl::IsNotFound(map.status())) {
        return absl::FailedPreconditionError(
            absl::StrCat("spec.chart_id: ", map.status().message()));
      }
      return map.status();
    }
    route::RouteOptions options = OptionsToEngine(spec.route_options());
    auto planner = route::RoutePlanner::Create(*map, ShipToEngine(spec.ship()), options);
    if (!planner.ok()) {
      return absl::Status(
          planner.status().code(),
          absl::StrCat("routing over chart '", spec.chart_id(), "': ", planner.status().message()));
    }
    auto routing = std::make_shared<ChartRouting>();
    routing->frame = (*map)->frame();
    routing->planner = std::make_shared<const route::RoutePlanner>(std::move(*planner));
    routing->env = EnvironmentToEngine(spec.environment());
    std::lock_guard lock(routings_mu_);
    if (routings_.size() >= kMaxCachedRoutings) routings_.erase(routings_.begin());
    return routings_.emplace(key, std::move(routing)).first->second;
  }

  // Plans a move over the chart; cached per (from, to) positions.
  static mission::RoutePlanner ChartRouter(std::shared_ptr<ChartRouting> shared, StopToken stop) {
    return [routing = std::move(shared),
            stop](const mission::RouteRequest& req) -> StatusOr<mission::Route> {
      const std::array<double, 4> key = {req.from_position.east_m, req.from_position.north_m,
                                         req.to_position.east_m, req.to_position.north_m};
      {
        std::lock_guard lock(routing->mu);
        if (auto it = routing->routes.find(key); it != routing->routes.end()) return it->second;
      }
      if (stop.StopRequested()) {
        return stop.Reason() == StopReason::kDeadline
                   ? absl::DeadlineExceededError("routing stopped: deadline")
                   : absl::CancelledError("routing stopped");
      }
      const EastNorth from{req.from_position.east_m, req.from_position.north_m};
      EastNorth start = from;
      bool way_out = false;
      if (routing->planner->field().Inside({from.east_m, from.north_m})) {
        std::optional<EastNorth> out = ShortestWayOut(routing->planner->field(), from);
        if (!out) {
          return absl::FailedPreconditionError(
              absl::StrCat("start (", from.east_m, ", ", from.north_m,
                           ") lies inside a grounding obstacle with no free water "
                           "within ",
                           kMaxWayOutM, " m"));
        }
        start = *out;
        way_out = true;
      }
      auto result = routing->planner->Plan(
          start, EastNorth{req.to_position.east_m, req.to_position.north_m}, routing->env, stop);
      if (!result.ok()) {
        if (absl::IsInvalidArgument(result.status())) {
          // A location outside the chart or inside an obstacle: the mission
          // cannot sail this leg as specified.
          return absl::FailedPreconditionError(result.status().message());
        }
        return result.status();
      }
      if (result->stopped) {
        return stop.Reason() == StopReason::kDeadline
                   ? absl::DeadlineExceededError("routing stopped: deadline")
                   : absl::CancelledError("routing stopped");
      }
      if (result->chosen < 0 || result->chosen >= static_cast<int>(result->alternatives.size()) ||
          !result->alternatives[static_cast<size_t>(result->chosen)].safe) {
        return absl::FailedPreconditionError("no obstacle-free route alternative");
      }
      mission::Route r = RouteFromEngine(*result);
      if (way_out) {
        PrependWayOut(from, &r);
        log::Info(
            "route from ({:.0f}, {:.0f}) inside the buffered obstacles leaves them at ({:.0f}, "
            "{:.0f})",
            from.east_m, from.north_m, start.east_m, start.north_m);
      }
      std::lock_guard lock(routing->mu);
      if (routing->routes.size() >= kMaxCachedRoutes) routing->routes.clear();
      routing->routes.emplace(key, r);
      return r;
    };
  }
#endif

  absl::StatusOr<Context> MakeContext(const v1::MissionSpec& spec,
                                      const std::string& locations_state,
                                      const StopToken& route_stop, bool replan) {
    Context c;
    SEAPLAN_ASSIGN_OR_RETURN(c.frame, FrameFor(spec));
    mission::MissionDefinition& def = c.definition;
    def.domain = spec.domain();
    def.problem = spec.problem();
    if (locations_state.empty()) {
      for (const auto& l : spec.locations()) {
        const EastNorth p =
            c.frame.ToLocal({l.position().latitude_deg(), l.position().longitude_deg()});
        def.locations[l.name()] = {p.east_m, p.north_m};
      }
    } else {
      auto decoded = mission::DecodeEngineState(locations_state);
      if (!decoded.ok()) {
        return absl::DataLossError(
            absl::StrCat("stored engine state is unreadable: ", decoded.status().message()));
      }
      def.locations = std::move(*decoded);
    }
    for (const auto& op : spec.port_operations())
      def.refine.port_operation_durations_s[op.action()] = op.duration_s();
    if (spec.planner_options().epsilon_s() > 0)
      def.refine.epsilon_s = spec.planner_options().epsilon_s();
    def.regeneration.ship_object = spec.ship_object();
    def.policy = Policy(spec);
    def.regeneration.fuel_threshold_fraction = def.policy.fuel_threshold_fraction;

    search::PlannerOptions options;
    const v1::PlannerOptions& o = spec.planner_options();
    if (o.has_time_limit()) {
      SEAPLAN_ASSIGN_OR_RETURN(double s,
                               DurationSeconds(o.time_limit(), "spec.planner_options.time_limit"));
      if (s > 0) options.time_limit_s = s;
    }
    if (o.memory_limit_mb() > 0) options.memory_limit_mb = o.memory_limit_mb();
    if (o.max_concurrent_actions() > 0) options.max_concurrent_actions = o.max_concurrent_actions();
    if (o.has_anytime()) options.anytime = o.anytime();
    if (o.random_seed() != 0) options.random_seed = o.random_seed();
    if (o.epsilon_s() > 0) options.epsilon_s = o.epsilon_s();
    if (absl::Status st = options.Validate(); !st.ok()) {
      return absl::InvalidArgumentError(absl::StrCat("spec.planner_options: ", st.message()));
    }
    c.planner = [options, replan](std::string_view domain, std::string_view problem,
                                  const StopToken& stop) -> StatusOr<mission::PlannerOutcome> {
      search::PlanResult r;
      if (replan && options.anytime) {
        // A replan is on the mission loop's critical path (the ship waits
        // for it): anytime search would use its whole time limit on
        // problems it cannot prove optimal. So: first plan, then a short
        // improvement run, keeping the better of the two.
        search::PlannerOptions first = options;
        first.anytime = false;
        r = search::Solve(domain, problem, first, stop);
        if (r.status == search::PlanStatus::kSolvedSatisficing && !stop.StopRequested()) {
          search::PlannerOptions improve = options;
          improve.time_limit_s = std::min(
              options.time_limit_s,
              std::clamp(2.0 * r.stats.search_time_s, kReplanImproveMinS, kReplanImproveMaxS));
          search::PlanResult better = search::Solve(domain, problem, improve, stop);
          const bool solved = better.status == search::PlanStatus::kSolvedSatisficing ||
                              better.status == search::PlanStatus::kSolvedOptimally;
          if (solved && better.makespan_s < r.makespan_s - 1e-9) r = std::move(better);
        }
      } else {
        r = search::Solve(domain, problem, options, stop);
      }
      if (r.status == search::PlanStatus::kError) return absl::InvalidArgumentError(r.message);
      mission::PlannerOutcome out;
      out.solved = r.status == search::PlanStatus::kSolvedSatisficing ||
                   r.status == search::PlanStatus::kSolvedOptimally;
      out.plan = std::move(r.plan);
      out.status = search::ToString(r.status);
      return out;
    };
    if (spec.chart_id().empty()) {
      const double speed = spec.ship().service_speed_mps() > 0 ? spec.ship().service_speed_mps()
                                                               : kDefaultServiceSpeedMps;
      c.router = mission::StraightLineRouter(speed);
    } else {
#if SEAPLAN_SERVER_HAS_ROUTE
      SEAPLAN_ASSIGN_OR_RETURN(std::shared_ptr<ChartRouting> routing, RoutingFor(spec));
      c.router = ChartRouter(std::move(routing), route_stop);
#else
      (void)route_stop;
      return absl::UnimplementedError(
          "missions with a chart_id: this server is built without engine/route; leave chart_id "
          "empty for "
          "straight-line legs");
#endif
    }
    return c;
  }

  PlannedVersion ToPlanned(const mission::PlanVersion& v, const Context& c,
                           const mission::LocationTable& locations,
                           const mission::NavigationLog& log) {
    PlannedVersion out;
    v1::PlanVersion& p = out.version;
    p.set_reason(v.reason);
    p.set_makespan_s(v.makespan_s);
    p.set_problem(v.problem);
    p.set_mission_time_origin_s(v.mission_time_origin_s);
    p.set_planner_status(v1::SOLVED_SATISFICING);
    for (const auto& s : v.plan.steps) *p.add_plan() = StepToProto(s);
    for (const auto& t : v.tasks) {
      v1::Task* task = p.add_tasks();
      task->set_task_id(t.id);
      task->set_kind(KindToProto(t.kind));
      task->set_start_s(t.start_s);
      task->set_duration_s(t.duration_s);
      *task->mutable_action() = StepToProto(t.action);
      task->set_from_location(t.from_location);
      task->set_to_location(t.to_location);
      if (t.route) {
        v1::RouteAlternative* r = task->mutable_route();
        r->set_index(t.route->alternative_index);
        r->set_length_m(t.route->length_m);
        r->set_sailing_time_s(t.route->sailing_time_s);
        r->set_fuel_kg(t.route->fuel_kg);
        r->set_expected_grounding_cost(t.route->expected_grounding_cost);
        r->set_max_grounding_probability(t.route->max_grounding_probability);
        for (const auto& w : t.route->waypoints) {
          v1::RouteWaypoint* rw = r->add_waypoints();
          const chart::LatLon ll = c.frame.ToLatLon({w.position.east_m, w.position.north_m});
          rw->mutable_position()->set_latitude_deg(ll.lat_deg);
          rw->mutable_position()->set_longitude_deg(ll.lon_deg);
          rw->set_mode(ModeToProto(w.mode));
          rw->set_eta_s(w.eta_s);
          rw->set_distance_from_start_m(w.distance_from_start_m);
          rw->set_time_to_grounding_s(w.time_to_grounding_s);
          rw->set_grounding_probability(w.grounding_probability);
          rw->set_expected_grounding_cost(w.expected_grounding_cost);
          rw->set_fuel_kg(w.fuel_kg);
        }
        for (const auto& e : mission::ModeSchedule(*t.route)) {
          v1::ModeScheduleEntry* m = task->add_mode_schedule();
          m->set_from_waypoint(e.from_waypoint);
          m->set_to_waypoint(e.to_waypoint);
          m->set_mode(ModeToProto(e.mode));
          m->set_start_s(e.start_s);
          m->set_duration_s(e.duration_s);
        }
      }
    }
    out.engine_state = mission::EncodeEngineState(locations);
    for (const auto& e : log.entries()) out.log_messages.push_back(e.message);
    return out;
  }

  // The engine's view of a stored version (routes are not needed to replan).
  static mission::PlanVersion FromProto(const v1::PlanVersion& p) {
    mission::PlanVersion v;
    v.version = p.version();
    v.reason = p.reason();
    v.mission_time_origin_s = p.mission_time_origin_s();
    v.makespan_s = p.makespan_s();
    v.problem = p.problem();
    for (const auto& a : p.plan()) v.plan.steps.push_back(StepFromProto(a));
    for (const auto& t : p.tasks()) {
      mission::Task task;
      task.id = t.task_id();
      task.kind = KindFromProto(t.kind());
      task.start_s = t.start_s();
      task.duration_s = t.duration_s();
      task.action = StepFromProto(t.action());
      task.from_location = t.from_location();
      task.to_location = t.to_location();
      v.tasks.push_back(std::move(task));
    }
    return v;
  }

  storage::ChartRepository& charts_;
#if SEAPLAN_SERVER_HAS_ROUTE
  std::mutex routings_mu_;
  std::map<std::string, std::shared_ptr<ChartRouting>> routings_;
#endif
};

}  // namespace

std::shared_ptr<MissionEngine> MakeMissionEngine(storage::ChartRepository& charts) {
  return std::make_shared<Adapter>(charts);
}

}  // namespace seaplan::server

#else

namespace seaplan::server {
std::shared_ptr<MissionEngine> MakeMissionEngine(storage::ChartRepository&) {
  return nullptr;
}
}  // namespace seaplan::server

#endif
