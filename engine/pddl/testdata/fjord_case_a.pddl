; Case A of paper 000 (Table 2); copy of bench/pddl_ground/fjord_case_a.h
(define (problem fjord-case-a) (:domain mission-planning-mass)
(:objects ship0 - ship
          port-a port-b port-c port-d port-e - port
          cont-x cont-y cont-w cont-z - cont
          teamr0 - team_rep teamf0 - team_refuel
          r-ab r-bc r-cd r-de - route)
(:init (at ship0 port-a) (available ship0) (no_rep ship0) (no_fuel ship0)
       (at cont-x port-a) (at cont-y port-b) (at cont-w port-c) (at cont-z port-d)
       (at teamr0 port-e) (at teamf0 port-e)
       (in_port port-a port-a) (in_port port-b port-b) (in_port port-c port-c)
       (in_port port-d port-d) (in_port port-e port-e)
       (connects r-ab port-a port-b) (connects r-ab port-b port-a)
       (connects r-bc port-b port-c) (connects r-bc port-c port-b)
       (connects r-cd port-c port-d) (connects r-cd port-d port-c)
       (connects r-de port-d port-e) (connects r-de port-e port-d)
       (route_available r-ab) (route_available r-bc) (route_available r-cd) (route_available r-de)
       (= (route-length r-ab) 52) (= (route-length r-bc) 102)
       (= (route-length r-cd) 107) (= (route-length r-de) 87)
       (= (speed ship0) 0.18))
(:goal (and (at ship0 port-e) (at cont-x port-b) (at cont-y port-c) (at cont-w port-d)
            (loaded cont-z ship0) (repaired ship0) (fuel ship0) (busy ship0)))
(:metric minimize (total-time)))
