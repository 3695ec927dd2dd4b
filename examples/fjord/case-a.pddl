; Case A of paper 000 (no event): deliver x A->B, y B->C, w C->D, load z at D,
; end at E repaired and refuelled. Route lengths are those implied by the
; paper's plan durations (length / 0.18 = duration).
(define (problem fjord-case-a)
  (:domain fjord)
  (:objects
    ship0 - ship
    port-a port-b port-c port-d port-e - port
    cont-x cont-y cont-w cont-z - cont
    teamr0 - team_rep
    teamf0 - team_refuel)
  (:init
    (at ship0 port-a) (available ship0) (no_rep ship0) (no_fuel ship0)
    (= (speed ship0) 0.18)
    (at cont-x port-a) (at cont-y port-b) (at cont-w port-c) (at cont-z port-d)
    (at teamr0 port-e) (at teamf0 port-e)
    (connected port-a port-b) (connected port-b port-a)
    (connected port-b port-c) (connected port-c port-b)
    (connected port-c port-d) (connected port-d port-c)
    (connected port-d port-e) (connected port-e port-d)
    (= (distance port-a port-b) 52)  (= (distance port-b port-a) 52)
    (= (distance port-b port-c) 102) (= (distance port-c port-b) 102)
    (= (distance port-c port-d) 107) (= (distance port-d port-c) 107)
    (= (distance port-d port-e) 87)  (= (distance port-e port-d) 87))
  (:goal (and
    (at ship0 port-e)
    (at cont-x port-b) (at cont-y port-c) (at cont-w port-d)
    (loaded cont-z ship0)
    (repaired ship0)
    (fuel ship0)))
  (:metric minimize (total-time)))
