// Plan refinement (paper 000, fig. 5 block 2 and fig. 7): every move of a
// temporal plan gets a route from a route-planning callback, its PDDL
// duration is replaced by the route's sailing time, and the plan is
// rescheduled with the new durations while keeping its causal order and its
// concurrency.
//
// Rescheduling lifts the plan to a partial order over its start/end events:
// event b is kept after event a (by epsilon) when a happened before b in the
// given plan and they interfere (one writes a fact or fluent the other reads
// or writes; over-all conditions count as reads of both the start and the
// end event). Everything else is free, so actions that ran concurrently stay
// concurrent and an action waiting for a move moves with it. Each action
// then starts at its earliest time (longest path from the origin in this
// simple temporal network). Routes may depend on the departure time, so
// route -> reschedule is repeated until start times settle (one extra pass
// when they do not depend on time).
//
// Thread-safety: pure functions; the callback is called from the caller's thread.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "seaplan/common/status.h"
#include "seaplan/mission/types.h"
#include "seaplan/validate/plan.h"

namespace seaplan::mission {

struct RouteRequest {
  std::string action;  // PDDL action name of the move
  std::string from;    // location objects
  std::string to;
  EastNorth from_position;
  EastNorth to_position;
  double depart_s = 0.0;  // mission time of departure (scheduled)
  // Set when the move starts where the ship is, under way (a replan during
  // a move): the route must begin the way the ship is going, since a hull
  // at speed cannot turn on the spot. nullopt: the ship starts from rest.
  std::optional<ShipMotion> start_motion;
};

// Route-planning callback. Returns the route to sail; NotFound or
// FailedPrecondition mean "no safe route" (the refinement then fails with
// FailedPrecondition naming the leg); other errors are passed through.
using RoutePlanner = std::function<StatusOr<Route>(const RouteRequest&)>;

// Straight line at a constant speed (no chart): length = distance, time =
// length / speed, two waypoints, no mode (kUnspecified). speed_mps > 0.
RoutePlanner StraightLineRouter(double speed_mps);

// How moves are recognised among the plan's actions.
struct MoveRecognition {
  // Actions that are moves by name (lower case). Default: the paper's two.
  std::vector<std::string> move_actions = {"move-ship", "move-fueling-ship"};
  // Also treat any action whose arguments name two different locations with
  // known positions as a move (first location = from, last different = to).
  bool by_arguments = true;
};

struct MoveLeg {
  std::string from;
  std::string to;
};
// The leg of a step when it is a move, nullopt otherwise. A step named in
// move_actions whose arguments do not name two known locations is not a move
// (it cannot be routed); RefinePlan reports it as an error.
std::optional<MoveLeg> RecognizeMove(const validate::PlanStep& step, const LocationTable& locations,
                                     const MoveRecognition& recognition);

struct RefineOptions {
  MoveRecognition moves;
  // Separation kept between interfering events, seconds (PDDL 2.1 epsilon).
  double epsilon_s = 0.001;
  // Upper bound on route -> reschedule passes.
  int max_iterations = 10;
  // Start times "settle" when no start moves by more than this, seconds.
  double tolerance_s = 1e-6;
  // Durations of port operations by action name (lower case), overriding the
  // plan's (e.g. measured crane times). Empty: keep the plan's durations.
  std::map<std::string, double> port_operation_durations_s;
  // The ship is under way at `location` (a replan during a move): the first
  // move of the plan from there is requested with this start motion.
  struct UnderWayStart {
    std::string location;
    ShipMotion motion;
  };
  std::optional<UnderWayStart> under_way;

  Status Validate() const;
};

struct RefinedPlan {
  // Rescheduled plan, steps sorted by start time (stable), starting at the
  // input plan's earliest start.
  validate::Plan plan;
  // routes[i] is the route of plan.steps[i] when it is a move.
  std::vector<std::optional<Route>> routes;
  int iterations = 0;       // route -> reschedule passes run
  double makespan_s = 0.0;  // latest end among the steps
};

// Refines `plan` (actions of `domain_text`/`problem_text`) and validates the
// result with engine/validate against the problem with the refined
// durations: each move's distance-like static fluent (the one its
// `(= ?duration ...)` is proportional to, e.g. (distance ?from ?to)) is
// scaled so that the duration is the route's sailing time; actions whose
// duration cannot be expressed so (a constant, one leg sailed at two
// different times, a port operation with a measured duration) have their
// duration constraint lifted. Errors: InvalidArgument for an unknown action
// or bad options; FailedPrecondition when a move has no safe route ("no safe
// route for leg port-a -> port-b (move-ship, step 2): ..."), when the refined
// durations make the plan's order impossible, or when the refined plan fails
// validation ("the plan refined with route durations is not valid ...": the
// validator's first failure); such a plan must not be sent to a ship.
StatusOr<RefinedPlan> RefinePlan(std::string_view domain_text, std::string_view problem_text,
                                 const validate::Plan& plan, const LocationTable& locations,
                                 const RoutePlanner& route_planner,
                                 const RefineOptions& options = {});

// Reschedules `plan` with new durations (durations_s[i] for plan.steps[i])
// keeping the partial order described above. Returns the steps in the input
// order (not sorted). FailedPrecondition when the order cannot be kept.
StatusOr<validate::Plan> Reschedule(std::string_view domain_text, std::string_view problem_text,
                                    const validate::Plan& plan,
                                    const std::vector<double>& durations_s,
                                    double epsilon_s = 0.001);

}  // namespace seaplan::mission
