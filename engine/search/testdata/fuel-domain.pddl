; Numeric fuel planned up front: each move burns fuel, refuelling is only
; possible at stations, so the plan must include refuelling stops.
(define (domain fuel-ship)
  (:requirements :typing :durative-actions :numeric-fluents)
  (:types ship port)
  (:predicates (at ?s - ship ?p - port) (link ?a ?b - port) (station ?p - port))
  (:functions (fuel ?s - ship) (distance ?a ?b - port) (speed ?s - ship) (fuel-used))
  (:durative-action move
    :parameters (?s - ship ?a ?b - port)
    :duration (= ?duration (/ (distance ?a ?b) (speed ?s)))
    :condition (and (at start (at ?s ?a)) (at start (link ?a ?b))
                    (at start (>= (fuel ?s) (distance ?a ?b))))
    :effect (and (at start (not (at ?s ?a))) (at end (at ?s ?b))
                 (at start (decrease (fuel ?s) (distance ?a ?b)))
                 (at start (increase (fuel-used) (distance ?a ?b)))))
  (:durative-action refuel
    :parameters (?s - ship ?p - port)
    :duration (= ?duration 10)
    :condition (and (at start (at ?s ?p)) (at start (station ?p)) (over all (at ?s ?p))
                    (at start (< (fuel ?s) 100)))
    :effect (at end (assign (fuel ?s) 100))))
