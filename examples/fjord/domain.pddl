; Fjord ship mission: seaplan's corrected version of the domain in Appendix A
; of paper 000 (see README.md for every change and why).
; Used by case-a.pddl and case-b.pddl.
(define (domain fjord)
  (:requirements :strips :typing :durative-actions :numeric-fluents)
  (:types
    vehicle cont team_rep team_refuel - subject   ; a vehicle is a subject, so (at ship0 ?l) is well typed
    ship - vehicle
    port - location)

  (:predicates
    (at ?x - subject ?l - location)
    (available ?v - vehicle)          ; free to load a container
    (busy ?v - vehicle)               ; carrying (or loading) a container
    (loaded ?c - cont ?v - vehicle)
    (connected ?from - port ?to - port) ; a navigable route from ?from to ?to
    (no_rep ?v - vehicle)
    (repaired ?v - vehicle)
    (no_fuel ?v - vehicle)
    (fuel ?v - vehicle))

  (:functions
    (distance ?from - port ?to - port) ; route length (same unit as speed * s)
    (speed ?v - vehicle))

  (:durative-action move-ship
    :parameters (?v - ship ?from - port ?to - port)
    :duration (= ?duration (/ (distance ?from ?to) (speed ?v)))
    :condition (and (at start (at ?v ?from))
                    (at start (connected ?from ?to)))
    :effect (and (at start (not (at ?v ?from)))
                 (at end (at ?v ?to))))

  (:durative-action load-cont
    :parameters (?v - ship ?l - port ?c - cont)
    :duration (= ?duration 60)
    :condition (and (over all (at ?v ?l))
                    (at start (at ?c ?l))
                    (at start (available ?v)))
    :effect (and (at start (not (available ?v)))
                 (at start (busy ?v))
                 (at start (not (at ?c ?l)))
                 (at end (loaded ?c ?v))))

  (:durative-action unload-cont
    :parameters (?c - cont ?l - port ?v - ship)
    :duration (= ?duration 50)
    :condition (and (over all (at ?v ?l))
                    (at start (loaded ?c ?v))
                    (at start (busy ?v)))
    :effect (and (at start (not (loaded ?c ?v)))
                 (at start (not (busy ?v)))
                 (at end (at ?c ?l))
                 (at end (available ?v))))

  (:durative-action repair-ship
    :parameters (?v - ship ?l - port ?k - team_rep)
    :duration (= ?duration 60)
    :condition (and (at start (at ?v ?l))
                    (over all (at ?v ?l))
                    (at start (at ?k ?l))
                    (at start (no_rep ?v)))
    :effect (and (at start (not (no_rep ?v)))
                 (at end (repaired ?v))))

  (:durative-action refuel-ship
    :parameters (?v - ship ?l - port ?y - team_refuel)
    :duration (= ?duration 80)
    :condition (and (at start (at ?v ?l))
                    (over all (at ?v ?l))
                    (at start (at ?y ?l))
                    (at start (no_fuel ?v)))
    :effect (and (at start (not (no_fuel ?v)))
                 (at end (fuel ?v)))))
