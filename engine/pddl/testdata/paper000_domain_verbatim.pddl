(define (domain mission-planning-mass)
(:requirements :typing :durative-actions)
(:types
  ship - vehicle
  port - location
  cont team_rep team_refuel - subject
  route)
(:predicates
  (at ?physical_obj1 - subject ?location1
    - location)
  (available ?vehicle1 - vehicle)
  (busy ?vehicle1 - vehicle)
  (loaded ?subject1 - subject ?vehicle1 - vehicle)
  (connects ?route1 - route ?location1 - location
    ?location2 - location)
  (in_port ?location1 - location ?port1 - port)
  (route_available ?route1 - route)
  (no_rep ?vehicle1 - vehicle)
  (repaired ?vehicle1 - vehicle)
  (no_fuel ?vehicle1 - vehicle)
  (fuel ?vehicle1 - vehicle)
  )
(:functions
  (distance ?O - location ?L - location)
  (route-length ?O - route)
  (speed ?V - vehicle)
  )
(:durative-action move-ship
:parameters ( ?V - vehicle ?O - location ?Port -
  port ?L - location ?Port1 - port ?R - route)
:duration (= ?duration
  (/ (route-length ?R) (speed ?V)))
:condition (and
  (at start (at ?V ?O))
  (at start (in_port ?O ?Port))
  (at start (in_port ?L ?Port1))
  (at start (fuel ?V))
  (at start (connects
    ?R ?Port ?Port1))
  )
:effect (and
  (at start (not (at ?V ?O)))
  (at end (at ?V ?L))
  ) )
(:durative-action move-fueling-ship
:parameters ( ?V - vehicle ?O - location ?Port -
  port ?L - location ?Port1 - port ?R - route)
:duration (= ?duration
  (/ (route-length ?R) (speed ?V)))

:condition (and
    (at start (at ?V ?0))
    (at start (in_port ?0 ?Port))
    (at start (in_port ?L ?Port1))
    (at start (no_fuel ?V))
    (at start (connects
        ?R ?Port ?Port1))
)
:effect (and
    (at start (not (at ?V ?0)))
    (at end (at ?V ?L))
)
)
(:durative-action load-cont
:parameters ( ?V - ship ?L - port ?P - cont)
:duration (= ?duration 60)
:condition (and
    (over all (at ?V ?L))
    (at start (at ?P ?L))
    (at start (fuel ?V))
    (at start (available ?V))
)
:effect (and
    (at start (not (available ?V)))
    (at start (busy ?V))
    (at start (not (at ?P ?L)))
    (at end (loaded ?P ?V))
)
)
(:durative-action unload-cont
:parameters ( ?P - cont ?L - port ?V - ship )
:duration (= ?duration 50)
:condition (and
    (over all (at ?V ?L))
    (at start (loaded ?P ?V))
    (at start (fuel ?V))
    (at start (busy ?V))
)
:effect (and
    (at start (not (loaded ?P ?V)))
    (at end (at ?P ?L))
    (at start (not (busy ?V)))
    (at end (available ?V))
)
)
(:durative-action repair-ship
:parameters ( ?V - ship ?L - port ?K - team_rep)
:duration (= ?duration 60)
:condition (and
    (at start (at ?V ?L))
    (at start (at ?K ?L))
    (at start (fuel ?V))
    (at start (no_rep ?V))
)
:effect (and
    (at start (not (no_rep ?V)))
    (at start (repaired ?V))
)
)
(:durative-action refuel-ship
:parameters ( ?V - ship ?L - port ?Y - team_refuel)
:duration (= ?duration 80)
:condition (and
    (at start (at ?V ?L))
    (at start (at ?Y ?L))
    (at start (no_fuel ?V))
)
