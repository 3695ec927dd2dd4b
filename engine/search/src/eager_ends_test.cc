// Eager ends: which actions SnapTask marks (SnapTask::EagerEnd), what the
// search prunes with them (SearchParams::eager_ends), and the planner's
// retry without them when the pruned search runs out of states.
#include <gtest/gtest.h>

#include <string>

#include "seaplan/search/planner.h"
#include "search_engine.h"
#include "search_test_util.h"

namespace seaplan::search {
namespace {

// A hoist carries crates from a bay into a row of cells, one crate per
// cell; a cell is clear when neither a crate nor the hoist is in it.
// `extra` is spliced into the domain to break one of EagerEnd's conditions.
std::string HoistDomain(const std::string& extra = "") {
  return R"(
(define (domain hoist-row)
  (:requirements :typing :durative-actions :negative-preconditions)
  (:types hoist crate cell)
  (:predicates (clear ?c - cell) (on ?x - crate ?c - cell) (at ?h - hoist ?c - cell)
               (free ?h - hoist) (holding ?h - hoist ?x - crate) (next ?a ?b - cell)
               (stored ?x - crate) (bay ?c - cell))
  (:durative-action lift
    :parameters (?h - hoist ?x - crate ?from ?stand - cell)
    :duration (= ?duration 2)
    :condition (and (at start (free ?h)) (at start (on ?x ?from))
                    (over all (at ?h ?stand)) (over all (next ?stand ?from)))
    :effect (and (at start (not (free ?h))) (at start (not (on ?x ?from)))
                 (at start (holding ?h ?x)) (at end (clear ?from))))
  (:durative-action drop
    :parameters (?h - hoist ?x - crate ?to ?stand - cell)
    :duration (= ?duration 2)
    :condition (and (at start (clear ?to)) (over all (holding ?h ?x))
                    (over all (at ?h ?stand)) (over all (next ?stand ?to)))
    :effect (and (at start (not (clear ?to))) (at end (not (holding ?h ?x)))
                 (at end (free ?h)) (at end (on ?x ?to)) (at end (stored ?x))))
  (:durative-action move
    :parameters (?h - hoist ?from ?to - cell)
    :duration (= ?duration 1)
    :condition (and (at start (at ?h ?from)) (at start (clear ?to))
                    (over all (next ?from ?to)))
    :effect (and (at start (not (at ?h ?from))) (at start (not (clear ?to)))
                 (at start (clear ?from)) (at end (at ?h ?to))))
)" + extra +
         ")";
}

// Crates c1..c3 in bay cells b1..b3 next to cell s; the row s - r1 - r2.
const char* kHoistProblem = R"(
(define (problem hoist-row-3) (:domain hoist-row)
  (:objects h - hoist c1 c2 c3 - crate s r1 r2 b1 b2 b3 - cell)
  (:init (at h s) (free h) (clear r1) (clear r2)
         (on c1 b1) (on c2 b2) (on c3 b3) (bay b1) (bay b2) (bay b3)
         (next s b1) (next s b2) (next s b3) (next s r1) (next r1 s) (next r1 r2) (next r2 r1))
  (:goal (and (stored c1) (stored c2) (stored c3) (on c1 r2) (on c2 r1)))
))";

// The domain text without its closing parenthesis, plus `action`.
std::string HoistDomainWith(const std::string& action) {
  std::string d = HoistDomain();
  d.pop_back();
  return d + action + ")";
}

bool EagerEndOf(const std::string& domain, const std::string& action) {
  auto task = testing::LoadTaskOrFail(domain, kHoistProblem);
  if (!task) return false;
  const SnapTask snap(*task);
  return snap.EagerEnd(testing::ActionIdOf(*task, action));
}

TEST(EagerEndTest, AnEndThatOnlyAddsWhatItsDeletersAskForIsEager) {
  const std::string d = HoistDomain();
  // The lift's end frees the cell; drop and move delete clear only where
  // they ask for it. The move's end adds at, which only moves delete, also
  // asking for it.
  EXPECT_TRUE(EagerEndOf(d, "(lift h c1 b1 s)"));
  EXPECT_TRUE(EagerEndOf(d, "(move h s r1)"));
  // The drop's end deletes holding.
  EXPECT_FALSE(EagerEndOf(d, "(drop h c1 r1 s)"));
}

TEST(EagerEndTest, AnyConditionAskingTheFactFalseMakesItsAddersWait) {
  const std::string d = HoistDomainWith(R"(
  (:action inspect :parameters (?c - cell) :precondition (not (clear ?c)) :effect (bay ?c)))");
  EXPECT_FALSE(EagerEndOf(d, "(lift h c1 b1 s)"));
  // at is asked false nowhere: the move stays eager.
  EXPECT_TRUE(EagerEndOf(d, "(move h s r1)"));
}

TEST(EagerEndTest, ADeleterThatDoesNotAskForTheFactMakesItsAddersWait) {
  const std::string d = HoistDomainWith(R"(
  (:action block :parameters (?c - cell) :precondition (bay ?c) :effect (not (clear ?c))))");
  EXPECT_FALSE(EagerEndOf(d, "(lift h c1 b1 s)"));
}

TEST(EagerEndTest, AnEndWithItsOwnConditionIsNotEager) {
  const std::string d = HoistDomainWith(R"(
  (:durative-action sweep :parameters (?c - cell) :duration (= ?duration 1)
    :condition (at end (clear ?c)) :effect (at end (bay ?c))))");
  auto task = testing::LoadTaskOrFail(d, kHoistProblem);
  ASSERT_NE(task, nullptr);
  const SnapTask snap(*task);
  EXPECT_FALSE(snap.EagerEnd(testing::ActionIdOf(*task, "(sweep b1)")));
}

struct SearchRun {
  LazySearch::Status status = LazySearch::Status::kInProgress;
  SearchCounters counters;
  bool complete = false;
};

SearchRun Greedy(const task::GroundTask& task, bool eager_ends, int max_steps) {
  testing::SearchParts parts(task);
  SearchParams params;
  params.weight = -1;
  params.epsilon_s = parts.kEpsilonS;
  params.eager_ends = eager_ends;
  LazySearch search(parts.snap, parts.registry, parts.heuristic, parts.transitions, parts.timeline,
                    params);
  search.Initialize(testing::InitialState(task, parts.snap));
  SearchRun run;
  for (int i = 0; i < max_steps && run.status == LazySearch::Status::kInProgress; ++i)
    run.status = search.Step();
  run.counters = search.counters();
  run.complete = search.complete();
  return run;
}

// Left pending, each lift's end multiplies the states by the places it can
// take among the drops and moves that follow; taken at once it does not
// (80 states expanded against 182 when written).
TEST(EagerEndTest, TheSearchTakesEagerEndsAndExpandsFewerStates) {
  auto task = testing::LoadTaskOrFail(HoistDomain(), kHoistProblem);
  ASSERT_NE(task, nullptr);
  const SearchRun eager = Greedy(*task, true, 200000);
  const SearchRun lazy = Greedy(*task, false, 200000);
  ASSERT_EQ(eager.status, LazySearch::Status::kSolved);
  ASSERT_EQ(lazy.status, LazySearch::Status::kSolved);
  EXPECT_GT(eager.counters.eager_ends, 0u);
  EXPECT_EQ(lazy.counters.eager_ends, 0u);
  EXPECT_LT(eager.counters.expanded, lazy.counters.expanded);
  // The states whose only successor was an eager end were not evaluated.
  EXPECT_EQ(eager.counters.evaluated + eager.counters.eager_ends, eager.counters.expanded);
}

// The only plan needs the end of `charge` after `spend`: `spend` consumes
// the fact a one-off `spark` and charge's end both add, and `use` needs it
// again afterwards. Charge's end qualifies (it only adds `power`, which
// its deleter asks for), but `power` does not stay false while charge
// runs (spark adds it), so taking the end at once loses the plan.
const char* kLateEndDomain = R"(
(define (domain late-end)
  (:requirements :durative-actions)
  (:predicates (ready) (charging) (power) (spark-left) (spent) (done))
  (:durative-action charge :parameters () :duration (= ?duration 1)
    :condition (at start (ready))
    :effect (and (at start (not (ready))) (at start (charging)) (at end (power))))
  (:action spark :parameters () :precondition (spark-left)
    :effect (power))
  (:action spend :parameters () :precondition (and (power) (charging) (spark-left))
    :effect (and (not (power)) (not (spark-left)) (spent)))
  (:action use :parameters () :precondition (and (power) (spent)) :effect (done))
))";
const char* kLateEndProblem = R"(
(define (problem late-end-1) (:domain late-end)
  (:init (ready) (spark-left)) (:goal (done)))
)";

TEST(EagerEndTest, ASearchThatRanOutOfStatesWithEagerEndsIsNoProof) {
  auto task = testing::LoadTaskOrFail(kLateEndDomain, kLateEndProblem);
  ASSERT_NE(task, nullptr);
  ASSERT_TRUE(SnapTask(*task).EagerEnd(testing::ActionIdOf(*task, "(charge)")));
  const SearchRun eager = Greedy(*task, true, 10000);
  EXPECT_EQ(eager.status, LazySearch::Status::kExhausted);
  EXPECT_GT(eager.counters.eager_ends, 0u);
  EXPECT_FALSE(eager.complete);
  EXPECT_EQ(Greedy(*task, false, 10000).status, LazySearch::Status::kSolved);
}

TEST(EagerEndTest, ThePlannerSearchesAgainWithoutEagerEndsWhenTheyRanOut) {
  auto task = testing::LoadTaskOrFail(kLateEndDomain, kLateEndProblem);
  ASSERT_NE(task, nullptr);
  const PlanResult r = testing::SolveFirstPlan(*task);
  EXPECT_EQ(r.status, PlanStatus::kSolvedSatisficing) << r.message;
  EXPECT_FALSE(r.plan.steps.empty());
  EXPECT_GT(r.stats.eager_ends, 0u);
}

// A concurrency bound orders every start after the ends before it in the
// schedule, so an early end would cost concurrency: none is taken.
TEST(EagerEndTest, AConcurrencyBoundTurnsThemOff) {
  auto task = testing::LoadTaskOrFail(HoistDomain(), kHoistProblem);
  ASSERT_NE(task, nullptr);
  PlannerOptions options;
  options.anytime = false;
  options.time_limit_s = 10;
  options.max_concurrent_actions = 2;
  const PlanResult r = SolveTask(*task, options, StopToken());
  EXPECT_EQ(r.status, PlanStatus::kSolvedSatisficing) << r.message;
  EXPECT_EQ(r.stats.eager_ends, 0u);
  options.max_concurrent_actions = 0;
  EXPECT_GT(SolveTask(*task, options, StopToken()).stats.eager_ends, 0u);
}

}  // namespace
}  // namespace seaplan::search
