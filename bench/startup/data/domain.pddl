; A one-action temporal domain: the smallest problem `seaplan plan` solves,
; so that the start-up benchmark measures the process, not the search.
(define (domain ferry)
  (:requirements :strips :typing :durative-actions)
  (:types ship place)
  (:predicates (at ?s - ship ?p - place))
  (:durative-action sail
    :parameters (?s - ship ?from ?to - place)
    :duration (= ?duration 10)
    :condition (at start (at ?s ?from))
    :effect (and (at start (not (at ?s ?from))) (at end (at ?s ?to)))))
