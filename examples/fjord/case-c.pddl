; Case C of paper 000 (fuel-triggered replanning), executor-fuel variant:
; six ports (A-E plus S at the fjord entrance), the ship starts at S with
; fuel (30 % of the tank, tracked by the executor, not by the planner).
; Charging teams teamf0 at B and teamf1 at D, repair team teamr0 at E.
; Extra route lengths: see README.md.
(define (problem fjord-case-c)
  (:domain fjord-fuel)
  (:objects
    ship0 - ship
    port-s port-a port-b port-c port-d port-e - port
    cont-x cont-y cont-w cont-z - cont
    teamr0 - team_rep
    teamf0 teamf1 - team_refuel)
  (:init
    (at ship0 port-s) (available ship0) (no_rep ship0) (fuel ship0)
    (= (speed ship0) 0.18)
    (at cont-x port-b) (at cont-y port-a) (at cont-w port-c) (at cont-z port-d)
    (at teamf0 port-b) (at teamf1 port-d) (at teamr0 port-e)
    (connected port-s port-a) (connected port-a port-s)
    (= (distance port-s port-a) 70) (= (distance port-a port-s) 70)
    (connected port-s port-b) (connected port-b port-s)
    (= (distance port-s port-b) 120) (= (distance port-b port-s) 120)
    (connected port-s port-c) (connected port-c port-s)
    (= (distance port-s port-c) 219) (= (distance port-c port-s) 219)
    (connected port-s port-d) (connected port-d port-s)
    (= (distance port-s port-d) 317) (= (distance port-d port-s) 317)
    (connected port-s port-e) (connected port-e port-s)
    (= (distance port-s port-e) 394) (= (distance port-e port-s) 394)
    (connected port-a port-b) (connected port-b port-a)
    (= (distance port-a port-b) 52) (= (distance port-b port-a) 52)
    (connected port-a port-c) (connected port-c port-a)
    (= (distance port-a port-c) 149) (= (distance port-c port-a) 149)
    (connected port-a port-d) (connected port-d port-a)
    (= (distance port-a port-d) 248) (= (distance port-d port-a) 248)
    (connected port-a port-e) (connected port-e port-a)
    (= (distance port-a port-e) 325) (= (distance port-e port-a) 325)
    (connected port-b port-c) (connected port-c port-b)
    (= (distance port-b port-c) 102) (= (distance port-c port-b) 102)
    (connected port-b port-d) (connected port-d port-b)
    (= (distance port-b port-d) 196) (= (distance port-d port-b) 196)
    (connected port-b port-e) (connected port-e port-b)
    (= (distance port-b port-e) 275) (= (distance port-e port-b) 275)
    (connected port-c port-d) (connected port-d port-c)
    (= (distance port-c port-d) 107) (= (distance port-d port-c) 107)
    (connected port-c port-e) (connected port-e port-c)
    (= (distance port-c port-e) 176) (= (distance port-e port-c) 176)
    (connected port-d port-e) (connected port-e port-d)
    (= (distance port-d port-e) 87) (= (distance port-e port-d) 87))
  (:goal (and
    (at ship0 port-e)
    (at cont-x port-c) (at cont-y port-b) (at cont-w port-d)
    (loaded cont-z ship0)
    (repaired ship0)))
  (:metric minimize (total-time)))
