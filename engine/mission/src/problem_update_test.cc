#include "seaplan/mission/problem_update.h"

#include <gtest/gtest.h>

#include "action_model.h"
#include "test_util.h"

namespace seaplan::mission {
namespace {

using testing::CaseALocations;
using testing::CaseAPlan;
using testing::ReadTestData;

// Searches the problem text before its goal (the goal names facts too).
bool Has(const std::string& text, const std::string& what) {
  return text.substr(0, text.find("(:goal")).find(what) != std::string::npos;
}

class ProblemUpdateTest : public ::testing::Test {
 protected:
  std::string domain_ = ReadTestData("domain.pddl");
  std::string problem_ = ReadTestData("case-a.pddl");
  validate::Plan plan_ = CaseAPlan();
};

// Case B: the load at A is done, the move A -> B is cut short by the GNSS
// jump, and the ship is 600 m off the A-B line.
TEST_F(ProblemUpdateTest, CaseBAddsPortSWithRoutesFromGeometry) {
  ShipObservation ship{{400, 600}, std::nullopt};
  auto r = RegenerateProblem(domain_, problem_, {plan_.steps[0]}, {plan_.steps[1]},
                             CaseALocations(), ship);
  ASSERT_TRUE(r.ok()) << r.status();
  const std::string& p = r->problem_text;
  EXPECT_TRUE(r->added_location);
  EXPECT_EQ(r->ship_location, "port-s");
  EXPECT_TRUE(Has(p, "port-s - port")) << p;
  EXPECT_TRUE(Has(p, "(at ship0 port-s)")) << p;
  EXPECT_FALSE(Has(p, "(at ship0 port-a)")) << p;
  EXPECT_TRUE(Has(p, "(loaded cont-x ship0)")) << p;
  EXPECT_FALSE(Has(p, "(at cont-x port-a)")) << p;
  EXPECT_TRUE(Has(p, "(in_port port-s port-s)")) << p;
  // Nearest location is port-a (|(400,600)| = 721 m < 854 m to port-b).
  EXPECT_TRUE(Has(p, "(connects r-port-s-port-b port-s port-b)")) << p;
  EXPECT_TRUE(Has(p, "(connects r-port-b-port-s port-b port-s)")) << p;
  EXPECT_TRUE(Has(p, "(connects r-port-s-port-a port-s port-a)")) << p;
  EXPECT_TRUE(Has(p, "(route_available r-port-s-port-b)")) << p;
  ASSERT_TRUE(r->locations.contains("port-s"));
  // Length S-B scaled from A-B: 52 * |S-B| / |A-B| = 52 * sqrt(600^2+600^2)/1000.
  auto model = internal::ActionModel::Create(domain_, p);
  ASSERT_TRUE(model.ok()) << model.status() << "\n" << p;
  auto state = model->InitialState();
  ASSERT_TRUE(state.fluents.contains("(route-length r-port-s-port-b)"));
  EXPECT_NEAR(state.fluents["(route-length r-port-s-port-b)"], 52 * std::sqrt(720000.0) / 1000,
              1e-9);
  EXPECT_FALSE(r->goal_satisfied);
}

TEST_F(ProblemUpdateTest, SnapsToANearbyLocation) {
  ShipObservation ship{{980, 40}, std::nullopt};
  auto r = RegenerateProblem(domain_, problem_, {plan_.steps[0], plan_.steps[1]}, {},
                             CaseALocations(), ship);
  ASSERT_TRUE(r.ok()) << r.status();
  EXPECT_FALSE(r->added_location);
  EXPECT_EQ(r->ship_location, "port-b");
  EXPECT_TRUE(Has(r->problem_text, "(at ship0 port-b)"));
  EXPECT_FALSE(Has(r->problem_text, "port-s"));
}

TEST_F(ProblemUpdateTest, FuelReadingSetsFlagsOnlyWhereFuelGatesActions) {
  std::vector<validate::PlanStep> all(plan_.steps.begin(), plan_.steps.end());
  // In the case A domain (fuel ship0) is only a goal: a tank reading leaves it alone.
  auto goal_only =
      RegenerateProblem(domain_, problem_, all, {}, CaseALocations(), {{3000, 2000}, 0.25});
  ASSERT_TRUE(goal_only.ok()) << goal_only.status();
  EXPECT_TRUE(Has(goal_only->problem_text, "(fuel ship0)"));
  EXPECT_TRUE(goal_only->goal_satisfied);
  // Executor-fuel domain: moves need (fuel ?v).
  std::string gated = domain_;
  const std::string cond = "(at start (route_available ?r))";
  gated.replace(gated.find(cond), cond.size(), cond + " (at start (fuel ?v))");
  auto high = RegenerateProblem(gated, problem_, all, {}, CaseALocations(), {{3000, 2000}, 0.9});
  ASSERT_TRUE(high.ok()) << high.status();
  EXPECT_TRUE(Has(high->problem_text, "(fuel ship0)"));
  EXPECT_FALSE(Has(high->problem_text, "(no_fuel ship0)"));
  auto low = RegenerateProblem(gated, problem_, all, {}, CaseALocations(), {{3000, 2000}, 0.25});
  ASSERT_TRUE(low.ok());
  EXPECT_FALSE(Has(low->problem_text, "(fuel ship0)"));
  EXPECT_TRUE(Has(low->problem_text, "(no_fuel ship0)"));
  EXPECT_FALSE(low->goal_satisfied);
  // 30 % summed from 10 % and 15 % steps (0.30000000000000004) is at the
  // threshold: the problem must say no_fuel, as the replan decision does.
  double summed = 1.0;
  for (double step : {0.1, 0.15, 0.1, 0.1, 0.15, 0.1}) summed -= step;
  auto at = RegenerateProblem(gated, problem_, all, {}, CaseALocations(), {{3000, 2000}, summed});
  ASSERT_TRUE(at.ok());
  EXPECT_TRUE(Has(at->problem_text, "(no_fuel ship0)"));
}

// The examples' domain style: (connected ?from ?to) + (distance ?from ?to).
TEST_F(ProblemUpdateTest, DistanceFunctionsOfTheTemplateAreScaledByGeometry) {
  std::string domain = R"((define (domain d) (:requirements :typing :durative-actions :fluents)
    (:types ship port) (:predicates (at ?v - ship ?p - port) (connected ?a ?b - port))
    (:functions (distance ?a ?b - port) (speed ?v - ship))
    (:durative-action move-ship :parameters (?v - ship ?a ?b - port)
      :duration (= ?duration (/ (distance ?a ?b) (speed ?v)))
      :condition (and (at start (at ?v ?a)) (at start (connected ?a ?b)))
      :effect (and (at start (not (at ?v ?a))) (at end (at ?v ?b))))))";
  std::string problem =
      R"((define (problem p) (:domain d) (:objects ship0 - ship port-a port-b - port)
    (:init (at ship0 port-a) (connected port-a port-b) (connected port-b port-a)
           (= (distance port-a port-b) 52) (= (distance port-b port-a) 52) (= (speed ship0) 0.18))
    (:goal (at ship0 port-b))))";
  LocationTable loc = {{"port-a", {0, 0}}, {"port-b", {1000, 0}}};
  auto r = RegenerateProblem(domain, problem, {}, {}, loc, {{0, 400}, std::nullopt});
  ASSERT_TRUE(r.ok()) << r.status();
  auto model = internal::ActionModel::Create(domain, r->problem_text);
  ASSERT_TRUE(model.ok()) << model.status() << r->problem_text;
  auto st = model->InitialState();
  EXPECT_TRUE(st.facts.contains("(connected port-s port-b)")) << r->problem_text;
  EXPECT_TRUE(st.facts.contains("(connected port-s port-a)")) << r->problem_text;
  EXPECT_NEAR(st.fluents["(distance port-s port-b)"], 52 * std::hypot(1000, 400) / 1000, 1e-9);
  EXPECT_NEAR(st.fluents["(distance port-s port-a)"], 52 * 400.0 / 1000, 1e-9);
  EXPECT_NEAR(st.fluents["(distance port-b port-s)"], 52 * std::hypot(1000, 400) / 1000, 1e-9);
}

TEST_F(ProblemUpdateTest, PlannedFuelFunctionIsTheConsumedAndBoundedFluent) {
  EXPECT_EQ(PlannedFuelFunction(domain_), "");
  // Declared only, whatever its name: not planned.
  std::string declared = domain_;
  declared.replace(declared.find("(speed ?v - vehicle)"), 20,
                   "(speed ?v - vehicle) (fuel-level ?v - vehicle)");
  EXPECT_EQ(PlannedFuelFunction(declared), "");
  // Consumed by the move and bounded below by its condition: the tank,
  // whatever its name.
  std::string planned = domain_;
  planned.replace(planned.find("(speed ?v - vehicle)"), 20,
                  "(speed ?v - vehicle) (charge ?v - vehicle)");
  planned.replace(planned.find("(at start (route_available ?r)))"), 32,
                  "(at start (route_available ?r)) (at start (>= (charge ?v) 15)))");
  planned.replace(planned.find("(at end (at ?v ?l))))"), 21,
                  "(at end (at ?v ?l)) (at start (decrease (charge ?v) 15))))");
  EXPECT_EQ(PlannedFuelFunction(planned), "charge");
  // Consumed but never required: not a tank the plan has to respect.
  std::string consumed = domain_;
  consumed.replace(consumed.find("(speed ?v - vehicle)"), 20,
                   "(speed ?v - vehicle) (charge ?v - vehicle)");
  consumed.replace(consumed.find("(at end (at ?v ?l))))"), 21,
                   "(at end (at ?v ?l)) (at start (decrease (charge ?v) 15))))");
  EXPECT_EQ(PlannedFuelFunction(consumed), "");
  EXPECT_EQ(PlannedFuelFunction("(define"), "");
}

TEST_F(ProblemUpdateTest, BadStepIsAnError) {
  validate::PlanStep bad{0, "teleport", {"ship0"}, 1};
  auto r = RegenerateProblem(domain_, problem_, {bad}, {}, CaseALocations(), {{0, 0}, 1.0});
  EXPECT_TRUE(absl::IsInvalidArgument(r.status())) << r.status();
}

}  // namespace
}  // namespace seaplan::mission
