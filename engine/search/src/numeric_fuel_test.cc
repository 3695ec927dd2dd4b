// Zenotravel in miniature: the relaxed plan must count the refuel a flight
// needs, and a flight from a city to itself (duration 0) is no successor.
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "heuristics/relaxed_plan_heuristic.h"
#include "seaplan/task/grounder.h"
#include "search_test_util.h"
#include "snap_task.h"
#include "state_registry.h"
#include "transitions.h"

namespace seaplan::search {
namespace {

constexpr char kDomain[] = R"(
(define (domain fuel)
  (:requirements :typing :durative-actions :fluents)
  (:types plane city)
  (:predicates (at ?p - plane ?c - city))
  (:functions (fuel ?p - plane) (capacity ?p - plane) (distance ?a ?b - city) (burnt))
  (:durative-action fly
    :parameters (?p - plane ?a ?b - city)
    :duration (= ?duration (/ (distance ?a ?b) 100))
    :condition (and (at start (at ?p ?a)) (at start (>= (fuel ?p) (distance ?a ?b))))
    :effect (and (at start (not (at ?p ?a))) (at end (at ?p ?b))
                 (at end (decrease (fuel ?p) (distance ?a ?b)))
                 (at end (increase (burnt) (distance ?a ?b)))))
  (:durative-action refuel
    :parameters (?p - plane ?c - city)
    :duration (= ?duration 2)
    :condition (and (at start (< (fuel ?p) (capacity ?p))) (over all (at ?p ?c)))
    :effect (at end (assign (fuel ?p) (capacity ?p)))))
)";

// Fuel 100 suffices for x-y (100) but not for y-z (300) without a refuel.
constexpr char kProblem[] = R"(
(define (problem fuel-1) (:domain fuel)
  (:objects p - plane x y z - city)
  (:init (at p y) (= (fuel p) 100) (= (capacity p) 500) (= (burnt) 0)
         (= (distance x x) 0) (= (distance y y) 0) (= (distance z z) 0)
         (= (distance x y) 100) (= (distance y x) 100)
         (= (distance y z) 300) (= (distance z y) 300)
         (= (distance x z) 400) (= (distance z x) 400))
  (:goal (at p z)))
)";

class FuelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = task::LoadTask(kDomain, kProblem);
    ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
    task_ = loaded.task;
    snap_ = std::make_unique<SnapTask>(*task_);
    state_ = testing::InitialState(*task_, *snap_);
  }
  task::ActionId Action(const std::string& display_name) const {
    return testing::ActionIdOf(*task_, display_name);
  }

  std::shared_ptr<const task::GroundTask> task_;
  std::unique_ptr<SnapTask> snap_;
  StateData state_;
};

TEST_F(FuelTest, RelaxedPlanCountsTheRefuelAFlightNeeds) {
  RelaxedPlanHeuristic h(*snap_, 0.001);
  std::vector<SnapId> preferred;
  // Refuel (start, end) and fly y-z (start, end); the refuel is the only
  // helpful start (the flight needs the fuel first).
  EXPECT_EQ(h.Evaluate(state_, &preferred), 4);
  EXPECT_EQ(preferred, std::vector<SnapId>{2 * Action("(refuel p y)")});
}

TEST_F(FuelTest, FlightToTheSameCityIsNoSuccessor) {
  Transitions transitions(*snap_, 0, 0.001);
  StateData next;
  Event stay;
  stay.snap = 2 * Action("(fly p y y)");
  // Duration 0: a durative action needs a positive one and could never end.
  EXPECT_FALSE(transitions.Apply(state_, &stay, &next));
  Event go;
  go.snap = 2 * Action("(fly p y x)");
  EXPECT_TRUE(transitions.Apply(state_, &go, &next));
  EXPECT_NEAR(go.min_duration_s, 1.0, 1e-9);
}

}  // namespace
}  // namespace seaplan::search
