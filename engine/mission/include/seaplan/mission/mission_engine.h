// The mission engine: what a mission service asks of engine/mission, over
// engine types (no wire format). A service stores missions, plan versions
// and feedback, serialises changes per mission and notifies watchers; the
// engine decides everything about the mission itself:
//
//   CheckSpec    cheap checks of a spec before anything is stored
//   PlanInitial  plan -> refine -> parse version 1 (paper 000 fig. 5)
//   OnFeedback   what a report means: tasks done, mission completed, replan
//   Replan       update the problem from the runtime state and plan again
//
// Routing: without a chart a move is the straight line sailed at the
// service speed; with one, moves are routed over the chart (chart_routing.h,
// one route planner per chart and settings, shared by every mission).
//
// Frames: the spec's named locations are WGS84. The engine works in a local
// metric frame (Frame()): the chart's frame when the mission names a chart,
// else the UTM zone of the first location. Positions in feedback, ship
// reports and plan versions are in that frame.
//
// Fuel: whether the domain plans fuel up front (and with which fluent) is
// decided once from the domain's structure when the mission is created
// (PlannedFuelFunction) and carried in the engine state of every version.
//
// Engine state stored with each version (opaque to the service):
// EncodeEngineState (session.h).
//
// Thread-safety: MakeMissionEngine's engine may be called from any thread;
// calls for different missions run in parallel.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/chart/geodesy.h"
#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/mission/chart_routing.h"
#include "seaplan/mission/replan_policy.h"
#include "seaplan/mission/session.h"
#include "seaplan/mission/types.h"
#include "seaplan/pddl/diagnostic.h"
#include "seaplan/search/planner.h"

namespace seaplan::mission {

inline constexpr double kDefaultServiceSpeedMps = 5.0;

struct NamedPosition {
  std::string name;  // PDDL location object
  chart::LatLon position;
};

// A ship state as reported: a full state, so fuel_fraction 0 is an empty tank.
struct ShipReport {
  std::optional<EastNorth> position;  // local frame
  double fuel_fraction = 0.0;
  std::optional<ShipMotion> motion;  // course and speed over ground
};

struct MissionSpec {
  std::string domain;
  std::string problem;
  std::vector<NamedPosition> locations;
  std::string chart_id;            // "" = straight legs
  double service_speed_mps = 0.0;  // straight legs; 0 = kDefaultServiceSpeedMps
  ChartRouteSettings routing;      // chart missions
  // Identifies `routing` (equal keys must mean equal settings): missions on
  // one chart with equal keys share a route planner and its routes.
  std::string routing_key;
  search::PlannerOptions planner;  // epsilon_s also separates refined events
  // Triggers; fuel_planned is ignored (the engine decides it from the domain).
  ReplanPolicy policy;
  std::map<std::string, double> port_operation_durations_s;  // by action name
  std::string ship_object;                                   // "" = first object of type ship
  chart::LatLon initial_position;
  double initial_fuel_fraction = 0.0;  // 0 = not given
};

// What the service knows about a running mission.
struct MissionRuntime {
  PlanVersion current;       // the version the vessel executes, routes included
  std::string engine_state;  // stored with `current`
  std::vector<std::string> completed_task_ids;
  std::optional<ShipReport> last_report;  // the latest reported ship state
  std::vector<Feedback> recent_feedback;  // the latest reports, oldest first
};

// A computed plan version (the service numbers and dates it).
struct PlannedVersion {
  PlanVersion version;
  std::string engine_state;               // store with the version
  std::vector<std::string> log_messages;  // navigation-log lines, paper wording
};

class MissionEngine {
 public:
  virtual ~MissionEngine() = default;

  // InvalidArgument with what and where; PDDL errors also fill `diagnostics`.
  virtual Status CheckSpec(const MissionSpec& spec, std::vector<pddl::Diagnostic>* diagnostics) = 0;

  // The local frame of the mission's positions.
  virtual StatusOr<chart::LocalFrame> Frame(const MissionSpec& spec) = 0;

  // Errors: InvalidArgument (bad input), FailedPrecondition (no plan, a leg
  // with no safe route, an unknown chart), or what `stop` caused.
  virtual StatusOr<PlannedVersion> PlanInitial(const MissionSpec& spec, const StopToken& stop) = 0;

  // nullopt when the goal already holds (the mission is complete).
  virtual StatusOr<std::optional<PlannedVersion>> Replan(const MissionSpec& spec,
                                                         const MissionRuntime& runtime,
                                                         std::string_view reason,
                                                         const StopToken& stop) = 0;

  // Fast (no planning). `runtime` does not include `feedback` yet.
  virtual FeedbackOutcome OnFeedback(const MissionSpec& spec, const MissionRuntime& runtime,
                                     const Feedback& feedback) = 0;

  // The chart was deleted: an engine that keeps charts in memory drops it.
  virtual void ForgetChart(const std::string& chart_id) { (void)chart_id; }
};

// The engine over engine/search (temporal planner) and engine/route
// (charts from `charts`).
std::shared_ptr<MissionEngine> MakeMissionEngine(ChartLoader charts);

}  // namespace seaplan::mission
