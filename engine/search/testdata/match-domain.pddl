; Required concurrency (match cellar): a fuse can only be mended while a
; match burns (over all (light ?m)), so every plan overlaps actions.
(define (domain match-small)
  (:requirements :typing :durative-actions)
  (:types match fuse)
  (:predicates (handfree) (unused ?m - match) (mended ?f - fuse) (light ?m - match))
  (:durative-action light-match
    :parameters (?m - match)
    :duration (= ?duration 5)
    :condition (at start (unused ?m))
    :effect (and (at start (not (unused ?m))) (at start (light ?m)) (at end (not (light ?m)))))
  (:durative-action mend-fuse
    :parameters (?f - fuse ?m - match)
    :duration (= ?duration 2)
    :condition (and (at start (handfree)) (over all (light ?m)))
    :effect (and (at start (not (handfree))) (at end (mended ?f)) (at end (handfree)))))
