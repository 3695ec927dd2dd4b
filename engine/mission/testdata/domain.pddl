; Corrected fjord domain of paper 000 (Appendix A), for the mission tests.
(define (domain fjord)
  (:requirements :typing :durative-actions :fluents)
  (:types subject location route - object
          vehicle cont team_rep team_refuel - subject
          ship - vehicle
          port - location)
  (:predicates (at ?x - subject ?l - location) (available ?v - vehicle) (busy ?v - vehicle)
               (loaded ?s - subject ?v - vehicle) (connects ?r - route ?l1 ?l2 - location)
               (in_port ?l - location ?p - port) (route_available ?r - route)
               (no_rep ?v - vehicle) (repaired ?v - vehicle) (no_fuel ?v - vehicle) (fuel ?v - vehicle))
  (:functions (route-length ?r - route) (speed ?v - vehicle))
  (:durative-action move-ship
    :parameters (?v - ship ?o - location ?p - port ?l - location ?p1 - port ?r - route)
    :duration (= ?duration (/ (route-length ?r) (speed ?v)))
    :condition (and (at start (at ?v ?o)) (at start (in_port ?o ?p)) (at start (in_port ?l ?p1))
                    (at start (connects ?r ?p ?p1)) (at start (route_available ?r)))
    :effect (and (at start (not (at ?v ?o))) (at end (at ?v ?l))))
  (:durative-action load-cont
    :parameters (?v - ship ?l - port ?p - cont)
    :duration (= ?duration 60)
    :condition (and (over all (at ?v ?l)) (at start (at ?p ?l)) (at start (available ?v)))
    :effect (and (at start (not (available ?v))) (at start (busy ?v)) (at start (not (at ?p ?l)))
                 (at end (loaded ?p ?v))))
  (:durative-action unload-cont
    :parameters (?p - cont ?l - port ?v - ship)
    :duration (= ?duration 50)
    :condition (and (over all (at ?v ?l)) (at start (loaded ?p ?v)) (at start (busy ?v)))
    :effect (and (at start (not (loaded ?p ?v))) (at start (not (busy ?v)))
                 (at end (at ?p ?l)) (at end (available ?v))))
  (:durative-action repair-ship
    :parameters (?v - ship ?l - port ?k - team_rep)
    :duration (= ?duration 60)
    :condition (and (at start (at ?v ?l)) (at start (at ?k ?l)) (at start (no_rep ?v)))
    :effect (and (at start (not (no_rep ?v))) (at start (repaired ?v))))
  (:durative-action refuel-ship
    :parameters (?v - ship ?l - port ?y - team_refuel)
    :duration (= ?duration 80)
    :condition (and (at start (at ?v ?l)) (at start (at ?y ?l)) (at start (no_fuel ?v)))
    :effect (and (at end (not (no_fuel ?v))) (at end (fuel ?v)))))
