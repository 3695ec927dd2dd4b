; The gate is open only for 3 s: passing (5 s) is impossible.
(define (problem gate-2) (:domain gate)
  (:init (before) (at 10 (open)) (at 13 (not (open))))
  (:goal (after)))
