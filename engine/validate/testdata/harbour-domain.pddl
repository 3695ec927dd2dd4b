; A small harbour: timed tide windows, fuel as a numeric fluent, charging with
; a duration range and ?duration in its effects, instantaneous actions.
(define (domain harbour)
  (:requirements :typing :durative-actions :numeric-fluents :timed-initial-literals
                 :duration-inequalities :negative-preconditions)
  (:types boat berth)
  (:predicates (tide-high) (at-sea ?b - boat) (moored ?b - boat ?x - berth)
               (free ?x - berth) (inspected ?b - boat) (logged))
  (:functions (fuel ?b - boat) (max-charge ?b - boat) (charged-time))
  (:durative-action enter
    :parameters (?b - boat ?x - berth)
    :duration (= ?duration 10)
    :condition (and (at start (at-sea ?b))
                    (at start (free ?x))
                    (over all (tide-high))
                    (at start (>= (fuel ?b) 5)))
    :effect (and (at start (not (at-sea ?b)))
                 (at start (not (free ?x)))
                 (at start (decrease (fuel ?b) 5))
                 (at end (moored ?b ?x))))
  (:durative-action charge
    :parameters (?b - boat ?x - berth)
    :duration (and (>= ?duration 5) (<= ?duration (max-charge ?b)))
    :condition (and (over all (moored ?b ?x))
                    (at end (tide-high)))      ; shore power is cut at low tide
    :effect (and (at end (increase (fuel ?b) (* 2 ?duration)))
                 (at end (increase (charged-time) ?duration))))
  (:action inspect
    :parameters (?b - boat ?x - berth)
    :precondition (and (moored ?b ?x) (not (inspected ?b)))
    :effect (inspected ?b))
  ; Deletes and adds the same fact: the add wins, the log stays written.
  (:action rewrite-log
    :parameters ()
    :precondition (logged)
    :effect (and (not (logged)) (logged)))
  (:action erase-log
    :parameters ()
    :precondition (logged)
    :effect (not (logged))))
