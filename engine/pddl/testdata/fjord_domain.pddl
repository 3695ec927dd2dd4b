; Corrected domain of paper 000 (cases A/B); copy of bench/pddl_ground/fjord_case_a.h
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
