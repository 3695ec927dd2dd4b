; Duration inequalities: a fuse takes between 2 and 5 s; a match burns for
; (burn-time) s; the planner must pick short mends to fit two into one match.
(define (domain tiny-match)
  (:requirements :typing :durative-actions :numeric-fluents :duration-inequalities)
  (:types match fuse)
  (:predicates (handfree) (unused ?m - match) (light) (mended ?f - fuse))
  (:functions (burn-time) (mended-count))
  (:durative-action light-match
    :parameters (?m - match)
    :duration (= ?duration (burn-time))
    :condition (and (at start (unused ?m)))
    :effect (and (at start (not (unused ?m))) (at start (light)) (at end (not (light)))))
  (:durative-action mend-fuse
    :parameters (?f - fuse)
    :duration (and (>= ?duration 2) (<= ?duration 5))
    :condition (and (at start (handfree)) (over all (light)))
    :effect (and (at start (not (handfree))) (at end (handfree)) (at end (mended ?f))
                 (at end (increase (mended-count) 1)))))
