; Unsolvable for the real semantics but solvable when deletes are ignored:
; `finish` needs a switch both on and off. With n switches the search space
; has 2^n states (proof of unsolvability, timeouts, cancellation).
(define (domain toggles)
  (:requirements :typing :durative-actions)
  (:types switch)
  (:predicates (on ?s - switch) (off ?s - switch) (done) (first ?s - switch))
  (:durative-action turn-on
    :parameters (?s - switch)
    :duration (= ?duration 1)
    :condition (at start (off ?s))
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
