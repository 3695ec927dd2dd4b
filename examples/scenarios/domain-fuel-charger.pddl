; Case C executor-fuel domain as the simulation client flies it: the domain
; of ../fjord/domain-fuel.pddl with one change, so that a plan never asks the
; executor for more than its percentage model can give (issue #6).
;
; Why: the executor charges 15 % per move and the server replans at <= 30 %
; (so at 30, 25 or 20 %). One move to a charger then leaves 15, 10 or 5 %;
; two leave 0 % or less. In ../fjord/domain-fuel.pddl move-fueling-ship only
; needs (no_fuel ?v), so a plan may chain it (S -> A -> B: the planner's
; first plan did, and ran the tank to 0 %). Here move-fueling-ship must end
; where a refuelling team is (parameter ?y, (at ?y ?to)): the first hop of a
; low-fuel plan goes to a charger, as the paper describes ("move-fueling-ship
; to the nearest charger"). Everything else is unchanged; the problem is
; ../fjord/case-c.pddl as it is.
; TODO(#6): fold this into ../fjord/domain-fuel.pddl (owned elsewhere).
(define (domain fjord-fuel)
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
                    (at start (connected ?from ?to))
                    (at start (fuel ?v)))
    :effect (and (at start (not (at ?v ?from)))
                 (at end (at ?v ?to))))

  ; The same move for a ship that must go refuelling (paper: move-fueling-ship),
  ; straight to a port with a refuelling team ?y.
  (:durative-action move-fueling-ship
    :parameters (?v - ship ?from - port ?to - port ?y - team_refuel)
    :duration (= ?duration (/ (distance ?from ?to) (speed ?v)))
    :condition (and (at start (at ?v ?from))
                    (at start (connected ?from ?to))
                    (at start (at ?y ?to))
                    (at start (no_fuel ?v)))
    :effect (and (at start (not (at ?v ?from)))
                 (at end (at ?v ?to))))

  (:durative-action load-cont
    :parameters (?v - ship ?l - port ?c - cont)
    :duration (= ?duration 60)
    :condition (and (over all (at ?v ?l))
                    (at start (at ?c ?l))
                    (at start (available ?v))
                    (at start (fuel ?v)))
    :effect (and (at start (not (available ?v)))
                 (at start (busy ?v))
                 (at start (not (at ?c ?l)))
                 (at end (loaded ?c ?v))))

  (:durative-action unload-cont
    :parameters (?c - cont ?l - port ?v - ship)
    :duration (= ?duration 50)
    :condition (and (over all (at ?v ?l))
                    (at start (loaded ?c ?v))
                    (at start (busy ?v))
                    (at start (fuel ?v)))
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
                    (at start (no_rep ?v))
                    (at start (fuel ?v)))
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
