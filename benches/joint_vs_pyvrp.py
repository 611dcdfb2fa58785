"""The joint problem of issue 19 (item 5) against PyVRP 0.14: order and returns together.

Usage:
    cargo run --release -p agripath --example bench_joint -- --export DIR [--planner KEY]
    .peers/bench/bin/python benches/joint_vs_pyvrp.py DIR [SECONDS] [--seed N]
        [--objective time|duration|distance] [--iterations N] [--results FILE] [--peer FILE]
    .peers/bench/bin/python benches/joint_vs_pyvrp.py --validate

For each instance of DIR (written by `bench_joint`), PyVRP solves the same problem as our
planner: one drone, one supply point, every pass flown once in either direction, a tank that
sprays at most `spray_per_tank_m` metres of pass per sortie, a battery that flies at most
`usable_battery_s` seconds per sortie (out-leg, passes, transfers, home-leg), a service at the
supply point before every sortie but the first (max(battery swap, refill by seed 003 eq. 5)).
The script prints, per farm, our total non-spray distance (transfers + supply legs) against
PyVRP's, the ratio ours / PyVRP, both sortie counts and both non-spray times; then the mean
ratio and the worst (the highest).

How PyVRP is modelled (it is a peer to measure against, not a dependency of the product):

- Each pass p is two clients, one per flying direction: "p flown A→B" (entry A, exit B) and
  "p flown B→A". Both sit in one required, mutually exclusive client group (exactly one is
  flown); the clients themselves are optional, as PyVRP requires of group members.
- PyVRP 0.14 keeps its matrices over locations, so each client gets its own location (placed
  at its entry end; coordinates only steer PyVRP's neighbourhoods) and the matrix is
  asymmetric: from client i to client j costs the transfer from i's exit end to j's entry
  end (seed 001 eq. 8, our exported matrix); from the depot (the supply point) to j costs
  the supply leg of j's entry end; from i to the depot the supply leg of i's exit end
  (`SortieModel::leg_m`). An edge between a pass's two clients is never flown: it gets a
  prohibitive value, so that it does not crowd PyVRP's neighbour lists.
- Durations: a transfer that climbs (leaves the field, +2h) is flown at transit speed, one
  that stays in the field at turn speed (as `WorkRoute::from_route` times them); supply legs
  at transit speed; a client's service duration is its pass's spray seconds.
- Each sortie is a vehicle: one vehicle type with capacity = one tank, shift duration = the
  usable battery seconds, and num_available = 2 × (lower bound on sorties) + 5, more than
  any solution uses. Delivery of a client = its pass's spray metres.
- Objective (`--objective time`, the default): the operator's non-spray time, as our planner
  minimises it, with nothing constant in it. PyVRP minimises unit_distance_cost × distance +
  unit_duration_cost × duration + fixed costs; the "distance" matrix given to PyVRP here holds
  each leg's flight seconds (transfer at its speed, supply leg at transit speed), with
  unit_distance_cost = 1 and unit_duration_cost = 0, and fixed_cost = one service time per
  used vehicle, taken as the service before a full tank (max(battery swap, refill of a full
  tank) = 120 s for the default vehicle). The duration matrix holds the same seconds and
  serves the battery limit only. Charging a service to the first sortie too adds a constant;
  PyVRP cannot express that the refill grows with the next sortie's spray (eq. 5), so the
  re-costing below charges it exactly. Two other objectives, for comparison:
  `--objective duration` puts the time in PyVRP's duration cost instead (unit_duration_cost =
  1, unit_distance_cost = 0, the same fixed cost): the same objective plus the spray seconds,
  a constant, and iteration for iteration the same search (same solution after 3,000
  iterations on seed 001), but 1.5 × slower per iteration, so that 20 s buy fewer of them;
  `--objective distance`
  minimises the acceptance's measure itself (metres in the distance matrix,
  unit_distance_cost = 1, no duration cost, no fixed cost; PyVRP's defaults).
- Integers: PyVRP's data are integers. Metres (the distance objective's) and loads in
  centimetres, seconds (durations, and the time objective's "distance") in centiseconds. Every edge duration, service duration and delivery is rounded up and the
  capacity and shift duration down, so that whatever PyVRP finds feasible is feasible on the
  float data (a conservative margin of at most 0.01 s per leg and 0.01 m per pass).
- Fixed time limit (default 20 s, `MaxRuntime`), fixed seed (default 1), default parameters.
  A wall-clock limit on a shared machine does not repeat exactly; `--iterations N` stops
  after N iterations (`MaxIterations`) instead, which does.

PyVRP's best solution is then re-costed on the float data: every pass exactly once, each
sortie within the tank and the battery (any violation is printed and the farm marked), the
non-spray distance = transfers + supply legs (the first out-leg and the last home-leg
included), the non-spray time = transfers at their speeds + supply legs at transit speed +
a service before every sortie but the first, the sorties flown in the order that spares the
largest service (sortie order changes nothing else). Our figures are the ones `bench_joint`
measured from the library's plan (which may return mid-pass, PyVRP only at pass ends).

`--validate` checks the model first on tiny instances, against brute force over every
order, direction and split of 4-5 passes.
"""
import argparse
import glob
import itertools
import json
import math
import os
import random
import sys

from pyvrp import Model
from pyvrp.stop import MaxIterations, MaxRuntime

DISTANCE_SCALE = 100  # centimetres
DURATION_SCALE = 100  # centiseconds
TOLERANCE = 1e-6


def entry_end(pass_index, reversed_):
    """End index (2p = A, 2p + 1 = B) a pass is entered by."""
    return 2 * pass_index + int(reversed_)


def exit_end(pass_index, reversed_):
    """End index a pass is left by."""
    return 2 * pass_index + 1 - int(reversed_)


def transfer_s(instance, from_end, to_end):
    """Seconds of the transfer between two ends: transit speed when it climbs (plus its climb
    and descent at climb speed, `transfer_climb_s`, as our split charges it), else turn speed."""
    vehicle = instance["vehicle"]
    metres = instance["transfer_m"][from_end][to_end]
    if instance["transfer_climbs"][from_end][to_end]:
        return metres / vehicle["transit_mps"] + vehicle.get("transfer_climb_s", 0.0)
    return metres / vehicle["turn_mps"]


def service_s(vehicle, spray_m):
    """The stop before a sortie spraying `spray_m`: max(battery swap, refill by eq. 5)."""
    tank = vehicle["spray_per_tank_m"]
    refill = vehicle["refill_base_s"]
    if tank is not None:
        refill += (vehicle["refill_max_s"] - vehicle["refill_base_s"]) * min(spray_m / tank, 1.0)
    return max(vehicle["battery_swap_s"], refill)


def cost_sorties(instance, sorties):
    """Re-costs sorties (lists of (pass, reversed)) on the float data; lists every violation."""
    vehicle = instance["vehicle"]
    passes = instance["passes"]
    legs = instance["supply_leg_m"]
    tank = vehicle["spray_per_tank_m"]
    problems = []
    flown = [pass_index for sortie in sorties for pass_index, _ in sortie]
    if sorted(flown) != list(range(len(passes))):
        missing = len(set(range(len(passes))) - set(flown))
        problems.append(f"{len(flown)} passes flown for {len(passes)} ({missing} missing)")
    transfers_m = supply_m = travel_s = 0.0
    services = []
    for number, sortie in enumerate(sorties, 1):
        if not sortie:
            continue
        first, last = sortie[0], sortie[-1]
        leg_m = legs[entry_end(*first)] + legs[exit_end(*last)]
        between_m = sum(
            instance["transfer_m"][exit_end(*a)][entry_end(*b)] for a, b in zip(sortie, sortie[1:])
        )
        between_s = sum(transfer_s(instance, exit_end(*a), entry_end(*b)) for a, b in zip(sortie, sortie[1:]))
        spray_m = sum(passes[p]["spray_m"] for p, _ in sortie)
        spray_s = sum(passes[p]["spray_s"] for p, _ in sortie)
        flight_s = leg_m / vehicle["transit_mps"] + between_s + spray_s
        if tank is not None and spray_m > tank + TOLERANCE:
            problems.append(f"sortie {number} sprays {spray_m:.2f} m of a {tank:.2f} m tank")
        if flight_s > vehicle["usable_battery_s"] + TOLERANCE:
            problems.append(f"sortie {number} flies {flight_s:.2f} s of {vehicle['usable_battery_s']:.2f} s")
        transfers_m += between_m
        supply_m += leg_m
        travel_s += leg_m / vehicle["transit_mps"] + between_s
        services.append(service_s(vehicle, spray_m))
    # No service before the first sortie: fly first the one whose service would cost most.
    service_total = sum(services) - max(services, default=0.0)
    return {
        "sorties": len([s for s in sorties if s]),
        "transfers_m": transfers_m,
        "supply_legs_m": supply_m,
        "non_spray_m": transfers_m + supply_m,
        "non_spray_s": travel_s + service_total,
        "problems": problems,
    }


def ceil_scaled(value, scale):
    return int(math.ceil(value * scale - 1e-9))


def floor_scaled(value, scale):
    return int(math.floor(value * scale + 1e-9))


def lower_bound_sorties(instance):
    vehicle = instance["vehicle"]
    spray_m = sum(p["spray_m"] for p in instance["passes"])
    spray_s = sum(p["spray_s"] for p in instance["passes"])
    by_tank = math.ceil(spray_m / vehicle["spray_per_tank_m"]) if vehicle["spray_per_tank_m"] else 1
    return max(1, by_tank, math.ceil(spray_s / vehicle["usable_battery_s"]))


def build_model(instance, objective):
    """The PyVRP model of the instance; returns it with the (pass, reversed) of each client."""
    vehicle = instance["vehicle"]
    passes = instance["passes"]
    legs = instance["supply_leg_m"]
    model = Model()
    supply = instance["supply"]
    depot_location = model.add_location(x=supply[0], y=supply[1])
    model.add_depot(depot_location)
    clients = []  # (pass, reversed) of each client, in PyVRP's client order
    locations = []
    for index, item in enumerate(passes):
        group = model.add_client_group(required=True)
        for reversed_ in (False, True):
            x, y, _ = item["ends"][int(reversed_)]
            location = model.add_location(x=x, y=y)
            model.add_client(
                location,
                delivery=[ceil_scaled(item["spray_m"], DISTANCE_SCALE)],
                service_duration=ceil_scaled(item["spray_s"], DURATION_SCALE),
                required=False,
                group=group,
            )
            clients.append((index, reversed_))
            locations.append(location)
    def edge(frm, to, metres, seconds):
        # The cost PyVRP minimises goes in its distance matrix (see the module's docstring);
        # the duration matrix always holds the flight seconds, for the battery.
        cost = seconds * DURATION_SCALE if objective == "time" else metres * DISTANCE_SCALE
        model.add_edge(frm, to, distance=ceil_scaled(cost, 1), duration=ceil_scaled(seconds, DURATION_SCALE))

    longest_s = (max(max(row) for row in instance["transfer_m"]) + 2 * max(legs)) / min(
        vehicle["turn_mps"], vehicle["transit_mps"]
    )
    for (pass_i, rev_i), loc_i in zip(clients, locations):
        out_end = exit_end(pass_i, rev_i)
        into = entry_end(pass_i, rev_i)
        edge(depot_location, loc_i, legs[into], legs[into] / vehicle["transit_mps"])
        edge(loc_i, depot_location, legs[out_end], legs[out_end] / vehicle["transit_mps"])
        for (pass_j, rev_j), loc_j in zip(clients, locations):
            if pass_i == pass_j:
                if rev_i != rev_j:  # never flown: one client of a group is
                    edge(loc_i, loc_j, 10 * longest_s * vehicle["transit_mps"], 10 * longest_s)
                continue
            to_end = entry_end(pass_j, rev_j)
            edge(loc_i, loc_j, instance["transfer_m"][out_end][to_end], transfer_s(instance, out_end, to_end))
    tank = vehicle["spray_per_tank_m"]
    capacity = floor_scaled(tank, DISTANCE_SCALE) if tank is not None else sum(
        ceil_scaled(p["spray_m"], DISTANCE_SCALE) for p in passes
    )
    service = ceil_scaled(service_s(vehicle, tank if tank is not None else 0.0), DURATION_SCALE)
    costs = {
        "time": dict(unit_distance_cost=1, unit_duration_cost=0, fixed_cost=service),
        "duration": dict(unit_distance_cost=0, unit_duration_cost=1, fixed_cost=service),
        "distance": dict(unit_distance_cost=1, unit_duration_cost=0, fixed_cost=0),
    }[objective]
    model.add_vehicle_type(
        num_available=2 * lower_bound_sorties(instance) + 5,
        capacity=[capacity],
        shift_duration=floor_scaled(vehicle["usable_battery_s"], DURATION_SCALE),
        **costs,
    )
    return model, clients


def solve(instance, seconds, seed, objective, iterations=None):
    """PyVRP's best sorties for the instance, as lists of (pass, reversed), and its result.

    Stops after `seconds` of wall time, or after `iterations` when given: a time limit on a
    shared machine gives a different number of iterations, and so a different result, from
    run to run even with the same seed; an iteration count repeats exactly.
    """
    model, clients = build_model(instance, objective)
    stop = MaxIterations(iterations) if iterations else MaxRuntime(seconds)
    result = model.solve(stop, seed=seed, display=False)
    sorties = [[clients[activity.idx] for activity in route if activity.is_client()] for route in result.best.routes()]
    return sorties, result


def ours_consistent(instance):
    """Re-costs our exported order's transfers on the matrix; None when they agree with ours."""
    ours = instance["ours"]
    order = ours["order"]
    total = sum(
        instance["transfer_m"][exit_end(*a)][entry_end(*b)] for a, b in zip(order, order[1:])
    )
    # The matrix is rounded to 0.1 mm; the transfers between a sortie's return and the next
    # one's first point, when it starts past it, are not flown.
    flown = ours["transfers_m"] + ours.get("skipped_transfers_m", 0.0)
    if abs(total - flown) > 1e-3 * len(order) + 1e-6:
        return f"our order's transfers re-cost to {total:.2f} m, bench_joint measured {flown:.2f} m (with the skipped)"
    return None


def run(folder, seconds, seed, objective, results_path, iterations=None, peer_path=None):
    paths = sorted(glob.glob(os.path.join(folder, "*.json")))
    if not paths:
        sys.exit(f"no instances in {folder}: run bench_joint --export {folder} first")
    # PyVRP's solutions depend only on the instance (passes, matrix, limits), not on our
    # planner: --peer reuses those of an earlier --results file, so that two of our variants
    # are compared against the very same PyVRP run.
    kept = None
    if peer_path:
        with open(peer_path) as handle:
            earlier = json.load(handle)
        kept = {row["name"]: row["pyvrp"] for row in earlier["farms"]}
        print(f"PyVRP's solutions from {peer_path} ({earlier['seconds']:g} s, seed {earlier['seed']}, "
              f"objective {earlier['objective']})")
    else:
        budget = f"{iterations} iterations" if iterations else f"{seconds:g} s"
        print(f"PyVRP, {budget} per farm, seed {seed}, objective {objective}")
    header = (
        f"{'farm':<18} {'passes':>6} | {'ours m (transfers + legs)':>27} | {'PyVRP m (transfers + legs)':>27} |"
        f" {'ratio':>6} | {'sorties':>7} | {'non-spray s ours / PyVRP':>24}"
    )
    print(header)
    print("-" * len(header))
    rows = []
    for path in paths:
        with open(path) as handle:
            instance = json.load(handle)
        ours = instance["ours"]
        if kept is not None:
            if instance["name"] not in kept:
                sys.exit(f"{instance['name']} is not in {peer_path}")
            peer = kept[instance["name"]]
            feasible = peer["feasible_by_pyvrp"]
        else:
            sorties, result = solve(instance, seconds, seed, objective, iterations)
            peer = {**cost_sorties(instance, sorties), "iterations": result.num_iterations,
                    "runtime_s": result.runtime, "feasible_by_pyvrp": result.best.is_feasible(),
                    "routes": [[[p, bool(r)] for p, r in sortie] for sortie in sorties]}
            feasible = result.best.is_feasible()
        ratio = ours["non_spray_m"] / peer["non_spray_m"]
        rows.append({"name": instance["name"], "passes": len(instance["passes"]), "ratio": ratio,
                     "ours": {k: ours[k] for k in ("sorties", "non_spray_m", "transfers_m", "supply_legs_m", "non_spray_s", "runtime_s", "planner")},
                     "pyvrp": peer})
        print(
            f"{instance['name']:<18} {len(instance['passes']):>6} |"
            f" {ours['non_spray_m']:>7.0f} ({ours['transfers_m']:>6.0f} + {ours['supply_legs_m']:>6.0f}) |"
            f" {peer['non_spray_m']:>7.0f} ({peer['transfers_m']:>6.0f} + {peer['supply_legs_m']:>6.0f}) |"
            f" {ratio:>6.3f} | {ours['sorties']:>3} / {peer['sorties']:<3}|"
            f" {ours['non_spray_s']:>9.0f} / {peer['non_spray_s']:<9.0f}"
        )
        for problem in peer["problems"] + ([] if feasible else ["PyVRP calls its solution infeasible"]):
            print(f"  PyVRP INFEASIBLE: {problem}")
        for failure in ours["check_failures"] + [m for m in [ours_consistent(instance)] if m]:
            print(f"  OURS CHECK: {failure}")
    ratios = [row["ratio"] for row in rows]
    worst = max(rows, key=lambda row: row["ratio"])
    print(f"mean ratio ours/PyVRP {sum(ratios) / len(ratios):.3f} over {len(rows)} farms; worst {worst['ratio']:.3f} ({worst['name']})")
    times = [row["ours"]["non_spray_s"] / row["pyvrp"]["non_spray_s"] for row in rows]
    print(f"non-spray time ours/PyVRP: mean {sum(times) / len(times):.3f}, worst {max(times):.3f}")
    random_rows = [row for row in rows if row["name"].startswith("random")]
    if random_rows and len(random_rows) != len(rows):
        mean = sum(row["ratio"] for row in random_rows) / len(random_rows)
        print(f"mean ratio over the {len(random_rows)} random farms {mean:.3f}")
    if results_path:
        with open(results_path, "w") as handle:
            settings = earlier if kept is not None else {"seconds": seconds, "seed": seed, "objective": objective}
            json.dump({"seconds": settings["seconds"], "seed": settings["seed"],
                       "objective": settings["objective"], "farms": rows}, handle, indent=1)


# ---------------------------------------------------------------- validation on tiny instances


def tiny_instance(passes, supply, tank_m, usable_s, h=18.0, field_box=None):
    """An instance in bench_joint's format from pass segments ((x, y), (x, y)) on flat ground.

    Transfers cost the straight distance, plus 2h (and transit speed) when either end lies
    outside `field_box` ((x0, y0, x1, y1)), a stand-in for eq. 8's leaves-the-field test.
    """
    ends = [end for segment in passes for end in segment]
    inside = lambda p: field_box is None or (field_box[0] <= p[0] <= field_box[2] and field_box[1] <= p[1] <= field_box[3])
    matrix, climbs = [], []
    for a in ends:
        row, climb_row = [], []
        for b in ends:
            leaves = not (inside(a) and inside(b))
            row.append(math.dist(a, b) + (2 * h if leaves and a != b else 0.0))
            climb_row.append(int(leaves and a != b))
        matrix.append(row)
        climbs.append(climb_row)
    vehicle = {"spray_per_tank_m": tank_m, "usable_battery_s": usable_s, "spray_mps": 3.0, "turn_mps": 3.0,
               "transit_mps": 6.0, "battery_swap_s": 60.0, "refill_base_s": 20.0, "refill_max_s": 120.0}
    return {
        "name": "tiny",
        "supply": [supply[0], supply[1], 0.0],
        "passes": [{"ends": [[*a, 0.0], [*b, 0.0]], "spray_m": math.dist(a, b), "spray_s": math.dist(a, b) / 3.0}
                   for a, b in passes],
        "transfer_m": matrix,
        "transfer_climbs": climbs,
        "supply_leg_m": [math.dist(end, supply) + 2 * h for end in ends],
        "vehicle": vehicle,
    }


def pyvrp_objective(instance, sorties, objective):
    """The objective the PyVRP model minimises, on the float data (None if infeasible)."""
    costed = cost_sorties(instance, sorties)
    if costed["problems"]:
        return None
    if objective == "distance":
        return costed["non_spray_m"]
    vehicle = instance["vehicle"]
    fixed = service_s(vehicle, vehicle["spray_per_tank_m"])
    spray_s = sum(p["spray_s"] for p in instance["passes"])
    travel_s = costed["non_spray_s"]
    # Undo the exact services of cost_sorties and charge the model's fixed one per sortie.
    sprays = [sum(instance["passes"][p]["spray_m"] for p, _ in s) for s in sorties if s]
    services = [service_s(vehicle, m) for m in sprays]
    travel_s -= sum(services) - max(services, default=0.0)
    # "duration" charges the route durations, spray seconds included; "time" travel only.
    return travel_s + (spray_s if objective == "duration" else 0.0) + fixed * len(sprays)


def brute_force(instance, objective):
    """The best objective over every giant tour (order × directions) and every split of it."""
    count = len(instance["passes"])
    best = (math.inf, None)
    for order in itertools.permutations(range(count)):
        for directions in itertools.product((False, True), repeat=count):
            tour = list(zip(order, directions))
            for cuts in itertools.product((False, True), repeat=count - 1):
                sorties, current = [], [tour[0]]
                for step, cut in zip(tour[1:], cuts):
                    if cut:
                        sorties.append(current)
                        current = []
                    current.append(step)
                sorties.append(current)
                value = pyvrp_objective(instance, sorties, objective)
                if value is not None and value < best[0]:
                    best = (value, sorties)
    return best


def validate():
    failures = 0
    # 1. Two parallel passes, one tank: the optimum is plain to see. Out to the south end of
    # one pass, up it, 5 m across, down the other, home: 2 legs of 30 m (+2h each) and 5 m.
    simple = tiny_instance([((0, 0), (0, 100)), ((5, 0), (5, 100))], supply=(2.5, -30), tank_m=250, usable_s=1000)
    sorties, _ = solve(simple, 1, 1, "time")
    costed = cost_sorties(simple, sorties)
    expected = 2 * (math.hypot(2.5, 30) + 36) + 5
    ok = abs(costed["non_spray_m"] - expected) < 1e-6 and costed["sorties"] == 1
    failures += not ok
    print(f"two passes, one tank: PyVRP {costed['non_spray_m']:.3f} m in {costed['sorties']} sortie(s),"
          f" expected {expected:.3f} m in 1: {'ok' if ok else 'FAILED'} {sorties}")
    # 2. The same with a tank of one pass: two sorties, each out to a south end and back from
    # the north end (direction is forced by nothing: both ends are equal by symmetry).
    one_each = tiny_instance([((0, 0), (0, 100)), ((5, 0), (5, 100))], supply=(2.5, -30), tank_m=150, usable_s=1000)
    sorties, _ = solve(one_each, 1, 1, "time")
    costed = cost_sorties(one_each, sorties)
    expected = 2 * (math.hypot(2.5, 30) + 36) + 2 * (math.hypot(2.5, 130) + 36)
    ok = abs(costed["non_spray_m"] - expected) < 1e-6 and costed["sorties"] == 2 and not costed["problems"]
    failures += not ok
    print(f"two passes, a pass per tank: PyVRP {costed['non_spray_m']:.3f} m in {costed['sorties']},"
          f" expected {expected:.3f} m in 2: {'ok' if ok else 'FAILED'}")
    # 3. Random tiny instances against brute force, both objectives, tank and battery binding.
    stream = random.Random(19)
    for case in range(8):
        count = 4 if case < 4 else 5
        passes = []
        for _ in range(count):
            x, y = stream.uniform(0, 200), stream.uniform(0, 200)
            angle, length = stream.uniform(0, math.pi), stream.uniform(40, 160)
            passes.append(((x, y), (x + length * math.cos(angle), y + length * math.sin(angle))))
        total = sum(math.dist(a, b) for a, b in passes)
        instance = tiny_instance(passes, supply=(stream.uniform(-50, 250), -40), tank_m=stream.uniform(0.3, 0.6) * total,
                                 usable_s=stream.uniform(250, 400), field_box=(0, 0, 150, 250))
        if any(p["spray_m"] > instance["vehicle"]["spray_per_tank_m"] for p in instance["passes"]):
            instance["vehicle"]["spray_per_tank_m"] = max(p["spray_m"] for p in instance["passes"]) * 1.2
        for objective in ("time", "duration", "distance"):
            best, best_sorties = brute_force(instance, objective)
            sorties, result = solve(instance, 1, 1, objective)
            found = pyvrp_objective(instance, sorties, objective)
            # The integer rounding may cost PyVRP at most a centi-unit per leg and pass.
            slack = 0.01 * 3 * (count + 2 * len(sorties)) + 1e-6
            # PyVRP's own cost, unscaled, is the float objective of its solution: the matrix
            # means what the re-costing reads it as.
            own = result.cost() / (DISTANCE_SCALE if objective == "distance" else DURATION_SCALE)
            ok = found is not None and found <= best + slack and abs(own - found) <= slack
            failures += not ok
            print(f"random {case} ({count} passes, {objective}): brute force {best:.3f} in"
                  f" {len(best_sorties)} sorties, PyVRP {found if found is None else round(found, 3)}"
                  f" (its own cost {own:.2f}) in {len(sorties)}: {'ok' if ok else 'FAILED'}")
    print("validation", "passed" if failures == 0 else f"FAILED ({failures})")
    return failures == 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("folder", nargs="?", help="instances written by bench_joint --export")
    parser.add_argument("seconds", nargs="?", type=float, default=20.0, help="PyVRP time limit per farm")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--iterations", type=int, help="stop after this many iterations, not SECONDS")
    parser.add_argument("--objective", choices=("time", "duration", "distance"), default="time")
    parser.add_argument("--results", help="write the per-farm figures as JSON here")
    parser.add_argument("--peer", help="reuse PyVRP's solutions of this earlier --results file")
    parser.add_argument("--validate", action="store_true", help="check the model on tiny instances")
    args = parser.parse_args()
    if args.validate:
        sys.exit(0 if validate() else 1)
    if not args.folder:
        parser.error("a folder of instances, or --validate")
    run(args.folder, args.seconds, args.seed, args.objective, args.results, args.iterations, args.peer)


if __name__ == "__main__":
    main()
