; The toggles of toggle-domain.pddl under a deadline: a switch turns on
; only while the shift lasts, and a timed literal ends the shift. Just as
; unsolvable, and the deadline makes the first-plan searches begin again
; with other seeds (planner.h, SearchStatistics::first_plan_restarts).
(define (domain toggles-deadline)
  (:requirements :typing :durative-actions :timed-initial-literals)
  (:types switch)
  (:predicates (on ?s - switch) (off ?s - switch) (done) (first ?s - switch) (shift))
  (:durative-action turn-on
    :parameters (?s - switch)
    :duration (= ?duration 1)
    :condition (and (at start (off ?s)) (over all (shift)))
    :effect (and (at start (not (off ?s))) (at end (on ?s))))
  (:durative-action turn-off
    :parameters (?s - switch)
    :duration (= ?duration 1)
    :condition (at start (on ?s))
    :effect (and (at start (not (on ?s))) (at end (off ?s))))
  (:durative-action finish
    :parameters (?s - switch)
    :duration (= ?duration 1)
    :condition (and (at start (first ?s)) (at start (on ?s)) (at start (off ?s)))
    :effect (at end (done))))
