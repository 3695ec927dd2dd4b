// The seaplan temporal planner: PDDL 2.1 durative actions (with numeric
// fluents, timed initial literals, duration inequalities, conditional
// effects), required concurrency included.
//
//   seaplan::search::PlannerOptions options;
//   options.time_limit_s = 10;
//   auto stop = seaplan::StopToken::WithTimeout(std::chrono::seconds(30));
//   seaplan::search::PlanResult r = seaplan::search::Solve(domain, problem, options, stop);
//   if (r.status == PlanStatus::kSolvedSatisficing) { ... r.plan ... }
//
// How it works (POPF/OPTIC style forward search over snap actions):
//   - every durative action is a start and an end event; a state holds the
//     facts, numeric values, running actions and the next timed literal;
//   - a simple temporal network over the path's events keeps the schedule
//     consistent: interfering events are at least epsilon apart, ends lie
//     within the [min, max] duration of their start, timed literals are
//     fixed-time events; an inconsistent network prunes the successor;
//   - first plan: lazy greedy best-first search with an FF relaxed-plan
//     heuristic on the snap actions (numeric fluents as intervals) and
//     helpful actions in a second, boosted open list; ties by makespan so
//     far, and, a quarter of the steps in turn with it, a second greedy
//     search that takes ties newest first (depth first on plateaus); when
//     the first finds nothing in second_greedy_after_share of the budget,
//     a third (the second's, delaying operators that undo held goals)
//     takes its steps while it waits; a plan from the second or third is
//     followed by the first, pruned by that plan; all with a type-based
//     exploration list and LAMA's landmark count (PlannerOptions::
//     landmarks); then, in tasks with two or more agents (ships), a greedy
//     search and then weighted A* (w = 3) whose relaxed plan spreads the
//     work over them (one agent: weighted A* alone), bounded (by the first
//     plan's makespan and, together, six times the first-plan searches'
//     expansions, at least 10,000), and weighted A* (w = 3) with FF's
//     relaxed plan as well (the first searches' expansions, at least
//     20,000), whose plans replace the first when shorter; then rounds of
//     the same with other seeds (PlannerOptions::seed_rounds_share); then
//     suffix searches, the incumbent's last sixths searched again with the
//     rest kept (PlannerOptions::suffix_search_share); that is the plan
//     returned without anytime, and the one the anytime phases start from;
//   - anytime: restarting weighted A* on makespan, pruned by the incumbent,
//     until the time limit, the expansion limit or an exhausted space;
//   - every plan is scheduled at its earliest STN times, printed with
//     validate::FormatPlan, parsed back and checked by validate::ValidatePlan
//     before anyone sees it; a plan that fails is logged and dropped.
//
// Thread-safety: SolveTask/Solve are reentrant (no shared state); the
// observer callbacks run on the calling thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "seaplan/common/status.h"
#include "seaplan/common/stop_token.h"
#include "seaplan/task/ground_task.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/plan.h"

namespace seaplan::search {

enum class PlanStatus {
  kSolvedSatisficing,  // a valid plan; better ones may exist
  kSolvedOptimally,    // a valid plan of minimal makespan (proven)
  kUnsolvableProven,   // the complete search space holds no plan
  kTimeout,            // time limit, expansion limit or deadline reached before any plan
  kMemout,             // memory limit reached before any plan
  kUnsupported,        // the input uses PDDL the planner does not handle
  kCancelled,          // StopToken cancelled before any plan
  kError,              // bad options or input (message says what)
};

// "solved", "solved-optimally", "unsolvable", "timeout", "memout",
// "unsupported", "cancelled", "error".
const char* ToString(PlanStatus status);

struct PlannerOptions {
  // Wall-clock budget of the search, seconds (> 0). The StopToken may stop earlier.
  double time_limit_s = 60;
  // Effort budget: states expanded, all phases together, after which the
  // search stops as at its time limit; 0 = none. A time limit buys more
  // search on a faster machine; this buys the same everywhere: with it set
  // and neither the time limit nor `stop` reached first, the same task and
  // options give the same plan on any machine. The first-plan search then
  // switches to its second configuration after second_greedy_after_share of
  // these expansions instead of that share of the time.
  std::uint64_t max_expansions = 0;
  // CPU budget, seconds of the calling thread's CPU time from the start of
  // the search (after grounding); 0 = none. Reached, the search stops as at
  // its time limit. Under load a wall-clock limit gives the search whatever
  // share of a core it gets; this gives it the same work on a busy machine
  // as on an idle one. When set (and max_expansions is not), the first-plan
  // search switches to its second configuration after
  // second_greedy_after_share of this budget instead of the wall time.
  double cpu_time_limit_s = 0;
  // Budget for the planner's own data (states, open lists, side tables,
  // the schedule's network, counted by capacity), MB (> 0). The process
  // needs more (the task, the heuristic's tables, a table that doubles),
  // so under a cgroup memory limit the search keeps to the room it leaves
  // (src/process_memory.h) when that is less; an allocation that fails
  // (an address-space limit) is survived (SolveTask).
  std::size_t memory_limit_mb = 2048;
  // Most actions running at once; 0 = unbounded. Smaller values shrink the
  // search space but can make required-concurrency tasks unsolvable.
  int max_concurrent_actions = 0;
  // Keep improving the makespan after the first plan (until the limit).
  // Off: the plan after the first greedy search, its bounded
  // work-spreading searches and the rounds with other seeds (above); on,
  // the anytime phases start from that plan.
  bool anytime = true;
  // Tie-breaking among equally good successors; same seed, same plan.
  std::uint64_t random_seed = 1;
  // Separation of interfering events, seconds (> 0, the validator's epsilon).
  double epsilon_s = 0.001;
  // Share of time_limit_s (of max_expansions, else cpu_time_limit_s, when set; in [0, 1])
  // after which, with no plan found, the first of the two first-plan
  // searches gives way to a third configuration (the second's, with
  // operators that undo held goals delayed in its relaxed plans), in turn
  // with the second (plateaus searched newest first instead of by
  // makespan), which goes on from where it is (or starts, with no turn
  // share), half the steps each, while the first waits to go on pruned by
  // the plan they find; 0: the second alone from the start; 1 never
  // switches. A quarter, not half: the largest generated driverlog
  // instances are found only after the switch (10 of 10 against 8 of 10
  // at 20 CPU s), with the fjord missions' and the shared set's first
  // plans as often shorter as longer (bench/planner/README.md, "The switch
  // at a quarter of the budget").
  double second_greedy_after_share = 0.25;
  // Until then, the share of the search steps (in [0, 1)) the second
  // configuration takes, a step in turn with the first; 0: it waits for
  // the switch. A quarter: with an eighth, larger generated driverlog and
  // elevators instances got their first plans later, most only after the
  // switch (bench/planner/README.md, "A quarter of the steps").
  double second_greedy_turn_share = 0.25;
  // The first-plan searches also pop, in turn with their best-first lists,
  // a random state of a random (h, depth) type (type-based exploration,
  // Xie, Müller and Holte 2014; random_seed seeds it): greedy search
  // escapes plateaus where every successor of the best states is worse.
  bool type_based_exploration = true;
  // The first-plan searches also alternate LAMA's landmark count (Richter
  // and Westphal 2010): fact landmarks of the delete relaxation and
  // disjunctive ones ("some ship holds container c") with greedy-necessary
  // orderings, found once per task, counted per path, with
  // their own open lists beside the relaxed plan's (popped half as often).
  // On by default: more problems solved and shorter first plans on the
  // benchmark set, every fjord mission of bench/missions solved
  // (engine/search/README.md).
  bool landmarks = true;
  // The first-plan searches drop a successor whose image under the task's
  // interchangeable objects (objects whose names can be swapped without
  // changing the ground task: crates the goal treats alike) is that of a
  // state already expanded (engine/search/README.md, "Interchangeable
  // objects"). Not used when timed literals close deadlines.
  bool symmetry_reduction = true;
  // The searches apply the end of an action that only adds facts no
  // condition asks false and no event deletes unasked as soon as it can
  // happen, and try no other order of it (SearchParams::eager_ends;
  // engine/search/README.md, "Eager ends"); not the last anytime pass,
  // whose exhaustion proves a plan optimal. Off with
  // max_concurrent_actions, whose schedule orders every start after the
  // ends before it.
  bool eager_ends = true;
  // After the first plan and the passes that shorten it (and before any
  // anytime phases), rounds of the same with the next seeds (a greedy search from the
  // initial state, then its passes, each round bounded by its own plans,
  // not the incumbent), begun while the rounds have expanded fewer than
  // this multiple of the states expanded before them (>= 0; 0: none). The
  // greedy search's ties decide which ship takes which container, and the
  // passes seldom undo that: with 1, 29 of the shared benchmark's plans
  // without anytime got shorter and none longer, for 1.6 times the wall
  // time over the set (bench/planner/README.md, "Rounds with other
  // seeds").
  double seed_rounds_share = 1;
  // After the rounds (and before any anytime phases), suffix searches: the
  // incumbent's first 5/6, 4/6, ... 1/6 of events kept (in the order the
  // search took them, so the kept part has its own schedule) and the rest
  // searched again by weighted A* (w = 3) with the makespan-aware relaxed
  // plan, bounded by the incumbent; again from the first cut while one of
  // them found a shorter plan, on at most this multiple of the states
  // expanded before them, in all (>= 0; 0: none). A plan that leaves its
  // last jobs to one agent while the others wait (one ship carrying the
  // last containers of a fjord-fuel mission) is mended where its tail is
  // searched again; the rounds and passes, all from the initial state,
  // keep making that choice (bench/missions/README.md, "Suffix searches").
  double suffix_search_share = 1;

  absl::Status Validate() const;
};

struct SearchStatistics {
  std::size_t expanded = 0, generated = 0, evaluated = 0;
  double search_time_s = 0, first_plan_time_s = -1, best_plan_time_s = -1;
  std::size_t peak_memory_mb = 0;
  int plans_found = 0;
  // Landmark generation (PlannerOptions::landmarks), once per task.
  int landmarks = 0, landmark_orderings = 0;
  double landmark_time_s = 0;
  // Interchangeable objects (PlannerOptions::symmetry_reduction): objects in
  // classes of two or more, the classes, and the successors dropped because
  // a symmetric state had been expanded.
  int symmetric_objects = 0, symmetry_classes = 0;
  std::size_t symmetric_drops = 0;
  // States whose only successor was an eager end (PlannerOptions::eager_ends).
  std::size_t eager_ends = 0;
  // Times a first-plan search began again with the next seed: with timed
  // literals that close deadlines, after 5,000 of its steps, then twice as
  // many each time.
  int first_plan_restarts = 0;
  // Rounds with other seeds begun (PlannerOptions::seed_rounds_share), and
  // the plans they found shorter than the incumbent.
  int seed_rounds = 0, seed_round_plans = 0;
  // Suffix searches run (PlannerOptions::suffix_search_share), and the
  // plans they found shorter than the incumbent.
  int suffix_searches = 0, suffix_plans = 0;
};

struct PlanResult {
  PlanStatus status = PlanStatus::kError;
  validate::Plan plan;  // empty unless solved
  double makespan_s = 0;
  std::optional<double> metric_value;  // the task's metric on the plan, when defined
  SearchStatistics stats;
  // Solve only: parse and per-stage grounding times and the task's size.
  task::GroundingStats grounding;
  std::string message;  // one line: what happened (error text for kError/kUnsupported)
};

// Called for every strictly better VALIDATED plan as soon as it is found
// (anytime), and for progress about every 0.5 s. Either may be empty.
struct PlanObserver {
  std::function<void(const PlanResult&)> on_plan;
  std::function<void(const SearchStatistics&)> on_progress;
};

// Plans for a ground task. Polls `stop` (deadline, cancellation) at least
// every millisecond of work; the result keeps the best plan found so far
// (status kSolvedSatisficing) when stopped after a plan, also when an
// allocation fails (std::bad_alloc, an address-space limit such as
// `ulimit -v`: the message says memory ran out; kMemout before a plan).
PlanResult SolveTask(const task::GroundTask& task, const PlannerOptions& options,
                     const StopToken& stop, const PlanObserver* observer = nullptr);

// A child of `stop` that also stops once options.time_limit_s has passed
// from now: what Solve grounds under, for callers that ground themselves
// before SolveTask (a huge task must not ground for minutes under a 1 s limit).
StopToken WithinTimeLimit(const PlannerOptions& options, const StopToken& stop);

// The result of a load that ended without a task for a reason other than
// its input (callers that ground themselves, as Solve does): kMemout when an
// allocation failed, kTimeout or kCancelled when `stop` ended grounding
// (grounding statistics kept); nullopt when the load finished, well or
// with diagnostics.
std::optional<PlanResult> UnfinishedLoadResult(const task::LoadResult& loaded);

// Parses and grounds (task::LoadTask), then SolveTask. Parse or grounding
// errors give kError, unsupported PDDL gives kUnsupported, with the
// diagnostics in `message`. options.time_limit_s and `stop` bound grounding
// too: stopped while grounding gives kTimeout (or kCancelled).
PlanResult Solve(std::string_view domain_text, std::string_view problem_text,
                 const PlannerOptions& options, const StopToken& stop,
                 const PlanObserver* observer = nullptr);

}  // namespace seaplan::search
