// Scenario files of the simulation client (examples/scenarios/*.scenario).
//
// A line-based "key = value" format: '#' starts a comment, keys may repeat
// where a list is meant, paths are relative to the scenario file, a path
// starting with "shared:" is relative to $SEAPLAN_SHARED (the shared data is
// read at run time, never copied). Positions are "lat lon" in degrees.
//
//   name = case-b
//   domain = ../fjord/domain.pddl
//   problem = ../fjord/case-a.pddl
//   chart = fjord-entrance.geojson          # uploaded with ChartService
//   location = port-a 63.4402 10.3551       # repeat per PDDL location
//   ship_object = ship0
//   vessel_id = mass-1
//   service_speed_mps = 3.6
//   start = 63.4402 10.3551                 # default: the ship's PDDL location
//   start_heading_deg = 90
//   initial_fuel = 1.0
//   fuel_model = percentage                 # or machinery
//   fuel_threshold = 0.3
//   fuel_function = fuel-level              # numeric fuel planned up front (optional)
//   position_deviation_m = 200
//   delay_tolerance_s = 1800
//   safety_distance_m = 150
//   port_operation = load-cont 60
//   wind = 10 250                           # speed m/s, from deg
//   current = 0.5 200                       # speed m/s, from deg
//   grid = 63.430 10.330 25                 # origin lat lon, cell size m
//   gnss_jump = 100 170 38 35 30 50         # start end from_i from_j to_i to_j
//   traffic = ferry ferry 0 63.45 10.36 ; 900 63.43 10.40    # name kind (t lat lon ;)+
//   planner_time_limit_s = 10
//   planner_max_expansions = 20000          # 0: none; the same plan on any machine
//   time_factor = 0                         # 0: as fast as possible
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "executor.h"
#include "seaplan/chart/geodesy.h"
#include "seaplan/common/status.h"

namespace seaplan::sim {

struct ScenarioTrafficPoint {
  double time_s = 0.0;
  chart::LatLon position;
};
struct ScenarioTraffic {
  std::string name, kind;
  std::vector<ScenarioTrafficPoint> track;
};

struct Scenario {
  std::string name;
  std::string file;  // where it was read from
  std::string domain_path, problem_path, chart_path;
  std::vector<std::pair<std::string, chart::LatLon>> locations;
  std::string ship_object;
  std::string vessel_id = "mass-1";
  double service_speed_mps = 4.0;
  std::optional<chart::LatLon> start;
  double start_heading_deg = 0.0;
  double initial_fuel = 1.0;
  FuelModelKind fuel_model = FuelModelKind::kPercentage;
  double fuel_threshold = 0.3;
  std::string fuel_function;
  double position_deviation_m = 200.0;
  double delay_tolerance_s = 1800.0;
  double safety_distance_m = 150.0;
  std::vector<std::pair<std::string, double>> port_operations;
  double wind_speed_mps = 0.0, wind_from_deg = 0.0;
  double current_speed_mps = 0.0, current_from_deg = 0.0;
  std::optional<chart::LatLon> grid_origin;
  double grid_cell_m = 25.0;
  std::vector<GnssJump> gnss_jumps;  // cells only; the grid places them
  std::vector<ScenarioTraffic> traffic;
  double planner_time_limit_s = 10.0;
  std::uint64_t planner_max_expansions = 0;  // PlannerOptions.max_expansions
  double time_factor = 0.0;
};

// Parses scenario text; `file` is used for messages and relative paths.
// InvalidArgument "file:line: ..." on a bad line or unknown key.
StatusOr<Scenario> ParseScenario(std::string_view text, std::string_view file = "scenario");
StatusOr<Scenario> LoadScenario(const std::string& path);

// A path of the scenario resolved: relative to the scenario's folder, or
// "shared:<rel>" under `shared_dir` ($SEAPLAN_SHARED).
StatusOr<std::string> ResolvePath(const Scenario& s, const std::string& path,
                                  const std::string& shared_dir);

// Local positions of the locations in `frame`.
mission::LocationTable LocalLocations(const Scenario& s, const chart::LocalFrame& frame);

// The executor configuration of a scenario in `frame`. The start is the
// `start` position, else the location of the ship in the PDDL problem
// (`ship_location`, may be empty), else the first location.
StatusOr<ExecutorConfig> MakeExecutorConfig(const Scenario& s, const chart::LocalFrame& frame,
                                            const std::string& ship_location);

// Seeded variations of a scenario: each traffic vessel's timing shifted by
// up to +-traffic_shift_s and the wind's speed (x0.8-1.2) and direction
// (+-20 deg) varied, so repeated runs meet the traffic in other geometries.
// Deterministic per seed.
void PerturbConfig(uint64_t seed, ExecutorConfig* config, double traffic_shift_s = 60.0);

}  // namespace seaplan::sim
