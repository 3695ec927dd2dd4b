(define (problem cross) (:domain ferry)
  (:objects ferry - ship quay-a quay-b - place)
  (:init (at ferry quay-a))
  (:goal (at ferry quay-b)))
