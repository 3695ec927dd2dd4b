#include "temporal_reachability.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "../mutex_groups.h"
#include "../search_test_util.h"
#include "../state_registry.h"
#include "../timeline.h"
#include "../transitions.h"
#include "seaplan/search/planner.h"
#include "seaplan/task/grounder.h"
#include "seaplan/validate/validator.h"

namespace seaplan::search {
namespace {

// A van delivers parcels before timed-literal deadlines (trucks-time-til in
// miniature): depot-a and depot-b take 5 s, a-b 12 s.
constexpr char kCourierDomain[] = R"(
(define (domain courier)
  (:requirements :typing :durative-actions :fluents :timed-initial-literals)
  (:types place parcel)
  (:predicates (van-at ?p - place) (at ?x - parcel ?p - place) (in ?x - parcel)
               (deliverable ?x - parcel ?p - place) (delivered ?x - parcel) (road ?a ?b - place))
  (:functions (drive-time ?a ?b - place))
  (:durative-action drive
    :parameters (?a ?b - place)
    :duration (= ?duration (drive-time ?a ?b))
    :condition (and (at start (van-at ?a)) (over all (road ?a ?b)))
    :effect (and (at start (not (van-at ?a))) (at end (van-at ?b))))
  (:durative-action load
    :parameters (?x - parcel ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (at ?x ?p)) (over all (van-at ?p)))
    :effect (and (at start (not (at ?x ?p))) (at end (in ?x))))
  (:durative-action deliver
    :parameters (?x - parcel ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (in ?x)) (over all (van-at ?p)) (at end (deliverable ?x ?p)))
    :effect (and (at start (not (in ?x))) (at end (delivered ?x)))))
)";

std::string CourierProblem(const std::string& goal, double deadline_a_s, double deadline_b_s) {
  return R"(
(define (problem courier-1) (:domain courier)
  (:objects depot a b - place pa pb - parcel)
  (:init (van-at depot) (at pa depot) (at pb depot)
         (road depot a) (road a depot) (road depot b) (road b depot) (road a b) (road b a)
         (= (drive-time depot a) 5) (= (drive-time a depot) 5)
         (= (drive-time depot b) 5) (= (drive-time b depot) 5)
         (= (drive-time a b) 12) (= (drive-time b a) 12)
         (deliverable pa a) (deliverable pb b)
         (at )" +
         std::to_string(deadline_a_s) + R"( (not (deliverable pa a)))
         (at )" +
         std::to_string(deadline_b_s) + R"( (not (deliverable pb b))))
  (:goal )" +
         goal + "))";
}

// The courier with its van an object: the van's places and drives are a
// mutex group (mutex_groups.h finds groups per object). With
// `registering`, a load at the depot (a constant) also registers the
// parcel: a conditional effect whose condition is a place of the van.
std::string VanDomain(bool registering = false) {
  return std::string(R"(
(define (domain van-courier)
  (:requirements :typing :durative-actions :fluents :timed-initial-literals :conditional-effects)
  (:types place parcel van)
  )") + (registering ? "(:constants depot - place)" : "") +
         R"(
  (:predicates (van-at ?v - van ?p - place) (at ?x - parcel ?p - place) (in ?x - parcel ?v - van)
               (deliverable ?x - parcel ?p - place) (delivered ?x - parcel) (road ?a ?b - place)
               (registered ?x - parcel))
  (:functions (drive-time ?a ?b - place))
  (:durative-action drive
    :parameters (?v - van ?a ?b - place)
    :duration (= ?duration (drive-time ?a ?b))
    :condition (and (at start (van-at ?v ?a)) (over all (road ?a ?b)))
    :effect (and (at start (not (van-at ?v ?a))) (at end (van-at ?v ?b))))
  (:durative-action load
    :parameters (?x - parcel ?v - van ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (at ?x ?p)) (over all (van-at ?v ?p)))
    :effect (and (at start (not (at ?x ?p))) (at end (in ?x ?v)))" +
         (registering
              ? "\n                 (when (at start (van-at ?v depot)) (at end (registered ?x)))"
              : "") +
         R"())
  (:durative-action deliver
    :parameters (?x - parcel ?v - van ?p - place)
    :duration (= ?duration 1)
    :condition (and (at start (in ?x ?v)) (over all (van-at ?v ?p)) (at end (deliverable ?x ?p)))
    :effect (and (at start (not (in ?x ?v))) (at end (delivered ?x)))))
)";
}

// One van at the depot, pa there, due at a by `deadline_s`.
std::string VanProblem(double deadline_s) {
  return R"(
(define (problem van-1) (:domain van-courier)
  (:objects depot a b - place pa - parcel v - van)
  (:init (van-at v depot) (at pa depot)
         (road depot a) (road a depot) (road depot b) (road b depot)
         (= (drive-time depot a) 5) (= (drive-time a depot) 5)
         (= (drive-time depot b) 5) (= (drive-time b depot) 5)
         (deliverable pa a) (at )" +
         std::to_string(deadline_s) + R"( (not (deliverable pa a))))
  (:goal (delivered pa))))";
}

// A gate opens at 10 s, closes at `close_s` (never when negative) and
// reopens at `reopen_s` (never when negative); passing it takes 5 s with the
// gate open over all, after a preparation of `prep_s`.
constexpr char kGateDomain[] = R"(
(define (domain gate)
  (:requirements :durative-actions :fluents :timed-initial-literals)
  (:predicates (open) (before) (ready) (after))
  (:functions (prep-time))
  (:durative-action prepare
    :parameters ()
    :duration (= ?duration (prep-time))
    :condition (at start (before))
    :effect (and (at start (not (before))) (at end (ready))))
  (:durative-action pass
    :parameters ()
    :duration (= ?duration 5)
    :condition (and (at start (ready)) (over all (open)))
    :effect (and (at start (not (ready))) (at end (after)))))
)";

std::string GateProblem(double close_s, double reopen_s = -1, double prep_s = 1) {
  std::string init = "(before) (= (prep-time) " + std::to_string(prep_s) + ") (at 10 (open))";
  if (close_s >= 0) init += " (at " + std::to_string(close_s) + " (not (open)))";
  if (reopen_s >= 0) init += " (at " + std::to_string(reopen_s) + " (open))";
  return "(define (problem gate-1) (:domain gate) (:init " + init + ") (:goal (after)))";
}

class Fixture {
 public:
  // With `mutex_groups`, the reachability waits for pairs of facts
  // (UseMutexGroups).
  Fixture(const std::string& domain, const std::string& problem, bool mutex_groups = false) {
    auto loaded = task::LoadTask(domain, problem);
    EXPECT_TRUE(loaded.ok()) << loaded.ErrorText();
    task_ = loaded.task;
    snap_ = std::make_unique<SnapTask>(*task_);
    transitions_ = std::make_unique<Transitions>(*snap_, 0, kEpsilon);
    timeline_ = std::make_unique<Timeline>(*snap_, kEpsilon);
    reachability_ = std::make_unique<TemporalReachability>(*snap_);
    if (mutex_groups) reachability_->UseMutexGroups(MutexGroups(*task_));
    state_ = testing::InitialState(*task_, *snap_);
  }

  bool ok() const { return task_ != nullptr; }
  TemporalReachability& reachability() { return *reachability_; }
  const StateData& state() const { return state_; }

  task::ActionId Action(const std::string& display_name) const {
    return testing::ActionIdOf(*task_, display_name);
  }
  int Fact(const std::string& display_name) const {
    return testing::FactIdOf(*task_, display_name);
  }
  SnapId Start(const std::string& name) const { return 2 * Action(name); }
  SnapId End(const std::string& name) const { return 2 * Action(name) + 1; }

  // Applies the snap to the current state and appends it to the path.
  void Apply(SnapId snap) {
    Event ev;
    ev.snap = snap;
    StateData next;
    ASSERT_TRUE(transitions_->Apply(state_, &ev, &next)) << snap;
    state_ = next;
    path_.push_back(ev);
  }

  // Evaluates the current state on the schedule of its path.
  bool Evaluate() {
    EXPECT_TRUE(timeline_->Build(path_));
    return reachability_->Evaluate(state_, *timeline_);
  }

 private:
  static constexpr double kEpsilon = 0.001;
  std::shared_ptr<const task::GroundTask> task_;
  std::unique_ptr<SnapTask> snap_;
  std::unique_ptr<Transitions> transitions_;
  std::unique_ptr<Timeline> timeline_;
  std::unique_ptr<TemporalReachability> reachability_;
  StateData state_;
  std::vector<Event> path_;
};

TEST(TemporalReachabilityTest, DrivingAwayFromAnUrgentDeliveryIsADeadEnd) {
  Fixture fx(kCourierDomain, CourierProblem("(and (delivered pa) (delivered pb))", 8, 40));
  ASSERT_TRUE(fx.ok());
  ASSERT_TRUE(fx.reachability().active());
  // Load pa (0-1), drive to a (1-6), deliver (6-7) meets the 8 s deadline.
  EXPECT_TRUE(fx.Evaluate());
  fx.Apply(fx.Start("(load pa depot)"));
  fx.Apply(fx.End("(load pa depot)"));
  EXPECT_TRUE(fx.Evaluate());
  // Via b, pa reaches a at 1 + 5 + 12 = 18 s at the earliest: too late,
  // though no deadline has passed on the schedule yet.
  fx.Apply(fx.Start("(drive depot b)"));
  EXPECT_FALSE(fx.Evaluate());
}

TEST(TemporalReachabilityTest, GoingTheRightWayStaysAliveAndTimesFollowTheSchedule) {
  Fixture fx(kCourierDomain, CourierProblem("(and (delivered pa) (delivered pb))", 8, 40));
  ASSERT_TRUE(fx.ok());
  fx.Apply(fx.Start("(load pa depot)"));
  fx.Apply(fx.End("(load pa depot)"));
  fx.Apply(fx.Start("(drive depot a)"));
  ASSERT_TRUE(fx.Evaluate());
  // The van is at a when the drive ends (1 + 5 s), pa delivered 1 s later.
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(van-at a)")), 6.0, 1e-6);
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(delivered pa)")), 7.0, 1e-6);
}

TEST(TemporalReachabilityTest, RelaxedPlanFollowsTheEarliestAchievers) {
  Fixture fx(kCourierDomain, CourierProblem("(delivered pa)", 8, 40));
  ASSERT_TRUE(fx.ok());
  fx.Apply(fx.Start("(load pa depot)"));
  fx.Apply(fx.End("(load pa depot)"));
  ASSERT_TRUE(fx.Evaluate());
  // The van held the depot over all of the load (0-1): it leaves at 1 s at
  // the earliest, not at 0 when the path last wrote (van-at depot).
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(van-at a)")), 6.0, 1e-6);
  // Drive to a and deliver: two durative actions, four snaps; only the
  // drive can start from the state.
  std::vector<SnapId> preferred;
  EXPECT_EQ(fx.reachability().RelaxedPlanLength(fx.state(), &preferred), 4);
  EXPECT_EQ(preferred, std::vector<SnapId>{fx.Start("(drive depot a)")});
}

// Vans v and w the same number of steps from pa, 5 s and 2 s from the
// depot; pa due at a by 30 s.
std::string NearVanProblem() {
  return R"(
(define (problem near-van) (:domain van-courier)
  (:objects depot a b c - place pa - parcel v w - van)
  (:init (van-at v b) (van-at w c) (at pa depot)
         (road b depot) (road c depot) (road depot a)
         (= (drive-time b depot) 5) (= (drive-time c depot) 2) (= (drive-time depot a) 5)
         (deliverable pa a) (at 30 (not (deliverable pa a))))
  (:goal (delivered pa))))";
}

// The plan along the earliest achievers sends the near van, so its helpful
// snaps (the search's, when deadlines apply) start that van. FF's relaxed
// plan counts steps, not seconds: to it the two vans are equal.
TEST(TemporalReachabilityTest, HelpfulSnapsStartTheVanThatArrivesFirst) {
  Fixture fx(VanDomain(), NearVanProblem());
  ASSERT_TRUE(fx.ok());
  ASSERT_TRUE(fx.Evaluate());
  // w: drive c-depot (0-2), load (2-3); relaxed, it leaves for a at 2
  // (without the mutex groups nothing keeps it at the depot while it
  // loads) and arrives at 7: delivered at 8.
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(delivered pa)")), 8.0, 1e-6);
  std::vector<SnapId> preferred;
  EXPECT_EQ(fx.reachability().RelaxedPlanLength(fx.state(), &preferred), 8);
  EXPECT_EQ(preferred, std::vector<SnapId>{fx.Start("(drive w c depot)")});
}

// The search follows those helpful snaps: its first plan sends w (9 s).
// With FF's, whose relaxed plan cannot tell the vans apart, the first plan
// sent v (12 s) and a later search found w's.
TEST(TemporalReachabilityTest, PlannerFirstSendsTheVanThatArrivesFirst) {
  auto loaded = task::LoadTask(VanDomain(), NearVanProblem());
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
  PlannerOptions options;
  options.time_limit_s = 10;
  options.anytime = false;
  std::vector<double> makespans;
  PlanObserver observer;
  observer.on_plan = [&](const PlanResult& plan) { makespans.push_back(plan.makespan_s); };
  const PlanResult r = SolveTask(*loaded.task, options, StopToken(), &observer);
  ASSERT_EQ(r.status, PlanStatus::kSolvedSatisficing) << r.message;
  ASSERT_FALSE(makespans.empty());
  EXPECT_NEAR(makespans.front(), 9.0, 1e-2);
}

TEST(TemporalReachabilityTest, ParcelLoadedElsewhereWaitsForTheVanToDriveBack) {
  // The van drives to a (0-5) without pa; pa's deadline at a is 16.5 s. The
  // van could drive back (5-10), load pa (10-11) and return (11-16): pa is
  // delivered at 17 at the earliest, too late. Without pairs the van is at
  // a from 5 s while it loads pa at the depot, and pa seems delivered at 12.
  for (const bool pairs : {false, true}) {
    SCOPED_TRACE(pairs ? "with pairs" : "without pairs");
    Fixture fx(VanDomain(), VanProblem(16.5), pairs);
    ASSERT_TRUE(fx.ok());
    EXPECT_EQ(fx.reachability().num_pair_facts() > 0, pairs);
    fx.Apply(fx.Start("(drive v depot a)"));
    fx.Apply(fx.End("(drive v depot a)"));
    EXPECT_EQ(fx.Evaluate(), !pairs);
  }
  // With a deadline of 17.5 s both stay alive, and the pair puts the
  // delivery at 17 s.
  Fixture fx(VanDomain(), VanProblem(17.5), true);
  ASSERT_TRUE(fx.ok());
  fx.Apply(fx.Start("(drive v depot a)"));
  fx.Apply(fx.End("(drive v depot a)"));
  ASSERT_TRUE(fx.Evaluate());
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(delivered pa)")), 17.0, 1e-6);
}

TEST(TemporalReachabilityTest, ParcelAlreadyInTheVanNeedsNoPairWait) {
  // pa was loaded at the depot (0-1) and the van drove to a (1-6): the pair
  // (in pa v) with (van-at v a) holds from the state, delivery at 7 s.
  Fixture fx(VanDomain(), VanProblem(7.5), true);
  ASSERT_TRUE(fx.ok());
  fx.Apply(fx.Start("(load pa v depot)"));
  fx.Apply(fx.End("(load pa v depot)"));
  fx.Apply(fx.Start("(drive v depot a)"));
  fx.Apply(fx.End("(drive v depot a)"));
  ASSERT_TRUE(fx.Evaluate());
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(delivered pa)")), 7.0, 1e-6);
}

TEST(TemporalReachabilityTest, ConditionalEffectConditionIsNoPlaceTheVanMustBeIn) {
  // pa waits at a, due there by 7.5 s: drive (0-5), load at a (5-6),
  // deliver (6-7). The load's conditional effect asks for the van at the
  // depot, but need not hold: the parcel is in the van at a with no wait.
  Fixture fx(VanDomain(true), R"(
(define (problem registering-1) (:domain van-courier)
  (:objects a - place pa - parcel v - van)
  (:init (van-at v depot) (at pa a) (road depot a) (road a depot)
         (= (drive-time depot a) 5) (= (drive-time a depot) 5)
         (deliverable pa a) (at 7.5 (not (deliverable pa a))))
  (:goal (delivered pa))))",
             true);
  ASSERT_TRUE(fx.ok());
  ASSERT_TRUE(fx.Evaluate());
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(delivered pa)")), 7.0, 1e-6);
}

TEST(TemporalReachabilityTest, SnapsThatMissedTheirDeadlineAreUnusable) {
  // Only pb is a goal: driving to b first is fine, but delivering pa no
  // longer can happen, and the relaxed plan heuristic is told so.
  Fixture fx(kCourierDomain, CourierProblem("(delivered pb)", 8, 40));
  ASSERT_TRUE(fx.ok());
  fx.Apply(fx.Start("(load pa depot)"));
  fx.Apply(fx.Start("(load pb depot)"));
  fx.Apply(fx.End("(load pa depot)"));
  fx.Apply(fx.End("(load pb depot)"));
  fx.Apply(fx.Start("(drive depot b)"));
  ASSERT_TRUE(fx.Evaluate());
  const auto usable = fx.reachability().usable_snaps();
  EXPECT_TRUE(usable[static_cast<std::size_t>(fx.End("(deliver pb b)"))]);
  EXPECT_FALSE(usable[static_cast<std::size_t>(fx.Start("(deliver pa a)"))]);
  EXPECT_FALSE(usable[static_cast<std::size_t>(fx.End("(deliver pa a)"))]);
}

TEST(TemporalReachabilityTest, OverAllConditionNeedsTheWholeDurationInsideAWindow) {
  {
    Fixture fx(kGateDomain, GateProblem(30));
    ASSERT_TRUE(fx.ok());
    ASSERT_TRUE(fx.reachability().active());
    ASSERT_TRUE(fx.Evaluate());
    // The gate opens at 10 s: passing ends at 15 s at the earliest.
    EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(after)")), 15.0, 1e-6);
  }
  {
    Fixture fx(kGateDomain, GateProblem(13));  // open for 3 s only
    ASSERT_TRUE(fx.ok());
    EXPECT_FALSE(fx.Evaluate());
  }
}

TEST(TemporalReachabilityTest, RunningActionMustEndBeforeItsWindowCloses) {
  // Open 10-16, again from 20. Preparing takes 12 s, so a pass started now
  // runs 12-17 and its gate closes under it; a pass started at 20 would do.
  Fixture fx(kGateDomain, GateProblem(16, 20, 12));
  ASSERT_TRUE(fx.ok());
  fx.Apply(fx.Start("(prepare)"));
  fx.Apply(fx.End("(prepare)"));
  fx.Apply(~0);  // the gate opens
  EXPECT_TRUE(fx.Evaluate());
  EXPECT_NEAR(fx.reachability().EarliestTime(fx.Fact("(after)")), 25.0, 1e-6);
  fx.Apply(fx.Start("(pass)"));
  EXPECT_FALSE(fx.Evaluate());
}

TEST(TemporalReachabilityTest, InactiveWhenNoWindowEverCloses) {
  Fixture fx(kGateDomain, GateProblem(-1));
  ASSERT_TRUE(fx.ok());
  EXPECT_FALSE(fx.reachability().active());
}

// Plans for at most 2 s; expects a plan the validator accepts.
PlanResult PlanAndValidate(const std::string& domain, const std::string& problem) {
  auto loaded = task::LoadTask(domain, problem);
  EXPECT_TRUE(loaded.ok()) << loaded.ErrorText();
  if (!loaded.ok()) return {};
  PlannerOptions options;
  options.time_limit_s = 2;
  PlanResult r = SolveTask(*loaded.task, options, StopToken());
  EXPECT_TRUE(r.status == PlanStatus::kSolvedSatisficing ||
              r.status == PlanStatus::kSolvedOptimally)
      << ToString(r.status) << ": " << r.message;
  auto parsed = validate::ParsePlan(validate::FormatPlan(r.plan));
  EXPECT_TRUE(parsed.ok()) << parsed.status();
  if (parsed.ok()) {
    const auto v = validate::ValidatePlan(*loaded.task, *parsed);
    EXPECT_TRUE(v.valid) << v.ToString() << "\n" << validate::FormatPlan(r.plan);
  }
  return r;
}

// The planner meets both deadlines (pa first) with a plan the validator accepts.
TEST(TemporalReachabilityTest, PlannerDeliversBeforeDeadlines) {
  const PlanResult r =
      PlanAndValidate(kCourierDomain, CourierProblem("(and (delivered pa) (delivered pb))", 8, 25));
  bool delivered_pa = false;
  for (const auto& step : r.plan.steps) {
    if (step.name == "deliver" && step.args.size() == 2 && step.args[0] == "pa") {
      delivered_pa = true;
      EXPECT_LE(step.end_s(), 8.0);
    }
  }
  EXPECT_TRUE(delivered_pa);
}

// Two vans, each with one parcel to deliver within half a second of the
// earliest it can: the pairs must not prune the only way (both vans load,
// drive and deliver at once).
TEST(TemporalReachabilityTest, PlannerMeetsTightDeadlinesWithTwoVans) {
  auto problem = [](const std::string& deadlines) {
    return R"(
(define (problem two-vans) (:domain van-courier)
  (:objects depot a b - place pa pb - parcel v w - van)
  (:init (van-at v depot) (van-at w b) (at pa depot) (at pb b)
         (road depot a) (road a depot) (road depot b) (road b depot)
         (= (drive-time depot a) 5) (= (drive-time a depot) 5)
         (= (drive-time depot b) 5) (= (drive-time b depot) 5)
         (deliverable pa a) (deliverable pb depot) )" +
           deadlines + R"()
  (:goal (and (delivered pa) (delivered pb)))))";
  };
  const PlanResult r = PlanAndValidate(
      VanDomain(),
      problem("(at 7.5 (not (deliverable pa a))) (at 7.5 (not (deliverable pb depot)))"));
  // The vans are interchangeable, but with deadlines no state is dropped
  // as a permutation of another: when each van is free matters.
  EXPECT_EQ(r.stats.symmetric_objects, 0);
  EXPECT_EQ(PlanAndValidate(VanDomain(), problem("")).stats.symmetric_objects, 2);
}

// A deadline even the relaxation cannot meet (the van reaches a at 5 s,
// delivering takes 1 s more) is proven unsolvable without any expansion.
TEST(TemporalReachabilityTest, PlannerProvesAMissedDeadlineUnsolvable) {
  auto loaded = task::LoadTask(kCourierDomain, CourierProblem("(delivered pa)", 4, 25));
  ASSERT_TRUE(loaded.ok()) << loaded.ErrorText();
  PlannerOptions options;
  options.time_limit_s = 2;
  const PlanResult r = SolveTask(*loaded.task, options, StopToken());
  EXPECT_EQ(r.status, PlanStatus::kUnsolvableProven) << ToString(r.status) << ": " << r.message;
  EXPECT_EQ(r.stats.expanded, 0u);
}

}  // namespace
}  // namespace seaplan::search
