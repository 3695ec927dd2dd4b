// Post-processing of a found plan: greedy action elimination (Fink and Yang
// 1992; Nakhost and Müller 2010, "plan neighbourhood graph search" keeps it
// as its first step).
//
// Greedy searches, above all the second first-plan search (plateaus newest
// first), return plans with detours: a ship sailing A -> B -> A, a container
// loaded and unloaded again. For each step in plan order the plan without
// it is replayed through Transitions::Apply from the state before it; a
// later start that no longer applies is dropped with its end (the rest of a
// detour goes with its first step), and the removal is kept when no end or
// timed literal fails and the replay ends in a goal state. The caller
// schedules and validates the result and keeps it only if valid and not
// longer.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "snap_task.h"
#include "state_registry.h"
#include "timeline.h"
#include "transitions.h"

namespace seaplan::search {

// The events of `events` (a plan from `initial`: every event applies in turn
// and the last state is a goal) without the steps no goal needs, in the same
// order, duration bounds as the replay set them; `events` itself when nothing
// can go. `max_replayed` bounds the work (events replayed over all tries):
// the steps not tried by then stay.
std::vector<Event> EliminateRedundantSteps(const Transitions& transitions, const StateData& initial,
                                           std::span<const Event> events,
                                           std::size_t max_replayed = 4'000'000);

}  // namespace seaplan::search
