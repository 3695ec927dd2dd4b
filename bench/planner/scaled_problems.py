#!/usr/bin/env python3
"""Problems larger than the shared benchmark's p01-p05, for ten of its domains.

The shared set holds only the first five problems of each domain; the
larger ones a planner is judged on are not here. This writes random
instances of the same domains at sizes past p05, so that how the planner
scales can be measured (bench/planner/README.md, "Larger generated
instances"):

  floortile ROWS COLS ROBOTS SEED  floortile-2011's domain: a grid of
      ROWS painted rows above a free row 0, COLS columns, checkered goal,
      robots on random tiles (its p01-p05: 3 x 3, 2 robots).
  driverlog DRIVERS TRUCKS PACKAGES SEED  driverlog-2014's domain:
      3 * DRIVERS - 1 road locations on a random connected road map and a
      walking map of path locations, random positions and goals (its p05:
      9 drivers, 9 trucks, 22 packages).

  elevators FLOORS PASSENGERS SEED  elevators-2011's domain: FLOORS + 1
      floors (FLOORS a multiple of 8), two fast elevators stopping every
      fourth floor and one slow elevator per block of eight floors (as in
      its p01-p05: 16-24 floors, 15-26 passengers), random start and
      destination floors.
  trucks TRUCKS LOCATIONS PACKAGES AREAS SEED  trucks-time-til's
      domain: a complete road map, about half the packages with a
      delivery deadline (a timed literal) that a witness plan meets (its
      p01-p05: 1 truck, 3 locations, 3-7 packages, 2 areas).
  satellite-tw SATELLITES DIRECTIONS IMAGES ANTENNAS SEED
      satellite-tw-til's domain: 1-3 instruments per satellite, 3 modes,
      a quarter of the directions ground stations (calibration targets),
      images to take and send, and one visibility window per antenna that
      a witness plan meets (its p01-p05: 1-3 satellites, 7-10 directions,
      3-7 images, 1-2 antennas).
  satellite SATELLITES INSTRUMENTS MODES DIRECTIONS IMAGES SEED
      satellite-2014's domain (constant durations): up to INSTRUMENTS
      instruments per satellite, each supporting 1-3 of MODES modes and
      calibrated at 1-4 of the first third of the directions (ground
      stations and stars), IMAGES images of the other directions, a
      pointing goal for about half the satellites (its p01-p05: 5
      satellites, 12-22 instruments, 5-7 modes, 30-38 directions, 21-33
      goals).
  depots DEPOTS DISTRIBUTORS TRUCKS PALLETS HOISTS CRATES SEED
      depots-time's domain: a pallet and a hoist at every place and the
      rest at random places, crates stacked on random pallets, a goal
      stack for every crate, random distances, speeds, weights and powers
      (its p01-p05: 1 depot, 2 distributors, 2 trucks, 3 pallets, 3 hoists,
      2-10 crates).
  driverlogshift DRIVERS TRUCKS PACKAGES LOCATIONS SEED
      driverlogshift-upf's domain (drivers drive and walk only within a
      102 s shift): sites linked by roads, a walking path between
      neighbours, everything to the last site; seed 1 starts the drivers
      there and the trucks and packages at the first, as its p01-p05 do
      (2-4 drivers, 2-3 trucks and packages, 2-3 sites), other seeds at
      random sites.
  turnandopen ROBOTS ROOMS BALLS SEED  turnandopen-2011's domain: ROOMS
      rooms in a row, a closed door between neighbours (a robot turns the
      knob with one gripper while it opens the door with the other),
      robots with two grippers in random rooms, balls in random rooms to
      carry to random rooms (its p01-p05: 2 robots, 8-9 rooms, 10-18 balls).
  parcprinter PRINTER SHEETS SEED  parcprinter-2011's domains: a print
      job of SHEETS one-sided Letter sheets, each with its own image, black
      or colour at random, to stack in order in the output tray. PRINTER
      is the domain the problem names: upp (the printer of its p01-p03,
      domain-1.pddl, 8-10 sheets) or eTipp (the larger printer of p04-p05,
      domain-4.pddl, 6-7 sheets).

The problem goes to standard output; the domain is the shared one, e.g.
  bench/planner/scaled_problems.py floortile 4 4 2 1 > /tmp/ft-4x4.pddl
  seaplan plan ../shared/bench/floortile-2011/domain.pddl /tmp/ft-4x4.pddl

The same arguments give the same problem (Python's seeded generator).
"""
import argparse
import random
import sys


def floortile(rows, cols, robots, rng):
    def tile(r, c):
        return f"tile_{r}-{c}"

    tiles = [tile(r, c) for r in range(rows + 1) for c in range(1, cols + 1)]
    names = [f"robot{i + 1}" for i in range(robots)]
    start = rng.sample(tiles, robots)
    out = [f"(define (problem floortile-{rows}x{cols}-{robots})", " (:domain floor-tile)",
           " (:objects " + " ".join(tiles) + " - tile",
           "   " + " ".join(names) + " - robot", "   white black - color)", " (:init"]
    for i, robot in enumerate(names):
        out.append(f"   (robot-at {robot} {start[i]})")
        out.append(f"   (robot-has {robot} {'white' if i % 2 == 0 else 'black'})")
    out += ["   (available-color white)", "   (available-color black)"]
    out += [f"   (clear {t})" for t in tiles if t not in start]
    for r in range(1, rows + 1):
        for c in range(1, cols + 1):
            out.append(f"   (up {tile(r, c)} {tile(r - 1, c)})")
            out.append(f"   (down {tile(r - 1, c)} {tile(r, c)})")
    for r in range(rows + 1):
        for c in range(2, cols + 1):
            out.append(f"   (right {tile(r, c)} {tile(r, c - 1)})")
            out.append(f"   (left {tile(r, c - 1)} {tile(r, c)})")
    out += [" )", " (:goal (and"]
    for r in range(1, rows + 1):
        for c in range(1, cols + 1):
            out.append(f"    (painted {tile(r, c)} {'white' if (r + c) % 2 == 0 else 'black'})")
    out += [" ))", " (:metric minimize (total-time)))"]
    return out


def connected_map(nodes, extra_edges, rng):
    """A random spanning tree over `nodes` plus `extra_edges` more edges."""
    order = nodes[:]
    rng.shuffle(order)
    edges = set()
    for i in range(1, len(order)):
        edges.add(tuple(sorted((order[i], rng.choice(order[:i])))))
    most = len(nodes) * (len(nodes) - 1) // 2  # a road between every two
    while len(edges) < min(len(nodes) - 1 + extra_edges, most):
        edges.add(tuple(sorted(rng.sample(nodes, 2))))
    return sorted(edges)


def driverlog(drivers, trucks, packages, rng):
    # The shared p05's proportions: 26 road locations for 9 drivers, about
    # 3.3 roads and 2 walking paths per location.
    sites = [f"s{i}" for i in range(3 * drivers - 1)]
    roads = connected_map(sites, int(len(sites) * 2.3), rng)
    walks = connected_map(sites, int(len(sites) * 1.1), rng)
    driver = [f"driver{i + 1}" for i in range(drivers)]
    truck = [f"truck{i + 1}" for i in range(trucks)]
    package = [f"package{i + 1}" for i in range(packages)]
    path_site = [f"p{a[1:]}-{b[1:]}" for a, b in walks]
    out = [f"(define (problem DLOG-{drivers}-{trucks}-{packages})", "(:domain driverlog)",
           "(:objects"]
    out += [f" {x} - driver" for x in driver] + [f" {x} - truck" for x in truck]
    out += [f" {x} - obj" for x in package] + [f" {x} - location" for x in sites + path_site]
    out += [")", "(:init"]
    out += [f" (at {x} {rng.choice(sites)})" for x in driver]
    for x in truck:
        out += [f" (at {x} {rng.choice(sites)})", f" (empty {x})"]
    out += [f" (at {x} {rng.choice(sites)})" for x in package]
    for a, b in roads:
        out += [f" (link {a} {b})", f" (link {b} {a})"]
    for (a, b), p in zip(walks, path_site):
        out += [f" (path {a} {p})", f" (path {p} {a})", f" (path {b} {p})", f" (path {p} {b})"]
    out += [")", "(:goal (and"]
    out += [f" (at {x} {rng.choice(sites)})" for x in rng.sample(driver, drivers * 3 // 4)]
    out += [f" (at {x} {rng.choice(sites)})" for x in rng.sample(truck, trucks * 3 // 4)]
    out += [f" (at {x} {rng.choice(sites)})" for x in package]
    out += ["))", "(:metric minimize (total-time)))"]
    return out


def elevators(floors, passengers, rng):
    # The shared p02-p05's figures (p01's elevators hold fewer): a slow
    # elevator takes 4 + 8 s x floors and holds 4, a fast one holds 6 and
    # takes 13, 17, 20, 22, 24, 26 s for 4, 8, ... 24 floors (2 s more per
    # further four).
    def fast_s(floors_apart):
        stops = floors_apart // 4
        return [13, 17, 20][stops - 1] if stops <= 3 else 20 + 2 * (stops - 3)

    n = [f"n{i}" for i in range(floors + 1)]
    person = [f"p{i}" for i in range(passengers)]
    fast = ["fast0", "fast1"]
    slow = [f"slow{b}-0" for b in range(floors // 8)]
    out = [f"(define (problem elevators-time-p{floors}_{passengers})", "(:domain elevators-time)",
           "(:objects", " " + " ".join(n) + " - count", " " + " ".join(person) + " - passenger",
           " " + " ".join(fast) + " - fast-elevator", " " + " ".join(slow) + " - slow-elevator", ")",
           "(:init"]
    out += [f" (next {n[i]} {n[i + 1]})" for i in range(floors)]
    out += [f" (above {n[i]} {n[j]})" for i in range(floors + 1) for j in range(i + 1, floors + 1)]
    stops = {lift: list(range(0, floors + 1, 4)) for lift in fast}
    stops.update({lift: list(range(8 * b, 8 * b + 9)) for b, lift in enumerate(slow)})
    for lift, floors_served in stops.items():
        capacity = 6 if lift in fast else 4
        out += [f" (lift-at {lift} {n[rng.choice(floors_served)]})", f" (passengers {lift} n0)"]
        out += [f" (can-hold {lift} {n[c]})" for c in range(1, capacity + 1)]
        out += [f" (reachable-floor {lift} {n[f]})" for f in floors_served]
    starts = [rng.randrange(floors + 1) for _ in person]
    ends = [rng.choice([f for f in range(floors + 1) if f != a]) for a in starts]
    out += [f" (passenger-at {p} {n[a]})" for p, a in zip(person, starts)]
    for b in range(floors // 8):
        for i in range(8 * b, 8 * b + 9):
            out += [f" (= (travel-slow {n[i]} {n[j]}) {4 + 8 * (j - i)})" for j in range(i + 1, 8 * b + 9)]
    for i in range(0, floors + 1, 4):
        out += [f" (= (travel-fast {n[i]} {n[j]}) {fast_s(j - i)})" for j in range(i + 4, floors + 1, 4)]
    out += [")", "(:goal (and"]
    out += [f" (passenger-at {p} {n[b]})" for p, b in zip(person, ends)]
    out += ["))", "(:metric minimize (total-time)))"]
    return out


def trucks(trucks_n, locations, packages, areas, rng):
    # The shared p01-p05's shape: a complete road map with drive times of
    # 200-310 s, packages between distinct locations, about half of them
    # with a delivery deadline. Each deadline is the time a plain witness
    # plan delivers the package (each truck carries its share of the
    # packages one at a time, in random order) stretched by up to 30 %, so
    # every instance is solvable and the first deadlines bind.
    loc = [f"l{i + 1}" for i in range(locations)]
    truck = [f"truck{i + 1}" for i in range(trucks_n)]
    package = [f"package{i + 1}" for i in range(packages)]
    area = [f"a{i + 1}" for i in range(areas)]
    point = [(rng.uniform(0, 220), rng.uniform(0, 220)) for _ in loc]
    drive = {(a, b): round(200 + ((point[a][0] - point[b][0]) ** 2 + (point[a][1] - point[b][1]) ** 2) ** 0.5 / 2.9, 1)
             for a in range(locations) for b in range(locations) if a != b}
    truck_at = [rng.randrange(locations) for _ in truck]
    origin = [rng.randrange(locations) for _ in package]
    dest = [rng.choice([b for b in range(locations) if b != a]) for a in origin]
    timed = set(rng.sample(range(packages), (packages + 1) // 2))
    deadline = {}
    for t in range(trucks_n):
        mine = [p for p in range(packages) if p % trucks_n == t]
        rng.shuffle(mine)
        clock, here = 0.0, truck_at[t]
        for p in mine:
            if here != origin[p]:
                clock += drive[here, origin[p]] + 0.1
            clock += 1.1 + drive[origin[p], dest[p]] + 0.1 + 1.1 + 1.0  # load, drive, unload, deliver
            here = dest[p]
            if p in timed:
                deadline[p] = round(clock * rng.uniform(1.0, 1.3) + 0.5, 1)
    out = [f"(define (problem trucks-{trucks_n}-{locations}-{packages}-{areas})", "(:domain Trucks-TimeTIL)",
           "(:objects"]
    out += [f" {x} - truck" for x in truck] + [f" {x} - package" for x in package]
    out += [f" {x} - location" for x in loc] + [f" {x} - truckarea" for x in area]
    out += [")", "(:init"]
    for x, at in zip(truck, truck_at):
        out += [f" (at {x} {loc[at]})"] + [f" (free {a} {x})" for a in area]
    out += [f" (closer {area[i]} {area[j]})" for i in range(areas) for j in range(i + 1, areas)]
    out += [f" (at {x} {loc[a]})" for x, a in zip(package, origin)]
    out += [f" (connected {loc[a]} {loc[b]})" for a, b in drive]
    out += [f" (deliverable {package[p]} {loc[dest[p]]})" for p in sorted(deadline)]
    out += [f" (at {deadline[p]} (not (deliverable {package[p]} {loc[dest[p]]})))" for p in sorted(deadline)]
    out += [f" (= (drive-time {loc[a]} {loc[b]}) {d})" for (a, b), d in drive.items()]
    out += [")", "(:goal (and"]
    out += [f" ({'delivered' if p in deadline else 'at-destination'} {package[p]} {loc[dest[p]]})" for p in range(packages)]
    out += ["))", "(:metric minimize (total-time)))"]
    return out


def satellite_tw_stations(directions):
    return max(1, directions // 4)


def satellite_tw(satellites, directions, images, antennas, rng):
    # satellite-tw-til's shape (its p01-p05: 1-3 satellites, 1-3
    # instruments each, 3 modes, 7-10 directions, 3-7 images, 1-2
    # antennas): symmetric slew times of 5-62 s, calibration 20-90 s, send
    # times 5-20 s, and one visibility window per antenna that opens for
    # some of the satellites at once. Each window is placed on a witness
    # plan (each satellite takes its images one instrument after another,
    # each antenna sends its share in the order they are taken) and
    # stretched by up to 30 %, so every instance is solvable.
    modes = ["thermograph0", "image1", "spectrograph2"]
    stations = satellite_tw_stations(directions)
    direction = [f"GroundStation{i}" for i in range(stations)]
    direction += [f"Star{i}" for i in range(stations, directions)]
    slew = {}
    for a in range(directions):
        for b in range(a + 1, directions):
            slew[a, b] = slew[b, a] = round(rng.uniform(5, 62), 2)
    sat = [f"satellite{i}" for i in range(satellites)]
    on_board, supports, target, cal_time = [], {}, {}, {}
    for s in range(satellites):
        for _ in range(rng.randint(1, 3)):
            i = len(on_board)
            on_board.append(s)
            supports[i] = sorted(rng.sample(range(3), rng.randint(1, 3)))
            target[i] = rng.randrange(stations)
            cal_time[i] = round(rng.uniform(20, 90), 1)
    for m in range(3):  # every mode on some instrument
        if not any(m in supports[i] for i in supports):
            supports[rng.randrange(len(on_board))].append(m)
    pointing = [rng.randrange(directions) for _ in sat]
    goal = rng.sample([(d, m) for d in range(stations, directions) for m in range(3)], images)
    send_time = {g: round(rng.uniform(5, 20), 2) for g in goal}
    # The witness: each image goes to a random instrument that supports its
    # mode; a satellite's instruments work one after another (they share
    # its power). Its steps are not epsilon apart, but a plan may turn to
    # the first image while calibrating (images are never ground stations),
    # which brings every image at least 5 s earlier than here.
    taken = {}
    for s in range(satellites):
        clock, at = 0.0, pointing[s]
        for i in [i for i in supports if on_board[i] == s]:
            mine = [g for g in goal if g not in taken and g[1] in supports[i]
                    and rng.random() < 0.7]
            if not mine:
                continue
            clock += 2.0 + slew.get((at, target[i]), 0.0) + cal_time[i]
            at = target[i]
            for g in mine:
                clock += slew.get((at, g[0]), 0.0) + 7.0
                at = g[0]
                taken[g] = (s, clock)
            clock += 1.0
    missing = [g for g in goal if g not in taken]
    for g in missing:  # no instrument drew it: one more pass
        i = rng.choice([i for i in supports if g[1] in supports[i]])
        s = on_board[i]
        last = max([t for (owner, t) in taken.values() if owner == s], default=0.0)
        taken[g] = (s, last + 2.0 + 62.0 + cal_time[i] + 62.0 + 7.0 + 1.0)
    ant = [f"antenna{i}" for i in range(antennas)]
    share = {a: [] for a in range(antennas)}
    for g in goal:
        share[rng.randrange(antennas)].append(g)
    window = {}
    for a in range(antennas):
        seen = sorted({taken[g][0] for g in share[a]} | {rng.randrange(satellites)})
        order = sorted(share[a], key=lambda g: taken[g][1])
        opens = round(min([taken[g][1] for g in order], default=60.0) * rng.uniform(0.5, 1.0), 2)
        clock = opens
        for g in order:  # 0.01 s apart from what comes before it (planners' epsilon)
            clock = max(clock, taken[g][1]) + 0.01 + send_time[g]
        closes = round(opens + (clock - opens) * rng.uniform(1.0, 1.3) + 0.04, 2)
        window[a] = (seen, opens, closes)
    out = [f"(define (problem satellite-tw-{satellites}-{directions}-{images}-{antennas})",
           "(:domain satellite)", "(:objects"]
    out += [f" {x} - satellite" for x in sat] + [f" instrument{i} - instrument" for i in supports]
    out += [f" {x} - mode" for x in modes] + [f" {x} - direction" for x in direction]
    out += [f" {x} - antenna" for x in ant] + [")", "(:init"]
    for i in supports:
        out += [f" (supports instrument{i} {modes[m]})" for m in supports[i]]
        out += [f" (calibration_target instrument{i} {direction[target[i]]})",
                f" (= (calibration_time instrument{i} {direction[target[i]]}) {cal_time[i]})",
                f" (on_board instrument{i} {sat[on_board[i]]})"]
    for s, x in enumerate(sat):
        out += [f" (power_avail {x})", f" (pointing {x} {direction[pointing[s]]})"]
    out += [f" (= (slew_time {direction[a]} {direction[b]}) {t})" for (a, b), t in sorted(slew.items())]
    out += [f" (= (send_time {direction[d]} {modes[m]}) {send_time[d, m]})" for d, m in goal]
    for a, (seen, opens, closes) in window.items():
        if share[a]:  # an antenna with nothing to send gets no window
            for s in seen:
                out += [f" (at {opens} (visible {ant[a]} {sat[s]}))",
                        f" (at {closes} (not (visible {ant[a]} {sat[s]})))"]
        out.append(f" (available {ant[a]})")
    out += [")", "(:goal (and"]
    out += [f" (sent_image {direction[d]} {modes[m]})" for d, m in goal]
    out += ["))", "(:metric minimize (total-time)))"]
    return out


def satellite(satellites, instruments, modes_n, directions, images, rng):
    # satellite-2014's shape: the first third of the directions can be
    # calibration targets (named GroundStation or Star), the rest are
    # observed (Star, Planet or Phenomenon); an image is of a direction
    # and a mode some instrument supports, so every instance is solvable
    # (any direction can be turned to).
    kinds = ["thermograph", "image", "spectrograph", "infrared"]
    mode = [f"{kinds[m % len(kinds)]}{m}" for m in range(modes_n)]
    targets = max(1, directions // 3)
    direction = [f"{rng.choice(['GroundStation', 'Star'])}{d}" for d in range(targets)]
    direction += [f"{rng.choice(['Star', 'Planet', 'Phenomenon'])}{d}"
                  for d in range(targets, directions)]
    sat = [f"satellite{s}" for s in range(satellites)]
    on_board, supports, calibrate = [], {}, {}
    for s in range(satellites):
        for _ in range(rng.randint(1, instruments)):
            i = len(on_board)
            on_board.append(s)
            supports[i] = sorted(rng.sample(range(modes_n), rng.randint(1, min(3, modes_n))))
            calibrate[i] = sorted(rng.sample(range(targets), rng.randint(1, min(4, targets))))
    for m in range(modes_n):  # every mode on some instrument
        if not any(m in supports[i] for i in supports):
            supports[rng.randrange(len(on_board))].append(m)
    goal = rng.sample([(d, m) for d in range(targets, directions) for m in range(modes_n)], images)
    out = [f"(define (problem satellite-{satellites}-{instruments}-{modes_n}-{directions}-{images})",
           "(:domain satellite)", "(:objects"]
    out += [f" {x} - satellite" for x in sat] + [f" instrument{i} - instrument" for i in supports]
    out += [f" {x} - mode" for x in mode] + [f" {x} - direction" for x in direction]
    out += [")", "(:init"]
    for s, x in enumerate(sat):
        for i in [i for i in supports if on_board[i] == s]:
            out += [f" (supports instrument{i} {mode[m]})" for m in sorted(supports[i])]
            out += [f" (calibration_target instrument{i} {direction[d]})" for d in calibrate[i]]
            out.append(f" (on_board instrument{i} {x})")
        out += [f" (power_avail {x})", f" (pointing {x} {direction[rng.randrange(directions)]})"]
    out += [")", "(:goal (and"]
    out += [f" (pointing {x} {direction[rng.randrange(directions)]})" for x in sat
            if rng.random() < 0.5]
    out += [f" (have_image {direction[d]} {mode[m]})" for d, m in goal]
    out += ["))", "(:metric minimize (total-time)))"]
    return out


def random_stacks(crates, pallets, rng):
    """Each crate in turn on top of a random pallet's stack: the (crate,
    pallet, what it lies on) triples, and what ends on top of each pallet."""
    top = {p: p for p in pallets}
    stacked = []
    for crate in crates:
        pallet = rng.choice(pallets)
        stacked.append((crate, pallet, top[pallet]))
        top[pallet] = crate
    return stacked, top


def depots(depots_n, distributors, trucks_n, pallets, hoists, crates, rng):
    places = [f"depot{i}" for i in range(depots_n)] + [f"distributor{i}" for i in range(distributors)]
    pallet_at = places + [rng.choice(places) for _ in range(pallets - len(places))]
    hoist_at = places + [rng.choice(places) for _ in range(hoists - len(places))]
    pallet_names = [f"pallet{i}" for i in range(pallets)]
    crate_names = [f"crate{i}" for i in range(crates)]
    truck_names = [f"truck{i}" for i in range(trucks_n)]
    hoist_names = [f"hoist{i}" for i in range(hoists)]
    out = [f"(define (problem depots-{depots_n}-{distributors}-{trucks_n}-{pallets}-{hoists}-{crates})",
           " (:domain Depot)",
           " (:objects " + " ".join(places[:depots_n]) + " - Depot"]
    if distributors > 0:
        out.append("   " + " ".join(places[depots_n:]) + " - Distributor")
    out += ["   " + " ".join(truck_names) + " - Truck",
            "   " + " ".join(pallet_names) + " - Pallet",
            "   " + " ".join(crate_names) + " - Crate",
            "   " + " ".join(hoist_names) + " - Hoist)", " (:init"]
    stacked, top = random_stacks(crate_names, pallet_names, rng)
    place_of = dict(zip(pallet_names, pallet_at))
    out += [f"   (at {crate} {place_of[pallet]}) (on {crate} {below})" for crate, pallet, below in stacked]
    out += [f"   (clear {t})" for t in top.values()]
    out += [f"   (at {p} {pallet_at[i]})" for i, p in enumerate(pallet_names)]
    for i, h in enumerate(hoist_names):
        out.append(f"   (at {h} {hoist_at[i]}) (available {h}) (= (power {h}) {rng.randint(1, 10)})")
    for t in truck_names:
        out.append(f"   (at {t} {rng.choice(places)}) (= (speed {t}) {rng.randint(1, 10)})")
    for a in places:
        for b in places:
            out.append(f"   (= (distance {a} {b}) {0 if a == b else rng.randint(1, 10)})")
    out += [f"   (= (weight {c}) {rng.randint(1, 100)})" for c in crate_names]
    out += [" )", " (:goal (and"]
    # Every crate on a random pallet's new stack, in a random order.
    order = crate_names[:]
    rng.shuffle(order)
    out += [f"    (on {crate} {below})" for crate, _, below in random_stacks(order, pallet_names, rng)[0]]
    out += [" ))", " (:metric minimize (total-time)))"]
    return out


def driverlogshift(drivers, trucks_n, packages, locations, rng, seed):
    sites = [f"l{i}" for i in range(locations)]
    paths = [f"p{i}-{i + 1}" for i in range(locations - 1)]
    last = sites[-1]
    # Seed 1 is the shared instances' layout (drivers at the last site,
    # trucks and packages at the first); other seeds place them at random.
    def place(default):
        return default if seed == 1 else rng.choice(sites)
    driver_at = [place(last) for _ in range(drivers)]
    truck_at = [place(sites[0]) for _ in range(trucks_n)]
    package_at = [place(sites[0]) for _ in range(packages)]
    names = {"driver": [f"d{i}" for i in range(drivers)], "truck": [f"t{i}" for i in range(trucks_n)],
             "obj": [f"p{i}" for i in range(packages)]}
    out = [f"(define (problem dlogshift-{drivers}-{trucks_n}-{packages}-{locations}-{seed})",
           " (:domain driverlogshift)",
           " (:objects " + " ".join(names["driver"]) + " - driver " + " ".join(names["truck"]) +
           " - truck " + " ".join(names["obj"]) + " - obj " + " ".join(sites + paths) + " - location)",
           " (:init"]
    out += [f"   (at {d} {driver_at[i]}) (rested {d})" for i, d in enumerate(names["driver"])]
    out += [f"   (at {t} {truck_at[i]}) (empty {t})" for i, t in enumerate(names["truck"])]
    out += [f"   (at {p} {package_at[i]})" for i, p in enumerate(names["obj"])]
    out += [f"   (link {a} {b})" for a in sites for b in sites if a != b]
    for i, p in enumerate(paths):
        for a in (sites[i], sites[i + 1]):
            out.append(f"   (path {a} {p}) (path {p} {a})")
    goal = [f"(at {x} {last})" for kind in ("driver", "truck", "obj") for x in names[kind]]
    out += [" )", " (:goal (and " + " ".join(goal) + "))", " (:metric minimize (total-time)))"]
    return out


def turnandopen(robots, rooms, balls, rng):
    room = [f"room{i + 1}" for i in range(rooms)]
    door = [f"door{i + 1}" for i in range(rooms - 1)]
    robot = [f"robot{i + 1}" for i in range(robots)]
    ball = [f"ball{i + 1}" for i in range(balls)]
    grippers = [g for i in range(robots) for g in (f"rgripper{i + 1}", f"lgripper{i + 1}")]
    out = [f"(define (problem turnandopen-{robots}-{rooms}-{balls})",
           " (:domain turnandopen-strips)",
           " (:objects " + " ".join(robot) + " - robot",
           "   " + " ".join(grippers) + " - gripper",
           "   " + " ".join(room) + " - room"]
    if door:
        out.append("   " + " ".join(door) + " - door")
    out += ["   " + " ".join(ball) + " - object)", " (:init"]
    out += [f"   (closed {d})" for d in door]
    for i, d in enumerate(door):
        out.append(f"   (connected {room[i]} {room[i + 1]} {d}) (connected {room[i + 1]} {room[i]} {d})")
    for i, r in enumerate(robot):
        out.append(f"   (at-robby {r} {rng.choice(room)}) (free {r} rgripper{i + 1}) "
                   f"(free {r} lgripper{i + 1})")
    out += [f"   (at {b} {rng.choice(room)})" for b in ball]
    out += [" )", " (:goal (and " + " ".join(f"(at {b} {rng.choice(room)})" for b in ball) + "))",
            " (:metric minimize (total-time)))"]
    return out


def parcprinter(printer, sheets, rng):
    sheet = [f"sheet{i + 1}" for i in range(sheets)]
    image = [f"image-{i + 1}" for i in range(sheets)]
    color = [rng.choice(("Black", "Color")) for _ in range(sheets)]
    tray = "Finisher1_Tray" if printer == "upp" else "sys_OutputTray"
    out = [f"(define (problem PrintJob-{sheets})", f" (:domain {printer})",
           " (:objects dummy-sheet " + " ".join(sheet) + " - sheet_t",
           "   " + " ".join(image) + " - image_t)",
           " (:init (Uninitialized) (Oppositeside Front Back) (Oppositeside Back Front)",
           "   (Location dummy-sheet Some_Finisher_Tray)"]
    for i, s in enumerate(sheet):
        below = sheet[i - 1] if i > 0 else "dummy-sheet"
        out.append(f"   (Prevsheet {s} {below}) (Sheetsize {s} Letter) "
                   f"(Location {s} Some_Feeder_Tray) (Imagecolor {image[i]} {color[i]})")
        out.append("   " + " ".join(f"(Notprintedwith {s} {side} {c})" for side in ("Front", "Back")
                                    for c in ("Black", "Color")))
    out += [" )", " (:goal (and"]
    for i, s in enumerate(sheet):
        # The front is printed with the image's own colour only; the back stays blank.
        other = "Color" if color[i] == "Black" else "Black"
        out.append(f"   (Hasimage {s} Front {image[i]}) (Notprintedwith {s} Front {other}) "
                   f"(Notprintedwith {s} Back Black) (Notprintedwith {s} Back Color) "
                   f"(Sideup {s} Front) (Stackedin {s} {tray})")
    out += [" ))", " (:metric minimize (total-time)))"]
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="domain", required=True)
    for name, (domain, params) in {
        "floortile": ("floortile-2011's domain", ["rows", "cols", "robots"]),
        "driverlog": ("driverlog-2014's domain", ["drivers", "trucks", "packages"]),
        "elevators": ("elevators-2011's domain", ["floors", "passengers"]),
        "trucks": ("trucks-time-til's domain", ["trucks", "locations", "packages", "areas"]),
        "satellite": ("satellite-2014's domain", ["satellites", "instruments", "modes", "directions",
                                                  "images"]),
        "satellite-tw": ("satellite-tw-til's domain", ["satellites", "directions", "images", "antennas"]),
        "depots": ("depots-time's domain", ["depots", "distributors", "trucks", "pallets", "hoists",
                                            "crates"]),
        "driverlogshift": ("driverlogshift-upf's domain", ["drivers", "trucks", "packages",
                                                           "locations"]),
        "turnandopen": ("turnandopen-2011's domain", ["robots", "rooms", "balls"]),
        "parcprinter": ("parcprinter-2011's domains", ["sheets"]),
    }.items():
        command = sub.add_parser(name, help=domain)
        if name == "parcprinter":
            command.add_argument("printer", choices=["upp", "eTipp"])
        for param in params + ["seed"]:
            command.add_argument(param, type=int)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    if args.domain == "floortile":
        # One tile at least must be clear, or no robot can move.
        if args.rows < 1 or args.cols < 1 or not 1 <= args.robots < (args.rows + 1) * args.cols:
            parser.error("floortile: rows, cols >= 1 and 1 <= robots < tiles ((rows + 1) * cols)")
        lines = floortile(args.rows, args.cols, args.robots, rng)
    elif args.domain == "elevators":
        if args.floors < 8 or args.floors % 8 != 0 or args.passengers < 1:
            parser.error("elevators: floors a positive multiple of 8, passengers >= 1")
        lines = elevators(args.floors, args.passengers, rng)
    elif args.domain == "trucks":
        if args.trucks < 1 or args.locations < 2 or args.packages < 1 or args.areas < 1:
            parser.error("trucks: trucks, packages, areas >= 1 and locations >= 2")
        lines = trucks(args.trucks, args.locations, args.packages, args.areas, rng)
    elif args.domain == "satellite-tw":
        if args.satellites < 1 or args.directions < 2 or args.antennas < 1 or not \
                1 <= args.images <= 3 * (args.directions - satellite_tw_stations(args.directions)):
            parser.error("satellite-tw: satellites, antennas >= 1, directions >= 2 and 1 <= images <= "
                         "3 x the directions that are not ground stations (a quarter are)")
        lines = satellite_tw(args.satellites, args.directions, args.images, args.antennas, rng)
    elif args.domain == "satellite":
        observed = args.directions - max(1, args.directions // 3)
        if min(args.satellites, args.instruments, args.modes) < 1 or observed < 1 or \
                not 0 <= args.images <= observed * args.modes:
            parser.error("satellite: satellites, instruments, modes >= 1, directions >= 2 and "
                         "0 <= images <= modes x the directions past the first third")
        lines = satellite(args.satellites, args.instruments, args.modes, args.directions,
                          args.images, rng)
    elif args.domain == "driverlogshift":
        if min(args.drivers, args.trucks, args.packages) < 1 or args.locations < 2:
            parser.error("driverlogshift: drivers, trucks, packages >= 1 and locations >= 2")
        lines = driverlogshift(args.drivers, args.trucks, args.packages, args.locations, rng,
                               args.seed)
    elif args.domain == "turnandopen":
        if min(args.robots, args.rooms, args.balls) < 1:
            parser.error("turnandopen: robots, rooms and balls >= 1")
        lines = turnandopen(args.robots, args.rooms, args.balls, rng)
    elif args.domain == "parcprinter":
        if args.sheets < 1:
            parser.error("parcprinter: sheets >= 1")
        lines = parcprinter(args.printer, args.sheets, rng)
    elif args.domain == "depots":
        places = args.depots + args.distributors
        if args.depots < 1 or args.trucks < 1 or args.crates < 1 or args.distributors < 0 or \
                args.pallets < places or args.hoists < places:
            parser.error("depots: depots, trucks, crates >= 1, distributors >= 0, and pallets and "
                         "hoists >= depots + distributors (one of each at every place)")
        lines = depots(args.depots, args.distributors, args.trucks, args.pallets, args.hoists,
                       args.crates, rng)
    else:
        if min(args.drivers, args.trucks, args.packages) < 1:
            parser.error("driverlog: drivers, trucks and packages >= 1")
        lines = driverlog(args.drivers, args.trucks, args.packages, rng)
    sys.stdout.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
