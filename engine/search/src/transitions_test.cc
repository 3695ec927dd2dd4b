// Transitions: a start is refused beside a running action when neither
// could end while the other runs (each end breaks an invariant of the
// other), and only then; the starts a state offers are every start whose
// conditions hold, in action order, whatever the index groups them by.
#include "transitions.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "search_test_util.h"

namespace seaplan::search {
namespace {

using testing::ActionIdOf;
using testing::InitialState;
using testing::LoadTaskOrFail;

constexpr char kDomain[] = R"(
(define (domain hoist)
  (:requirements :typing :durative-actions)
  (:types crate place)
  (:predicates (lifting ?c - crate) (on ?c - crate ?p - place) (loaded ?c - crate)
               (painted ?c - crate))
  ; Both end the lifting that both need over all.
  (:durative-action drop :parameters (?c - crate ?p - place) :duration (= ?duration 1)
    :condition (over all (lifting ?c))
    :effect (and (at end (not (lifting ?c))) (at end (on ?c ?p))))
  (:durative-action load :parameters (?c - crate) :duration (= ?duration 2)
    :condition (over all (lifting ?c))
    :effect (and (at end (not (lifting ?c))) (at end (loaded ?c))))
  ; Needs the lifting over all but leaves it: it can end first.
  (:durative-action paint :parameters (?c - crate) :duration (= ?duration 3)
    :condition (over all (lifting ?c))
    :effect (at end (painted ?c))))
)";

constexpr char kProblem[] = R"(
(define (problem two-crates) (:domain hoist)
  (:objects c1 c2 - crate p1 p2 - place)
  (:init (lifting c1) (lifting c2))
  (:goal (and (on c1 p1) (painted c1))))
)";

class TransitionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    task_ = LoadTaskOrFail(kDomain, kProblem);
    ASSERT_TRUE(task_);
    snap_ = std::make_unique<SnapTask>(*task_);
    transitions_ = std::make_unique<Transitions>(*snap_, 0, 0.001);
    initial_ = InitialState(*task_, *snap_);
  }
  // `first`'s start applied to the initial state, then `second`'s start:
  // whether the second applies.
  bool StartsBeside(const char* first, const char* second) {
    Event e1{2 * ActionIdOf(*task_, first), 0, 0};
    StateData s1, s2;
    EXPECT_TRUE(transitions_->Apply(initial_, &e1, &s1)) << first;
    Event e2{2 * ActionIdOf(*task_, second), 0, 0};
    return transitions_->Apply(s1, &e2, &s2);
  }

  std::shared_ptr<const task::GroundTask> task_;
  std::unique_ptr<SnapTask> snap_;
  std::unique_ptr<Transitions> transitions_;
  StateData initial_;
};

TEST_F(TransitionsTest, AStartIsRefusedBesideAnActionItCouldNeverEndBefore) {
  EXPECT_FALSE(StartsBeside("(drop c1 p1)", "(load c1)"));
  EXPECT_FALSE(StartsBeside("(load c1)", "(drop c1 p1)"));
  EXPECT_FALSE(StartsBeside("(drop c1 p1)", "(drop c1 p2)"));
}

TEST_F(TransitionsTest, AStartIsAllowedWhenOneOfTheTwoCanEndFirst) {
  // The paint can end while the drop runs; then the drop ends.
  EXPECT_TRUE(StartsBeside("(drop c1 p1)", "(paint c1)"));
  EXPECT_TRUE(StartsBeside("(paint c1)", "(drop c1 p1)"));
  // Another crate's lifting: no conflict at all.
  EXPECT_TRUE(StartsBeside("(drop c1 p1)", "(load c2)"));
}

TEST_F(TransitionsTest, ThePlannerStillSolvesTheTask) {
  const PlanResult r = testing::SolveFirstPlan(*task_);
  EXPECT_EQ(r.status, PlanStatus::kSolvedSatisficing) << r.message;
}

constexpr char kDriveDomain[] = R"(
(define (domain drive)
  (:requirements :typing :durative-actions)
  (:types truck driver place)
  (:predicates (at ?t - truck ?p - place) (driving ?d - driver ?t - truck))
  (:durative-action drive :parameters (?t - truck ?from ?to - place ?d - driver)
    :duration (= ?duration 2)
    :condition (and (at start (at ?t ?from)) (at start (driving ?d ?t)))
    :effect (and (at start (not (at ?t ?from))) (at end (at ?t ?to))))
  ; One condition fact only: a group of its own under the truck's place.
  (:durative-action wait :parameters (?t - truck ?p - place) :duration (= ?duration 1)
    :condition (at start (at ?t ?p))
    :effect (at end (at ?t ?p)))
  ; Needs the driving: more starts need it than a place, so the drives are
  ; indexed under the truck's place and grouped by driver, an order that is
  ; not the action order.
  (:durative-action honk :parameters (?d - driver ?t - truck ?p - place)
    :duration (= ?duration 1)
    :condition (at start (driving ?d ?t))
    :effect (at end (driving ?d ?t))))
)";

constexpr char kDriveProblem[] = R"(
(define (problem one-truck) (:domain drive)
  (:objects t1 - truck d1 d2 d3 - driver p1 p2 p3 - place)
  ; d3's driving first: its fact comes before d2's, its drives after, so
  ; the groups by driver are not in action order.
  (:init (driving d3 t1) (at t1 p1) (driving d2 t1))
  (:goal (at t1 p3)))
)";

TEST(TransitionsCandidatesTest, EveryStartWhoseConditionsHoldInActionOrder) {
  const auto task = LoadTaskOrFail(kDriveDomain, kDriveProblem);
  ASSERT_TRUE(task);
  const SnapTask snap(*task);
  const Transitions transitions(snap, 0, 0.001);
  const StateData state = InitialState(*task, snap);
  std::vector<Event> candidates;
  transitions.Candidates(state, &candidates);
  auto is_honk = [&](SnapId s) {
    return task->actions[static_cast<std::size_t>(s / 2)].name == "honk";
  };
  // Starts come in the order of the facts they are indexed under, and in
  // action order under one: the drives and the wait share the truck's place.
  std::vector<SnapId> starts, at_place;
  for (const Event& e : candidates) {
    if (e.is_til() || (e.snap & 1) != 0) continue;
    starts.push_back(e.snap);
    if (!is_honk(e.snap)) at_place.push_back(e.snap);
  }
  std::vector<SnapId> expected, expected_at_place;
  for (int a = 0; a < snap.num_actions(); ++a) {
    if (snap.Pruned(a) ||
        !ConditionHolds(task->actions[static_cast<std::size_t>(a)].at_start, state))
      continue;
    expected.push_back(2 * a);
    if (!is_honk(2 * a)) expected_at_place.push_back(2 * a);
  }
  // Drives by d2 and d3 to each of the three places (p1 too: nothing
  // forbids it), the wait at p1 and the honks by d2 and d3; none by d1,
  // who is not aboard, and no drive from another place.
  EXPECT_EQ(expected.size(), 13u);
  EXPECT_EQ(expected_at_place.size(), 7u);
  EXPECT_EQ(at_place, expected_at_place);
  std::sort(starts.begin(), starts.end());
  EXPECT_EQ(starts, expected);
}

}  // namespace
}  // namespace seaplan::search
