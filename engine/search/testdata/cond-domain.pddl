; Conditional effects and quantifiers: unloading a truck drops every
; package in it at the truck's location.
(define (domain cond-truck)
  (:requirements :typing :durative-actions :adl)
  (:types truck loc pkg)
  (:predicates (at ?t - truck ?l - loc) (in ?p - pkg ?t - truck) (pat ?p - pkg ?l - loc) (link ?a ?b - loc))
  (:durative-action drive
    :parameters (?t - truck ?a ?b - loc)
    :duration (= ?duration 3)
    :condition (and (at start (at ?t ?a)) (at start (link ?a ?b)))
    :effect (and (at start (not (at ?t ?a))) (at end (at ?t ?b))))
  (:durative-action load
    :parameters (?p - pkg ?t - truck ?l - loc)
    :duration (= ?duration 1)
    :condition (and (at start (pat ?p ?l)) (over all (at ?t ?l)))
    :effect (and (at start (not (pat ?p ?l))) (at end (in ?p ?t))))
  (:durative-action unload-all
    :parameters (?t - truck ?l - loc)
    :duration (= ?duration 1)
    :condition (and (over all (at ?t ?l)) (at start (exists (?p - pkg) (in ?p ?t))))
    :effect (forall (?p - pkg) (at end (when (in ?p ?t) (and (not (in ?p ?t)) (pat ?p ?l)))))))
