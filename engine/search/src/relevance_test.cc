#include "relevance.h"

#include <gtest/gtest.h>

#include <string>

#include "seaplan/task/grounder.h"
#include "search_test_util.h"

namespace seaplan::search {
namespace {

constexpr char kDomain[] = R"(
(define (domain rel)
  (:requirements :strips :typing :durative-actions :negative-preconditions :numeric-fluents)
  (:types item)
  (:predicates (made ?i - item) (packed ?i - item) (blocked) (lamp))
  (:functions (fuel))
  (:durative-action make
    :parameters (?i - item) :duration (= ?duration 1)
    :condition (and (at start (not (blocked))) (at start (>= (fuel) 1)))
    :effect (at end (made ?i)))
  (:durative-action pack
    :parameters (?i - item) :duration (= ?duration 1)
    :condition (at start (made ?i))
    :effect (at end (packed ?i)))
  (:durative-action unblock
    :parameters () :duration (= ?duration 1)
    :condition (at start (lamp))
    :effect (at end (not (blocked))))
  (:durative-action block
    :parameters () :duration (= ?duration 1)
    :effect (at end (blocked)))
  (:durative-action refuel
    :parameters () :duration (= ?duration 1)
    :effect (at end (increase (fuel) 1)))
  (:durative-action light
    :parameters () :duration (= ?duration 1)
    :effect (at end (lamp))))
)";

constexpr char kProblem[] = R"(
(define (problem p) (:domain rel) (:objects a b - item)
  (:init (blocked) (= (fuel) 0))
  (:goal (packed a)))
)";

bool Relevant(const task::GroundTask& task, const std::vector<bool>& relevant,
              const std::string& name) {
  return relevant[static_cast<std::size_t>(testing::ActionIdOf(task, name))];
}

TEST(RelevanceTest, KeepsWhatTheGoalNeedsThroughFactsNegationsAndNumbers) {
  auto loaded = task::LoadTask(kDomain, kProblem);
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
  const task::GroundTask& task = *loaded.task;
  const std::vector<bool> relevant = RelevantActions(task);
  EXPECT_TRUE(Relevant(task, relevant, "(pack a)"));
  EXPECT_TRUE(Relevant(task, relevant, "(make a)"));
  // Nothing needs (packed b) or (made b).
  EXPECT_FALSE(Relevant(task, relevant, "(pack b)"));
  EXPECT_FALSE(Relevant(task, relevant, "(make b)"));
  // make needs (not (blocked)): its deleter is relevant, and the condition
  // of that deleter too; adding (blocked) only hurts, so block is not.
  EXPECT_TRUE(Relevant(task, relevant, "(unblock)"));
  EXPECT_TRUE(Relevant(task, relevant, "(light)"));
  EXPECT_FALSE(Relevant(task, relevant, "(block)"));
  // make reads (fuel).
  EXPECT_TRUE(Relevant(task, relevant, "(refuel)"));
}

}  // namespace
}  // namespace seaplan::search
