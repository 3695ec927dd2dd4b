; Fjord ship mission: seaplan's corrected version of the domain in Appendix A
; of paper 000 (see README.md for every change and why).
; Executor-fuel variant (case C): every action but refuelling needs (fuel ?v);
; the executor sets (no_fuel ?v) when the tank reaches 30 % and replans, and
; move-fueling-ship is then the only way to reach a charging team.
; Used by case-c.pddl.
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

  ; The same move for a ship that must go refuelling (paper: move-fueling-ship
  ; "to the nearest charger"): straight to a port with a refuelling team ?y.
  ; Without (at ?y ?to) a plan could chain it (S -> A -> B), asking for two
  ; moves on a tank the executor refuses below 30 %: 15 % each leaves 0 %.
  (:durative-action move-fueling-ship
    :parameters (?v - ship ?from - port ?to - port ?y - team_refuel)
    :duration (= ?duration (/ (distance ?from ?to) (speed ?v)))
    :condition (and (at start (at ?v ?from))
                    (at start (connected ?from ?to))
                    (at start (no_fuel ?v))
                    (at start (at ?y ?to)))
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
