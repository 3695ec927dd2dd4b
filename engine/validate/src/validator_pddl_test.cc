// Validator rules on small PDDL domains (engine/validate/testdata) through the
// real parser and grounder: each rule with a valid and an invalid plan.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "absl/strings/str_cat.h"
#include "seaplan/task/grounder.h"
#include "seaplan/testing/shared_data.h"
#include "seaplan/validate/plan.h"
#include "seaplan/validate/validator.h"

namespace seaplan::validate {
namespace {

using ::testing::HasSubstr;
using Kind = ValidationFailure::Kind;

std::string TestData(const std::string& name) {
  return seaplan::testing::ReadFile(seaplan::testing::SourceDir() / "engine" / "validate" /
                                    "testdata" / name);
}

class PddlValidatorTest : public ::testing::Test {
 protected:
  void Load(const std::string& domain, const std::string& problem) {
    loaded_ = task::LoadTask(TestData(domain), TestData(problem));
    ASSERT_TRUE(loaded_.ok()) << loaded_.ErrorText();
    options_.explain_missing_action = ExplainerFor(loaded_);
  }
  ValidationResult Validate(std::string_view plan_text) {
    const auto plan = ParsePlan(plan_text);
    EXPECT_TRUE(plan.ok()) << plan.status();
    if (!plan.ok()) return {};
    return ValidatePlan(*loaded_.task, *plan, options_);
  }
  task::LoadResult loaded_;
  ValidationOptions options_;
};

#define EXPECT_VALID(result) EXPECT_TRUE((result).valid) << (result).ToString()

#define EXPECT_FAILS(result, expected_kind, expected_step)                     \
  do {                                                                         \
    const ValidationResult& r_ = (result);                                     \
    ASSERT_FALSE(r_.valid) << "expected an invalid plan";                      \
    ASSERT_TRUE(r_.first_failure.has_value());                                 \
    EXPECT_EQ(r_.first_failure->kind, (expected_kind)) << r_.ToString();       \
    EXPECT_EQ(r_.first_failure->step_index, (expected_step)) << r_.ToString(); \
  } while (false)

class MatchCellarTest : public PddlValidatorTest {
 protected:
  void SetUp() override { Load("match-cellar-domain.pddl", "match-cellar-problem.pddl"); }
};

TEST_F(MatchCellarTest, MendingInsideTheBurningMatchIsValid) {
  const auto r = Validate(
      "0.000: (light-match m1) [8]\n"
      "0.001: (mend-fuse f1 m1) [5]\n"
      "5.002: (light-match m2) [8]\n"
      "5.003: (mend-fuse f2 m2) [5]\n");
  EXPECT_VALID(r);
  EXPECT_NEAR(r.makespan_s, 13.002, 1e-9);
}

TEST_F(MatchCellarTest, MendingAfterTheMatchIsOutFailsTheOverAllCondition) {
  const auto r = Validate(
      "0.000: (light-match m1) [8]\n"
      "8.001: (mend-fuse f1 m1) [5]\n");
  EXPECT_FAILS(r, Kind::kOverAll, 1);
  EXPECT_EQ(r.first_failure->condition, "(light m1)");
}

TEST_F(MatchCellarTest, MendingThatOutlastsTheMatchIsBrokenByItsEnd) {
  const auto r = Validate(
      "0.000: (light-match m1) [8]\n"
      "0.001: (mend-fuse f1 m1) [5]\n"
      "5.002: (mend-fuse f2 m1) [5]\n");
  EXPECT_FAILS(r, Kind::kOverAll, 2);
  EXPECT_EQ(r.first_failure->other_step_index, 0);
  EXPECT_DOUBLE_EQ(r.first_failure->time_s, 8.0);
}

TEST_F(MatchCellarTest, InvariantsAreNotPartOfTheEpsilonMutex) {
  // The mend's invariant reads (light m1), which the match's start adds; the
  // invariant belongs to neither snap action, so the two starts do not
  // interfere: the mend may start within epsilon of the match, or with it
  // (the state after that happening has the light).
  for (const char* mend_start : {"0.001", "0.0005", "0"}) {
    EXPECT_VALID(
        Validate(absl::StrCat("0: (light-match m1) [8]\n", mend_start,
                              ": (mend-fuse f1 m1) [5]\n"
                              "5.002: (light-match m2) [8]\n5.003: (mend-fuse f2 m2) [5]\n")))
        << mend_start;
  }
  // Snap actions that do interfere still need epsilon: both mends read and
  // delete (handfree) at their starts.
  const auto r = Validate(
      "0: (light-match m1) [8]\n0.001: (mend-fuse f1 m1) [5]\n"
      "0.0015: (mend-fuse f2 m1) [5]\n");
  EXPECT_FAILS(r, Kind::kMutex, 1);
  EXPECT_EQ(r.first_failure->other_action, "(mend-fuse f2 m1)");
  EXPECT_EQ(r.first_failure->condition, "(handfree)");
}

TEST_F(MatchCellarTest, ActionsOutsideTheTaskAreExplained) {
  const auto r = Validate("0: (light-match f1) [8]\n");
  EXPECT_FAILS(r, Kind::kUnknownAction, 0);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("(light-match f1)"));
  EXPECT_THAT(r.first_failure->reason, HasSubstr("f1")) << r.ToString();
  const auto wrong_arity = Validate("0: (light-match) [8]\n");
  EXPECT_FAILS(wrong_arity, Kind::kUnknownAction, 0);
}

TEST_F(MatchCellarTest, AMatchBurnsOnce) {
  const auto r = Validate(
      "0: (light-match m1) [8]\n0.001: (mend-fuse f1 m1) [5]\n"
      "8.001: (light-match m1) [8]\n8.002: (mend-fuse f2 m1) [5]\n");
  EXPECT_FAILS(r, Kind::kAtStart, 2);
  EXPECT_EQ(r.first_failure->condition, "(unused m1)");
}

TEST_F(MatchCellarTest, TheGoalMustHold) {
  EXPECT_FAILS(Validate("0: (light-match m1) [8]\n0.001: (mend-fuse f1 m1) [5]\n"), Kind::kGoal,
               -1);
}

class HarbourTest : public PddlValidatorTest {
 protected:
  void SetUp() override { Load("harbour-domain.pddl", "harbour-problem.pddl"); }
  static constexpr const char* kValid =
      "10.001: (enter b1 x1) [10]\n"
      "20.002: (charge b1 x1) [10]\n"
      "30.003: (inspect b1 x1)\n"
      "30.004: (rewrite-log)\n";
};

TEST_F(HarbourTest, ValidPlanAndMetric) {
  const auto r = Validate(kValid);
  EXPECT_VALID(r);
  EXPECT_NEAR(r.makespan_s, 30.004, 1e-9);
  ASSERT_TRUE(r.metric_value.has_value());
  EXPECT_NEAR(*r.metric_value, 30.004 + 10, 1e-9);  // total-time + charged-time
}

TEST_F(HarbourTest, TimedInitialLiterals) {
  // The tide rises at 10: entering at 5 breaks the invariant right away.
  const auto early = Validate("5: (enter b1 x1) [10]\n15.001: (charge b1 x1) [10]\n");
  EXPECT_FAILS(early, Kind::kOverAll, 0);
  EXPECT_EQ(early.first_failure->condition, "(tide-high)");
  // It falls at 100: an entry at 95 is cut off.
  const auto late = Validate("95: (enter b1 x1) [10]\n");
  EXPECT_FAILS(late, Kind::kOverAll, 0);
  EXPECT_DOUBLE_EQ(late.first_failure->time_s, 100.0);
  EXPECT_THAT(late.first_failure->reason, HasSubstr("timed initial literal"));
  // The tide is only an invariant of the entry, which no snap action reads:
  // entering with the rising tide (in the same happening) or within epsilon
  // after it is fine, entering just before it is not.
  EXPECT_VALID(
      Validate("10: (enter b1 x1) [10]\n20.001: (charge b1 x1) [10]\n"
               "30.002: (inspect b1 x1)\n"));
  EXPECT_VALID(
      Validate("10.0005: (enter b1 x1) [10]\n20.0015: (charge b1 x1) [10]\n"
               "30.0025: (inspect b1 x1)\n"));
  const auto just_before = Validate("9.9995: (enter b1 x1) [10]\n");
  EXPECT_FAILS(just_before, Kind::kOverAll, 0);
  EXPECT_DOUBLE_EQ(just_before.first_failure->time_s, 9.9995);
  // Ending exactly when the tide falls is fine (the interval is open); a
  // fall just before the end is inside it.
  const auto at_end = Validate("90: (enter b1 x1) [10]\n");
  ASSERT_FALSE(at_end.valid);
  EXPECT_EQ(at_end.first_failure->kind, Kind::kGoal)
      << at_end.ToString();  // only the goal is missing
  const auto inside = Validate("90.0005: (enter b1 x1) [10]\n");
  EXPECT_FAILS(inside, Kind::kOverAll, 0);
  EXPECT_DOUBLE_EQ(inside.first_failure->time_s, 100.0);
}

TEST_F(HarbourTest, NumericConditionsAndEffects) {
  // 6 - 5 = 1 fuel after entering, + 2 * 7 = 15 < 20 after charging 7 s.
  const auto r = Validate(
      "10.001: (enter b1 x1) [10]\n20.002: (charge b1 x1) [7]\n"
      "27.003: (inspect b1 x1)\n");
  EXPECT_FAILS(r, Kind::kGoal, -1);
  EXPECT_EQ(r.first_failure->condition, "(>= (fuel b1) 20)");
}

TEST_F(HarbourTest, NumericPreconditions) {
  // With 4 units of fuel the boat cannot enter (it needs 5).
  Load("harbour-domain.pddl", "harbour-problem-low-fuel.pddl");
  const auto r = Validate("10.001: (enter b1 x1) [10]\n");
  EXPECT_FAILS(r, Kind::kAtStart, 0);
  EXPECT_EQ(r.first_failure->condition, "(>= (fuel b1) 5)");
  EXPECT_THAT(r.first_failure->reason, HasSubstr("4 vs 5"));
}

TEST_F(HarbourTest, AtEndConditions) {
  // Charging must end while the tide is still high (before 100).
  EXPECT_VALID(
      Validate("10.001: (enter b1 x1) [10]\n79.9: (charge b1 x1) [20]\n"
               "99.901: (inspect b1 x1)\n"));
  const auto r = Validate(
      "10.001: (enter b1 x1) [10]\n85: (charge b1 x1) [20]\n"
      "105.001: (inspect b1 x1)\n");
  EXPECT_FAILS(r, Kind::kAtEnd, 1);
  EXPECT_EQ(r.first_failure->condition, "(tide-high)");
  EXPECT_DOUBLE_EQ(r.first_failure->time_s, 105.0);
}

TEST_F(HarbourTest, DurativeAtStartConditions) {
  // The berth is taken after the first entry.
  const auto r = Validate("10.001: (enter b1 x1) [10]\n30: (enter b1 x1) [10]\n");
  EXPECT_FAILS(r, Kind::kAtStart, 1);
  EXPECT_EQ(r.first_failure->condition, "(at-sea b1)");
}

TEST_F(HarbourTest, DurationInequalities) {
  EXPECT_VALID(
      Validate("10.001: (enter b1 x1) [10]\n20.002: (charge b1 x1) [20]\n"
               "40.003: (inspect b1 x1)\n"));
  const auto too_short = Validate("10.001: (enter b1 x1) [10]\n20.002: (charge b1 x1) [4]\n");
  EXPECT_FAILS(too_short, Kind::kDuration, 1);
  EXPECT_THAT(too_short.first_failure->condition, HasSubstr(">= ?duration 5"));
  const auto too_long = Validate("10.001: (enter b1 x1) [10]\n20.002: (charge b1 x1) [20.5]\n");
  EXPECT_FAILS(too_long, Kind::kDuration, 1);
  EXPECT_THAT(too_long.first_failure->condition, HasSubstr("<= ?duration"));
}

TEST_F(HarbourTest, InstantaneousActions) {
  // Inspecting before the boat is moored.
  const auto r = Validate("10.001: (enter b1 x1) [10]\n15: (inspect b1 x1)\n");
  EXPECT_FAILS(r, Kind::kAtStart, 1);
  EXPECT_EQ(r.first_failure->condition, "(moored b1 x1)");
  // An instantaneous action with a duration is malformed.
  EXPECT_FAILS(Validate("10.001: (enter b1 x1) [10]\n20.002: (charge b1 x1) [10]\n"
                        "30.003: (inspect b1 x1) [1]\n"),
               Kind::kBadStep, 2);
  // A durative one without a duration too.
  EXPECT_FAILS(Validate("10.001: (enter b1 x1)\n"), Kind::kBadStep, 0);
}

TEST_F(HarbourTest, AddAfterDeleteKeepsTheFact) {
  EXPECT_VALID(Validate(kValid));  // rewrite-log deletes and adds (logged)
  const auto r = Validate(
      "10.001: (enter b1 x1) [10]\n20.002: (charge b1 x1) [10]\n"
      "30.003: (inspect b1 x1)\n30.004: (erase-log)\n");
  EXPECT_FAILS(r, Kind::kGoal, -1);
  EXPECT_EQ(r.first_failure->condition, "(logged)");
}

}  // namespace
}  // namespace seaplan::validate
