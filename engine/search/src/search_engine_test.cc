#include "search_engine.h"

#include <gtest/gtest.h>

#include <span>
#include <vector>

#include "seaplan/testing/shared_data.h"
#include "search_test_util.h"

namespace seaplan::search {
namespace {

// Everything one greedy search step observes: its outcome and counters.
struct Trace {
  std::vector<int> statuses, best_h;
  SearchCounters counters;
  std::vector<Event> plan;
  double makespan_s = 0;
  std::size_t rebuilt = 0;
};

// A greedy search with type-based exploration on `domain`/`problem`,
// `steps` steps at most, keeping `schedule_paths` schedules built.
Trace RunGreedy(const std::string& domain, const std::string& problem, int schedule_paths,
                int steps) {
  auto task =
      testing::LoadTaskOrFail(seaplan::testing::ReadFile(seaplan::testing::SourceDir() / domain),
                              seaplan::testing::ReadFile(seaplan::testing::SourceDir() / problem));
  Trace trace;
  if (!task) return trace;
  testing::SearchParts parts(*task);
  SearchParams params;
  params.weight = -1;
  params.epsilon_s = parts.kEpsilonS;
  params.type_based_exploration = true;
  params.schedule_paths = schedule_paths;
  LazySearch search(parts.snap, parts.registry, parts.heuristic, parts.transitions, parts.timeline,
                    params);
  search.Initialize(testing::InitialState(*task, parts.snap));
  for (int i = 0; i < steps; ++i) {
    const LazySearch::Status status = search.Step();
    trace.statuses.push_back(static_cast<int>(status));
    trace.best_h.push_back(search.best_h());
    if (status != LazySearch::Status::kInProgress) break;
  }
  trace.counters = search.counters();
  trace.plan = search.plan();
  trace.makespan_s = search.plan_makespan_s();
  trace.rebuilt = search.schedule_events_rebuilt();
  return trace;
}

void ExpectSameSearch(const Trace& a, const Trace& b) {
  EXPECT_EQ(a.statuses, b.statuses);
  EXPECT_EQ(a.best_h, b.best_h);
  EXPECT_EQ(a.counters.expanded, b.counters.expanded);
  EXPECT_EQ(a.counters.generated, b.counters.generated);
  EXPECT_EQ(a.counters.evaluated, b.counters.evaluated);
  ASSERT_EQ(a.plan.size(), b.plan.size());
  for (std::size_t i = 0; i < a.plan.size(); ++i) {
    EXPECT_EQ(a.plan[i].snap, b.plan[i].snap) << i;
    EXPECT_EQ(a.plan[i].min_duration_s, b.plan[i].min_duration_s) << i;
  }
  EXPECT_EQ(a.makespan_s, b.makespan_s);
}

// Extra schedule paths only save rebuilding: every schedule is exact on
// any path, so the search (its steps, counters, best h after each step and
// plan) is the same as with one, and its random pops rebuild fewer states.
// The mission (`seaplan-mission-gen --domain fjord --ships 2 --ports 8
// --containers 8 --seed 1`) is the smallest generated one found whose
// greedy search runs long enough for the typed list to get turns.
TEST(LazySearchTest, ExtraSchedulePathsChangeNothingButTheRebuilding) {
  const std::string domain = "examples/fjord/domain.pddl";
  const std::string problem = "engine/search/testdata/fjord-s2-p8-c8-seed1.pddl";
  const Trace one = RunGreedy(domain, problem, 1, 100000);
  ASSERT_FALSE(one.statuses.empty());
  EXPECT_EQ(one.statuses.back(), static_cast<int>(LazySearch::Status::kSolved));
  EXPECT_GT(one.counters.expanded, 1000u);
  const Trace two = RunGreedy(domain, problem, 2, 100000);
  ExpectSameSearch(one, two);
  EXPECT_LT(two.rebuilt, one.rebuilt);
  const Trace four = RunGreedy(domain, problem, 4, 100000);
  ExpectSameSearch(one, four);
  EXPECT_LE(four.rebuilt, two.rebuilt);
}

// SearchParams::prefix: the search takes the prefix's events first, one
// after another, and searches only the completions of that prefix; a prefix
// event that cannot happen where it is due leaves it without states.
TEST(LazySearchTest, APrefixIsTakenFirst) {
  auto task = testing::LoadTaskOrFail(
      seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "examples/fjord/domain.pddl"),
      seaplan::testing::ReadFile(seaplan::testing::SourceDir() /
                                 "engine/search/testdata/fjord-s2-p8-c8-seed1.pddl"));
  ASSERT_TRUE(task);
  // Weighted A* counts a relaxed plan's event as the greedy plan's seconds
  // per event, as the planner's bounded searches do.
  double scale_s = 1;
  const auto solve = [&](std::span<const Event> prefix, double weight, LazySearch::Status* status,
                         std::size_t* expanded) {
    testing::SearchParts parts(*task);
    SearchParams params;
    params.weight = weight;
    params.scale_s = scale_s;
    params.epsilon_s = parts.kEpsilonS;
    params.prefix = prefix;
    LazySearch search(parts.snap, parts.registry, parts.heuristic, parts.transitions,
                      parts.timeline, params);
    search.Initialize(testing::InitialState(*task, parts.snap));
    *status = LazySearch::Status::kInProgress;
    for (int i = 0; i < 200000 && *status == LazySearch::Status::kInProgress; ++i) {
      *status = search.Step();
    }
    *expanded = search.counters().expanded;
    if (*status == LazySearch::Status::kSolved && weight < 0) {
      scale_s = search.plan_makespan_s() / static_cast<double>(search.plan().size());
    }
    return search.plan();
  };
  LazySearch::Status status;
  std::size_t expanded = 0;
  const std::vector<Event> plan = solve({}, -1, &status, &expanded);
  ASSERT_EQ(status, LazySearch::Status::kSolved);
  ASSERT_GE(plan.size(), 8u);

  // The plan's second half, searched again by weighted A*, is another one,
  // after the same first half. The first event a plain weighted A* search
  // takes is not the greedy plan's.
  const std::span<const Event> half(plan.data(), plan.size() / 2);
  const std::vector<Event> completed = solve(half, 3, &status, &expanded);
  ASSERT_EQ(status, LazySearch::Status::kSolved);
  ASSERT_GT(completed.size(), half.size());
  for (std::size_t i = 0; i < half.size(); ++i) EXPECT_EQ(completed[i].snap, half[i].snap) << i;
  const std::vector<Event> unforced = solve({}, 3, &status, &expanded);
  ASSERT_EQ(status, LazySearch::Status::kSolved);
  bool differs = false;
  for (std::size_t i = 0; i < half.size() && i < unforced.size(); ++i) {
    differs = differs || unforced[i].snap != half[i].snap;
  }
  EXPECT_TRUE(differs) << "the prefix changed nothing to test";

  // The end of the first plan's first start cannot happen in the initial
  // state: nothing runs there.
  ASSERT_EQ(plan[0].snap % 2, 0) << "the plan begins with a start";
  const Event end_first{plan[0].snap + 1};
  solve(std::span<const Event>(&end_first, 1), 3, &status, &expanded);
  EXPECT_EQ(status, LazySearch::Status::kExhausted);
  EXPECT_EQ(expanded, 1u);
}

}  // namespace
}  // namespace seaplan::search
