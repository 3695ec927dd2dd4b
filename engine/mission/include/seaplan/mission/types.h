// Value types of the mission engine (paper 000, fig. 5 and 7): positions of
// the mission's named locations, refined routes, executable tasks and plan
// versions. Everything here is a copyable value with no reference to a
// ground task, a chart or the wire format; the server translates these to
// and from seaplan.v1 messages at its edge.
//
// Frame: positions are seaplan::EastNorth in a local metric frame (metres),
// the frame of the mission's chart (seaplan::chart::LocalFrame) or any flat
// frame the caller chooses; the engine never converts to lat/lon itself.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/east_north.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission {

// Positions of the PDDL location objects (names lower case).
using LocationTable = std::map<std::string, EastNorth, std::less<>>;

// How a ship under way moves: course over ground (clockwise from north)
// and speed. A replan that starts where the ship is starts with it.
struct ShipMotion {
  double course_rad = 0.0;
  double speed_mps = 0.0;
};

// Machinery-system operating mode of a route segment (paper 002).
enum class MsoMode { kUnspecified, kPto, kMec, kPti };
std::string_view MsoModeName(MsoMode mode);  // "PTO", "MEC", "PTI", "-"

struct RouteWaypoint {
  EastNorth position;
  MsoMode mode = MsoMode::kUnspecified;  // of the segment that starts here
  double eta_s = 0.0;                    // sailing time from the route start
  double distance_from_start_m = 0.0;
  double time_to_grounding_s = 0.0;  // 0 when not estimated
  double grounding_probability = 0.0;
  double expected_grounding_cost = 0.0;
  double fuel_kg = 0.0;  // fuel of the segment that starts here
};

// A refined route for one move. sailing_time_s is what replaces the PDDL
// duration of the move.
struct Route {
  std::vector<RouteWaypoint> waypoints;  // at least start and goal
  double length_m = 0.0;
  double sailing_time_s = 0.0;
  double fuel_kg = 0.0;
  double expected_grounding_cost = 0.0;
  double max_grounding_probability = 0.0;
  int alternative_index = 0;
};

// One contiguous run of segments in the same MSO mode.
struct ModeScheduleEntry {
  int from_waypoint = 0;
  int to_waypoint = 0;
  MsoMode mode = MsoMode::kUnspecified;
  double start_s = 0.0;  // relative to the start of the route
  double duration_s = 0.0;
};
std::vector<ModeScheduleEntry> ModeSchedule(const Route& route);

enum class TaskKind { kMove, kLoad, kUnload, kRepair, kRefuel, kOther };
std::string_view TaskKindName(TaskKind kind);  // "move", "load", ...
// By action name: "move" anywhere -> move (checked first, so
// move-fueling-ship is a move), then "unload", "load", "repair",
// "refuel"/"fuel"; anything else kOther.
TaskKind TaskKindOfAction(std::string_view action_name);

// An executable task (one plan step) in mission time.
struct Task {
  std::string id;  // "v<version>-t<index>", stable within a version
  TaskKind kind = TaskKind::kOther;
  double start_s = 0.0;  // mission time
  double duration_s = 0.0;
  validate::PlanStep action;  // the PDDL action, times in mission time
  std::string from_location;  // moves: where from / to; port ops: the port in to_location
  std::string to_location;
  std::optional<Route> route;  // moves only
  double end_s() const { return start_s + duration_s; }
};

// What the temporal planner proved about a version's plan.
enum class PlanQuality {
  kSatisficing,  // valid; better plans may exist
  kOptimal,      // of minimal makespan (proven)
};

// One plan version of a mission, everything in mission time.
struct PlanVersion {
  int version = 0;
  std::string reason;  // "initial plan", "task v1-t2 move-ship failed", "fuel 28% <= 30%"
  double mission_time_origin_s = 0.0;
  validate::Plan plan;      // refined, in mission time
  double makespan_s = 0.0;  // end of the last task, mission time
  std::vector<Task> tasks;
  std::string problem;  // the PDDL problem this version was planned from
  PlanQuality quality = PlanQuality::kSatisficing;  // of the temporal plan before refinement
};

}  // namespace seaplan::mission
