(define (problem toggles-3) (:domain toggles)
  (:objects s1 s2 s3 - switch)
  (:init (off s1) (off s2) (off s3) (first s1))
  (:goal (done)))
