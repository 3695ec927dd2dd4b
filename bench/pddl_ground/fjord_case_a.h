// The paper's case A (fjord mission: 5 ports, 4 containers, one ship), with
// the domain of paper 000 Appendix A corrected (vehicles are subjects, ?0 ->
// ?O, refuel effects restored, no fuel preconditions as in cases A/B) and the
// goal of its Table 2 ((refuel ship0) read as (fuel ship0)). Kept in the
// benchmark so it runs without any data folder; examples/fjord is the
// project's user-facing copy.
#pragma once

namespace seaplan::bench {

inline constexpr const char* kFjordDomain = R"PDDL(
(define (domain mission-planning-mass)
(:requirements :typing :durative-actions)
(:types ship - vehicle
        port - location
        vehicle cont team_rep team_refuel - subject
        route)
(:predicates
  (at ?x - subject ?l - location)
  (available ?v - vehicle)
  (busy ?v - vehicle)
  (loaded ?s - subject ?v - vehicle)
  (connects ?r - route ?l1 - location ?l2 - location)
  (in_port ?l - location ?p - port)
  (route_available ?r - route)
  (no_rep ?v - vehicle)
  (repaired ?v - vehicle)
  (no_fuel ?v - vehicle)
  (fuel ?v - vehicle))
(:functions (distance ?o ?l - location) (route-length ?r - route) (speed ?v - vehicle))
(:durative-action move-ship
 :parameters (?V - vehicle ?O - location ?Port - port ?L - location ?Port1 - port ?R - route)
 :duration (= ?duration (/ (route-length ?R) (speed ?V)))
 :condition (and (at start (at ?V ?O)) (at start (in_port ?O ?Port)) (at start (in_port ?L ?Port1))
                 (at start (connects ?R ?Port ?Port1)))
 :effect (and (at start (not (at ?V ?O))) (at end (at ?V ?L))))
(:durative-action load-cont
 :parameters (?V - ship ?L - port ?P - cont)
 :duration (= ?duration 60)
 :condition (and (over all (at ?V ?L)) (at start (at ?P ?L)) (at start (available ?V)))
 :effect (and (at start (not (available ?V))) (at start (busy ?V)) (at start (not (at ?P ?L)))
              (at end (loaded ?P ?V))))
(:durative-action unload-cont
 :parameters (?P - cont ?L - port ?V - ship)
 :duration (= ?duration 50)
 :condition (and (over all (at ?V ?L)) (at start (loaded ?P ?V)) (at start (busy ?V)))
 :effect (and (at start (not (loaded ?P ?V))) (at end (at ?P ?L)) (at start (not (busy ?V)))
              (at end (available ?V))))
(:durative-action repair-ship
 :parameters (?V - ship ?L - port ?K - team_rep)
 :duration (= ?duration 60)
 :condition (and (at start (at ?V ?L)) (at start (at ?K ?L)) (at start (no_rep ?V)))
 :effect (and (at start (not (no_rep ?V))) (at start (repaired ?V))))
(:durative-action refuel-ship
 :parameters (?V - ship ?L - port ?Y - team_refuel)
 :duration (= ?duration 80)
 :condition (and (at start (at ?V ?L)) (at start (at ?Y ?L)) (at start (no_fuel ?V)))
 :effect (and (at end (not (no_fuel ?V))) (at end (fuel ?V)))))
)PDDL";

inline constexpr const char* kFjordProblemCaseA = R"PDDL(
(define (problem fjord-case-a) (:domain mission-planning-mass)
(:objects ship0 - ship
          port-a port-b port-c port-d port-e - port
          cont-x cont-y cont-w cont-z - cont
          teamr0 - team_rep teamf0 - team_refuel
          r-ab r-bc r-cd r-de - route)
(:init (at ship0 port-a) (available ship0) (no_rep ship0) (no_fuel ship0)
       (at cont-x port-a) (at cont-y port-b) (at cont-w port-c) (at cont-z port-d)
       (at teamr0 port-e) (at teamf0 port-e)
       (in_port port-a port-a) (in_port port-b port-b) (in_port port-c port-c)
       (in_port port-d port-d) (in_port port-e port-e)
       (connects r-ab port-a port-b) (connects r-ab port-b port-a)
       (connects r-bc port-b port-c) (connects r-bc port-c port-b)
       (connects r-cd port-c port-d) (connects r-cd port-d port-c)
       (connects r-de port-d port-e) (connects r-de port-e port-d)
       (route_available r-ab) (route_available r-bc) (route_available r-cd) (route_available r-de)
       (= (route-length r-ab) 52) (= (route-length r-bc) 102)
       (= (route-length r-cd) 107) (= (route-length r-de) 87)
       (= (speed ship0) 0.18))
(:goal (and (at ship0 port-e) (at cont-x port-b) (at cont-y port-c) (at cont-w port-d)
            (loaded cont-z ship0) (repaired ship0) (fuel ship0) (busy ship0)))
(:metric minimize (total-time)))
)PDDL";

}  // namespace seaplan::bench
