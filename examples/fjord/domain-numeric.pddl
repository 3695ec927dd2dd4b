; Fjord ship mission with fuel as a numeric fluent (for case-c-numeric.pddl).
; Same actions as domain.pddl; instead of the executor's fuel/no_fuel flags
; the planner tracks (fuel-level ?v) in % of a full tank: move-ship costs 15,
; load-cont / unload-cont / repair-ship 10 (taken at the start, where the
; action also requires that much fuel, so the tank never goes below 0), and
; refuel-ship fills the tank to 100 at its end.
(define (domain fjord-numeric)
  (:requirements :strips :typing :durative-actions :numeric-fluents)
  (:types
    vehicle cont team_rep team_refuel - subject
    ship - vehicle
    port - location)

  (:predicates
    (at ?x - subject ?l - location)
    (available ?v - vehicle)
    (busy ?v - vehicle)
    (loaded ?c - cont ?v - vehicle)
    (connected ?from - port ?to - port)
    (no_rep ?v - vehicle)
    (repaired ?v - vehicle))

  (:functions
    (distance ?from - port ?to - port)
    (speed ?v - vehicle)
    (fuel-level ?v - vehicle))

  (:durative-action move-ship
    :parameters (?v - ship ?from - port ?to - port)
    :duration (= ?duration (/ (distance ?from ?to) (speed ?v)))
    :condition (and (at start (at ?v ?from))
                    (at start (connected ?from ?to))
                    (at start (>= (fuel-level ?v) 15)))
    :effect (and (at start (not (at ?v ?from)))
                 (at start (decrease (fuel-level ?v) 15))
                 (at end (at ?v ?to))))

  (:durative-action load-cont
    :parameters (?v - ship ?l - port ?c - cont)
    :duration (= ?duration 60)
    :condition (and (over all (at ?v ?l))
                    (at start (at ?c ?l))
                    (at start (available ?v))
                    (at start (>= (fuel-level ?v) 10)))
    :effect (and (at start (not (available ?v)))
                 (at start (busy ?v))
                 (at start (not (at ?c ?l)))
                 (at start (decrease (fuel-level ?v) 10))
                 (at end (loaded ?c ?v))))

  (:durative-action unload-cont
    :parameters (?c - cont ?l - port ?v - ship)
    :duration (= ?duration 50)
    :condition (and (over all (at ?v ?l))
                    (at start (loaded ?c ?v))
                    (at start (busy ?v))
                    (at start (>= (fuel-level ?v) 10)))
    :effect (and (at start (not (loaded ?c ?v)))
                 (at start (not (busy ?v)))
                 (at start (decrease (fuel-level ?v) 10))
                 (at end (at ?c ?l))
                 (at end (available ?v))))

  (:durative-action repair-ship
    :parameters (?v - ship ?l - port ?k - team_rep)
    :duration (= ?duration 60)
    :condition (and (at start (at ?v ?l))
                    (over all (at ?v ?l))
                    (at start (at ?k ?l))
                    (at start (no_rep ?v))
                    (at start (>= (fuel-level ?v) 10)))
    :effect (and (at start (not (no_rep ?v)))
                 (at start (decrease (fuel-level ?v) 10))
                 (at end (repaired ?v))))

  (:durative-action refuel-ship
    :parameters (?v - ship ?l - port ?y - team_refuel)
    :duration (= ?duration 80)
    :condition (and (at start (at ?v ?l))
                    (over all (at ?v ?l))
                    (at start (at ?y ?l)))
    :effect (at end (assign (fuel-level ?v) 100))))
