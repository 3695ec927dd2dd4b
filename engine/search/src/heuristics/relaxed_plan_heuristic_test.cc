#include "relaxed_plan_heuristic.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "../search_test_util.h"
#include "seaplan/task/grounder.h"

namespace seaplan::search {
namespace {

// A one-satellite world: turning from any direction to any other, and an
// image of a direction taken while pointing at it (needs calibration).
// Once the satellite can point everywhere, every further turn_to is a
// redundant start/end pair for the relaxed exploration.
constexpr char kDomain[] = R"((define (domain turn)
  (:requirements :typing :equality :durative-actions)
  (:types dir)
  (:predicates (pointing ?d - dir) (image ?d - dir) (power) (calibrated))
  (:durative-action turn_to :parameters (?to ?from - dir) :duration (= ?duration 5)
    :condition (and (at start (pointing ?from)) (over all (not (= ?to ?from))))
    :effect (and (at start (not (pointing ?from))) (at end (pointing ?to))))
  (:durative-action calibrate :parameters () :duration (= ?duration 1)
    :condition (at start (power))
    :effect (and (at start (not (power))) (at end (calibrated))))
  (:durative-action take_image :parameters (?d - dir) :duration (= ?duration 7)
    :condition (and (over all (pointing ?d)) (at start (calibrated)))
    :effect (at end (image ?d)))))";

constexpr char kProblem[] = R"((define (problem turn-1) (:domain turn)
  (:objects d0 d1 d2 d3 - dir)
  (:init (pointing d0) (calibrated) (power))
  (:goal (and (image d3) (pointing d1)))))";

class RelaxedPlanHeuristicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto loaded = task::LoadTask(kDomain, kProblem);
    ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
    task_ = loaded.task;
    snap_ = std::make_unique<SnapTask>(*task_);
    registry_ = std::make_unique<StateRegistry>(snap_->num_facts(), snap_->num_vars());
    heuristic_ = std::make_unique<RelaxedPlanHeuristic>(*snap_, 0.001);
  }

  int Action(const std::string& display_name) const {
    return testing::ActionIdOf(*task_, display_name);
  }
  int Fact(const std::string& display_name) const {
    return testing::FactIdOf(*task_, display_name);
  }
  StateData State(const std::vector<std::string>& facts) const {
    StateData s = registry_->MakeEmpty();
    for (const auto& f : facts) s.Set(Fact(f));
    return s;
  }

  std::shared_ptr<const task::GroundTask> task_;
  std::unique_ptr<SnapTask> snap_;
  std::unique_ptr<StateRegistry> registry_;
  std::unique_ptr<RelaxedPlanHeuristic> heuristic_;
};

TEST_F(RelaxedPlanHeuristicTest, RedundantTurnsAreSkippedWithoutChangingThePlan) {
  // Layer 0: turns away from d0 and the image of d0 start; calibrate would
  // only re-add (calibrated): skipped. Layer 2: d1..d3 are reached, so the
  // 9 turns between d1..d3 and back to d0 that start then add nothing new:
  // skipped. Relaxed plan: turn d3<-d0, turn d1<-d0, image d3 (start and
  // end each) = 6; helpful: the two turns' starts.
  std::vector<SnapId> preferred;
  const int h =
      heuristic_->Evaluate(State({"(pointing d0)", "(calibrated)", "(power)"}), &preferred);
  EXPECT_EQ(h, 6);
  EXPECT_EQ(heuristic_->last_skipped_pairs(), 10);
  std::vector<SnapId> expected = {2 * Action("(turn_to d3 d0)"), 2 * Action("(turn_to d1 d0)")};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(preferred, expected);
}

TEST_F(RelaxedPlanHeuristicTest, RunningActionIsNotSkipped) {
  // turn_to d1 d0 runs: started(a) holds, so its end is applicable at once
  // and achieves (pointing d1); from d1 the satellite reaches d0, d2, d3,
  // after which the turns starting from them are redundant, except the
  // running one (its started(a) is no news, but it is not skipped): 8.
  // Plan: end of the running turn, turn d3<-d1, image d3 = 5; helpful: the
  // running turn's end.
  StateData s = State({"(calibrated)"});
  const int turn = Action("(turn_to d1 d0)");
  s.running.push_back(RunningAction{turn, 5.0, 5.0});
  std::vector<SnapId> preferred;
  const int h = heuristic_->Evaluate(s, &preferred);
  EXPECT_EQ(h, 5);
  EXPECT_EQ(heuristic_->last_skipped_pairs(), 8);
  EXPECT_EQ(preferred, std::vector<SnapId>{2 * turn + 1});
}

TEST_F(RelaxedPlanHeuristicTest, DeadEndWithOnlyRedundantPairsLeftIsProven) {
  // Neither calibrated nor power: no image can be taken, however far the
  // satellite turns; the exploration must still stop and call it proven.
  std::vector<SnapId> preferred;
  const int h = heuristic_->Evaluate(State({"(pointing d0)"}), &preferred);
  EXPECT_EQ(h, RelaxedPlanHeuristic::kDeadEnd);
  EXPECT_TRUE(heuristic_->last_dead_end_proven());
  EXPECT_EQ(heuristic_->last_skipped_pairs(), 9);
}

TEST_F(RelaxedPlanHeuristicTest, PairWithAnUnreachedAddIsKept) {
  // calibrate's start adds nothing real, but its end adds (calibrated),
  // not reached yet: kept, and needed. Plan: calibrate, turn d3<-d0,
  // turn d1<-d0, image d3 = 8; the 9 turns from layer 2 on are skipped.
  std::vector<SnapId> preferred;
  const int h = heuristic_->Evaluate(State({"(pointing d0)", "(power)"}), &preferred);
  EXPECT_EQ(h, 8);
  EXPECT_EQ(heuristic_->last_skipped_pairs(), 9);
  const int calibrate = Action("(calibrate)");
  EXPECT_TRUE(std::find(preferred.begin(), preferred.end(), 2 * calibrate) != preferred.end());
}

// Two ways out of the press, equally long for the delete relaxation: the
// first (in declaration order, so FF's first achiever) turns the sheet
// face down, undoing a goal the state holds.
constexpr char kExitDomain[] = R"((define (domain exit)
  (:requirements :durative-actions)
  (:predicates (at-exit) (face-up) (turned) (half) (out))
  (:durative-action turn-over :parameters () :duration (= ?duration 1)
    :condition (at start (at-exit))
    :effect (and (at start (not (at-exit))) (at start (not (face-up))) (at end (turned))))
  (:durative-action leave-turned :parameters () :duration (= ?duration 1)
    :condition (at start (turned))
    :effect (and (at end (out)) (at end (face-up))))
  (:durative-action slide :parameters () :duration (= ?duration 1)
    :condition (at start (at-exit))
    :effect (and (at start (not (at-exit))) (at end (half))))
  (:durative-action leave-straight :parameters () :duration (= ?duration 1)
    :condition (at start (half))
    :effect (at end (out)))))";

constexpr char kExitProblem[] = R"((define (problem exit-1) (:domain exit)
  (:init (at-exit) (face-up))
  (:goal (and (out) (face-up)))))";

// A task loaded from text with its snap compilation and a heuristic on it
// (all null when the task does not load: LoadTaskOrFail has failed the test).
struct HeuristicOnTask {
  HeuristicOnTask(std::string_view domain, std::string_view problem)
      : task(testing::LoadTaskOrFail(domain, problem)) {
    if (task == nullptr) return;
    snap = std::make_unique<SnapTask>(*task);
    heuristic = std::make_unique<RelaxedPlanHeuristic>(*snap, 0.001);
  }
  StateData Initial() const { return testing::InitialState(*task, *snap); }

  std::shared_ptr<const task::GroundTask> task;
  std::unique_ptr<SnapTask> snap;
  std::unique_ptr<RelaxedPlanHeuristic> heuristic;
};

TEST(RelaxedPlanHeuristicGoalTest, OnTiesTheRelaxedPlanKeepsTheGoalsTheStateHolds) {
  const HeuristicOnTask loaded(kExitDomain, kExitProblem);
  ASSERT_NE(loaded.task, nullptr);
  const task::GroundTask& task = *loaded.task;
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  StateData state = loaded.Initial();  // (at-exit), (face-up)
  const std::vector<SnapId> slide = {2 * testing::ActionIdOf(task, "(slide)")};
  const std::vector<SnapId> turn_over = {2 * testing::ActionIdOf(task, "(turn-over)")};
  std::vector<SnapId> preferred;
  // Either way is two actions (four snaps). FF's first achiever (the
  // default) turns the sheet over.
  EXPECT_EQ(heuristic.Evaluate(state, &preferred), 4);
  EXPECT_EQ(preferred, turn_over);
  // Keeping held goals, the plan slides out: the helpful event is slide's
  // start.
  heuristic.SetKeepHeldGoals(true);
  EXPECT_EQ(heuristic.Evaluate(state, &preferred), 4);
  EXPECT_EQ(preferred, slide);
  // Once the sheet is face down, turning it is no detour: the first way
  // found is kept (neither undoes anything the state holds).
  state.Clear(testing::FactIdOf(task, "(face-up)"));
  EXPECT_EQ(heuristic.Evaluate(state, &preferred), 4);
  EXPECT_EQ(preferred, turn_over);
}

// A courier who must end at home with the van parked there, and make a
// delivery: going out undoes both goals the start state holds, which the
// relaxation does not see. (Delivering also "leaves home", a second
// operator deleting a goal already undone.)
constexpr char kCourierDomain[] = R"((define (domain courier)
  (:requirements :durative-actions)
  (:predicates (home) (van-home) (out) (delivered))
  (:durative-action go-out :parameters () :duration (= ?duration 1)
    :condition (at start (home))
    :effect (and (at start (not (home))) (at start (not (van-home))) (at end (out))))
  (:durative-action deliver :parameters () :duration (= ?duration 1)
    :condition (at start (out))
    :effect (and (at start (not (home))) (at end (delivered))))
  (:durative-action come-back :parameters () :duration (= ?duration 1)
    :condition (at start (out))
    :effect (and (at start (not (out))) (at end (home)) (at end (van-home))))))";

constexpr char kCourierProblem[] = R"((define (problem courier-1) (:domain courier)
  (:init (home) (van-home))
  (:goal (and (home) (van-home) (delivered)))))";

TEST(RelaxedPlanHeuristicGoalTest, KeepingHeldGoalsChargesTheGoalsTheRelaxedPlanUndoes) {
  const HeuristicOnTask loaded(kCourierDomain, kCourierProblem);
  ASSERT_NE(loaded.task, nullptr);
  const task::GroundTask& task = *loaded.task;
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  StateData at_home = loaded.Initial();
  StateData out = at_home;
  out.Clear(testing::FactIdOf(task, "(home)"));
  out.Clear(testing::FactIdOf(task, "(van-home)"));
  out.Set(testing::FactIdOf(task, "(out)"));
  // The relaxed plan from home: go-out, deliver (four snaps); the real one
  // must also come back.
  EXPECT_EQ(heuristic.Evaluate(at_home, nullptr), 4);
  heuristic.SetKeepHeldGoals(true);
  // Two goals undone, (home) by both operators but charged once; the same
  // again on a second evaluation (nothing left over from the first).
  const int charged = 4 + 2 * RelaxedPlanHeuristic::kUndoneGoalCost;
  EXPECT_EQ(heuristic.Evaluate(at_home, nullptr), charged);
  EXPECT_EQ(heuristic.Evaluate(at_home, nullptr), charged);
  // Out, nothing the state holds is undone: deliver, come-back.
  EXPECT_EQ(heuristic.Evaluate(out, nullptr), 4);
  EXPECT_EQ(heuristic.Evaluate(at_home, nullptr), charged);
  // Delivered and home: the goal, nothing to charge.
  at_home.Set(testing::FactIdOf(task, "(delivered)"));
  EXPECT_EQ(heuristic.Evaluate(at_home, nullptr), 0);
}

// A driver must reach the depot while the van stays parked at home, its
// goal: riding the van there is one action but takes the van off home (it
// can ride back); walking takes three.
constexpr char kDepotDomain[] = R"((define (domain depot)
  (:requirements :typing :durative-actions)
  (:types place)
  (:constants depot - place)
  (:predicates (driver-at ?p - place) (van-at ?p - place) (road ?a ?b - place)
               (path ?a ?b - place) (checked-in))
  (:durative-action ride :parameters (?a ?b - place) :duration (= ?duration 1)
    :condition (and (at start (road ?a ?b)) (at start (driver-at ?a)) (at start (van-at ?a)))
    :effect (and (at start (not (driver-at ?a))) (at start (not (van-at ?a)))
                 (at end (driver-at ?b)) (at end (van-at ?b))))
  (:durative-action walk :parameters (?a ?b - place) :duration (= ?duration 1)
    :condition (and (at start (path ?a ?b)) (at start (driver-at ?a)))
    :effect (and (at start (not (driver-at ?a))) (at end (driver-at ?b))))
  (:durative-action check-in :parameters () :duration (= ?duration 1)
    :condition (at start (driver-at depot))
    :effect (at end (checked-in)))))";

// With `paths`, the walk home-m1-m2-depot; `goal` is added to the goal.
std::string DepotProblem(bool paths, const std::string& goal = "") {
  return std::string(R"((define (problem depot-1) (:domain depot)
  (:objects home m1 m2 - place)
  (:init (driver-at home) (van-at home) (road home depot) (road depot home))") +
         (paths ? "(path home m1) (path m1 m2) (path m2 depot)" : "") + R"()
  (:goal (and (van-at home) (checked-in) )" +
         goal + ")))";
}

TEST(RelaxedPlanHeuristicGoalTest, DelayedGoalUndoersTakeTheWayThatKeepsHeldGoals) {
  const HeuristicOnTask loaded(kDepotDomain, DepotProblem(true));
  ASSERT_NE(loaded.task, nullptr);
  const task::GroundTask& task = *loaded.task;
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  const StateData state = loaded.Initial();
  const std::vector<SnapId> ride = {2 * testing::ActionIdOf(task, "(ride home depot)")};
  const std::vector<SnapId> walk = {2 * testing::ActionIdOf(task, "(walk home m1)")};
  std::vector<SnapId> preferred;
  // FF rides: ride, check-in (four snaps). Keeping held goals charges the
  // van's goal, but the ride is still the first achiever.
  EXPECT_EQ(heuristic.Evaluate(state, &preferred), 4);
  EXPECT_EQ(preferred, ride);
  heuristic.SetKeepHeldGoals(true);
  EXPECT_EQ(heuristic.Evaluate(state, &preferred), 4 + RelaxedPlanHeuristic::kUndoneGoalCost);
  EXPECT_EQ(preferred, ride);
  // With the undoer delayed, the walks come first: three walks and the
  // check-in, eight snaps, nothing undone.
  heuristic.SetDelayGoalUndoers(true);
  EXPECT_EQ(heuristic.Evaluate(state, &preferred), 8);
  EXPECT_EQ(preferred, walk);
  // Nothing is left over for the next state: two walks done, one left.
  StateData at_m2 = state;
  at_m2.Clear(testing::FactIdOf(task, "(driver-at home)"));
  at_m2.Set(testing::FactIdOf(task, "(driver-at m2)"));
  EXPECT_EQ(heuristic.Evaluate(at_m2, &preferred), 4);
  EXPECT_EQ(preferred, std::vector<SnapId>{2 * testing::ActionIdOf(task, "(walk m2 depot)")});
}

// The ride also needs fuel: an operator with a numeric condition waits in
// another list of the exploration, and is delayed all the same.
TEST(RelaxedPlanHeuristicGoalTest, AGoalUndoerWithANumericConditionIsDelayedToo) {
  std::string domain = kDepotDomain;
  const std::string ride_condition = "(at start (van-at ?a)))";
  domain.replace(domain.find(ride_condition), ride_condition.size(),
                 "(at start (van-at ?a)) (at start (>= (fuel) 1)))");
  domain.replace(domain.find(":durative-actions)"), 18, ":durative-actions :fluents)");
  domain.replace(domain.find("(checked-in))"), 13, "(checked-in)) (:functions (fuel))");
  std::string problem = DepotProblem(true);
  problem.replace(problem.find("(road home depot)"), 17, "(road home depot) (= (fuel) 5)");
  const HeuristicOnTask loaded(domain, problem);
  ASSERT_NE(loaded.task, nullptr);
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  std::vector<SnapId> preferred;
  EXPECT_EQ(heuristic.Evaluate(loaded.Initial(), &preferred), 4);
  EXPECT_EQ(preferred,
            std::vector<SnapId>{2 * testing::ActionIdOf(*loaded.task, "(ride home depot)")});
  heuristic.SetDelayGoalUndoers(true);
  EXPECT_EQ(heuristic.Evaluate(loaded.Initial(), &preferred), 8);
  EXPECT_EQ(preferred,
            std::vector<SnapId>{2 * testing::ActionIdOf(*loaded.task, "(walk home m1)")});
}

// A goal no operator reaches: the exploration still applies the delayed
// operators before it gives up, and the dead end stays proven.
TEST(RelaxedPlanHeuristicGoalTest, WithDelayedGoalUndoersADeadEndIsStillProven) {
  std::string domain = kDepotDomain;
  domain.replace(domain.find("(checked-in))"), 13, "(checked-in) (never))");
  const HeuristicOnTask loaded(domain, DepotProblem(true, "(never)"));
  ASSERT_NE(loaded.task, nullptr);
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  heuristic.SetKeepHeldGoals(true);
  heuristic.SetDelayGoalUndoers(true);
  EXPECT_EQ(heuristic.Evaluate(loaded.Initial(), nullptr), RelaxedPlanHeuristic::kDeadEnd);
  EXPECT_TRUE(heuristic.last_dead_end_proven());
}

TEST(RelaxedPlanHeuristicGoalTest, ADelayedGoalUndoerIsStillTakenWhenItIsTheOnlyWay) {
  const HeuristicOnTask loaded(kDepotDomain, DepotProblem(false));
  ASSERT_NE(loaded.task, nullptr);
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  heuristic.SetKeepHeldGoals(true);
  heuristic.SetDelayGoalUndoers(true);
  std::vector<SnapId> preferred;
  EXPECT_EQ(heuristic.Evaluate(loaded.Initial(), &preferred),
            4 + RelaxedPlanHeuristic::kUndoneGoalCost);
  EXPECT_EQ(preferred,
            std::vector<SnapId>{2 * testing::ActionIdOf(*loaded.task, "(ride home depot)")});
}

// Trucks driven by whichever driver is aboard: each drive exists once per
// driver, and the copies differ only in (driving ?d ?t), an over-all
// condition. They form one group per truck and road. (t1 is both driven
// and empty so that others can board it: the relaxation does not mind.)
constexpr char kHaulDomain[] = R"((define (domain haul)
  (:requirements :typing :durative-actions)
  (:types truck driver place)
  (:predicates (at ?t - truck ?p - place) (driving ?d - driver ?t - truck)
    (road ?a ?b - place) (in ?d - driver ?p - place) (empty ?t - truck))
  (:durative-action drive :parameters (?t - truck ?from ?to - place ?d - driver)
    :duration (= ?duration 10)
    :condition (and (at start (at ?t ?from)) (at start (road ?from ?to))
      (over all (driving ?d ?t)))
    :effect (and (at start (not (at ?t ?from))) (at end (at ?t ?to))))
  (:durative-action board :parameters (?d - driver ?t - truck ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (in ?d ?p)) (at start (at ?t ?p)) (at start (empty ?t)))
    :effect (and (at start (not (in ?d ?p))) (at start (not (empty ?t)))
      (at end (driving ?d ?t))))))";

constexpr char kHaulProblem[] = R"((define (problem haul-1) (:domain haul)
  (:objects t1 t2 - truck d1 d2 d3 - driver a b c - place)
  (:init (at t1 a) (driving d2 t1) (empty t1) (at t2 c) (empty t2) (in d1 c) (in d3 a)
    (road a b) (road b a) (road b c) (road c b))
  (:goal (and (at t1 c) (at t2 a)))))";

TEST(RelaxedPlanHeuristicGroupTest, DrivesByEachDriverAreOneOperatorWithTheSamePlan) {
  const HeuristicOnTask loaded(kHaulDomain, kHaulProblem);
  ASSERT_NE(loaded.task, nullptr);
  const task::GroundTask& task = *loaded.task;
  RelaxedPlanHeuristic& heuristic = *loaded.heuristic;
  // 2 trucks x 4 roads: t1 by d1, d2 or d3, t2 by d1 or d3 (d2 is in no
  // place, so he boards nothing).
  EXPECT_EQ(heuristic.num_operator_groups(), 8);
  auto id = [&](const char* name) { return testing::ActionIdOf(task, name); };
  // t1: two drives (4 snaps); t2: d1 boards, then two drives (6 snaps).
  // Helpful: the drive by the driver aboard t1, and the boarding.
  const StateData initial = loaded.Initial();
  std::vector<SnapId> grouped, exact;
  const int h = heuristic.Evaluate(initial, &grouped);
  EXPECT_EQ(h, 10);
  std::vector<SnapId> expected = {2 * id("(drive t1 a b d2)"), 2 * id("(board d1 t2 c)")};
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(grouped, expected);
  heuristic.SetGroupOperators(false);
  EXPECT_EQ(heuristic.Evaluate(initial, &exact), h);
  EXPECT_EQ(exact, grouped);

  // d2's drive from a to b runs: its end is the helpful event, and the
  // plan is one snap shorter (the start is done).
  StateData driving = initial;
  driving.Clear(testing::FactIdOf(task, "(at t1 a)"));
  const int drive = id("(drive t1 a b d2)");
  driving.running.push_back(RunningAction{drive, 10.0, 10.0});
  EXPECT_EQ(heuristic.Evaluate(driving, &exact), 9);
  heuristic.SetGroupOperators(true);
  EXPECT_EQ(heuristic.Evaluate(driving, &grouped), 9);
  EXPECT_EQ(grouped, exact);
  EXPECT_TRUE(std::find(grouped.begin(), grouped.end(), 2 * drive + 1) != grouped.end());

  // Nobody can drive t1 once d2 is gone and the others are elsewhere with
  // no truck to reach it: t1's goal is unreachable with or without groups.
  StateData stranded = initial;
  stranded.Clear(testing::FactIdOf(task, "(driving d2 t1)"));
  stranded.Clear(testing::FactIdOf(task, "(in d3 a)"));
  EXPECT_EQ(heuristic.Evaluate(stranded, &grouped), RelaxedPlanHeuristic::kDeadEnd);

  // Two members of one group running (d1 and d2 both drive t1 from a to
  // b; the relaxation does not mind d1 being at c too): each needs its
  // end, as without groups. (Which end is helpful may differ: both reach
  // (at t1 b) in the same layer.)
  StateData both = driving;
  both.Set(testing::FactIdOf(task, "(driving d1 t1)"));
  both.running.push_back(RunningAction{id("(drive t1 a b d1)"), 10.0, 10.0});
  const int h_both = heuristic.Evaluate(both, &grouped);
  EXPECT_NE(h_both, RelaxedPlanHeuristic::kDeadEnd);
  heuristic.SetGroupOperators(false);
  EXPECT_EQ(heuristic.Evaluate(both, &exact), h_both);

  // d2's drives cannot happen any more (a deadline passed): t1 needs d3 to
  // board first. The group must not drive on d2's (driving d2 t1).
  std::vector<std::uint8_t> usable(static_cast<std::size_t>(heuristic.num_relaxed_ops()), 1);
  heuristic.SetGroupOperators(true);
  EXPECT_EQ(heuristic.Evaluate(initial, &grouped, {}, usable), h);
  heuristic.SetGroupOperators(false);
  for (const char* name :
       {"(drive t1 a b d2)", "(drive t1 b a d2)", "(drive t1 b c d2)", "(drive t1 c b d2)"}) {
    usable[2 * id(name)] = usable[2 * id(name) + 1] = 0;
  }
  const int h_exact = heuristic.Evaluate(initial, &exact, {}, usable);
  heuristic.SetGroupOperators(true);
  EXPECT_EQ(heuristic.Evaluate(initial, &grouped, {}, usable), h_exact);
  EXPECT_GT(h_exact, h);
  EXPECT_EQ(grouped, exact);
}

}  // namespace
}  // namespace seaplan::search
