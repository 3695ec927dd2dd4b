#include "object_symmetry.h"

#include <gtest/gtest.h>

#include "seaplan/search/planner.h"
#include "search_test_util.h"

namespace seaplan::search {
namespace {

using testing::ActionIdOf;
using testing::FactIdOf;
using testing::InitialState;
using testing::LoadTaskOrFail;

// A hoist carries crates between slots; the goal names crates a and b
// alike and crate c apart (it must reach s3), and slot s3 is connected
// differently from s1 and s2.
constexpr std::string_view kDomain = R"(
(define (domain slots)
  (:requirements :typing :durative-actions)
  (:types crate slot)
  (:predicates (on ?c - crate ?s - slot) (clear ?s - slot) (holding ?c - crate) (free)
               (link ?s1 ?s2 - slot) (done ?c - crate))
  (:durative-action lift
    :parameters (?c - crate ?s - slot)
    :duration (= ?duration 2)
    :condition (and (at start (on ?c ?s)) (at start (free)))
    :effect (and (at start (not (on ?c ?s))) (at start (not (free))) (at end (clear ?s))
                 (at end (holding ?c))))
  (:durative-action drop
    :parameters (?c - crate ?s - slot)
    :duration (= ?duration 2)
    :condition (and (at start (holding ?c)) (at start (clear ?s)))
    :effect (and (at start (not (clear ?s))) (at start (not (holding ?c)))
                 (at end (on ?c ?s)) (at end (free)) (at end (done ?c)))))
)";

constexpr std::string_view kProblem = R"(
(define (problem three)
  (:domain slots)
  (:objects a b c - crate s1 s2 s3 s4 - slot)
  (:init (on a s1) (on b s2) (on c s4) (clear s3) (free) (link s1 s2) (link s2 s1))
  (:goal (and (done a) (done b) (on c s3))))
)";

TEST(ObjectSymmetryTest, FindsTheCratesTheGoalTreatsAlike) {
  auto task = LoadTaskOrFail(kDomain, kProblem);
  ASSERT_NE(task, nullptr);
  SnapTask snap(*task);
  ObjectSymmetry symmetry(snap);
  ASSERT_TRUE(symmetry.active());
  // {a, b}; the slots are all alike to the actions (link is read by none),
  // and the goal names none of s1, s2, s4 but does name s3: {s1, s2, s4}.
  EXPECT_EQ(symmetry.num_classes(), 2);
  EXPECT_EQ(symmetry.num_symmetric_objects(), 5);
}

TEST(ObjectSymmetryTest, StatesThatSwapInterchangeableCratesShareTheirImage) {
  auto task = LoadTaskOrFail(kDomain, kProblem);
  ASSERT_NE(task, nullptr);
  SnapTask snap(*task);
  ObjectSymmetry symmetry(snap);
  const StateData initial = InitialState(*task, snap);

  // a lifted from s1 (running), b on s2; and the same with a and b
  // swapped: b lifted from s1, a on s2.
  StateData x = initial, y = initial;
  x.Clear(FactIdOf(*task, "(on a s1)"));
  x.Clear(FactIdOf(*task, "(free)"));
  x.running.push_back({ActionIdOf(*task, "(lift a s1)"), 2.0, 2.0});
  y.Clear(FactIdOf(*task, "(on a s1)"));
  y.Clear(FactIdOf(*task, "(on b s2)"));
  y.Set(FactIdOf(*task, "(on a s2)"));
  y.Clear(FactIdOf(*task, "(free)"));
  y.running.push_back({ActionIdOf(*task, "(lift b s1)"), 2.0, 2.0});
  StateData cx, cy;
  symmetry.Canonicalize(x, &cx);
  symmetry.Canonicalize(y, &cy);
  EXPECT_EQ(cx.facts, cy.facts);
  EXPECT_EQ(cx.running, cy.running);

  // Crate c is not interchangeable with a (the goal sends c to s3): a done
  // and b done share their image, a done and c done do not.
  // (With a on s1 and b on s2 the images of "a done" and "b done" would
  // differ: those states are symmetric only by swapping the slots as
  // well, and the classes are renamed one after the other.)
  StateData held = initial;
  held.Clear(FactIdOf(*task, "(on a s1)"));
  held.Clear(FactIdOf(*task, "(on b s2)"));
  held.Set(FactIdOf(*task, "(holding a)"));
  held.Set(FactIdOf(*task, "(holding b)"));
  StateData done_a = held, done_b = held, done_c = held;
  done_a.Set(FactIdOf(*task, "(done a)"));
  done_b.Set(FactIdOf(*task, "(done b)"));
  done_c.Set(FactIdOf(*task, "(done c)"));
  StateData ca, cb, cc;
  symmetry.Canonicalize(done_a, &ca);
  symmetry.Canonicalize(done_b, &cb);
  symmetry.Canonicalize(done_c, &cc);
  EXPECT_EQ(ca.facts, cb.facts);
  EXPECT_NE(ca.facts, cc.facts);

  // The image is a state of the task: as many facts and running actions.
  auto count = [](const StateData& s) {
    int n = 0;
    for (auto w : s.facts) n += __builtin_popcountll(w);
    return n;
  };
  EXPECT_EQ(count(cx), count(x));
  EXPECT_EQ(cx.running.size(), 1u);
}

// The planner solves the task with the reduction on and off (every plan it
// returns has passed the validator); its statistics name the classes only
// when the reduction is on.
TEST(ObjectSymmetryTest, PlannerSolvesWithAndWithoutTheReduction) {
  for (const bool on : {true, false}) {
    PlannerOptions options;
    options.time_limit_s = 10;
    options.anytime = false;
    options.symmetry_reduction = on;
    const PlanResult result = Solve(kDomain, kProblem, options, StopToken());
    EXPECT_EQ(result.status, PlanStatus::kSolvedSatisficing) << "reduction " << on;
    EXPECT_FALSE(result.plan.steps.empty());
    EXPECT_EQ(result.stats.symmetric_objects, on ? 5 : 0);
    EXPECT_EQ(result.stats.symmetry_classes, on ? 2 : 0);
    if (!on) {
      EXPECT_EQ(result.stats.symmetric_drops, 0u);
    }
  }
}

// One hoist cannot hold two crates, so this goal is unreachable, though
// the relaxed plan (which never loses `free`) reaches it: the search must
// exhaust every arrangement of the crates. Crates a and b, crates c and d,
// and the slots are classes; with the reduction every permutation of an
// expanded arrangement is dropped (counted), the space shrinks, and the
// result is still a proof.
TEST(ObjectSymmetryTest, PermutedStatesAreDroppedAndTheProofStands) {
  constexpr std::string_view kTwoInHand = R"(
(define (problem two-in-hand)
  (:domain slots)
  (:objects a b c d - crate s1 s2 s3 s4 s5 - slot)
  (:init (on a s1) (on b s2) (on c s3) (on d s4) (clear s5) (free))
  (:goal (and (holding a) (holding b))))
)";
  PlannerOptions options;
  options.time_limit_s = 30;
  options.anytime = false;
  const PlanResult with = Solve(kDomain, kTwoInHand, options, StopToken());
  options.symmetry_reduction = false;
  const PlanResult without = Solve(kDomain, kTwoInHand, options, StopToken());
  ASSERT_EQ(with.status, PlanStatus::kUnsolvableProven) << with.message;
  ASSERT_EQ(without.status, PlanStatus::kUnsolvableProven) << without.message;
  EXPECT_EQ(with.stats.symmetry_classes, 3);
  EXPECT_GT(with.stats.symmetric_drops, 0u);
  EXPECT_EQ(without.stats.symmetric_drops, 0u);
  EXPECT_LT(2 * with.stats.expanded, without.stats.expanded);
}

}  // namespace
}  // namespace seaplan::search
