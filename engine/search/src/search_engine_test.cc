#include "search_engine.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace seaplan::search
