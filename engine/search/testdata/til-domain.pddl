; Timed initial literals: a gate opens at t=10 and closes at t=30; the
; delivery must pass the gate while it is open.
(define (domain gate)
  (:requirements :typing :durative-actions :timed-initial-literals)
  (:predicates (open) (before) (after) (ready) (done-prep))
  (:durative-action prepare
    :parameters ()
    :duration (= ?duration 4)
    :condition (at start (before))
    :effect (at end (ready)))
  (:durative-action pass
    :parameters ()
    :duration (= ?duration 5)
    :condition (and (at start (ready)) (over all (open)))
    :effect (and (at start (not (before))) (at end (after)))))
