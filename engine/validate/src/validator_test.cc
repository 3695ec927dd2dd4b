// Validator rules on hand-built ground tasks (the PDDL-text versions are in
// validator_pddl_test.cc). Each rule has a valid and an invalid plan.
#include "seaplan/validate/validator.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "task_builder_test_util.h"

namespace seaplan::validate {
namespace {

using testing::Binary;
using testing::DurationExpr;
using ::testing::HasSubstr;
using testing::TaskBuilder;
using Kind = ValidationFailure::Kind;
using Op = task::NumericExpr::Op;
using task::AssignOp;
using task::Comparator;
using task::NumericExpr;

PlanStep Step(double t, std::string_view display, double d = 0.0) {
  auto [name, args] = testing::SplitAtom(display);
  return PlanStep{t, name, args, d, 0};
}

Plan MakePlan(std::initializer_list<PlanStep> steps) {
  return Plan{std::vector<PlanStep>(steps)};
}

// Validates with both entry points and checks they agree.
ValidationResult Check(const task::GroundTask& task, const Plan& plan,
                       const ValidationOptions& options = {}) {
  ValidationResult one_shot = ValidatePlan(task, plan, options);
  auto validator = Validator::Create(std::make_shared<task::GroundTask>(task), options);
  EXPECT_TRUE(validator.ok());
  if (validator.ok()) {
    ValidationResult indexed = validator->Validate(plan);
    EXPECT_EQ(indexed.ToString(), one_shot.ToString());
  }
  return one_shot;
}

#define EXPECT_VALID(result) EXPECT_TRUE((result).valid) << (result).ToString()

#define EXPECT_FAILS(result, expected_kind, expected_step, expected_condition)     \
  do {                                                                             \
    const ValidationResult& r_ = (result);                                         \
    ASSERT_FALSE(r_.valid) << "expected an invalid plan";                          \
    ASSERT_TRUE(r_.first_failure.has_value());                                     \
    EXPECT_EQ(r_.first_failure->kind, (expected_kind)) << r_.ToString();           \
    EXPECT_EQ(r_.first_failure->step_index, (expected_step)) << r_.ToString();     \
    EXPECT_EQ(r_.first_failure->condition, (expected_condition)) << r_.ToString(); \
  } while (false)

// (move a b): at start (at a), at start (not (at a)), at end (at b).
task::Action Move(TaskBuilder& b, const std::string& from, const std::string& to, double d) {
  auto a = TaskBuilder::Durative("(move " + from + " " + to + ")", d);
  a.at_start.positive = {b.Fact("(at " + from + ")")};
  a.start_effects.del = {b.Fact("(at " + from + ")")};
  a.end_effects.add = {b.Fact("(at " + to + ")")};
  return a;
}

TEST(ValidatorTest, AtStartConditions) {
  TaskBuilder b;
  b.Init("(at a)");
  b.Add(Move(b, "a", "b", 10));
  b.Add(Move(b, "b", "c", 10));
  b.Goal("(at c)");
  EXPECT_VALID(
      Check(b.task(), MakePlan({Step(0, "(move a b)", 10), Step(10.001, "(move b c)", 10)})));
  // The second move starts before the first has arrived.
  const auto r = Check(b.task(), MakePlan({Step(0, "(move a b)", 10), Step(9, "(move b c)", 10)}));
  EXPECT_FAILS(r, Kind::kAtStart, 1, "(at b)");
  EXPECT_EQ(r.first_failure->time_s, 9.0);
  EXPECT_EQ(r.first_failure->action, "(move b c)");
  EXPECT_THAT(r.ToString(), HasSubstr("at-start condition (at b) is false"));
}

TEST(ValidatorTest, NegativeConditions) {
  TaskBuilder b;
  auto a = TaskBuilder::Instant("(open door)");
  a.at_start.negative = {b.Fact("(locked door)")};
  a.start_effects.add = {b.Fact("(open door)")};
  b.Add(a);
  b.Goal("(open door)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(1, "(open door)")})));
  b.Init("(locked door)");
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(1, "(open door)")})), Kind::kAtStart, 0,
               "(not (locked door))");
}

// Match-cellar (required concurrency): the fuse can only be mended while the
// match burns.
TaskBuilder MatchCellar() {
  TaskBuilder b;
  b.Init("(unused match)");
  b.Init("(handfree)");
  auto light = TaskBuilder::Durative("(light-match match)", 8);
  light.at_start.positive = {b.Fact("(unused match)")};
  light.start_effects.del = {b.Fact("(unused match)")};
  light.start_effects.add = {b.Fact("(light match)")};
  light.end_effects.del = {b.Fact("(light match)")};
  b.Add(light);
  auto mend = TaskBuilder::Durative("(mend-fuse fuse)", 5);
  mend.at_start.positive = {b.Fact("(handfree)")};
  mend.over_all.positive = {b.Fact("(light match)")};
  mend.start_effects.del = {b.Fact("(handfree)")};
  mend.end_effects.add = {b.Fact("(mended fuse)"), b.Fact("(handfree)")};
  b.Add(mend);
  b.Goal("(mended fuse)");
  return b;
}

TEST(ValidatorTest, OverAllConditionsRequireConcurrency) {
  TaskBuilder b = MatchCellar();
  const auto ok = Check(
      b.task(), MakePlan({Step(0, "(light-match match)", 8), Step(0.001, "(mend-fuse fuse)", 5)}));
  EXPECT_VALID(ok);
  EXPECT_DOUBLE_EQ(ok.makespan_s, 8.0);
  EXPECT_EQ(ok.action_count, 2u);
  // Sequential: the match is out before the fuse work starts.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(light-match match)", 8),
                                         Step(8.001, "(mend-fuse fuse)", 5)})),
               Kind::kOverAll, 1, "(light match)");
  // Both start together: the state after that happening has the light.
  EXPECT_VALID(Check(
      b.task(), MakePlan({Step(0, "(light-match match)", 8), Step(0, "(mend-fuse fuse)", 5)})));
  // Mending outlasts the match: the match's end breaks the invariant.
  const auto r = Check(
      b.task(), MakePlan({Step(0, "(light-match match)", 8), Step(4, "(mend-fuse fuse)", 5)}));
  EXPECT_FAILS(r, Kind::kOverAll, 1, "(light match)");
  EXPECT_EQ(r.first_failure->time_s, 8.0);
  EXPECT_EQ(r.first_failure->other_step_index, 0);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("broken by (light-match match) end at t=8"));
}

TEST(ValidatorTest, OverAllIsNotCheckedAtTheEndPoint) {
  // The invariant is deleted by the action's own end effect: fine, the
  // interval is open.
  TaskBuilder b;
  b.Init("(p)");
  auto a = TaskBuilder::Durative("(use)", 5);
  a.over_all.positive = {b.Fact("(p)")};
  a.end_effects.del = {b.Fact("(p)")};
  a.end_effects.add = {b.Fact("(done)")};
  b.Add(a);
  b.Goal("(done)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(1, "(use)", 5)})));
  b.task().initial_facts.clear();
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(1, "(use)", 5)})), Kind::kOverAll, 0, "(p)");
}

// A ship at port a: (load) needs it there over all, (sail a b) leaves at its
// start and arrives at its end, (unload) needs it at b over all. No snap
// action reads (at a) or (at b) except the sail's start: the invariants are
// only checked on the open intervals (PDDL 2.1, VAL).
TaskBuilder Harbour() {
  TaskBuilder b;
  b.Init("(at a)");
  b.Init("(cargo)");
  auto load = TaskBuilder::Durative("(load)", 60);
  load.at_start.positive = {b.Fact("(cargo)")};
  load.over_all.positive = {b.Fact("(at a)")};
  load.start_effects.del = {b.Fact("(cargo)")};
  load.end_effects.add = {b.Fact("(loaded)")};
  b.Add(load);
  b.Add(Move(b, "a", "b", 10));
  auto unload = TaskBuilder::Durative("(unload)", 50);
  unload.at_start.positive = {b.Fact("(loaded)")};
  unload.over_all.positive = {b.Fact("(at b)")};
  unload.start_effects.del = {b.Fact("(loaded)")};
  unload.end_effects.add = {b.Fact("(delivered)")};
  b.Add(unload);
  b.Goal("(delivered)");
  return b;
}

TEST(ValidatorTest, AnInvariantIsNotNeededAtItsEndPoint) {
  TaskBuilder b = Harbour();
  // The sail deletes (at a) exactly when the load ends: valid.
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(load)", 60), Step(60, "(move a b)", 10),
                                         Step(70, "(unload)", 50)})));
  // Half an epsilon before the end the deletion is inside the interval.
  const auto r = Check(b.task(), MakePlan({Step(0, "(load)", 60), Step(59.9995, "(move a b)", 10),
                                           Step(70, "(unload)", 50)}));
  EXPECT_FAILS(r, Kind::kOverAll, 0, "(at a)");
  EXPECT_EQ(r.first_failure->time_s, 59.9995);
  EXPECT_EQ(r.first_failure->other_step_index, 1);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("broken by (move a b) start at t=59.9995"));
  // And well inside.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(load)", 60), Step(30, "(move a b)", 10),
                                         Step(70, "(unload)", 50)})),
               Kind::kOverAll, 0, "(at a)");
}

TEST(ValidatorTest, AnInvariantAddedInTheStartingHappeningHolds) {
  TaskBuilder b = Harbour();
  // The sail's end adds (at b) in the happening where the unload starts.
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(load)", 60), Step(60, "(move a b)", 10),
                                         Step(70, "(unload)", 50)})));
  // Starting before the arrival, even by less than epsilon, is not.
  const auto r = Check(b.task(), MakePlan({Step(0, "(load)", 60), Step(60, "(move a b)", 10),
                                           Step(69.9995, "(unload)", 50)}));
  EXPECT_FAILS(r, Kind::kOverAll, 2, "(at b)");
  EXPECT_EQ(r.first_failure->time_s, 69.9995);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("just after the action starts"));
}

TEST(ValidatorTest, AnInvariantDeletedInTheStartingHappeningFails) {
  TaskBuilder b = Harbour();
  // Load and sail start together: the state after that happening has no
  // (at a). Whatever the order of the steps in the plan.
  for (const bool load_first : {true, false}) {
    const Plan plan = load_first ? MakePlan({Step(0, "(load)", 60), Step(0, "(move a b)", 10)})
                                 : MakePlan({Step(0, "(move a b)", 10), Step(0, "(load)", 60)});
    const int load = load_first ? 0 : 1;
    const auto r = Check(b.task(), plan);
    EXPECT_FAILS(r, Kind::kOverAll, load, "(at a)");
    EXPECT_EQ(r.first_failure->time_s, 0.0);
    EXPECT_EQ(r.first_failure->other_step_index, 1 - load);
    EXPECT_THAT(r.first_failure->reason,
                HasSubstr("(move a b) start at t=0, in the same happening"));
  }
}

TEST(ValidatorTest, AnInvariantIsCheckedAfterTheWholeHappening) {
  // Match-cellar with both starts in one happening: the match's start adds
  // the mend's invariant, whichever step comes first in the plan.
  TaskBuilder b = MatchCellar();
  EXPECT_VALID(Check(
      b.task(), MakePlan({Step(0, "(light-match match)", 8), Step(0, "(mend-fuse fuse)", 5)})));
  EXPECT_VALID(Check(
      b.task(), MakePlan({Step(0, "(mend-fuse fuse)", 5), Step(0, "(light-match match)", 8)})));
  // Numeric: two additive updates in one happening commute and do not
  // interfere; the invariant sees their sum, not an intermediate value.
  TaskBuilder n;
  n.Var("(fuel)", 10);
  auto run = TaskBuilder::Durative("(run)", 10);
  run.over_all.numeric = {
      {n.VarExpr("(fuel)"), Comparator::kGreaterEqual, NumericExpr::Constant(5)}};
  run.end_effects.add = {n.Fact("(ran)")};
  n.Add(run);
  auto burn = TaskBuilder::Instant("(burn)");
  burn.start_effects.numeric = {{n.Var("(fuel)"), AssignOp::kDecrease, NumericExpr::Constant(8)}};
  n.Add(burn);
  auto fill = TaskBuilder::Instant("(fill)");
  fill.start_effects.numeric = {{n.Var("(fuel)"), AssignOp::kIncrease, NumericExpr::Constant(8)}};
  n.Add(fill);
  n.Goal("(ran)");
  EXPECT_VALID(
      Check(n.task(), MakePlan({Step(0, "(run)", 10), Step(5, "(burn)"), Step(5, "(fill)")})));
  const auto r =
      Check(n.task(), MakePlan({Step(0, "(run)", 10), Step(5, "(burn)"), Step(6, "(fill)")}));
  EXPECT_FAILS(r, Kind::kOverAll, 0, "(>= (fuel) 5)");
  EXPECT_EQ(r.first_failure->other_step_index, 1);
  EXPECT_EQ(r.first_failure->time_s, 5.0);
  // At the end point the burn does not matter.
  EXPECT_VALID(Check(n.task(), MakePlan({Step(0, "(run)", 10), Step(10, "(burn)")})));
}

TEST(ValidatorTest, AtEndConditions) {
  TaskBuilder b;
  b.Til(3, "(window)", true);
  b.Til(6, "(window)", false);
  auto a = TaskBuilder::Durative("(shoot)", 2);
  a.at_end.positive = {b.Fact("(window)")};
  a.end_effects.add = {b.Fact("(photo)")};
  b.Add(a);
  b.Goal("(photo)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(2, "(shoot)", 2)})));
  const auto r = Check(b.task(), MakePlan({Step(0, "(shoot)", 2)}));
  EXPECT_FAILS(r, Kind::kAtEnd, 0, "(window)");
  EXPECT_EQ(r.first_failure->time_s, 2.0);
}

TEST(ValidatorTest, AddWinsWhenAnEventAddsAndDeletesTheSameFact) {
  TaskBuilder b;
  b.Init("(token)");
  auto a = TaskBuilder::Instant("(refresh)");
  a.start_effects.del = {b.Fact("(token)")};
  a.start_effects.add = {b.Fact("(token)")};
  b.Add(a);
  b.Goal("(token)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(1, "(refresh)")})));
  // Without the add, the delete stands.
  b.task().actions[0].start_effects.add.clear();
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(1, "(refresh)")})), Kind::kGoal, -1, "(token)");
}

TEST(ValidatorTest, StartEffectsHappenAtStartEndEffectsAtEnd) {
  TaskBuilder b;
  b.Init("(at a)");
  b.Add(Move(b, "a", "b", 10));
  auto look = TaskBuilder::Instant("(look a)");
  look.at_start.positive = {b.Fact("(at a)")};
  look.start_effects.add = {b.Fact("(seen a)")};
  b.Add(look);
  b.Goal("(seen a)");
  b.Goal("(at b)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(look a)"), Step(0.001, "(move a b)", 10)})));
  // During the move the ship is neither at a nor at b.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(move a b)", 10), Step(5, "(look a)")})),
               Kind::kAtStart, 1, "(at a)");
}

TEST(ValidatorTest, NumericEffectsAtStartAndEndWithDuration) {
  TaskBuilder b;
  b.Var("(fuel)", 30);
  b.Var("(odometer)", 0);
  b.Var("(factor)", 1);
  // (drive): at start (>= (fuel) 15), decrease fuel by 15 at start,
  // increase odometer by 2 * ?duration at end, scale factor up by 2 at end.
  auto drive = TaskBuilder::Durative("(drive)", 10);
  drive.at_start.numeric = {
      {b.VarExpr("(fuel)"), Comparator::kGreaterEqual, NumericExpr::Constant(15)}};
  drive.start_effects.numeric = {{b.Var("(fuel)"), AssignOp::kDecrease, NumericExpr::Constant(15)}};
  drive.end_effects.numeric = {{b.Var("(odometer)"), AssignOp::kIncrease,
                                Binary(Op::kMul, NumericExpr::Constant(2), DurationExpr())},
                               {b.Var("(factor)"), AssignOp::kScaleUp, NumericExpr::Constant(2)}};
  b.Add(drive);
  auto refuel = TaskBuilder::Instant("(refuel)");
  refuel.start_effects.numeric = {{b.Var("(fuel)"), AssignOp::kAssign, NumericExpr::Constant(100)}};
  b.Add(refuel);
  auto halve = TaskBuilder::Instant("(halve)");
  halve.start_effects.numeric = {
      {b.Var("(factor)"), AssignOp::kScaleDown, NumericExpr::Constant(8)}};
  b.Add(halve);
  // Goal: odometer >= 60 (three drives) and factor = 1 after the halving.
  b.task().goal.numeric = {
      {b.VarExpr("(odometer)"), Comparator::kGreaterEqual, NumericExpr::Constant(60)},
      {b.VarExpr("(factor)"), Comparator::kEqual, NumericExpr::Constant(1)}};

  const auto ok = Check(b.task(), MakePlan({Step(0, "(drive)", 10), Step(10.001, "(drive)", 10),
                                            Step(20.002, "(refuel)"), Step(20.003, "(drive)", 10),
                                            Step(30.004, "(halve)")}));
  EXPECT_VALID(ok);
  // Without refuelling the third drive finds 0 fuel.
  const auto r = Check(b.task(), MakePlan({Step(0, "(drive)", 10), Step(10.001, "(drive)", 10),
                                           Step(20.003, "(drive)", 10), Step(30.004, "(halve)")}));
  EXPECT_FAILS(r, Kind::kAtStart, 2, "(>= (fuel) 15)");
  EXPECT_THAT(r.first_failure->reason, HasSubstr("0 vs 15"));
  // ?duration in the effect: two drives of 10 s give 40 < 60.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(drive)", 10), Step(10.001, "(drive)", 10),
                                         Step(20.002, "(halve)")})),
               Kind::kGoal, -1, "(>= (odometer) 60)");
}

TEST(ValidatorTest, UndefinedNumericValuesFail) {
  TaskBuilder b;
  b.Var("(level)");  // undefined initially
  auto bump = TaskBuilder::Instant("(bump)");
  bump.start_effects.numeric = {{b.Var("(level)"), AssignOp::kIncrease, NumericExpr::Constant(1)}};
  b.Add(bump);
  auto set = TaskBuilder::Instant("(set)");
  set.start_effects.numeric = {{b.Var("(level)"), AssignOp::kAssign, NumericExpr::Constant(0)}};
  b.Add(set);
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(set)"), Step(1, "(bump)")})));
  const auto r = Check(b.task(), MakePlan({Step(1, "(bump)")}));
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.first_failure->kind, Kind::kEffect);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("(level)"));
}

TEST(ValidatorTest, DurationEqualityWithTolerance) {
  TaskBuilder b;
  b.Var("(length)", 52);
  b.Var("(speed)", 0.18);
  b.Init("(at a)");
  auto move = Move(b, "a", "b", 0);
  move.duration = {
      {Comparator::kEqual, Binary(Op::kDiv, b.VarExpr("(length)"), b.VarExpr("(speed)"))}};
  b.Add(move);
  b.Goal("(at b)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(move a b)", 52 / 0.18)})));
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(move a b)", 288.889)})));  // 3 decimals
  const auto r = Check(b.task(), MakePlan({Step(0, "(move a b)", 288.8)}));
  EXPECT_FAILS(r, Kind::kDuration, 0, "(= ?duration (/ (length) (speed)))");
  EXPECT_THAT(r.first_failure->reason, HasSubstr("288.888889"));
  ValidationOptions strict;
  strict.duration_tolerance_s = 0;
  EXPECT_FALSE(Check(b.task(), MakePlan({Step(0, "(move a b)", 288.889)}), strict).valid);
}

TEST(ValidatorTest, DurationInequalitiesEvaluatedInTheStateAtStart) {
  TaskBuilder b;
  b.Var("(battery)", 20);
  auto charge = TaskBuilder::Durative("(charge)", 0);
  // 5 <= ?duration <= (battery); the start effect halves the battery, which
  // must not matter (the bound is read in the state before the start).
  charge.duration = {{Comparator::kGreaterEqual, NumericExpr::Constant(5)},
                     {Comparator::kLessEqual, b.VarExpr("(battery)")}};
  charge.start_effects.numeric = {
      {b.Var("(battery)"), AssignOp::kScaleDown, NumericExpr::Constant(2)}};
  charge.end_effects.add = {b.Fact("(charged)")};
  b.Add(charge);
  b.Goal("(charged)");
  for (const double d : {5.0, 12.5, 20.0}) {
    EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(charge)", d)}))) << d;
  }
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(charge)", 4)})), Kind::kDuration, 0,
               "(>= ?duration 5)");
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(charge)", 21)})), Kind::kDuration, 0,
               "(<= ?duration (battery))");
  // Strict bounds are exact.
  b.task().actions[0].duration = {{Comparator::kGreater, NumericExpr::Constant(5)},
                                  {Comparator::kLess, NumericExpr::Constant(10)}};
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(charge)", 5.5)})));
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(charge)", 10)})), Kind::kDuration, 0,
               "(< ?duration 10)");
}

TEST(ValidatorTest, InstantaneousAndDurativeStepShapes) {
  TaskBuilder b;
  auto tick = TaskBuilder::Instant("(tick)");
  tick.start_effects.add = {b.Fact("(ticked)")};
  b.Add(tick);
  auto wait = TaskBuilder::Durative("(wait)", 3);
  b.Add(wait);
  b.Goal("(ticked)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(tick)"), Step(0, "(wait)", 3)})));
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(tick)", 2)})), Kind::kBadStep, 0, "");
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(tick)"), Step(1, "(wait)")})), Kind::kBadStep, 1,
               "");
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(-1, "(tick)")})), Kind::kBadStep, 0, "");
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(tick)"), Step(1, "(wait)", -3)})),
               Kind::kBadStep, 1, "");
}

TEST(ValidatorTest, TimedInitialLiteralsHappenAtTheirTimes) {
  TaskBuilder b;
  b.Til(10, "(daylight)", true);
  b.Til(20, "(daylight)", false);
  auto survey = TaskBuilder::Durative("(survey)", 5);
  survey.at_start.positive = {b.Fact("(daylight)")};
  survey.over_all.positive = {b.Fact("(daylight)")};
  survey.end_effects.add = {b.Fact("(surveyed)")};
  b.Add(survey);
  b.Goal("(surveyed)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(10.5, "(survey)", 5)})));
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(5, "(survey)", 5)})), Kind::kAtStart, 0,
               "(daylight)");
  // Dusk falls during the survey.
  const auto r = Check(b.task(), MakePlan({Step(17, "(survey)", 5)}));
  EXPECT_FAILS(r, Kind::kOverAll, 0, "(daylight)");
  EXPECT_EQ(r.first_failure->time_s, 20.0);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("timed initial literal (at 20 (not (daylight)))"));
  // A literal within epsilon of an event that reads it is a mutex.
  const auto m = Check(b.task(), MakePlan({Step(10.0005, "(survey)", 5)}));
  EXPECT_FAILS(m, Kind::kMutex, -1, "(daylight)");
  EXPECT_EQ(m.first_failure->other_step_index, 0);
}

TEST(ValidatorTest, GoalMustHoldAfterTheLastTimedLiteral) {
  TaskBuilder b;
  b.Init("(berth free)");
  b.Til(100, "(berth free)", false);
  auto dock = TaskBuilder::Durative("(dock)", 10);
  dock.at_start.positive = {b.Fact("(berth free)")};
  dock.end_effects.add = {b.Fact("(docked)")};
  b.Add(dock);
  b.Goal("(docked)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(dock)", 10)})));
  EXPECT_FAILS(Check(b.task(), MakePlan({})), Kind::kGoal, -1, "(docked)");
  // The berth closes after the plan ends; a goal on it fails at t=100.
  b.Goal("(berth free)");
  const auto r = Check(b.task(), MakePlan({Step(0, "(dock)", 10)}));
  EXPECT_FAILS(r, Kind::kGoal, -1, "(berth free)");
  EXPECT_EQ(r.first_failure->time_s, 100.0);
}

TEST(ValidatorTest, TimedInitialFluents) {
  TaskBuilder b;
  b.Var("(tide)", 1);
  b.task().timed_fluents.push_back({50, b.Var("(tide)"), 4});
  auto enter = TaskBuilder::Instant("(enter)");
  enter.at_start.numeric = {
      {b.VarExpr("(tide)"), Comparator::kGreaterEqual, NumericExpr::Constant(3)}};
  enter.start_effects.add = {b.Fact("(inside)")};
  b.Add(enter);
  b.Goal("(inside)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(51, "(enter)")})));
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(49, "(enter)")})), Kind::kAtStart, 0,
               "(>= (tide) 3)");
}

// Two lamps share a switch fact; toggling it interferes with anything reading it.
TaskBuilder Interfering() {
  TaskBuilder b;
  b.Init("(power)");
  auto cut = TaskBuilder::Instant("(cut)");
  cut.at_start.positive = {b.Fact("(power)")};
  cut.start_effects.del = {b.Fact("(power)")};
  cut.start_effects.add = {b.Fact("(cut-done)")};
  b.Add(cut);
  auto weld = TaskBuilder::Durative("(weld)", 1);
  weld.at_start.positive = {b.Fact("(power)")};
  weld.end_effects.add = {b.Fact("(welded)")};
  b.Add(weld);
  auto paint = TaskBuilder::Durative("(paint)", 1);
  paint.end_effects.add = {b.Fact("(painted)")};
  b.Add(paint);
  b.Goal("(welded)");
  b.Goal("(cut-done)");
  return b;
}

TEST(ValidatorTest, EpsilonSeparationOfInterferingEvents) {
  TaskBuilder b = Interfering();
  // weld reads (power) at its start, cut deletes it.
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0.001, "(cut)")})));
  const auto r = Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0.0005, "(cut)")}));
  EXPECT_FAILS(r, Kind::kMutex, 0, "(power)");
  EXPECT_EQ(r.first_failure->action, "(weld)");
  EXPECT_EQ(r.first_failure->other_step_index, 1);
  EXPECT_EQ(r.first_failure->other_action, "(cut)");
  EXPECT_THAT(r.first_failure->reason, HasSubstr("0.0005 s apart"));
  // Exactly simultaneous interfering events are a mutex too, even with epsilon 0.
  ValidationOptions zero;
  zero.epsilon_s = 0;
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0, "(cut)")}), zero),
               Kind::kMutex, 0, "(power)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0.0005, "(cut)")}), zero));
  // A larger epsilon needs a larger separation.
  ValidationOptions wide;
  wide.epsilon_s = 0.2;
  EXPECT_FALSE(Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0.1, "(cut)")}), wide).valid);
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0.2, "(cut)")}), wide));
}

TEST(ValidatorTest, SeparationsOfEpsilonComputedInFloatingPointCount) {
  // A long chain whose every start touches the previous end, scheduled the
  // way a planner does it: start = previous start + duration + epsilon, with
  // durations off the decimal grid. No gap may be judged below epsilon.
  TaskBuilder b;
  constexpr int kMoves = 300;
  b.Init("(at p0)");
  Plan plan;
  double t = 0.0;
  for (int i = 0; i < kMoves; ++i) {
    const std::string from = "p" + std::to_string(i);
    const std::string to = "p" + std::to_string(i + 1);
    const double d = (37.0 * i + 11.0) / 0.18;
    b.Add(Move(b, from, to, d));
    plan.steps.push_back({t, "move", {from, to}, d, 0});
    t = t + d + 0.001;
  }
  b.Goal("(at p" + std::to_string(kMoves) + ")");
  EXPECT_VALID(Check(b.task(), plan));
  // And through printing, as the planner returns it.
  const auto reparsed = ParsePlan(FormatPlan(plan));
  ASSERT_TRUE(reparsed.ok());
  EXPECT_VALID(Check(b.task(), *reparsed));
  // One microsecond less than epsilon anywhere is a mutex.
  plan.steps[kMoves / 2].start_s -= 1e-6;
  EXPECT_FAILS(Check(b.task(), plan), Kind::kMutex, kMoves / 2 - 1,
               "(at p" + std::to_string(kMoves / 2) + ")");
}

TEST(ValidatorTest, SimultaneousNonInterferingEventsAreFine) {
  TaskBuilder b = Interfering();
  b.Goal("(painted)");
  EXPECT_VALID(Check(
      b.task(), MakePlan({Step(0, "(weld)", 1), Step(0, "(paint)", 1), Step(1.001, "(cut)")})));
  // Two readers of the same fact at once are fine too.
  auto weld2 = TaskBuilder::Durative("(weld2)", 1);
  weld2.at_start.positive = {b.Fact("(power)")};
  b.Add(weld2);
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(weld)", 1), Step(0, "(weld2)", 1),
                                         Step(0, "(paint)", 1), Step(2, "(cut)")})));
}

TEST(ValidatorTest, NumericMutexRules) {
  TaskBuilder b;
  b.Var("(stock)", 10);
  auto take = TaskBuilder::Instant("(take)");
  take.start_effects.numeric = {{b.Var("(stock)"), AssignOp::kDecrease, NumericExpr::Constant(1)}};
  b.Add(take);
  auto give = TaskBuilder::Instant("(give)");
  give.start_effects.numeric = {{b.Var("(stock)"), AssignOp::kIncrease, NumericExpr::Constant(2)}};
  b.Add(give);
  auto count = TaskBuilder::Instant("(count)");
  count.at_start.numeric = {{b.VarExpr("(stock)"), Comparator::kGreater, NumericExpr::Constant(0)}};
  b.Add(count);
  auto reset = TaskBuilder::Instant("(reset)");
  reset.start_effects.numeric = {{b.Var("(stock)"), AssignOp::kAssign, NumericExpr::Constant(5)}};
  b.Add(reset);
  b.task().goal.numeric = {
      {b.VarExpr("(stock)"), Comparator::kGreaterEqual, NumericExpr::Constant(0)}};
  // Additive updates commute.
  EXPECT_VALID(Check(b.task(), MakePlan({Step(1, "(take)"), Step(1, "(give)")})));
  // An update and a read do not.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(1, "(take)"), Step(1, "(count)")})), Kind::kMutex, 0,
               "(stock)");
  // An assignment and an update do not.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(1, "(reset)"), Step(1.0002, "(give)")})),
               Kind::kMutex, 0, "(stock)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(1, "(reset)"), Step(1.001, "(give)")})));
}

TEST(ValidatorTest, EffectsOnTheSameFactWithDifferentValuesInterfere) {
  TaskBuilder b;
  auto on = TaskBuilder::Instant("(on)");
  on.start_effects.add = {b.Fact("(lit)")};
  b.Add(on);
  auto off = TaskBuilder::Instant("(off)");
  off.start_effects.del = {b.Fact("(lit)")};
  b.Add(off);
  auto on2 = TaskBuilder::Instant("(on2)");
  on2.start_effects.add = {b.Fact("(lit)")};
  b.Add(on2);
  b.Goal("(lit)");
  const auto r = Check(b.task(), MakePlan({Step(1, "(on)"), Step(1, "(off)")}));
  EXPECT_FAILS(r, Kind::kMutex, 0, "(lit)");
  EXPECT_THAT(r.first_failure->reason, HasSubstr("added by the first and deleted by the second"));
  // Two adds of the same fact agree (VAL allows it).
  EXPECT_VALID(Check(b.task(), MakePlan({Step(1, "(on)"), Step(1, "(on2)")})));
}

TEST(ValidatorTest, UnknownActionsAreExplained) {
  TaskBuilder b;
  b.Init("(at a)");
  b.Add(Move(b, "a", "b", 10));
  b.Goal("(at b)");
  auto r = Check(b.task(), MakePlan({Step(0, "(fly a b)", 10)}));
  EXPECT_FAILS(r, Kind::kUnknownAction, 0, "");
  EXPECT_THAT(r.first_failure->reason, HasSubstr("no action named 'fly'"));
  r = Check(b.task(), MakePlan({Step(0, "(move a)", 10)}));
  EXPECT_THAT(r.first_failure->reason, HasSubstr("takes 2 argument(s), the step gives 1"));
  r = Check(b.task(), MakePlan({Step(0, "(move a x)", 10)}));
  EXPECT_THAT(r.first_failure->reason, HasSubstr("no ground action has these arguments"));
  // Structural failures come before anything simulated, even when later in the plan.
  r = Check(b.task(), MakePlan({Step(0, "(move a b)", 5), Step(50, "(move a zz)", 10)}));
  EXPECT_FAILS(r, Kind::kUnknownAction, 1, "");
  // A caller-provided explanation (the grounder's) is used when it has one.
  ValidationOptions options;
  options.explain_missing_action = [](std::string_view name, std::span<const std::string> args) {
    return std::string(name) + "/" + std::to_string(args.size()) + ": (connected a x) is false";
  };
  r = ValidatePlan(b.task(), MakePlan({Step(0, "(move a x)", 10)}), options);
  EXPECT_THAT(r.first_failure->reason, HasSubstr("move/2: (connected a x) is false"));
  // Case does not matter.
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(MOVE A B)", 10)})));
}

TEST(ValidatorTest, DisjunctiveVariantsAnyMayHold) {
  TaskBuilder b;
  b.Init("(key)");
  // (enter) with (or (key) (code)) compiled into two variants.
  auto with_key = TaskBuilder::Instant("(enter)");
  with_key.at_start.positive = {b.Fact("(key)")};
  with_key.start_effects.add = {b.Fact("(inside)")};
  auto with_code = with_key;
  with_code.variant = 1;
  with_code.at_start.positive = {b.Fact("(code)")};
  b.Add(with_code);
  b.Add(with_key);
  b.Goal("(inside)");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(enter)")})));
  b.task().initial_facts.clear();
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(enter)")})), Kind::kAtStart, 0, "(code)");
}

TEST(ValidatorTest, ConditionalEffects) {
  TaskBuilder b;
  b.Init("(raining)");
  auto walk = TaskBuilder::Durative("(walk)", 10);
  task::ConditionalEffect wet;
  wet.condition.positive = {b.Fact("(raining)")};
  wet.condition_time = task::TimePoint::kStart;
  wet.add = {b.Fact("(wet)")};
  walk.end_effects.conditional = {wet};
  walk.end_effects.add = {b.Fact("(home)")};
  b.Add(walk);
  auto stop = TaskBuilder::Instant("(stop-rain)");
  stop.start_effects.del = {b.Fact("(raining)")};
  b.Add(stop);
  b.Goal("(home)");
  b.task().goal.negative = {b.Fact("(wet)")};
  // It rains when the walk starts: wet at the end although the rain stopped.
  EXPECT_FAILS(Check(b.task(), MakePlan({Step(0, "(walk)", 10), Step(5, "(stop-rain)")})),
               Kind::kGoal, -1, "(not (wet))");
  EXPECT_VALID(Check(b.task(), MakePlan({Step(0, "(stop-rain)"), Step(1, "(walk)", 10)})));
}

TEST(ValidatorTest, MetricValue) {
  TaskBuilder b = MatchCellar();
  const Plan plan =
      MakePlan({Step(0, "(light-match match)", 8), Step(0.001, "(mend-fuse fuse)", 5)});
  auto r = Check(b.task(), plan);
  ASSERT_TRUE(r.metric_value.has_value());
  EXPECT_DOUBLE_EQ(*r.metric_value, 8.0);  // total-time = makespan
  b.Var("(cost)", 7);
  b.task().metric.expression =
      Binary(Op::kAdd, b.VarExpr("(cost)"),
             Binary(Op::kMul, NumericExpr::Constant(2), testing::TotalTimeExpr()));
  r = Check(b.task(), plan);
  ASSERT_TRUE(r.metric_value.has_value());
  EXPECT_DOUBLE_EQ(*r.metric_value, 23.0);
  // No metric for invalid plans.
  EXPECT_FALSE(Check(b.task(), MakePlan({})).metric_value.has_value());
}

TEST(ValidatorTest, OptionsAreValidated) {
  ValidationOptions bad;
  bad.epsilon_s = -1;
  EXPECT_FALSE(bad.Validate().ok());
  TaskBuilder b = MatchCellar();
  EXPECT_FALSE(Validator::Create(std::make_shared<task::GroundTask>(b.task()), bad).ok());
  EXPECT_FALSE(Validator::Create(nullptr).ok());
  const auto r = ValidatePlan(b.task(), MakePlan({}), bad);
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.first_failure->kind, Kind::kInvalidOptions);
  ValidationOptions nan_tolerance;
  nan_tolerance.duration_tolerance_s = std::nan("");
  EXPECT_FALSE(nan_tolerance.Validate().ok());
}

}  // namespace
}  // namespace seaplan::validate
