// Post-processing of a found plan: lift the totally ordered schedule to a
// partial order and reschedule it at the earliest times that order allows.
//
// The search's schedule orders events by what its path did; the validator
// needs less. Kept orderings, each between events in their schedule order:
//   - epsilon between events that interfere under the validator's mutex rule
//     (one adds what the other deletes, changes what the other reads, or
//     assigns/scales a variable the other updates);
//   - zero between events that touch the same fact or variable without
//     interfering (two adds, two increases, a write and an invariant), so
//     every fact's and variable's sequence of values, and what every
//     condition and invariant sees, stays as validated, while such events may
//     now share a happening;
//   - the exact found duration between a step's start and end;
//   - timed literals fixed at their times;
//   - with `bound_concurrency` (PlannerOptions::max_concurrent_actions), as
//     in Timeline: every start epsilon after every end scheduled before it.
// Unrelated events get no ordering at all, so independent actions that the
// search sequenced run in parallel. The earliest solution of that network
// (longest paths from time zero, Bellman-Ford through Stn) is the new
// schedule. The caller validates it and keeps it only if valid and not longer.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "snap_task.h"
#include "timeline.h"

namespace seaplan::search {

// Pairs of events looked at over a whole plan (each event with those that
// share a fact or a variable with it, counted once per shared fact, and
// with `bound_concurrency` every start with the ends before it), beyond
// which lifting gives up: about a second. So with the bound, plans of more
// than about 6,000 durative actions are always left as found.
inline constexpr std::size_t kMaxLiftPairs = 20'000'000;

// `times[i]` is the scheduled time of `events[i]` (a valid schedule).
// Returns the rescheduled times (same indexing), or nullopt when the network
// is inconsistent (it cannot be for a valid input) or the plan needs more
// than `max_pairs` pairs looked at; the caller then keeps `times`.
std::optional<std::vector<double>> LiftAndReschedule(
    const SnapTask& task, std::span<const Event> events, std::span<const double> times,
    double epsilon_s, bool bound_concurrency = false, std::size_t max_pairs = kMaxLiftPairs);

}  // namespace seaplan::search
