(define (problem gate-1) (:domain gate)
  (:init (before) (at 10 (open)) (at 30 (not (open))))
  (:goal (after))
  (:metric minimize (total-time)))
