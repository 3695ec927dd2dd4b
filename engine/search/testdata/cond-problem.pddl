(define (problem cond-1) (:domain cond-truck)
  (:objects t - truck a b - loc p q - pkg)
  (:init (at t a) (pat p a) (pat q a) (link a b) (link b a))
  (:goal (and (pat p b) (pat q b))))
