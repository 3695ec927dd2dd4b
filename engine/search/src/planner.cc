#include "seaplan/search/planner.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <memory>
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

 private:
  enum class Outcome { kContinue, kStop, kMemout };
  // Polls stop/expansion limit/memory/progress; called once per search step.
  Outcome Poll(const LazySearch& search);
  // Counters so far, finished phases and `search` together.
  SearchCounters TotalCounters(const LazySearch& search) const {
    return Sum(done_counters_, search.counters());
  }
  std::size_t Expanded(const LazySearch& search) const { return TotalCounters(search).expanded; }
  void AddCounters(const LazySearch& search);
  // Builds and validates; true when it is a new incumbent.
  bool Offer(const LazySearch& search);
  // The task's initial state (built once, for initial_).
  StateData InitialState() const;
  // After the first plan: bounded searches with the makespan-aware relaxed
  // plan (agents' work spread, relaxed_plan_heuristic.h); with fewer than
  // two agents, weighted A* alone with FF's.
  void ShortenFirstPlan();
  // A search pruned by the incumbent (weight < 0: greedy, else weighted A*
  // with the incumbent's seconds per event as the heuristic's unit).
  SearchParams BoundedParams(double weight) const;
  // PlannerOptions::eager_ends, unless the schedule bounds concurrency.
  bool EagerEnds() const { return options_.eager_ends && options_.max_concurrent_actions == 0; }
  // Stop token, timed-literal reachability and the initial state.
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
  bool has_plan_ = false;
  std::size_t plan_events_ = 0;
  SearchCounters done_counters_;  // of finished phases
  std::size_t steps_ = 0;
  bool expansion_limit_reached_ = false;
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

void PlannerRun::AddCounters(const LazySearch& search) {
  done_counters_ = TotalCounters(search);
}

PlannerRun::Outcome PlannerRun::Poll(const LazySearch& search) {
  ++steps_;
  if (stop_.StopRequested()) return Outcome::kStop;
  if (options_.max_expansions > 0 && Expanded(search) >= options_.max_expansions) {
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
    const std::size_t bytes = registry_.MemoryBytes() + search.MemoryBytes() +
                              timeline_.MemoryBytes() + plan_timeline_.MemoryBytes();
    const std::size_t mb = bytes >> 20;
    best_.stats.peak_memory_mb = std::max(best_.stats.peak_memory_mb, mb);
    if (mb >= options_.memory_limit_mb) return Outcome::kMemout;
    if (observer_ && observer_->on_progress &&
        std::chrono::duration<double>(Clock::now() - last_progress_).count() >= 0.5) {
      last_progress_ = Clock::now();
      SearchStatistics stats = best_.stats;
      SetCounters(TotalCounters(search), stats);
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
  log::Debug("planner: redundant steps looked for in {:.3f} s", Seconds(eliminate_start));
  if (needed.size() < search.plan().size()) {
    std::string needed_error;
    auto shorter = BuildValidatedPlan(snap_, needed, plan_timeline_, validator_, &needed_error);
    if (!shorter) {
      log::Debug("planner: plan without redundant steps rejected: {}", needed_error);
    } else if (shorter->makespan_s <= built->makespan_s) {
      log::Debug("planner: {} of {} events redundant, makespan {} -> {}",
                 search.plan().size() - needed.size(), search.plan().size(), built->makespan_s,
                 shorter->makespan_s);
      built = std::move(shorter);
    }
  }
  if (has_plan_ && built->makespan_s >= best_.makespan_s - options_.epsilon_s / 2) return false;
  const double now = Seconds(start_);
  has_plan_ = true;
  plan_events_ = search.plan().size();
  best_.status = PlanStatus::kSolvedSatisficing;
  best_.plan = std::move(built->plan);
  best_.makespan_s = built->makespan_s;
  best_.metric_value = built->metric_value;
  best_.stats.plans_found++;
  if (best_.stats.first_plan_time_s < 0) best_.stats.first_plan_time_s = now;
  best_.stats.best_plan_time_s = now;
  if (observer_ && observer_->on_plan) {
    PlanResult copy = best_;
    SetCounters(TotalCounters(search), copy.stats);
    copy.stats.search_time_s = now;
    copy.message = absl::StrCat("plan ", best_.stats.plans_found, ", makespan ", best_.makespan_s);
    observer_->on_plan(copy);
  }
  return true;
}

SearchParams PlannerRun::BoundedParams(double weight) const {
  SearchParams params;
  params.weight = weight;
  params.scale_s = best_.makespan_s / std::max<double>(1.0, static_cast<double>(plan_events_));
  params.bound_s = best_.makespan_s;
  params.epsilon_s = options_.epsilon_s;
  params.seed = options_.random_seed;
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
}

bool PlannerRun::RunBounded(LazySearch& search, std::size_t max_expanded, bool stop_at_plan) {
  while (search.counters().expanded <= max_expanded) {
    if (Poll(search) != Outcome::kContinue) return true;
    const LazySearch::Status status = search.Step();
    if (status == LazySearch::Status::kSolved) {
      const bool improved = Offer(search);
      if (stop_at_plan) break;
      if (improved) search.SetBound(best_.makespan_s);
      continue;
    }
    if (status == LazySearch::Status::kExhausted) break;
  }
  return false;
}

void PlannerRun::ShortenFirstPlan() {
  heuristic_.SetMakespanAware(true);
  if (!has_plan_) return;
  // With fewer than two agents there is no work to spread, but the greedy
  // plan's detours are there all the same (satellite-time p01: a turn to a
  // target before the turn to calibrate): weighted A* alone, with FF's
  // relaxed plan.
  const bool spread = heuristic_.makespan_aware();
  // Pruned by the incumbent and given, in all, at most six times the first
  // search's expansions without anytime phases (their plan is the one
  // returned: with twice, the budget of the anytime case, both passes were
  // cut short on generated fjord missions), twice with them (which improve
  // it further and should not wait): the first plan stays the fallback, so
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
  const std::size_t first_expanded = done_counters_.expanded;
  const std::size_t budget_factor = options_.anytime ? 2 : 6;
  // With one agent, once the first search's expansions: the pass costs
  // more per state where schedules branch (matchcellar p05: 3.5 s more with
  // six times, for no shorter plan).
  std::size_t left = std::max<std::size_t>(1000, (spread ? budget_factor : 1) * first_expanded);
  std::size_t landmark_left = std::max<std::size_t>(1000, 2 * first_expanded);
  struct Pass {
    double weight;
    bool landmarks;
  };
  for (const Pass pass : {Pass{-1.0, false}, Pass{3.0, false}, Pass{-1.0, true}}) {
    if (pass.landmarks && !landmarks_) continue;
    if (!spread && pass.weight < 0) continue;
    std::size_t& budget = pass.landmarks ? landmark_left : left;
    if (budget == 0) continue;
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
    if (stop) return;
  }
}

PlanResult PlannerRun::Run() {
  best_.status = PlanStatus::kTimeout;
  auto finish = [&](PlanStatus status_if_no_plan, std::string message) {
    SetCounters(done_counters_, best_.stats);
    best_.stats.search_time_s = Seconds(start_);
    if (!has_plan_) {
      best_.status = status_if_no_plan;
      best_.message = std::move(message);
    } else if (best_.message.empty()) {
      best_.message =
          absl::StrCat(best_.stats.plans_found, " plan(s), best makespan ", best_.makespan_s);
    }
    return best_;
  };
  auto stopped_status = [&]() {
    return stop_.Reason() == StopReason::kCancelled ? PlanStatus::kCancelled : PlanStatus::kTimeout;
  };

  // Phase 1: greedy best-first search for a first plan. If it exhausts the
  // space without a proof (merged states whose schedules differ), retry
  // once keeping many more schedule variants apart. If it has found nothing
  // when its share of the time is up, the rest goes to a greedy search that
  // breaks ties newest first: the makespan order searches a plateau breadth
  // first, which is what leaves sokoban and rtam instances unsolved. Under an
  // expansion limit the share is of that limit, so that the clock decides
  // nothing but the time limit; under a CPU budget, of that budget.
  const Clock::time_point switch_at =
      start_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                   options_.time_limit_s * options_.second_greedy_after_share));
  const auto switch_after_expansions = static_cast<std::size_t>(
      static_cast<double>(options_.max_expansions) * options_.second_greedy_after_share);
  auto switch_due = [&](const LazySearch& search) {
    if (options_.max_expansions > 0) return Expanded(search) >= switch_after_expansions;
    if (options_.cpu_time_limit_s > 0) {
      return cpu_seconds_ >= options_.cpu_time_limit_s * options_.second_greedy_after_share;
    }
    if ((steps_ & 255) != 0) return false;
    return Clock::now() >= switch_at;
  };
  if (snap_.num_goal_breaking() > 0) {
    log::Debug("planner: {} actions left out: each deletes a goal fact nothing adds back",
               snap_.num_goal_breaking());
  }
  if (options_.landmarks) {
    const Clock::time_point landmarks_start = Clock::now();
    landmarks_.emplace(snap_, heuristic_, &stop_);
    best_.stats.landmark_time_s = Seconds(landmarks_start);
    best_.stats.landmarks = landmarks_->size();
    best_.stats.landmark_orderings = landmarks_->num_orderings();
    log::Debug("planner: {} landmarks, {} orderings in {:.3f} s", landmarks_->size(),
               landmarks_->num_orderings(), best_.stats.landmark_time_s);
  }
  {
    // Mutex groups and the dead ends the order of goals shows (goal_order.h).
    const Clock::time_point mutex_start = Clock::now();
    const MutexGroups mutex(snap_.task());
    goal_order_.emplace(snap_.task(), mutex);
    log::Debug("planner: {} mutex groups, {} goals watched for their order ({}), in {:.3f} s",
               mutex.groups().size(), goal_order_->num_goals(),
               goal_order_->active() ? "active" : "inactive", Seconds(mutex_start));
    if (!goal_order_->active()) goal_order_.reset();
  }
  if (options_.symmetry_reduction) {
    symmetry_.emplace(snap_);
    best_.stats.symmetric_objects = symmetry_->num_symmetric_objects();
    best_.stats.symmetry_classes = symmetry_->num_classes();
    log::Debug("planner: {} objects in {} classes of interchangeable objects",
               symmetry_->num_symmetric_objects(), symmetry_->num_classes());
  }
  bool many_variants = false, newest_first = options_.second_greedy_after_share <= 0;
  bool eager_ends = EagerEnds();
  while (true) {
    SearchParams params;
    params.weight = -1;
    params.epsilon_s = options_.epsilon_s;
    params.seed = options_.random_seed;
    params.type_based_exploration = options_.type_based_exploration;
    if (landmarks_) params.landmarks = &*landmarks_;
    if (symmetry_) params.symmetry = &*symmetry_;
    if (goal_order_) params.goal_order = &*goal_order_;
    params.eager_ends = eager_ends;
    if (many_variants) {
      params.max_variants = 64;
      params.bound_dominance = false;
    }
    if (newest_first) params.plateau_order = SearchParams::PlateauOrder::kNewestFirst;
    // The second search also differs in its relaxed plan: on ties it keeps
    // the goals the state holds (RelaxedPlanHeuristic::SetKeepHeldGoals).
    // Only there: in the first it made 17 of 154 first plans of the shared
    // benchmark longer (driverlog-2014 p03 360 -> 449) and lost
    // elevators-2011 p05 at 10 CPU s; as the second it solves parcprinter
    // p04 and p05 and driverlog-2014 p05 there, which the first misses.
    heuristic_.SetKeepHeldGoals(newest_first);
    LazySearch search(snap_, registry_, heuristic_, transitions_, timeline_, params);
    Start(search);
    bool switch_now = false;
    while (true) {
      if (!newest_first && options_.second_greedy_after_share < 1 && switch_due(search)) {
        switch_now = true;
        break;
      }
      const Outcome poll = Poll(search);
      if (poll != Outcome::kContinue) {
        AddCounters(search);
        if (poll == Outcome::kMemout)
          return finish(PlanStatus::kMemout, "memory limit reached before a plan");
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
      const LazySearch::Status status = search.Step();
      if (status == LazySearch::Status::kSolved) {
        if (Offer(search)) break;
        continue;  // invalid plan: logged, keep searching
      }
      if (status == LazySearch::Status::kExhausted) {
        AddCounters(search);
        if (search.complete()) {
          return finish(PlanStatus::kUnsolvableProven, "search space exhausted: no plan exists");
        }
        if (search.counters().eager_ends > 0) {
          // The orders eager ends left out may hold the plan: search them too.
          eager_ends = false;
          break;
        }
        if (!many_variants) {
          many_variants = true;
          break;
        }
        return finish(PlanStatus::kError,
                      "search space exhausted without a plan, but duplicate states with running "
                      "actions or timed literals were merged, so this is no proof");
      }
    }
    if (has_plan_) {
      AddCounters(search);
      break;
    }
    if (switch_now) {
      AddCounters(search);
      newest_first = true;
    }
  }
  heuristic_.SetKeepHeldGoals(false);  // the searches for shorter plans: FF's ties
  ShortenFirstPlan();
  heuristic_.SetMakespanAware(false);  // the anytime phases: FF's (see below)
  if (!options_.anytime) return finish(PlanStatus::kSolvedSatisficing, "");

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
  auto run = std::make_unique<PlannerRun>(task, options, stop, observer);
  return run->Run();
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

PlanResult Solve(std::string_view domain_text, std::string_view problem_text,
                 const PlannerOptions& options, const StopToken& stop,
                 const PlanObserver* observer) {
  const auto start = Clock::now();
  task::LoadResult loaded = task::LoadTask(domain_text, problem_text, task::GroundingOptions{},
                                           WithinTimeLimit(options, stop));
  if (loaded.stopped()) {
    PlanResult r;
    const bool cancelled = loaded.stop_reason == StopReason::kCancelled;
    r.status = cancelled ? PlanStatus::kCancelled : PlanStatus::kTimeout;
    r.message = cancelled ? "cancelled while grounding" : "time limit reached while grounding";
    r.grounding = loaded.stats;
    r.stats.search_time_s = Seconds(start);
    return r;
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
