#include "seaplan/search/planner.h"

#include <algorithm>
#include <cassert>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <memory>
#include <new>
#include <optional>

#include "absl/strings/str_cat.h"
#include "goal_order.h"
#include "heuristics/landmarks.h"
#include "heuristics/relaxed_plan_heuristic.h"
#include "heuristics/temporal_reachability.h"
#include "mutex_groups.h"
#include "object_symmetry.h"
#include "plan_builder.h"
#include "plan_elimination.h"
#include "process_memory.h"
#include "seaplan/common/log.h"
#include "seaplan/task/grounder.h"
#include "search_engine.h"
#include "snap_task.h"
#include "state_registry.h"
#include "timeline.h"
#include "transitions.h"

namespace seaplan::search {

const char* ToString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kSolvedSatisficing:
      return "solved";
    case PlanStatus::kSolvedOptimally:
      return "solved-optimally";
    case PlanStatus::kUnsolvableProven:
      return "unsolvable";
    case PlanStatus::kTimeout:
      return "timeout";
    case PlanStatus::kMemout:
      return "memout";
    case PlanStatus::kUnsupported:
      return "unsupported";
    case PlanStatus::kCancelled:
      return "cancelled";
    case PlanStatus::kError:
      return "error";
  }
  return "unknown";
}

absl::Status PlannerOptions::Validate() const {
  if (!(time_limit_s > 0) || !std::isfinite(time_limit_s)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "time_limit_s must be a positive finite number of seconds, got ", time_limit_s));
  }
  if (memory_limit_mb == 0) return absl::InvalidArgumentError("memory_limit_mb must be > 0");
  if (!(cpu_time_limit_s >= 0) || !std::isfinite(cpu_time_limit_s)) {
    return absl::InvalidArgumentError(
        absl::StrCat("cpu_time_limit_s must be a finite number of seconds >= 0 (0 = none), got ",
                     cpu_time_limit_s));
  }
  if (max_concurrent_actions < 0) {
    return absl::InvalidArgumentError(absl::StrCat(
        "max_concurrent_actions must be >= 0 (0 = unbounded), got ", max_concurrent_actions));
  }
  if (!(second_greedy_after_share >= 0) || !(second_greedy_after_share <= 1)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "second_greedy_after_share must be in [0, 1], got ", second_greedy_after_share));
  }
  if (!(second_greedy_turn_share >= 0) || !(second_greedy_turn_share < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("second_greedy_turn_share must be in [0, 1), got ", second_greedy_turn_share));
  }
  if (!(seed_rounds_share >= 0) || !std::isfinite(seed_rounds_share)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "seed_rounds_share must be a finite number >= 0 (0 = no rounds), got ", seed_rounds_share));
  }
  if (!(suffix_search_share >= 0) || !std::isfinite(suffix_search_share)) {
    return absl::InvalidArgumentError(absl::StrCat(
        "suffix_search_share must be a finite number >= 0 (0 = no suffix searches), got ",
        suffix_search_share));
  }
  if (!(epsilon_s > 0) || !(epsilon_s < 1)) {
    return absl::InvalidArgumentError(
        absl::StrCat("epsilon_s must be in (0, 1) seconds, got ", epsilon_s));
  }
  return absl::OkStatus();
}

namespace {

using Clock = std::chrono::steady_clock;

double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double Seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

SearchCounters Sum(const SearchCounters& a, const SearchCounters& b) {
  return {a.expanded + b.expanded, a.generated + b.generated, a.evaluated + b.evaluated,
          a.symmetric_drops + b.symmetric_drops, a.eager_ends + b.eager_ends};
}

void SetCounters(const SearchCounters& counters, SearchStatistics& stats) {
  stats.expanded = counters.expanded;
  stats.generated = counters.generated;
  stats.evaluated = counters.evaluated;
  stats.symmetric_drops = counters.symmetric_drops;
  stats.eager_ends = counters.eager_ends;
}

// Drives the phases (greedy first plan, then weighted A* with a bound) and
// owns the per-call components. One instance per SolveTask call.
class PlannerRun {
 public:
  PlannerRun(const task::GroundTask& task, const PlannerOptions& options, const StopToken& stop,
             const PlanObserver* observer)
      : task_(task),
        options_(options),
        stop_(stop.Child(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(options.time_limit_s)))),
        observer_(observer),
        snap_(task),
        registry_(snap_.num_facts(), snap_.num_vars()),
        heuristic_(snap_, options.epsilon_s),
        reachability_(snap_),
        transitions_(snap_, options.max_concurrent_actions, options.epsilon_s),
        timeline_(snap_, options.epsilon_s, options.max_concurrent_actions > 0),
        plan_timeline_(snap_, options.epsilon_s, options.max_concurrent_actions > 0),
        validator_(task, options.epsilon_s),
        initial_(InitialState()) {}

  PlanResult Run();
  // "memory limit (N MB) reached", or that all the process's planning runs
  // reached the room its cgroup leaves them.
  std::string MemoryLimitText() const;
  // After a std::bad_alloc left Run: the plan found so far (status
  // kSolvedSatisficing) or kMemout, the counters of the last poll. Reads
  // best_ (Offer moves a finished plan into it, so it is whole at any
  // allocation), the flags and the counters, never the searches.
  PlanResult AfterAllocationFailure();
  // The same without allocating (no message): when that failed too.
  PlanResult TakeBest();

 private:
  // The result: best_ (moved out), counters and time set.
  PlanResult Finish(const SearchCounters& counters, PlanStatus status_if_no_plan,
                    std::string message);
  enum class Outcome { kContinue, kStop, kMemout };
  // Polls stop/expansion limit/memory/progress for the searches running
  // now; called once per search step.
  Outcome Poll();
  // Counters so far: finished searches and those running now.
  SearchCounters TotalCounters() const;
  std::size_t Expanded() const { return TotalCounters().expanded; }
  // A search ends: its counters join done_counters_ (Start began it).
  void AddCounters(const LazySearch& search);
  // Builds and validates; true when it is shorter than the round's plans
  // (round_), and then the incumbent too when shorter than it.
  bool Offer(const LazySearch& search);
  // The task's initial state (built once, for initial_).
  StateData InitialState() const;
  // After the first plan: bounded searches with the makespan-aware relaxed
  // plan (agents' work spread, relaxed_plan_heuristic.h); with fewer than
  // two agents, weighted A* alone with FF's. Their budgets are multiples of
  // `first_expanded`, the first-plan searches' expansions together.
  // `quick`: the budgets of a round with another seed (smaller, no pass
  // with FF's relaxed plan). True when Poll stopped it.
  bool ShortenFirstPlan(std::size_t first_expanded, bool quick);
  // After ShortenFirstPlan, with or without anytime phases: rounds of the
  // same with other seeds (a greedy first search, then its passes, each
  // round bounded by its own plans), begun while their expansions stay
  // within `budget`. True when Poll stopped it.
  bool ShortenWithOtherSeeds(std::size_t budget);
  // After the rounds: the incumbent's first cut/6 events kept, for cut =
  // 5 down to 1, and the rest searched again by weighted A* (w = 3) with
  // the makespan-aware relaxed plan, bounded by the incumbent, each on a
  // fifth of `budget`; again while one of them found a shorter plan and
  // the budget lasts, or until Poll stops it.
  void ShortenSuffixes(std::size_t budget);
  static constexpr std::size_t kSuffixCuts = 5;
  static constexpr double kSuffixWeight = 3;
  // The first-plan searches' greedy search (with its exploration lists and
  // pruning), unbounded.
  SearchParams GreedyParams(std::uint64_t seed, bool eager_ends) const;
  // A search pruned by the round's plan (round_; weight < 0: greedy, else
  // weighted A* with that plan's seconds per event as the heuristic's unit).
  SearchParams BoundedParams(double weight) const;
  // PlannerOptions::eager_ends, unless the schedule bounds concurrency.
  bool EagerEnds() const { return options_.eager_ends && options_.max_concurrent_actions == 0; }
  // Stop token, timed-literal reachability and the initial state; the
  // search counts as running (Poll, TotalCounters) until AddCounters.
  void Start(LazySearch& search);
  // Steps a search pruned by the incumbent until it is exhausted or has
  // expanded more than `max_expanded`. A plan found is offered; unless
  // `stop_at_plan`, the search goes on under the tightened bound. True when
  // Poll stopped it (time, limits, memory, cancellation).
  bool RunBounded(LazySearch& search, std::size_t max_expanded, bool stop_at_plan);

  const task::GroundTask& task_;
  PlannerOptions options_;
  StopToken stop_;
  const PlanObserver* observer_;
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_progress_ = Clock::now();
  const double cpu_start_s_ = ThreadCpuSeconds();
  SnapTask snap_;
  StateRegistry registry_;
  RelaxedPlanHeuristic heuristic_;
  std::optional<LandmarkGraph> landmarks_;       // PlannerOptions::landmarks
  std::optional<ObjectSymmetry> symmetry_;       // PlannerOptions::symmetry_reduction
  std::optional<GoalOrderDeadEnds> goal_order_;  // null when no pair of goals can order
  TemporalReachability reachability_;
  Transitions transitions_;
  Timeline timeline_;
  Timeline plan_timeline_;
  PlanValidator validator_;
  const StateData initial_;
  PlanResult best_;
  // A plan's makespan and events, as the bound of the searches after it.
  struct PlanBound {
    bool found = false;
    double makespan_s = 0;
    std::size_t events = 0;  // of the search's path (BoundedParams' scale)
    // The events in the order the search took them, without redundant
    // steps when Offer dropped them: what a suffix search keeps the first
    // part of.
    std::vector<Event> path;
    // `makespan_s` is shorter than this plan's by more than half the
    // separation of events (every makespan when none is found).
    bool ShorterBy(double makespan, double epsilon_s) const {
      return !found || makespan < makespan_s - epsilon_s / 2;
    }
  };
  PlanBound incumbent_;  // best_'s (found: best_ holds a plan)
  bool has_plan() const { return incumbent_.found; }
  // The shortest plan of this round of searches (Offer), which bounds them:
  // the first plan and the passes that shorten it, or a round begun again
  // with another seed (ShortenWithOtherSeeds). The incumbent outside those
  // rounds.
  PlanBound round_;
  std::uint64_t round_seed_ = options_.random_seed;
  SearchCounters done_counters_;            // of finished searches
  SearchCounters polled_counters_;          // of all searches, at the last memory poll
  std::vector<const LazySearch*> running_;  // started, not yet in done_counters_
  // The second first-plan search's own states and schedule (Run): searches
  // in turn on one timeline would each find the other's path built where
  // they left theirs. Freed when the first plan is found.
  std::optional<StateRegistry> second_registry_;
  std::optional<Timeline> second_timeline_;
  // The schedule of the search that takes the first's place at the switch,
  // while the first waits on timeline_ (Run). Freed with the second's.
  std::optional<Timeline> third_timeline_;
  std::size_t steps_ = 0;
  bool expansion_limit_reached_ = false;
  bool memory_limit_reached_ = false;
  // This run's line in the count of all the process's planning runs, and
  // the room the cgroup leaves them all (0: no cgroup limit); see
  // process_memory.h.
  PlanningMemoryLedger::Entry memory_entry_{PlanningMemoryLedger::OfProcess()};
  std::size_t room_for_all_mb_ = 0;
  bool cpu_limit_reached_ = false;
  // The search's CPU time so far (cpu_time_limit_s), and its last reading in
  // Poll.
  double CpuSeconds() const { return ThreadCpuSeconds() - cpu_start_s_; }
  double cpu_seconds_ = 0;
};

StateData PlannerRun::InitialState() const {
  StateData s = registry_.MakeEmpty();
  for (auto f : task_.initial_facts) s.Set(f);
  for (std::size_t v = 0; v < s.values.size() && v < task_.initial_values.size(); ++v) {
    s.values[v] = task_.initial_values[v];
  }
  return s;
}

SearchCounters PlannerRun::TotalCounters() const {
  SearchCounters total = done_counters_;
  for (const LazySearch* search : running_) total = Sum(total, search->counters());
  return total;
}

void PlannerRun::AddCounters(const LazySearch& search) {
  done_counters_ = Sum(done_counters_, search.counters());
  std::erase(running_, &search);
}

PlannerRun::Outcome PlannerRun::Poll() {
  ++steps_;
  // Once reached, a limit stops every later phase at its first poll.
  if (cpu_limit_reached_ || stop_.StopRequested()) return Outcome::kStop;
  if (options_.max_expansions > 0 && Expanded() >= options_.max_expansions) {
    expansion_limit_reached_ = true;
    return Outcome::kStop;
  }
  // A clock read costs about as much as a cheap expansion: every 256 steps,
  // and the phase switch reads the same figure.
  if (options_.cpu_time_limit_s > 0 && (steps_ & 255) == 0) {
    cpu_seconds_ = CpuSeconds();
    if (cpu_seconds_ >= options_.cpu_time_limit_s) {
      cpu_limit_reached_ = true;
      return Outcome::kStop;
    }
  }
  if ((steps_ & 15) == 0) {
    std::size_t bytes =
        registry_.MemoryBytes() + timeline_.MemoryBytes() + plan_timeline_.MemoryBytes();
    for (const LazySearch* search : running_) bytes += search->MemoryBytes();
    if (second_registry_) bytes += second_registry_->MemoryBytes();
    if (second_timeline_) bytes += second_timeline_->MemoryBytes();
    if (third_timeline_) bytes += third_timeline_->MemoryBytes();
    polled_counters_ = TotalCounters();
    const std::size_t mb = bytes >> 20;
    best_.stats.peak_memory_mb = std::max(best_.stats.peak_memory_mb, mb);
    const std::size_t all_runs_mb = memory_entry_.Update(bytes) >> 20;
    if (mb >= options_.memory_limit_mb ||
        (room_for_all_mb_ > 0 && all_runs_mb >= room_for_all_mb_)) {
      memory_limit_reached_ = true;
      return Outcome::kMemout;
    }
    if (observer_ && observer_->on_progress &&
        std::chrono::duration<double>(Clock::now() - last_progress_).count() >= 0.5) {
      last_progress_ = Clock::now();
      SearchStatistics stats = best_.stats;
      SetCounters(TotalCounters(), stats);
      stats.search_time_s = Seconds(start_);
      observer_->on_progress(stats);
    }
  }
  return Outcome::kContinue;
}

bool PlannerRun::Offer(const LazySearch& search) {
  std::string error;
  auto built = BuildValidatedPlan(snap_, search.plan(), plan_timeline_, validator_, &error);
  if (!built) {
    log::Error("planner: dropping a plan that fails validation (planner bug): {}", error);
    return false;
  }
  // Without the steps no goal needs (plan_elimination.h), kept when it
  // validates and is not longer.
  const Clock::time_point eliminate_start = Clock::now();
  const std::vector<Event> needed = EliminateRedundantSteps(transitions_, initial_, search.plan());
  const std::vector<Event>* events_used = &search.plan();
  log::Debug("planner: redundant steps looked for in {:.3f} s", Seconds(eliminate_start));
  if (needed.size() < search.plan().size()) {
    std::string needed_error;
    auto shorter = BuildValidatedPlan(snap_, needed, plan_timeline_, validator_, &needed_error);
    if (!shorter) {
      log::Debug("planner: plan without redundant steps rejected: {}", needed_error);
    } else if (shorter->makespan_s <= built->makespan_s) {
      events_used = &needed;
      log::Debug("planner: {} of {} events redundant, makespan {} -> {}",
                 search.plan().size() - needed.size(), search.plan().size(), built->makespan_s,
                 shorter->makespan_s);
      built = std::move(shorter);
    }
  }
  if (!round_.ShorterBy(built->makespan_s, options_.epsilon_s)) return false;
  round_ = {true, built->makespan_s, search.plan().size(), *events_used};
  // Shorter than this round's plans, not than the incumbent: the round goes
  // on under its own bound.
  if (!incumbent_.ShorterBy(built->makespan_s, options_.epsilon_s)) return true;
  const double now = Seconds(start_);
  incumbent_ = round_;
  best_.status = PlanStatus::kSolvedSatisficing;
  best_.plan = std::move(built->plan);
  best_.makespan_s = built->makespan_s;
  best_.metric_value = built->metric_value;
  best_.stats.plans_found++;
  if (best_.stats.first_plan_time_s < 0) best_.stats.first_plan_time_s = now;
  best_.stats.best_plan_time_s = now;
  if (observer_ && observer_->on_plan) {
    PlanResult copy = best_;
    SetCounters(TotalCounters(), copy.stats);
    copy.stats.search_time_s = now;
    copy.message = absl::StrCat("plan ", best_.stats.plans_found, ", makespan ", best_.makespan_s);
    observer_->on_plan(copy);
  }
  return true;
}

SearchParams PlannerRun::GreedyParams(std::uint64_t seed, bool eager_ends) const {
  SearchParams params;
  params.weight = -1;
  params.epsilon_s = options_.epsilon_s;
  params.seed = seed;
  params.type_based_exploration = options_.type_based_exploration;
  if (landmarks_) params.landmarks = &*landmarks_;
  if (symmetry_) params.symmetry = &*symmetry_;
  if (goal_order_) params.goal_order = &*goal_order_;
  params.eager_ends = eager_ends;
  return params;
}

SearchParams PlannerRun::BoundedParams(double weight) const {
  SearchParams params;
  params.weight = weight;
  params.scale_s = round_.makespan_s / std::max<double>(1.0, static_cast<double>(round_.events));
  params.bound_s = round_.makespan_s;
  params.epsilon_s = options_.epsilon_s;
  params.seed = round_seed_;
  // No symmetry reduction here: these searches look for a shorter makespan,
  // and a symmetric state is dropped on its makespan bound alone, not its
  // schedule (fjord 3x12x12 seed 1 returned 15,073.8 s with it, 12,988.7 s
  // without).
  params.eager_ends = EagerEnds();
  if (goal_order_) params.goal_order = &*goal_order_;
  return params;
}

void PlannerRun::Start(LazySearch& search) {
  search.SetStopToken(&stop_);
  search.SetTemporalReachability(&reachability_);
  search.Initialize(initial_);
  running_.push_back(&search);
}

bool PlannerRun::RunBounded(LazySearch& search, std::size_t max_expanded, bool stop_at_plan) {
  while (search.counters().expanded <= max_expanded) {
    if (Poll() != Outcome::kContinue) return true;
    const LazySearch::Status status = search.Step();
    if (status == LazySearch::Status::kSolved) {
      const bool improved = Offer(search);
      if (stop_at_plan) break;
      if (improved) search.SetBound(round_.makespan_s);
      continue;
    }
    if (status == LazySearch::Status::kExhausted) break;
  }
  return false;
}

bool PlannerRun::ShortenFirstPlan(std::size_t first_expanded, bool quick) {
  heuristic_.SetMakespanAware(true);
  if (!round_.found) return false;
  // With fewer than two agents there is no work to spread, but the greedy
  // plan's detours are there all the same (satellite-time p01: a turn to a
  // target before the turn to calibrate): weighted A* alone, with FF's
  // relaxed plan.
  const bool spread = heuristic_.makespan_aware();
  // Pruned by the round's plan and given, in all, at most six times the
  // first search's expansions (with twice, both passes were cut short on
  // generated fjord missions), with or without anytime phases (with twice
  // before them, a minute of anytime search returned longer plans than
  // `--no-anytime` on 8 of 20 fjord 4x16x16 missions; with six times it
  // starts from that plan, and its plan after 1 s on the shared benchmark
  // was as good), twice when `quick` (in a round with another seed more
  // rounds found shorter plans than longer passes did: fjord-fuel 3x12x12
  // seed 3, 10,353 s against 11,123 s for the same share, and seed 5 no
  // worse): the first plan stays the fallback, so
  // neither coverage nor the first plan's makespan can get worse, and the
  // cost is bounded where spreading misleads the search (floortile,
  // depots). A greedy pass (large missions: another ship assignment; it
  // stops at its plan: going on under that plan's bound spent case C
  // numeric's whole budget without a shorter one), then, with what is left,
  // weighted A* (w = 3) on makespan (small ones: the greedy search's
  // detours), which goes on until the budget is spent or its space
  // exhausted.
  //
  // With the landmark count (PlannerOptions::landmarks), a third pass: a
  // greedy search that also counts landmarks, on a budget of its own (twice
  // the first search's expansions, with or without anytime phases: with
  // once, the anytime run kept 41,516 s on seed 4 below). Where the
  // relaxed plan's length is flat (a container delivered by whichever ship)
  // the count is what let the first search reach a goal, and the passes
  // without it often find no other assignment (fjord 3x12x12 seed 4: 41,516
  // s kept; with this pass 31,185 s). Last, so that the passes before it run
  // as they do without it (the registry's state ids, which break ties, and
  // their bound): placed first, its plan's bound sent them elsewhere (seed
  // 2: 19,712 s returned instead of 15,752 s).
  const std::size_t budget_factor = quick ? 2 : 6;
  // With one agent, once the first search's expansions: the pass costs
  // more per state where schedules branch (matchcellar p05: 3.5 s more with
  // six times, for no shorter plan).
  // At least kMinExpansions (unless `quick`, ten times as many: a
  // first plan found after a few hundred expansions left the pass too
  // little to take a greedy plan's detours out; case C numeric returned
  // 4,610 s where 10,000 expansions reach 3,419 s).
  constexpr std::size_t kMinExpansions = 1000;
  const std::size_t min_expansions = quick ? kMinExpansions : 10 * kMinExpansions;
  std::size_t left =
      std::max<std::size_t>(min_expansions, (spread ? budget_factor : 1) * first_expanded);
  std::size_t landmark_left = std::max<std::size_t>(kMinExpansions, 2 * first_expanded);
  // Unless `quick`, a fourth pass: weighted A* (w = 3) with FF's
  // relaxed plan, like the anytime phases' first search, on a budget of its
  // own (the first search's expansions, at least 20,000). Which estimate
  // leads to the shorter plan depends on the mission: on some the
  // makespan-aware passes keep a plan whose ships relay containers, and
  // FF's finds a shorter one within that budget (fjord-fuel 4x16x16 seed 2:
  // 22,847 s returned without this pass, 16,122 s with it; fjord 3x12x12
  // seed 2: 13,067 s, 12,204 s). Last, so the passes before it run as they
  // did.
  std::size_t ff_left =
      quick || !spread ? 0 : std::max<std::size_t>(2 * min_expansions, first_expanded);
  struct Pass {
    double weight;
    bool landmarks;
    bool makespan_aware;
  };
  for (const Pass pass : {Pass{-1.0, false, true}, Pass{3.0, false, true}, Pass{-1.0, true, true},
                          Pass{3.0, false, false}}) {
    if (pass.landmarks && !landmarks_) continue;
    if (!spread && pass.weight < 0) continue;
    std::size_t& budget = !pass.makespan_aware ? ff_left : pass.landmarks ? landmark_left : left;
    if (budget == 0) continue;
    heuristic_.SetMakespanAware(pass.makespan_aware);
    SearchParams params = BoundedParams(pass.weight);
    if (pass.landmarks) params.landmarks = &*landmarks_;
    LazySearch search(snap_, registry_, heuristic_, transitions_, timeline_, params);
    Start(search);
    // The greedy passes stop at their plan; weighted A* goes on under the
    // new bound, as the anytime phases do (case C numeric: 6,594 s returned
    // when it stopped at its first plan, 5,703 s now).
    const bool stop = RunBounded(search, budget, pass.weight < 0);
    AddCounters(search);
    budget -= std::min(budget, search.counters().expanded);
    if (stop) return true;
  }
  return false;
}

bool PlannerRun::ShortenWithOtherSeeds(std::size_t budget) {
  const std::size_t start_expanded = Expanded();
  const int plans_before = best_.stats.plans_found;
  bool stopped = false;
  for (std::uint64_t round = 1; !stopped && Expanded() - start_expanded < budget; ++round) {
    ++best_.stats.seed_rounds;
    round_ = {};
    round_seed_ = options_.random_seed + round;
    heuristic_.SetMakespanAware(false);
    LazySearch search(snap_, registry_, heuristic_, transitions_, timeline_,
                      GreedyParams(round_seed_, EagerEnds()));
    Start(search);
    const std::size_t left = budget - (Expanded() - start_expanded);
    stopped = RunBounded(search, left, true);
    const std::size_t first_expanded = search.counters().expanded;
    AddCounters(search);
    if (!stopped && round_.found) stopped = ShortenFirstPlan(first_expanded, true);
  }
  round_ = incumbent_;
  round_seed_ = options_.random_seed;
  best_.stats.seed_round_plans += best_.stats.plans_found - plans_before;
  return stopped;
}

void PlannerRun::ShortenSuffixes(std::size_t budget) {
  if (!round_.found || budget == 0) return;
  heuristic_.SetMakespanAware(true);
  // The kept part is a prefix in the search's order, so the searches need
  // nothing but their start (SearchParams::prefix): its schedule is built
  // as any path's. The shortest suffixes first: their spaces are the
  // smallest, and on generated fjord-fuel missions the last one often
  // holds the mistake (one ship carrying the last containers one after
  // another while the others wait), where the greedy searches and the
  // rounds, all from the initial state, keep making it. Weighted A* on
  // makespan, not greedy: it compares the ways the other ships could take
  // over. Five cuts: nine on about the same budget (a ninth each) gave
  // shorter plans on two of ten fjord-fuel 3x12x12 missions and longer
  // ones on two others, and fewer searches each get more states.
  const std::size_t per_search = std::max<std::size_t>(1, budget / kSuffixCuts);
  const std::size_t start_expanded = Expanded();
  for (bool improved = true; improved;) {
    improved = false;
    for (std::size_t cut = kSuffixCuts; cut >= 1; --cut) {
      const std::size_t spent = Expanded() - start_expanded;
      if (spent >= budget) return;
      const std::size_t kept = round_.path.size() * cut / (kSuffixCuts + 1);
      // A copy: Offer replaces round_.path while the search runs.
      const std::vector<Event> prefix(round_.path.begin(),
                                      round_.path.begin() + static_cast<std::ptrdiff_t>(kept));
      SearchParams params = BoundedParams(kSuffixWeight);
      params.prefix = prefix;
      LazySearch search(snap_, registry_, heuristic_, transitions_, timeline_, params);
      Start(search);
      ++best_.stats.suffix_searches;
      const int plans_before = best_.stats.plans_found;
      const bool stop = RunBounded(search, std::min(per_search, budget - spent), false);
      AddCounters(search);
      // round_ is the incumbent here: its plans are the incumbent's.
      const int found = best_.stats.plans_found - plans_before;
      best_.stats.suffix_plans += found;
      if (stop) return;
      improved = improved || found > 0;
    }
  }
}

PlanResult PlannerRun::Finish(const SearchCounters& counters, PlanStatus status_if_no_plan,
                              std::string message) {
  SetCounters(counters, best_.stats);
  best_.stats.search_time_s = Seconds(start_);
  if (!has_plan()) {
    best_.status = status_if_no_plan;
    best_.message = std::move(message);
  } else if (best_.message.empty()) {
    best_.message =
        absl::StrCat(best_.stats.plans_found, " plan(s), best makespan ", best_.makespan_s);
    if (memory_limit_reached_) absl::StrAppend(&best_.message, "; ", MemoryLimitText());
  }
  return std::move(best_);
}

PlanResult PlannerRun::AfterAllocationFailure() {
  // Run's searches went with its frame; running_ points at them.
  running_.clear();
  second_registry_.reset();
  second_timeline_.reset();
  const SearchCounters& counters =
      polled_counters_.expanded > done_counters_.expanded ? polled_counters_ : done_counters_;
  if (has_plan()) {
    best_.message =
        absl::StrCat("memory ran out (an allocation failed) after ", best_.stats.plans_found,
                     " plan(s); best makespan ", best_.makespan_s);
  }
  return Finish(counters, PlanStatus::kMemout,
                "memory ran out (an allocation failed) before a plan was found");
}

std::string PlannerRun::MemoryLimitText() const {
  if (room_for_all_mb_ > 0 && (memory_entry_.bytes() >> 20) < options_.memory_limit_mb) {
    return absl::StrCat("memory limit reached (the planning runs at once reached the ",
                        room_for_all_mb_, " MB the process's cgroup leaves them)");
  }
  return absl::StrCat("memory limit (", options_.memory_limit_mb, " MB) reached");
}

PlanResult PlannerRun::TakeBest() {
  best_.message.clear();
  if (!has_plan()) best_.status = PlanStatus::kMemout;
  return std::move(best_);
}

PlanResult PlannerRun::Run() {
  best_.status = PlanStatus::kTimeout;
  // Past a cgroup memory limit the kernel kills the process, plan and all
  // (process_memory.h): the memory limit stays under the room it leaves.
  // Other planning runs of the process share that room.
  if (const auto room = ProcessMemoryHeadroom()) {
    room_for_all_mb_ = std::max<std::size_t>(
        1, PlanningMemoryLedger::RoomForAllMb(
               room->mb, PlanningMemoryLedger::OfProcess().total_bytes() - memory_entry_.bytes()));
    if (room->mb < options_.memory_limit_mb) {
      log::Info("planner: memory limit {} MB instead of {} MB: the process's {} leaves no more",
                std::max<std::size_t>(room->mb, 1), options_.memory_limit_mb, room->limit);
      options_.memory_limit_mb = std::max<std::size_t>(room->mb, 1);
    }
  }
  auto finish = [&](PlanStatus status_if_no_plan, std::string message) {
    return Finish(done_counters_, status_if_no_plan, std::move(message));
  };
  auto stopped_status = [&]() {
    return stop_.Reason() == StopReason::kCancelled ? PlanStatus::kCancelled : PlanStatus::kTimeout;
  };

  if (snap_.num_goal_breaking() > 0) {
    log::Debug("planner: {} actions left out: each deletes a goal fact nothing adds back",
               snap_.num_goal_breaking());
  }
  if (heuristic_.num_operator_groups() > 0) {
    log::Debug("planner: {} groups of actions that differ in one condition only, explored as one",
               heuristic_.num_operator_groups());
  }
  if (options_.landmarks) {
    const Clock::time_point landmarks_start = Clock::now();
    landmarks_.emplace(snap_, heuristic_, &stop_);
    best_.stats.landmark_time_s = Seconds(landmarks_start);
    best_.stats.landmarks = landmarks_->size();
    best_.stats.landmark_orderings = landmarks_->num_orderings();
    log::Debug("planner: {} landmarks, {} of them disjunctive, {} orderings in {:.3f} s",
               landmarks_->size(), landmarks_->num_disjunctive(), landmarks_->num_orderings(),
               best_.stats.landmark_time_s);
  }
  // Mutex groups (mutex_groups.h): the dead ends the order of goals shows
  // (goal_order.h), the landmark count's reasonable orderings
  // (landmarks.h) and the pairs of facts a deadline's reachability waits
  // for (temporal_reachability.h).
  const bool watch_goals = GoalOrderDeadEnds::NumWatchableGoals(snap_.task()) >= 2;
  if (!watch_goals) {
    log::Debug("planner: fewer than two goals nothing deletes: no goal order to watch");
  }
  const bool order_landmarks = landmarks_ && landmarks_->size() > 0;
  if (watch_goals || reachability_.active() || order_landmarks) {
    const Clock::time_point mutex_start = Clock::now();
    const MutexGroups mutex(snap_.task());
    log::Debug("planner: {} mutex groups in {:.3f} s", mutex.groups().size(), Seconds(mutex_start));
    if (order_landmarks) {
      const Clock::time_point orderings_start = Clock::now();
      const int added = landmarks_->AddReasonableOrderings(heuristic_, mutex, &stop_);
      best_.stats.landmark_time_s += Seconds(orderings_start);
      best_.stats.landmark_orderings = landmarks_->num_orderings();
      log::Debug("planner: {} reasonable orderings of landmarks in {:.3f} s", added,
                 Seconds(orderings_start));
    }
    if (watch_goals) {
      const Clock::time_point goals_start = Clock::now();
      goal_order_.emplace(snap_.task(), mutex);
      log::Debug("planner: {} goals watched for their order ({}), in {:.3f} s",
                 goal_order_->num_goals(), goal_order_->active() ? "active" : "inactive",
                 Seconds(goals_start));
      if (!goal_order_->active()) goal_order_.reset();
    }
    if (reachability_.active()) {
      const Clock::time_point pairs_start = Clock::now();
      reachability_.UseMutexGroups(mutex);
      log::Debug(
          "planner: deadline reachability waits for {} pairs of facts ({} reached per "
          "evaluation at most), found in {:.3f} s",
          reachability_.num_pair_facts(), reachability_.num_pair_reaches(), Seconds(pairs_start));
    }
  }
  // With deadlines, when each object is free matters, and a symmetric
  // state is dropped on its makespan bound alone: generated trucks-time-til
  // instances with three trucks lost their only timely states.
  if (options_.symmetry_reduction && reachability_.active()) {
    log::Debug("planner: no symmetry reduction: timed literals close deadlines");
  } else if (options_.symmetry_reduction) {
    symmetry_.emplace(snap_);
    best_.stats.symmetric_objects = symmetry_->num_symmetric_objects();
    best_.stats.symmetry_classes = symmetry_->num_classes();
    log::Debug("planner: {} objects in {} classes of interchangeable objects",
               symmetry_->num_symmetric_objects(), symmetry_->num_classes());
  }
  // Phase 1: two greedy best-first searches for a first plan. The first
  // breaks ties by makespan so far. The second breaks them newest first
  // (the makespan order searches a plateau breadth first, which is what
  // left sokoban and rtam instances unsolved), and its relaxed plan keeps
  // the goals the state holds (RelaxedPlanHeuristic::SetKeepHeldGoals: in
  // the first it made 17 of 154 first plans of the shared benchmark longer,
  // and lost elevators-2011 p05 at 10 CPU s). It takes
  // second_greedy_turn_share of the steps, in turn with the first: it is
  // the much faster one on some domains (parcprinter-2011 p04: 0.021 s
  // against 2.6 s), but its plans are often longer, and with half the
  // steps the fjord missions' first plans came later or longer
  // (bench/planner/README.md, "The two first-plan searches in turn"). If
  // nothing is found in second_greedy_after_share of the time, the first
  // gives way to a third, in turn with the second, half the steps each: the
  // second's configuration, but an operator that undoes a held goal comes
  // kGoalUndoerDelayLayers layers late in its relaxed plans
  // (RelaxedPlanHeuristic::SetDelayGoalUndoers). From the start, in the
  // second search, it found generated driverlogshift instances that need
  // three drivers to walk within 0.2 s, where none was found in 60 s, but
  // made first plans of larger fjord missions up to 19 times as long
  // (bench/planner/README.md, "Held goals undone last"). Under an expansion limit that
  // share is of the limit, so that the clock decides nothing but the time
  // limit; under a CPU budget, of that budget. The second search has its own
  // states and schedule: two searches in turn on one timeline would each
  // find the other's path built where they left theirs. A search that
  // exhausts its space without a proof starts again, first without eager
  // ends, then keeping many more schedule variants apart.
  const Clock::time_point switch_at =
      start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                   options_.time_limit_s * options_.second_greedy_after_share));
  const auto switch_after_expansions = static_cast<std::size_t>(
      static_cast<double>(options_.max_expansions) * options_.second_greedy_after_share);
  auto switch_due = [&]() {
    if (options_.max_expansions > 0) return Expanded() >= switch_after_expansions;
    if (options_.cpu_time_limit_s > 0) {
      return cpu_seconds_ >= options_.cpu_time_limit_s * options_.second_greedy_after_share;
    }
    if ((steps_ & 255) != 0) return false;
    return Clock::now() >= switch_at;
  };
  struct FirstPlanSearch {
    bool newest_first = false;
    bool keep_held_goals = false;     // RelaxedPlanHeuristic::SetKeepHeldGoals
    bool delay_goal_undoers = false;  // RelaxedPlanHeuristic::SetDelayGoalUndoers
    double share = 0;                 // of the steps
    StateRegistry* registry = nullptr;
    Timeline* timeline = nullptr;
    bool eager_ends = true;
    bool many_variants = false;
    std::unique_ptr<LazySearch> search;  // null: not run, or out of fallbacks
    bool out_of_fallbacks = false;       // exhausted without a proof, every way
    std::size_t steps = 0;
    // With deadlines: how often it began again with another seed, and at
    // how many steps it begins again next (below).
    int restarts = 0;
    std::size_t restart_at_steps = 0;
  };
  // With timed literals closing deadlines, a greedy search either finds a
  // plan soon or, after an early commitment that misses a deadline much
  // later (a truck sent off with the wrong packages), expands a subtree
  // without one for the rest of the budget: generated trucks-time-til
  // instances unsolved in 20 CPU s were solved within 3 s with three other
  // seeds of four. So there each first-plan search begins again, with the
  // next seed (another order of ties among successors), after
  // kFirstRestartSteps steps, then after twice as many each time: at worst
  // about half the budget is lost to the restarts (engine/search/README.md,
  // "Restarts under deadlines").
  constexpr std::size_t kFirstRestartSteps = 5'000;
  const bool restart_under_deadlines = reachability_.active();
  FirstPlanSearch searches[2];
  const bool switched_at_start = options_.second_greedy_after_share <= 0;
  searches[0].share = switched_at_start ? 0 : 1 - options_.second_greedy_turn_share;
  searches[1].share = switched_at_start ? 1 : options_.second_greedy_turn_share;
  searches[1].newest_first = true;
  searches[1].keep_held_goals = true;
  for (FirstPlanSearch& s : searches) {
    s.registry = &registry_;
    s.timeline = &timeline_;
    s.eager_ends = EagerEnds();
  }
  // States and a schedule apart from the first search's (freed at the
  // first plan), for a search that runs in turn with one on those.
  auto use_second_states = [&](FirstPlanSearch& s) {
    second_registry_.emplace(snap_.num_facts(), snap_.num_vars());
    second_timeline_.emplace(snap_, options_.epsilon_s, options_.max_concurrent_actions > 0);
    s.registry = &*second_registry_;
    s.timeline = &*second_timeline_;
  };
  if (searches[0].share > 0 && searches[1].share > 0) use_second_states(searches[1]);
  auto begin_search = [&](FirstPlanSearch& s) {
    SearchParams params =
        GreedyParams(options_.random_seed + static_cast<std::uint64_t>(s.restarts), s.eager_ends);
    s.restart_at_steps = s.steps + (kFirstRestartSteps << std::min(s.restarts, 40));
    if (s.many_variants) {
      params.max_variants = 64;
      params.bound_dominance = false;
    }
    if (s.newest_first) params.plateau_order = SearchParams::PlateauOrder::kNewestFirst;
    assert(!s.search);  // a running search must go through AddCounters first
    s.search = std::make_unique<LazySearch>(snap_, *s.registry, heuristic_, transitions_,
                                            *s.timeline, params);
    Start(*s.search);
  };
  for (FirstPlanSearch& s : searches) {
    if (s.share > 0) begin_search(s);
  }
  // The first search from the switch on: it waits, and goes on pruned by
  // the plan the others find (below).
  std::unique_ptr<LazySearch> waiting_first;
  auto end_all = [&]() {
    for (FirstPlanSearch& s : searches) {
      if (s.search) AddCounters(*s.search);
      s.search.reset();
    }
    if (waiting_first) AddCounters(*waiting_first);
    waiting_first.reset();
  };
  const FirstPlanSearch* found_by = nullptr;
  while (!has_plan()) {
    // The search furthest behind its share of the steps.
    FirstPlanSearch* next = nullptr;
    for (FirstPlanSearch& s : searches) {
      if (!s.search) continue;
      if (next == nullptr ||
          static_cast<double>(s.steps) * next->share < static_cast<double>(next->steps) * s.share) {
        next = &s;
      }
    }
    if (next == nullptr && searches[1].steps == 0 && !searches[1].out_of_fallbacks) {
      // The first ran out of fallbacks before the second took a step
      // (second_greedy_turn_share 0): the second now, alone.
      searches[1].share = 1;
      begin_search(searches[1]);
      continue;
    }
    if (next == nullptr) {
      end_all();
      return finish(PlanStatus::kError,
                    searches[0].out_of_fallbacks || searches[1].out_of_fallbacks
                        ? "search space exhausted without a plan, but duplicate states with "
                          "running actions or timed literals were merged, so this is no proof"
                        : "no first-plan search to run");
    }
    // The switch. The first search's place goes to the third, which starts
    // as many steps behind as the second has taken, so that the two
    // alternate (the second goes on, or starts, unless it is out of
    // fallbacks). Each has states and a schedule of its own: with no turn
    // share the second has been using the first's. Otherwise the first
    // waits with its schedule, and the third gets one of its own.
    if (!switched_at_start && !searches[0].delay_goal_undoers &&
        options_.second_greedy_after_share < 1 && switch_due()) {
      const bool first_waits = searches[0].search && searches[1].timeline != &timeline_;
      if (first_waits) {
        waiting_first = std::move(searches[0].search);
      } else if (searches[0].search) {
        AddCounters(*searches[0].search);
        searches[0].search.reset();
      }
      searches[0] = FirstPlanSearch{};
      searches[0].newest_first = searches[0].keep_held_goals = true;
      searches[0].delay_goal_undoers = true;
      searches[0].share = searches[1].share = 0.5;
      searches[0].registry = &registry_;
      searches[0].timeline = first_waits
                                 ? &third_timeline_.emplace(snap_, options_.epsilon_s,
                                                            options_.max_concurrent_actions > 0)
                                 : &timeline_;
      if (!first_waits && searches[1].registry == &registry_) use_second_states(searches[0]);
      searches[0].eager_ends = EagerEnds();
      searches[0].steps = searches[1].steps;
      begin_search(searches[0]);
      if (!searches[1].search && !searches[1].out_of_fallbacks) begin_search(searches[1]);
      continue;
    }
    const Outcome poll = Poll();
    if (poll != Outcome::kContinue) {
      end_all();
      if (poll == Outcome::kMemout)
        return finish(PlanStatus::kMemout, absl::StrCat(MemoryLimitText(), " before a plan"));
      if (expansion_limit_reached_) {
        return finish(PlanStatus::kTimeout,
                      absl::StrCat("expansion limit (", options_.max_expansions,
                                   ") reached before a plan was found"));
      }
      if (cpu_limit_reached_) {
        return finish(PlanStatus::kTimeout,
                      absl::StrCat("CPU time limit (", options_.cpu_time_limit_s,
                                   " s) reached before a plan was found"));
      }
      return finish(stopped_status(), stop_.Reason() == StopReason::kCancelled
                                          ? "cancelled before a plan was found"
                                          : "time limit reached before a plan was found");
    }
    heuristic_.SetKeepHeldGoals(next->keep_held_goals);
    heuristic_.SetDelayGoalUndoers(next->delay_goal_undoers);
    LazySearch& search = *next->search;
    ++next->steps;
    const LazySearch::Status status = search.Step();
    if (status == LazySearch::Status::kSolved) {
      // An invalid plan is logged, and the search goes on.
      if (Offer(search)) found_by = next;
      continue;
    }
    if (status == LazySearch::Status::kInProgress && restart_under_deadlines &&
        next->steps >= next->restart_at_steps) {
      AddCounters(search);
      next->search.reset();
      ++next->restarts;
      ++best_.stats.first_plan_restarts;
      log::Debug("planner: first-plan search begins again with seed {} at its step {}",
                 options_.random_seed + static_cast<std::uint64_t>(next->restarts), next->steps);
      begin_search(*next);
      continue;
    }
    if (status != LazySearch::Status::kExhausted) continue;
    if (search.complete()) {
      end_all();
      return finish(PlanStatus::kUnsolvableProven, "search space exhausted: no plan exists");
    }
    const bool had_eager_ends = search.counters().eager_ends > 0;
    AddCounters(search);
    next->search.reset();
    if (had_eager_ends) {
      // The orders eager ends left out may hold the plan: search them too.
      next->eager_ends = false;
    } else if (!next->many_variants) {
      next->many_variants = true;
    } else {
      next->out_of_fallbacks = true;
      continue;
    }
    begin_search(*next);
  }
  const std::size_t first_plan_expanded = Expanded();
  // A first plan from the second or third search (newest first) is often
  // much longer than the first search's would have been: the first goes
  // on, pruned by it, until its own plan or twelve times the expansions so
  // far. With six times, elevators-2011 p03 and p05 kept the second's plans
  // (1,455 and 1,965 against 388 and 558), for 2 % less time over the
  // shared benchmark; going on until the switch (the budget the first
  // search had without the second) took 1.3 times as long as six times
  // (bench/planner/README.md, "The two first-plan searches in turn").
  // After the switch it goes on from where it waited: the third's plans of
  // larger fjord missions were up to eleven times as long as the first's
  // (bench/missions/README.md, "The first search goes on after the switch").
  LazySearch* first = waiting_first.get();
  if (found_by == &searches[1] && searches[0].search && !searches[0].delay_goal_undoers) {
    first = searches[0].search.get();
  }
  if (first != nullptr) {
    constexpr std::size_t kFirstSearchGoesOn = 12;
    heuristic_.SetKeepHeldGoals(false);
    heuristic_.SetDelayGoalUndoers(false);
    first->SetBound(best_.makespan_s);
    RunBounded(*first, first->counters().expanded + kFirstSearchGoesOn * first_plan_expanded, true);
  }
  end_all();
  second_registry_.reset();
  second_timeline_.reset();
  third_timeline_.reset();
  heuristic_.SetKeepHeldGoals(false);  // the searches for shorter plans: FF's ties
  heuristic_.SetDelayGoalUndoers(false);
  // The same passes and rounds with or without anytime phases, so that
  // those start from the plan `--no-anytime` returns.
  if (!ShortenFirstPlan(first_plan_expanded, /*quick=*/false) &&
      !ShortenWithOtherSeeds(
          static_cast<std::size_t>(options_.seed_rounds_share * static_cast<double>(Expanded())))) {
    ShortenSuffixes(
        static_cast<std::size_t>(options_.suffix_search_share * static_cast<double>(Expanded())));
  }
  if (!options_.anytime) return finish(PlanStatus::kSolvedSatisficing, "");
  heuristic_.SetMakespanAware(false);  // the anytime phases: FF's (see below)

  // Phase 2: restarting weighted A* on makespan, pruned by the incumbent,
  // with FF's relaxed plan: with the makespan-aware one it missed the
  // improvements it finds on some generated fjord missions (fjord-fuel
  // 3x12x12 seed 1: 19,701 s kept for 20 s instead of 12,144 s at 5 s).
  bool proven = false;
  const double weights[] = {3, 2, 1.5, 1.2, 1};
  for (double w : weights) {
    SearchParams params = BoundedParams(w);
    // The last pass proves the incumbent optimal when it runs out of
    // states; with eager ends that would be no proof.
    if (w == 1) params.eager_ends = false;
    LazySearch search(snap_, registry_, heuristic_, transitions_, timeline_, params);
    Start(search);
    const bool stop = RunBounded(search, std::numeric_limits<std::size_t>::max(), false);
    AddCounters(search);
    if (stop) break;
    if (search.exhaustive_without_merges()) {
      proven = true;
      break;
    }
  }
  if (proven) {
    best_.status = PlanStatus::kSolvedOptimally;
    best_.message = absl::StrCat("makespan ", best_.makespan_s,
                                 " is optimal (no better plan in the exhausted search space)");
  }
  return finish(PlanStatus::kSolvedSatisficing, "");
}

}  // namespace

PlanResult SolveTask(const task::GroundTask& task, const PlannerOptions& options,
                     const StopToken& stop, const PlanObserver* observer) {
  if (absl::Status s = options.Validate(); !s.ok()) {
    PlanResult r;
    r.status = PlanStatus::kError;
    r.message = std::string(s.message());
    return r;
  }
  // Under an address-space limit (ulimit -v, as benchmark runners set it)
  // an allocation can fail before the memory limit's poll sees it coming
  // (a table doubling): the plan found so far is returned, not lost.
  std::unique_ptr<PlannerRun> run;
  try {
    run = std::make_unique<PlannerRun>(task, options, stop, observer);
  } catch (const std::bad_alloc&) {
    PlanResult r;
    r.status = PlanStatus::kMemout;
    r.message = "memory ran out (an allocation failed) building the search's tables";
    return r;
  }
  try {
    return run->Run();
  } catch (const std::bad_alloc&) {
  }
  try {
    return run->AfterAllocationFailure();
  } catch (const std::bad_alloc&) {  // the message could not be allocated
    return run->TakeBest();
  }
}

StopToken WithinTimeLimit(const PlannerOptions& options, const StopToken& stop) {
  // Clamped as Solve clamps the search's share (and to a year, so that the
  // deadline cannot overflow the clock); SolveTask reports invalid options.
  double limit_s = options.time_limit_s;
  if (!(limit_s > 1e-3)) limit_s = 1e-3;
  if (limit_s > 3.2e7) limit_s = 3.2e7;
  return stop.Child(Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                       std::chrono::duration<double>(limit_s)));
}

std::optional<PlanResult> UnfinishedLoadResult(const task::LoadResult& loaded) {
  if (!loaded.memory_ran_out && !loaded.stopped()) return std::nullopt;
  PlanResult r;
  r.grounding = loaded.stats;
  if (loaded.memory_ran_out) {
    r.status = PlanStatus::kMemout;
    r.message = "memory ran out (an allocation failed) while grounding";
    return r;
  }
  const bool cancelled = loaded.stop_reason == StopReason::kCancelled;
  r.status = cancelled ? PlanStatus::kCancelled : PlanStatus::kTimeout;
  r.message = cancelled ? "cancelled while grounding" : "time limit reached while grounding";
  return r;
}

PlanResult Solve(std::string_view domain_text, std::string_view problem_text,
                 const PlannerOptions& options, const StopToken& stop,
                 const PlanObserver* observer) {
  const auto start = Clock::now();
  task::LoadResult loaded = task::LoadTask(domain_text, problem_text, task::GroundingOptions{},
                                           WithinTimeLimit(options, stop));
  if (std::optional<PlanResult> r = UnfinishedLoadResult(loaded)) {
    r->stats.search_time_s = Seconds(start);
    return *std::move(r);
  }
  if (!loaded.ok()) {
    PlanResult r;
    r.status = loaded.unsupported() ? PlanStatus::kUnsupported : PlanStatus::kError;
    r.message = loaded.ErrorText();
    if (r.message.empty()) r.message = "the task could not be loaded";
    r.grounding = loaded.stats;
    return r;
  }
  PlannerOptions rest = options;
  rest.time_limit_s = std::max(1e-3, options.time_limit_s - Seconds(start));
  PlanResult r = SolveTask(*loaded.task, rest, stop, observer);
  r.grounding = loaded.stats;
  r.stats.search_time_s = Seconds(start);
  return r;
}

}  // namespace seaplan::search
