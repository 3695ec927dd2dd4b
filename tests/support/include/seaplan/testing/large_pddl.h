// A PDDL task that is large to ground on purpose, for tests of grounding
// budgets, deadlines and cancellation: one action over three `obj`
// parameters with no precondition, so every one of objects^3 instances is
// reachable (100 objects: a million ground actions, seconds of grounding and
// hundreds of MB).
#pragma once

#include <string>

namespace seaplan::testing {

struct PddlTexts {
  std::string domain;
  std::string problem;
};

inline PddlTexts CubicGroundingTask(int objects) {
  std::string names;
  for (int i = 0; i < objects; ++i) names += " o" + std::to_string(i);
  return {R"(
(define (domain big) (:requirements :typing) (:types obj)
 (:predicates (p ?a ?b ?c - obj))
 (:action a :parameters (?x ?y ?z - obj) :precondition () :effect (p ?x ?y ?z))))",
          "(define (problem q) (:domain big) (:objects" + names +
              " - obj) (:init) (:goal (p o1 o2 o3)))"};
}

}  // namespace seaplan::testing
