; Case B of paper 000: the replan after the GNSS jump. Container x was loaded
; at port-a, then the ship's position jumped during move-ship A->B; the
; planner replans from where the ship really is, the new location port-s,
; 12 units from port-b (12 / 0.18 = 66.7 s). Time 0 here is the replan time.
(define (problem fjord-case-b)
  (:domain fjord)
  (:objects
    ship0 - ship
    port-s port-a port-b port-c port-d port-e - port
    cont-x cont-y cont-w cont-z - cont
    teamr0 - team_rep
    teamf0 - team_refuel)
  (:init
    (at ship0 port-s) (busy ship0) (loaded cont-x ship0) (no_rep ship0) (no_fuel ship0)
    (= (speed ship0) 0.18)
    (at cont-y port-b) (at cont-w port-c) (at cont-z port-d)
    (at teamr0 port-e) (at teamf0 port-e)
    (connected port-s port-b) (= (distance port-s port-b) 12)
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
