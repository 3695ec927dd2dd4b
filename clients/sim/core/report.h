// The mission report the simulation client writes: navigation log, closest
// point of approach per traffic vessel, fuel over time, the trajectory, and
// every plan version with its reason; as JSON, and as two SVG plots (the
// trajectory over the chart's obstacles with the traffic, and the plan
// versions as a Gantt chart).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "seaplan/colav/geometry.h"
#include "seaplan/common/json.h"  // JsonString, used with the report
#include "seaplan/common/status.h"
#include "seaplan/mission/navigation_log.h"
#include "seaplan/mission/types.h"

namespace seaplan::sim {

using colav::Kinematics;

struct CpaRecord {
  std::string vessel;
  double min_distance_m = 1e18;  // true distance, every simulation step
  double time_s = 0.0;
};

struct TimedPoint {
  double time_s = 0.0;
  EastNorth position;
  // Own ship: the machinery mode in use; traffic: unspecified.
  mission::MsoMode mode = mission::MsoMode::kUnspecified;
};

struct MissionReport {
  std::string mission_id;
  std::string scenario;
  mission::NavigationLog log;
  std::map<int, CpaRecord> cpa;                 // by traffic id
  std::vector<std::pair<double, double>> fuel;  // (mission time, fraction)
  std::vector<TimedPoint> trajectory;
  std::map<std::string, std::vector<TimedPoint>> traffic_tracks;
  std::vector<mission::PlanVersion> versions;
  double safety_distance_m = 0.0;
  double end_time_s = 0.0;
  bool completed = false;
  bool tank_ran_dry = false;
  double min_fuel_fraction = 1.0;
  int fuel_triggered_replans = 0;
  // Closest approach of the ship's position to the land (sampled every 2 s,
  // up to 1000 m; negative = aground, how far in) and the time spent aground.
  // Only when the scenario has a chart.
  bool land_known = false;
  double min_land_clearance_m = 1000.0;
  double min_land_clearance_time_s = 0.0;
  double aground_s = 0.0;
};

std::string ToJson(const MissionReport& report);

// Obstacles as outer rings in the local frame (for the plot only).
using Rings = std::vector<std::vector<EastNorth>>;
// The trajectory over the obstacles, north up: the track coloured by the
// machinery mode in use, time marks along it, the traffic's tracks, the named
// locations, a scale bar (metres and nautical miles), a north arrow and a
// legend. The Gantt chart: every plan version's tasks on a mission-time axis
// with its replan reason, coloured by task kind, with a legend. Both are
// well-formed XML (text escaped).
std::string TrajectorySvg(const MissionReport& report, const Rings& obstacles,
                          const mission::LocationTable& locations);
std::string GanttSvg(const MissionReport& report);

// Writes <dir>/report.json, trajectory.svg and gantt.svg.
Status WriteReport(const std::string& dir, const MissionReport& report, const Rings& obstacles,
                   const mission::LocationTable& locations);

}  // namespace seaplan::sim
