#include "seaplan/mission/mission_engine.h"

#include <algorithm>
#include <utility>

#include "absl/strings/str_cat.h"
#include "seaplan/mission/mission_planner.h"
#include "seaplan/mission/problem_update.h"
#include "seaplan/mission/search_planner.h"
#include "seaplan/task/grounder.h"

namespace seaplan::mission {
namespace {

// Everything one call plans with.
struct Context {
  MissionDefinition definition;
  TemporalPlanner planner;
  RoutePlanner router;
  std::string fuel_function;
};

class Engine final : public MissionEngine {
 public:
  explicit Engine(ChartLoader charts) : routings_(std::move(charts)) {}

  Status CheckSpec(const MissionSpec& spec, std::vector<pddl::Diagnostic>* diagnostics) override {
    task::LoadResult loaded = task::LoadTask(spec.domain, spec.problem);
    if (loaded.memory_ran_out) {
      return absl::ResourceExhaustedError(
          "spec: memory ran out (an allocation failed) grounding the task");
    }
    for (const auto& d : loaded.diagnostics) {
      if (d.severity == pddl::Severity::kError) {
        if (diagnostics) *diagnostics = loaded.diagnostics;
        return absl::InvalidArgumentError(absl::StrCat("spec: malformed PDDL: ", d.ToString()));
      }
    }
    for (size_t i = 0; i < spec.locations.size(); ++i) {
      if (spec.locations[i].name.empty())
        return absl::InvalidArgumentError(absl::StrCat("spec.locations[", i, "].name is empty"));
    }
    if (spec.service_speed_mps < 0)
      return absl::InvalidArgumentError("spec.ship.service_speed_mps must not be negative");
    return absl::OkStatus();
  }

  StatusOr<chart::LocalFrame> Frame(const MissionSpec& spec) override {
    if (!spec.chart_id.empty()) {
      SEAPLAN_ASSIGN_OR_RETURN(std::shared_ptr<ChartRouting> routing, Routing(spec));
      return routing->frame();
    }
    if (!spec.locations.empty()) return chart::LocalFrame::ForCentre(spec.locations[0].position);
    return chart::LocalFrame();
  }

  StatusOr<PlannedVersion> PlanInitial(const MissionSpec& spec, const StopToken& stop) override {
    // Decided once for the mission, from the domain's structure.
    EngineState state;
    state.fuel_function = PlannedFuelFunction(spec.domain);
    SEAPLAN_ASSIGN_OR_RETURN(Context c, MakeContext(spec, state, stop, PlanningPhase::kInitial));
    NavigationLog log;
    SEAPLAN_ASSIGN_OR_RETURN(PlanVersion v,
                             PlanInitialVersion(c.definition, c.planner, c.router, stop, &log));
    return ToPlanned(std::move(v), c.definition.locations, c.fuel_function, log);
  }

  StatusOr<std::optional<PlannedVersion>> Replan(const MissionSpec& spec,
                                                 const MissionRuntime& runtime,
                                                 std::string_view reason,
                                                 const StopToken& stop) override {
    // The locations are the engine state's (they include a port-s a
    // previous replan added), not the spec's.
    SEAPLAN_ASSIGN_OR_RETURN(EngineState state, Decode(runtime.engine_state));
    SEAPLAN_ASSIGN_OR_RETURN(Context c, MakeContext(spec, state, stop, PlanningPhase::kReplan));
    const PlanVersion& current = runtime.current;
    double now_s = current.mission_time_origin_s;
    std::vector<Feedback> recent;
    for (const Feedback& f : runtime.recent_feedback) {
      if (f.plan_version == current.version || f.plan_version == 0) {
        now_s = std::max(now_s, f.mission_time_s);
        recent.push_back(f);
      }
    }
    SEAPLAN_ASSIGN_OR_RETURN(chart::LocalFrame frame, Frame(spec));
    const EastNorth initial = frame.ToLocal(spec.initial_position);
    ShipObservation ship;
    ship.position = {initial.east_m, initial.north_m};
    if (runtime.last_report) {
      // A reported state is a full state: fuel 0 is an empty tank.
      if (runtime.last_report->position) ship.position = *runtime.last_report->position;
      ship.fuel_fraction = runtime.last_report->fuel_fraction;
      ship.motion = runtime.last_report->motion;
    } else if (spec.initial_fuel_fraction > 0) {
      ship.fuel_fraction = spec.initial_fuel_fraction;
    }
    const ReplanInput input = MakeReplanInput(current, runtime.completed_task_ids, recent,
                                              std::string(reason), ship, now_s);
    NavigationLog log;
    SEAPLAN_ASSIGN_OR_RETURN(ReplanResult r,
                             mission::Replan(c.definition, current, c.definition.locations, input,
                                             c.planner, c.router, stop, &log));
    if (!r.version) return std::optional<PlannedVersion>();
    return std::optional<PlannedVersion>(
        ToPlanned(std::move(*r.version), r.locations, c.fuel_function, log));
  }

  FeedbackOutcome OnFeedback(const MissionSpec& spec, const MissionRuntime& runtime,
                             const Feedback& feedback) override {
    auto state = Decode(runtime.engine_state);
    const std::string fuel_function = state.ok() && state->fuel_function
                                          ? *state->fuel_function
                                          : PlannedFuelFunction(spec.domain);
    ReplanPolicy policy = spec.policy;
    policy.fuel_planned = !fuel_function.empty();
    return mission::OnFeedback(policy, runtime.current, runtime.completed_task_ids, feedback);
  }

  void ForgetChart(const std::string& chart_id) override { routings_.Forget(chart_id); }

 private:
  static StatusOr<EngineState> Decode(const std::string& engine_state) {
    auto decoded = DecodeEngineState(engine_state);
    if (!decoded.ok()) {
      return absl::DataLossError(
          absl::StrCat("stored engine state is unreadable: ", decoded.status().message()));
    }
    return decoded;
  }

  StatusOr<std::shared_ptr<ChartRouting>> Routing(const MissionSpec& spec) {
    return routings_.Get(spec.chart_id, spec.routing_key, spec.routing);
  }

  // `state` without locations: the spec's. Without a fuel function (a
  // state stored before it was recorded): decided from the domain now.
  StatusOr<Context> MakeContext(const MissionSpec& spec, const EngineState& state,
                                const StopToken& route_stop, PlanningPhase phase) {
    Context c;
    SEAPLAN_ASSIGN_OR_RETURN(chart::LocalFrame frame, Frame(spec));
    MissionDefinition& def = c.definition;
    def.domain = spec.domain;
    def.problem = spec.problem;
    if (state.locations.empty()) {
      for (const NamedPosition& l : spec.locations) {
        const EastNorth p = frame.ToLocal(l.position);
        def.locations[l.name] = {p.east_m, p.north_m};
      }
    } else {
      def.locations = state.locations;
    }
    c.fuel_function = state.fuel_function ? *state.fuel_function : PlannedFuelFunction(spec.domain);
    def.refine.port_operation_durations_s = spec.port_operation_durations_s;
    def.refine.epsilon_s = spec.planner.epsilon_s;
    def.regeneration.ship_object = spec.ship_object;
    def.policy = spec.policy;
    def.policy.fuel_planned = !c.fuel_function.empty();
    def.regeneration.fuel_threshold_fraction = def.policy.fuel_threshold_fraction;
    def.regeneration.fuel_function = c.fuel_function;
    if (Status st = spec.planner.Validate(); !st.ok())
      return absl::InvalidArgumentError(absl::StrCat("spec.planner_options: ", st.message()));
    c.planner = SearchPlanner(spec.planner, phase);
    if (spec.chart_id.empty()) {
      c.router = StraightLineRouter(spec.service_speed_mps > 0 ? spec.service_speed_mps
                                                               : kDefaultServiceSpeedMps);
    } else {
      SEAPLAN_ASSIGN_OR_RETURN(std::shared_ptr<ChartRouting> routing, Routing(spec));
      c.router = ChartRouter(std::move(routing), route_stop);
    }
    return c;
  }

  static PlannedVersion ToPlanned(PlanVersion v, const LocationTable& locations,
                                  const std::string& fuel_function, const NavigationLog& log) {
    PlannedVersion out;
    out.version = std::move(v);
    out.engine_state = EncodeEngineState({locations, fuel_function});
    for (const auto& e : log.entries()) out.log_messages.push_back(e.message);
    return out;
  }

  ChartRoutingCache routings_;
};

}  // namespace

std::shared_ptr<MissionEngine> MakeMissionEngine(ChartLoader charts) {
  return std::make_shared<Engine>(std::move(charts));
}

}  // namespace seaplan::mission
