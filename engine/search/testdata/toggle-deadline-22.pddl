; toggle-22.pddl with the shift of toggle-deadline-domain.pddl, which ends at
; t = 100000.
(define (problem toggles-deadline-22) (:domain toggles-deadline)
  (:objects s1 s2 s3 s4 s5 s6 s7 s8 s9 s10 s11 s12 s13 s14 s15 s16 s17 s18 s19 s20 s21 s22 - switch)
  (:init (off s1) (off s2) (off s3) (off s4) (off s5) (off s6) (off s7) (off s8) (off s9) (off s10) (off s11) (off s12) (off s13) (off s14) (off s15) (off s16) (off s17) (off s18) (off s19) (off s20) (off s21) (off s22) (first s1) (shift) (at 100000 (not (shift))))
  (:goal (and (done) (on s2) (on s3) (on s4) (on s5) (on s6) (on s7) (on s8) (on s9) (on s10) (on s11) (on s12) (on s13) (on s14) (on s15) (on s16) (on s17) (on s18) (on s19) (on s20) (on s21) (on s22))))
