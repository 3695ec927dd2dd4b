// State update and problem regeneration for replanning (paper 000, fig. 5
// block 4): from the problem a plan version was planned from, the steps of
// that version that were executed, and what the ship reports (position,
// fuel), build a new PDDL problem whose initial state is "now" and whose goal
// is the mission's goal.
//
// Semantics:
//  * Completed steps are applied with PDDL 2.1 semantics (every start and end
//    event in time order; deletes before adds). Interrupted steps (a failed
//    move) get only their start effects: the ship has left, it has not
//    arrived. A port operation under way when the replan happens is not
//    interrupted: the executor lets it finish, and the caller passes it as
//    completed (the new plan starts after it; see MissionPlanner::Replan).
//  * Ship position: within `snap_distance_m` of a named location the ship is
//    placed there; otherwise a new location object (port-s, port-s2, ...) is
//    added at the ship's position, modelled on the nearest named location T:
//    every static fact mentioning T is copied with T -> new location (and
//    once more with the other location of the fact -> T, which connects the
//    new location with T itself). Objects that carry a length (a route in
//    (connects ?r ?a ?b) with (route-length ?r)) are copied as new objects
//    (r-port-s-port-b) with their static numeric values scaled by the
//    geometric distance ratio (new length = old length x new distance / old
//    distance), so lengths stay in the problem's own units.
//  * Fuel: with a fuel fraction reported, the (fuel ?v)/(no_fuel ?v)
//    predicates (names configurable) are set from fraction <= threshold, but
//    only in domains where (fuel ?v) is a condition of some action (executor
//    fuel, case C); where it is only a goal (case A's "refuel at E") it is
//    left alone. A numeric tank fluent (fuel_function, decided once per
//    mission by PlannedFuelFunction) is set to fraction x fuel_function_full.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/mission/types.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission {

struct ShipObservation {
  EastNorth position;
  std::optional<double> fuel_fraction;  // 0..1
  std::optional<ShipMotion> motion;     // as reported; the problem does not use it
};

struct RegenerationOptions {
  std::string ship_object;                // "" = first object of type "ship"
  std::string location_predicate = "at";  // (at ?ship ?location)
  double snap_distance_m = 150.0;
  std::string new_location_name = "port-s";
  std::string fuel_predicate = "fuel";
  std::string no_fuel_predicate = "no_fuel";
  double fuel_threshold_fraction = 0.3;
  std::string fuel_function;  // e.g. "fuel-level"; "" = none
  double fuel_function_full = 100.0;

  Status Validate() const;
};

struct RegeneratedProblem {
  std::string problem_text;
  std::string ship_location;    // where the new problem puts the ship
  bool added_location = false;  // ship_location is a new object
  LocationTable locations;      // input locations plus the new one
  bool goal_satisfied = false;  // the mission's goal already holds now
};

// The numeric fluent the domain plans fuel with, decided from its structure:
// a one-argument function (over the ship) that some action consumes (a
// decrease effect) and that some action's condition bounds from below
// ((>= (f ?v) x) or (> (f ?v) x)), e.g. (fuel-level ?v) in case C numeric;
// the first in declaration order when several qualify. "" when there is
// none (or the text does not parse). Decide it once per mission: it sets
// ReplanPolicy::fuel_planned and RegenerationOptions::fuel_function.
std::string PlannedFuelFunction(std::string_view domain_text);

StatusOr<RegeneratedProblem> RegenerateProblem(std::string_view domain_text,
                                               std::string_view problem_text,
                                               const std::vector<validate::PlanStep>& completed,
                                               const std::vector<validate::PlanStep>& interrupted,
                                               const LocationTable& locations,
                                               const ShipObservation& ship,
                                               const RegenerationOptions& options = {});

}  // namespace seaplan::mission
