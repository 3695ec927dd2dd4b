#include "landmarks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "../search_test_util.h"

namespace seaplan::search {
namespace {

// Two ways in (the door, the window with a ladder), both through the
// unlocked door's (open), which needs the key, found at home or bought
// with money earned: (open), the unlock started, (key) and (home) are
// landmarks of (inside); the ladder, the money and either way of getting
// the key are not. (leave) keeps (home) from being folded away as static.
constexpr char kDomain[] = R"(
(define (domain house)
  (:requirements :strips :durative-actions)
  (:predicates (home) (money) (key) (open) (inside) (ladder))
  (:durative-action find-key :parameters () :duration (= ?duration 1)
    :condition (at start (home)) :effect (at end (key)))
  (:durative-action earn :parameters () :duration (= ?duration 1)
    :effect (at end (money)))
  (:durative-action buy-key :parameters () :duration (= ?duration 1)
    :condition (at start (money)) :effect (at end (key)))
  (:durative-action unlock :parameters () :duration (= ?duration 1)
    :condition (and (at start (key)) (over all (home))) :effect (at end (open)))
  (:durative-action enter :parameters () :duration (= ?duration 1)
    :condition (at start (open)) :effect (at end (inside)))
  (:durative-action leave :parameters () :duration (= ?duration 1)
    :effect (at end (not (home))))
  (:durative-action fetch-ladder :parameters () :duration (= ?duration 1)
    :effect (at end (ladder)))
  (:durative-action climb :parameters () :duration (= ?duration 1)
    :condition (and (at start (ladder)) (at start (open))) :effect (at end (inside))))
)";

constexpr char kProblem[] = R"(
(define (problem p) (:domain house) (:init (home)) (:goal (inside)))
)";

struct House {
  std::shared_ptr<const task::GroundTask> task;
  std::unique_ptr<SnapTask> snap;
  std::unique_ptr<RelaxedPlanHeuristic> relaxed;
  std::unique_ptr<LandmarkGraph> graph;

  House() {
    task = testing::LoadTaskOrFail(kDomain, kProblem);
    if (!task) return;
    snap = std::make_unique<SnapTask>(*task);
    relaxed = std::make_unique<RelaxedPlanHeuristic>(*snap, 0.001);
    graph = std::make_unique<LandmarkGraph>(*snap, *relaxed);
  }
  int Fact(const std::string& name) const { return graph->IndexOf(testing::FactIdOf(*task, name)); }
  // started(a) as a relaxed fact.
  int Started(const std::string& action) const {
    return graph->IndexOf(snap->num_facts() + testing::ActionIdOf(*task, action));
  }
  SnapId Start(const std::string& action) const { return 2 * testing::ActionIdOf(*task, action); }
  SnapId End(const std::string& action) const { return Start(action) + 1; }
  std::vector<int> Parents(int i) const {
    std::vector<int> p(graph->parents(i).begin(), graph->parents(i).end());
    std::sort(p.begin(), p.end());
    return p;
  }
};

TEST(LandmarksTest, FindsTheFactsEveryRelaxedPlanNeedsAndTheirGreedyNecessaryOrderings) {
  House h;
  ASSERT_TRUE(h.graph);
  const int inside = h.Fact("(inside)"), open = h.Fact("(open)"), key = h.Fact("(key)");
  const int home = h.Fact("(home)"), unlocking = h.Started("(unlock)");
  for (int i : {inside, open, key, home, unlocking}) EXPECT_GE(i, 0);
  EXPECT_EQ(h.graph->size(), 5);
  EXPECT_LT(h.Fact("(ladder)"), 0);
  EXPECT_LT(h.Fact("(money)"), 0);
  EXPECT_LT(h.Started("(enter)"), 0);
  EXPECT_LT(h.Started("(find-key)"), 0);
  EXPECT_TRUE(h.graph->is_goal(inside));
  EXPECT_FALSE(h.graph->is_goal(open));
  // Greedy-necessary: what every first achiever needs.
  // The two ends adding (inside) share no precondition (each needs its own
  // start; (open) is needed at the starts, which are no landmarks).
  EXPECT_TRUE(h.Parents(inside).empty());
  std::vector<int> open_parents{unlocking, home};
  std::sort(open_parents.begin(), open_parents.end());
  EXPECT_EQ(h.Parents(open), open_parents);
  std::vector<int> unlock_parents{key, home};
  std::sort(unlock_parents.begin(), unlock_parents.end());
  EXPECT_EQ(h.Parents(unlocking), unlock_parents);
  EXPECT_TRUE(h.Parents(key).empty());  // found or bought: nothing shared
  EXPECT_TRUE(h.Parents(home).empty());
  EXPECT_EQ(h.graph->num_orderings(), 4);
  // Snaps adding landmarks.
  EXPECT_EQ(h.graph->added_by(h.End("(find-key)")).size(), 1u);
  EXPECT_EQ(h.graph->added_by(h.Start("(unlock)")).size(), 1u);
  EXPECT_TRUE(h.graph->added_by(h.End("(earn)")).empty());
}

TEST(LandmarksTest, CountsLandmarksNotAcceptedAndThoseRequiredAgain) {
  House h;
  ASSERT_TRUE(h.graph);
  LandmarkCounter counter(*h.graph);
  ASSERT_EQ(counter.words(), 1u);
  const StateData initial = testing::InitialState(*h.task, *h.snap);
  std::vector<std::uint64_t> init_acc(1), acc(1), next(1);
  // Only (home) holds: four landmarks to go.
  EXPECT_EQ(counter.Update({}, initial, init_acc), 4);
  EXPECT_EQ(init_acc[0], std::uint64_t{1} << h.Fact("(home)"));
  // The key can be accepted next; the unlock cannot start before it is.
  EXPECT_TRUE(counter.AddsNextLandmark(init_acc, initial, h.End("(find-key)")));
  EXPECT_TRUE(counter.AddsNextLandmark(init_acc, initial, h.End("(buy-key)")));
  EXPECT_FALSE(counter.AddsNextLandmark(init_acc, initial, h.Start("(unlock)")));
  EXPECT_FALSE(counter.AddsNextLandmark(init_acc, initial, h.End("(earn)")));

  // (open) true without the unlock accepted: not accepted (its parent is not).
  StateData s = initial;
  s.Set(testing::FactIdOf(*h.task, "(open)"));
  EXPECT_EQ(counter.Update(init_acc, s, acc), 4);
  EXPECT_FALSE((acc[0] >> h.Fact("(open)")) & 1u);

  // With the key: accepted, three to go, and the unlock is next.
  s = initial;
  s.Set(testing::FactIdOf(*h.task, "(key)"));
  EXPECT_EQ(counter.Update(init_acc, s, acc), 3);
  EXPECT_TRUE(counter.AddsNextLandmark(acc, s, h.Start("(unlock)")));
  EXPECT_FALSE(counter.AddsNextLandmark(acc, s, h.End("(find-key)")));  // the key holds

  // The key lost before the unlock started: required again.
  StateData lost = initial;
  EXPECT_EQ(counter.Update(acc, lost, next), 4);
  // (home) lost while the unlock is not accepted: (home) is required again too.
  lost.Clear(testing::FactIdOf(*h.task, "(home)"));
  EXPECT_EQ(counter.Update(acc, lost, next), 5);

  // The goal accepted and then false again counts once more.
  std::vector<std::uint64_t> all(1, (std::uint64_t{1} << h.graph->size()) - 1);
  // Only (inside) counts: the others are false but their children accepted.
  EXPECT_EQ(counter.Update(all, initial, next), 1);
}

}  // namespace
}  // namespace seaplan::search
