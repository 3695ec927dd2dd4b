// Transitions: a start is refused beside a running action when neither
// could end while the other runs (each end breaks an invariant of the
// other), and only then.
#include "transitions.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace seaplan::search
