// engine/search as the mission's temporal planner (the TemporalPlanner
// callback of mission_planner.h).
//
// A replan is on the mission loop's critical path: the ship waits for it.
// Anytime search would use its whole time limit on problems it cannot prove
// optimal, so a replan with anytime search asks for the first plan, then
// runs a short improvement search (twice the first search's time, between
// kReplanImproveMinS and kReplanImproveMaxS, within the time limit) and
// keeps the better of the two; under an expansion limit
// (PlannerOptions::max_expansions) the improvement search gets twice the
// first search's expansions instead (at most the limit; the time limit
// stays), so that a replan does not depend on the machine's speed either.
// The first plan of a mission uses the options as given.
#pragma once

#include "seaplan/common/wall_clock.h"
#include "seaplan/mission/mission_planner.h"
#include "seaplan/search/planner.h"

namespace seaplan::mission {

// Stretched in slower builds (wall_clock.h) so that their replans search as much.
inline constexpr double kReplanImproveMinS = 0.01 * kWallClockScale;
inline constexpr double kReplanImproveMaxS = 0.04 * kWallClockScale;

enum class PlanningPhase { kInitial, kReplan };

// The planner's kError (bad input) is InvalidArgument with its message; the
// other statuses are results (PlannerOutcome::solved, status,
// quality: kOptimal for search's SOLVED_OPTIMALLY).
TemporalPlanner SearchPlanner(const search::PlannerOptions& options, PlanningPhase phase);

}  // namespace seaplan::mission
