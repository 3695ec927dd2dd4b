#include "landmarks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "../mutex_groups.h"
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

// A task's snap task, relaxed operators and landmark graph, with lookups
// by name.
struct Landmarks {
  std::shared_ptr<const task::GroundTask> task;
  std::unique_ptr<SnapTask> snap;
  std::unique_ptr<RelaxedPlanHeuristic> relaxed;
  std::unique_ptr<LandmarkGraph> graph;

  Landmarks(std::string_view domain, std::string_view problem) {
    task = testing::LoadTaskOrFail(domain, problem);
    if (!task) return;
    snap = std::make_unique<SnapTask>(*task);
    relaxed = std::make_unique<RelaxedPlanHeuristic>(*snap, 0.001);
    graph = std::make_unique<LandmarkGraph>(*snap, *relaxed);
  }
  std::int32_t FactId(const std::string& name) const { return testing::FactIdOf(*task, name); }
  // started(a) as a relaxed fact.
  std::int32_t StartedId(const std::string& action) const {
    return snap->num_facts() + testing::ActionIdOf(*task, action);
  }
  int Fact(const std::string& name) const { return graph->IndexOf(FactId(name)); }
  int Started(const std::string& action) const { return graph->IndexOf(StartedId(action)); }
  // The landmark whose members are exactly `relaxed_facts`, -1 when none is.
  int Find(std::vector<std::int32_t> relaxed_facts) const {
    std::sort(relaxed_facts.begin(), relaxed_facts.end());
    for (int i = 0; i < graph->size(); ++i) {
      const auto m = graph->members(i);
      if (std::equal(m.begin(), m.end(), relaxed_facts.begin(), relaxed_facts.end())) return i;
    }
    return -1;
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
  const Landmarks h(kDomain, kProblem);
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
  const Landmarks h(kDomain, kProblem);
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

// Crates stacked by one hoist (depots' lift and drop without places): a,
// b and c each on its own pallet, to be stacked a on b on c. A drop keeps
// its target clear over all and ends by making it not clear.
constexpr char kStackDomain[] = R"(
(define (domain stack)
  (:requirements :typing :durative-actions)
  (:types hoist surface - object crate pallet - surface)
  (:predicates (on ?c - crate ?s - surface) (clear ?s - surface) (available ?h - hoist)
               (lifting ?h - hoist ?c - crate))
  (:durative-action lift :parameters (?h - hoist ?c - crate ?s - surface)
    :duration (= ?duration 1)
    :condition (and (at start (available ?h)) (at start (on ?c ?s)) (at start (clear ?c)))
    :effect (and (at start (not (available ?h))) (at start (lifting ?h ?c))
                 (at start (not (clear ?c))) (at start (clear ?s)) (at start (not (on ?c ?s)))))
  (:durative-action drop :parameters (?h - hoist ?c - crate ?s - surface)
    :duration (= ?duration 1)
    :condition (and (over all (clear ?s)) (over all (lifting ?h ?c)))
    :effect (and (at end (available ?h)) (at end (not (lifting ?h ?c)))
                 (at end (not (clear ?s))) (at end (clear ?c)) (at end (on ?c ?s))))
))";

constexpr char kStackProblem[] = R"(
(define (problem abc) (:domain stack)
  (:objects h - hoist a b c - crate p1 p2 p3 - pallet)
  (:init (available h) (on a p1) (on b p2) (on c p3) (clear a) (clear b) (clear c))
  (:goal (and (on a b) (on b c))))
)";

// b goes on c before a goes on b: every drop of b adds (clear b), which
// cannot hold with a on b. Seeing that needs the drop's over-all (clear ?s)
// as what its end requires, or (clear b) and (on a b) share no group.
TEST(LandmarksTest, ACrateGoesOnItsTargetBeforeAnotherGoesOnIt) {
  auto task = testing::LoadTaskOrFail(kStackDomain, kStackProblem);
  ASSERT_NE(task, nullptr);
  const SnapTask snap(*task);
  const RelaxedPlanHeuristic relaxed(snap, 0.001);
  LandmarkGraph graph(snap, relaxed);
  const auto fact = [&](const char* name) { return testing::FactIdOf(*task, name); };
  const MutexGroups mutex(*task);
  EXPECT_TRUE(mutex.Mutex(fact("(clear b)"), fact("(on a b)")));
  const int a_on_b = graph.IndexOf(fact("(on a b)")), b_on_c = graph.IndexOf(fact("(on b c)"));
  ASSERT_GE(a_on_b, 0);
  ASSERT_GE(b_on_c, 0);
  const auto has_parent = [&](int i, int parent) {
    const auto p = graph.parents(i);
    return std::find(p.begin(), p.end(), parent) != p.end();
  };
  EXPECT_FALSE(has_parent(a_on_b, b_on_c));
  const LandmarkGraph plain(snap, relaxed);  // without them
  EXPECT_GE(graph.AddReasonableOrderings(relaxed, mutex), 1);
  EXPECT_TRUE(has_parent(a_on_b, b_on_c));
  // Not the other way round: a drop of a adds (clear a), which can hold
  // with b on c.
  EXPECT_FALSE(has_parent(b_on_c, a_on_b));

  // Every landmark but the two accepted; then a on b: with the ordering it
  // is not accepted before b is on c, without it it is.
  const auto accepted_after = [&](const LandmarkGraph& g, const StateData& state, int i) {
    LandmarkCounter counter(g);
    std::vector<std::uint64_t> most(counter.words(), ~std::uint64_t{0}), acc(counter.words());
    for (int x : {a_on_b, b_on_c})
      most[static_cast<std::size_t>(x) >> 6] &= ~(std::uint64_t{1} << (x & 63));
    counter.Update(most, state, acc);
    return ((acc[static_cast<std::size_t>(i) >> 6] >> (i & 63)) & 1u) != 0;
  };
  // The initial state with `crate` moved from `from` onto `to`.
  const auto moved = [&](const std::string& crate, const std::string& from, const std::string& to) {
    StateData state = testing::InitialState(*task, snap);
    state.Clear(testing::FactIdOf(*task, "(on " + crate + " " + from + ")"));
    state.Clear(testing::FactIdOf(*task, "(clear " + to + ")"));
    state.Set(testing::FactIdOf(*task, "(on " + crate + " " + to + ")"));
    state.Set(testing::FactIdOf(*task, "(clear " + from + ")"));
    return state;
  };
  const StateData wrong = moved("a", "p1", "b");
  EXPECT_FALSE(accepted_after(graph, wrong, a_on_b));
  EXPECT_TRUE(accepted_after(plain, wrong, a_on_b));
  EXPECT_TRUE(accepted_after(graph, moved("b", "p2", "c"), b_on_c));
}

// a on b and b on a (no plan reaches both, but the relaxation does): each
// drop uncovers the crate it drops, so each goal would be ordered before
// the other. Only one of the two orderings is kept: a cycle would leave
// neither goal ever accepted.
TEST(LandmarksTest, ReasonableOrderingsCloseNoCycle) {
  const std::string problem = R"(
(define (problem ab) (:domain stack)
  (:objects h - hoist a b - crate p1 p2 - pallet)
  (:init (available h) (on a p1) (on b p2) (clear a) (clear b))
  (:goal (and (on a b) (on b a))))
)";
  auto task = testing::LoadTaskOrFail(kStackDomain, problem);
  ASSERT_NE(task, nullptr);
  const SnapTask snap(*task);
  const RelaxedPlanHeuristic relaxed(snap, 0.001);
  LandmarkGraph graph(snap, relaxed);
  const MutexGroups mutex(*task);
  const int a_on_b = graph.IndexOf(testing::FactIdOf(*task, "(on a b)"));
  const int b_on_a = graph.IndexOf(testing::FactIdOf(*task, "(on b a)"));
  ASSERT_GE(a_on_b, 0);
  ASSERT_GE(b_on_a, 0);
  EXPECT_GE(graph.AddReasonableOrderings(relaxed, mutex), 1);
  const auto has_parent = [&](int i, int parent) {
    const auto p = graph.parents(i);
    return std::find(p.begin(), p.end(), parent) != p.end();
  };
  EXPECT_NE(has_parent(a_on_b, b_on_a), has_parent(b_on_a, a_on_b));
}

// One package, two trucks: t1 where the package is, t2 elsewhere. No fact
// but the package's own is a landmark: either truck can carry it. What
// every plan does all the same, whichever truck, is disjunctive: some
// truck holds the package, some unload of it at b starts, some truck is at
// b, some load of it starts.
constexpr char kHaulDomain[] = R"(
(define (domain haul)
  (:requirements :typing :durative-actions)
  (:types truck package place)
  (:predicates (at ?t - truck ?l - place) (pkg-at ?p - package ?l - place)
               (in ?p - package ?t - truck) (road ?a ?b - place))
  (:durative-action drive :parameters (?t - truck ?a ?b - place) :duration (= ?duration 2)
    :condition (and (at start (at ?t ?a)) (at start (road ?a ?b)))
    :effect (and (at start (not (at ?t ?a))) (at end (at ?t ?b))))
  (:durative-action load :parameters (?t - truck ?p - package ?l - place) :duration (= ?duration 1)
    :condition (and (at start (pkg-at ?p ?l)) (over all (at ?t ?l)))
    :effect (and (at start (not (pkg-at ?p ?l))) (at end (in ?p ?t))))
  (:durative-action unload :parameters (?t - truck ?p - package ?l - place)
    :duration (= ?duration 1)
    :condition (and (at start (in ?p ?t)) (over all (at ?t ?l)))
    :effect (and (at start (not (in ?p ?t))) (at end (pkg-at ?p ?l)))))
)";

constexpr char kHaulProblem[] = R"(
(define (problem one) (:domain haul)
  (:objects t1 t2 - truck p - package a b c - place)
  (:init (at t1 a) (at t2 c) (pkg-at p a)
         (road a b) (road b a) (road a c) (road c a) (road c b) (road b c))
  (:goal (pkg-at p b)))
)";

TEST(LandmarksTest, FindsDisjunctiveLandmarksWhereAnyOfSeveralAgentsWill) {
  const Landmarks h(kHaulDomain, kHaulProblem);
  ASSERT_TRUE(h.graph);
  const LandmarkGraph& graph = *h.graph;
  const int goal = h.Fact("(pkg-at p b)");
  const int held = h.Find({h.FactId("(in p t1)"), h.FactId("(in p t2)")});
  const int unloading = h.Find({h.StartedId("(unload t1 p b)"), h.StartedId("(unload t2 p b)")});
  const int truck_at_b = h.Find({h.FactId("(at t1 b)"), h.FactId("(at t2 b)")});
  ASSERT_GE(goal, 0);
  ASSERT_GE(held, 0);
  ASSERT_GE(unloading, 0);
  ASSERT_GE(truck_at_b, 0);
  EXPECT_EQ(graph.num_disjunctive(), graph.size() - 2);  // besides (pkg-at p b), (pkg-at p a)
  // A truck at a does not make one: t1 is there from the start.
  EXPECT_EQ(h.Find({h.FactId("(at t1 a)"), h.FactId("(at t2 a)")}), -1);
  std::vector<int> goal_parents{unloading, truck_at_b};
  std::sort(goal_parents.begin(), goal_parents.end());
  EXPECT_EQ(h.Parents(goal), goal_parents);
  const auto unloading_parents = h.Parents(unloading);
  EXPECT_TRUE(std::binary_search(unloading_parents.begin(), unloading_parents.end(), held));
  EXPECT_EQ(graph.added_by(h.Start("(unload t2 p b)")).size(), 1u);

  // Holding in either truck: the landmark holds, and loading is progress
  // the count sees (with fact landmarks alone it saw none).
  StateData state = testing::InitialState(*h.task, *h.snap);
  EXPECT_FALSE(graph.Holds(held, state));
  LandmarkCounter counter(graph);
  std::vector<std::uint64_t> at_start(counter.words()), loading(counter.words()),
      loaded(counter.words());
  const int h0 = counter.Update({}, state, at_start);
  state.Clear(h.FactId("(pkg-at p a)"));
  state.running.push_back({testing::ActionIdOf(*h.task, "(load t1 p a)"), 1.0, 1.0});
  const int h1 = counter.Update(at_start, state, loading);
  state.running.clear();
  state.Set(h.FactId("(in p t1)"));
  EXPECT_TRUE(graph.Holds(held, state));
  const int h2 = counter.Update(loading, state, loaded);
  EXPECT_LT(h1, h0);
  EXPECT_LT(h2, h1);
  EXPECT_TRUE((loaded[static_cast<std::size_t>(held) >> 6] >> (held & 63)) & 1u);
}

// A match from either drawer lights the lamp. "Some fetch of a match
// starts" is a disjunctive landmark of the goal (have-match), but not of
// (have-match) below the goal (lit): it would only say again that the
// fact landmark is on its way.
TEST(LandmarksTest, RunningActionsAreDisjunctiveLandmarksOnlyBelowGoalsAndDisjunctions) {
  const std::string domain = R"(
(define (domain lamp)
  (:requirements :typing :durative-actions)
  (:types drawer)
  (:predicates (in ?d - drawer) (have-match) (lit))
  (:durative-action fetch :parameters (?d - drawer) :duration (= ?duration 1)
    :condition (at start (in ?d)) :effect (at end (have-match)))
  (:durative-action light :parameters () :duration (= ?duration 1)
    :condition (at start (have-match)) :effect (at end (lit))))
)";
  const auto problem = [](const char* goal) {
    return std::string(R"((define (problem p) (:domain lamp) (:objects d1 d2 - drawer)
      (:init (in d1) (in d2)) (:goal )") +
           goal + "))";
  };
  for (const bool match_is_goal : {true, false}) {
    const Landmarks h(domain, problem(match_is_goal ? "(have-match)" : "(lit)"));
    ASSERT_TRUE(h.graph);
    EXPECT_GE(h.Fact("(have-match)"), 0);
    const int fetching = h.Find({h.StartedId("(fetch d1)"), h.StartedId("(fetch d2)")});
    EXPECT_EQ(fetching >= 0, match_is_goal) << (match_is_goal ? "goal (have-match)" : "goal (lit)");
  }
}

}  // namespace
}  // namespace seaplan::search
