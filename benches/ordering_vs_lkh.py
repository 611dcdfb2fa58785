"""Swath ordering quality against LKH-3 (through elkai): `best` / LKH on open paths and closed
tours over the same pass ends (issue 19 items 1, 4 and 5).

The instances come from `cargo run --release -p agripath --example bench_sequence -- --export
DIR --lkh-only`: the seed 001 farm (Table 7's layout, 130 swaths) and 12 irregular farms of
about 100-250 swaths; for each, the full eq. (8) cost matrix between pass ends (node 2p is
pass p's first end, 2p+1 its last) and our open-path and closed-tour costs and times (median
of 3 runs), with each end's position and each pass's field (to draw and compare the
tours). A pass is two nodes kept adjacent by adding a large constant to every other arc
(as ../shared/peers/tsp_instances.py does). An open path is a tour through one more node, a
dummy at cost 0 (plus the constant) from and to every end: cutting the tour there leaves the
path with free first and last pass. Costs go to LKH as integers twice, in centimetres (pair
constant 20 × the longest edge) and in decimetres (2 ×), RUNS = 10 each by default; the
cheaper tour that keeps every pair, re-costed on the float matrix, is the reference.

Run (one command: builds and runs the Rust side into a temporary folder, then LKH):
    .peers/bench/bin/python benches/ordering_vs_lkh.py [DIR] [RUNS] [-- BENCH_SEQUENCE_ARGS...]
With DIR given and holding instances, the Rust side is not run again; arguments after `--`
go to bench_sequence (e.g. `-- --kicks 800`). With LKH_CACHE=FILE, LKH's results are kept
in FILE by instance, kind, runs and a hash of the matrix, and reused when all four match
(LKH's side does not change with ours; a changed matrix is run again).
"""
import hashlib
import json
import os
import subprocess
import sys
import tempfile
import time

import elkai

SCALE = 100  # centimetres


def lkh_encoded(matrix, open_path, runs, scale, big_factor):
    """LKH's best open path (dummy node) or closed tour on the pass-end matrix, costs given to
    LKH as integers in units of 1/`scale` m with the pass-pair constant `big_factor` × the
    longest edge: (cost re-costed on the float matrix, s, whether every pass pair was kept)."""
    ends = len(matrix)
    offset = 1 if open_path else 0
    nodes = ends + offset
    max_edge = max(max(row) for row in matrix)
    big = int(round(big_factor * max_edge * scale)) + 1
    costs = [[0] * nodes for _ in range(nodes)]
    for i in range(nodes):
        for j in range(nodes):
            if i == j:
                continue
            if offset and (i == 0 or j == 0):
                costs[i][j] = big  # the dummy: free first and last pass
            else:
                a, b = i - offset, j - offset
                costs[i][j] = 0 if a // 2 == b // 2 else int(round(matrix[a][b] * scale)) + big
    started = time.time()
    tour = elkai.DistanceMatrix(costs).solve_tsp(runs=runs)
    seconds = time.time() - started
    if tour[0] == tour[-1]:
        tour = tour[:-1]
    if offset:
        k = tour.index(0)
        sequence = [node - 1 for node in tour[k + 1:] + tour[:k]]
    else:
        sequence = list(tour)
        # Align so that each pass's two ends are consecutive.
        if sequence[0] // 2 != sequence[1] // 2:
            sequence = sequence[1:] + sequence[:1]
    kept = all(sequence[i] // 2 == sequence[i + 1] // 2 for i in range(0, len(sequence), 2))
    total = sum(matrix[sequence[i]][sequence[i + 1]] for i in range(1, len(sequence) - 1, 2))
    if not offset:
        total += matrix[sequence[-1]][sequence[0]]
    return total, seconds, kept


# The encodings LKH is run with; the cheapest tour that keeps every pass pair is the
# reference. LKH's result depends on the size of the integers it is given: on these
# matrices centimetres with a constant of 20 × the longest edge (the first) left it up to
# 3.5 % above the decimetre encoding with 2 × (the second) on some instances, and below it
# on others (decision 0018).
ENCODINGS = ((SCALE, 20.0), (SCALE / 10, 2.0))


def lkh(matrix, open_path, runs):
    """The best of LKH's tours over `ENCODINGS`: (cost, total s, kept)."""
    results = [lkh_encoded(matrix, open_path, runs, scale, factor) for scale, factor in ENCODINGS]
    kept = [result for result in results if result[2]]
    seconds = sum(result[1] for result in results)
    if not kept:
        return min(result[0] for result in results), seconds, False
    return min(result[0] for result in kept), seconds, True


def recost(matrix, ends, closed):
    """Our tour (pass ends in flight order) on the same matrix LKH sees."""
    total = sum(matrix[ends[i]][ends[i + 1]] for i in range(1, len(ends) - 1, 2))
    if closed:
        total += matrix[ends[-1]][ends[0]]
    return total


def export(folder, extra):
    subprocess.run(
        ["cargo", "run", "--release", "-q", "-p", "agripath", "--example", "bench_sequence",
         "--", "--export", folder, "--lkh-only", *extra],
        check=True,
    )


def cached_lkh(cache, matrix, open_path, runs, key):
    """`lkh`, through the cache dictionary `cache` (None: no cache)."""
    if cache is None:
        return lkh(matrix, open_path, runs)
    digest = hashlib.sha256(json.dumps(matrix).encode()).hexdigest()[:16]
    entry = f"{key}/{'open' if open_path else 'closed'}/{runs}/{digest}"
    if entry not in cache:
        cache[entry] = list(lkh(matrix, open_path, runs))
    return tuple(cache[entry])


def main():
    arguments = sys.argv[1:]
    extra = arguments[arguments.index("--") + 1:] if "--" in arguments else []
    arguments = arguments[:arguments.index("--")] if "--" in arguments else arguments
    folder = arguments[0] if arguments else tempfile.mkdtemp(prefix="ordering_vs_lkh_")
    runs = int(arguments[1]) if len(arguments) > 1 else 10
    os.makedirs(folder, exist_ok=True)
    if not any(name.endswith(".json") for name in os.listdir(folder)):
        export(folder, extra)
    cache_file = os.environ.get("LKH_CACHE")
    cache = None
    if cache_file:
        cache = json.load(open(cache_file)) if os.path.exists(cache_file) else {}
    print(f"{'instance':<14} {'passes':>6} | {'open m':>9} {'LKH m':>9} {'ours/LKH':>8} {'ms':>6} |"
          f" {'closed m':>9} {'LKH m':>9} {'ours/LKH':>8} {'ms':>6} | {'LKH s':>5}")
    ratios = {"open": [], "closed": []}
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".json"):
            continue
        instance = json.load(open(os.path.join(folder, name)))
        cells = []
        lkh_seconds = 0.0
        for kind in ("open", "closed"):
            theirs, seconds, kept = cached_lkh(cache, instance["matrix"], kind == "open", runs,
                                               instance["name"])
            lkh_seconds += seconds
            ours = recost(instance["matrix"], instance[f"{kind}_ends"], kind == "closed")
            if abs(ours - instance[f"{kind}_m"]) > 0.01 * len(instance["matrix"]):
                print(f"{name}: our {kind} tour costs {ours:.2f} m on the matrix, {instance[f'{kind}_m']:.2f} m in Rust")
            ratio = ours / theirs
            ratios[kind].append((ratio, instance[f"{kind}_ms"]))
            flag = "" if kept else "!"
            cells.append(f"{ours:>9.1f} {theirs:>9.1f}{flag:1}{ratio:>7.4f} {instance[f'{kind}_ms']:>6.1f}")
        print(f"{instance['name']:<14} {instance['passes']:>6} | {cells[0]} | {cells[1]} | {lkh_seconds:>5.1f}")
        if cache_file:
            json.dump(cache, open(cache_file, "w"))
    for kind, values in ratios.items():
        within = sum(1 for ratio, _ in values if ratio <= 1.01)
        fast = sum(1 for ratio, ms in values if ratio <= 1.01 and ms <= 100.0)
        print(f"{kind:<6}: worst ours/LKH {max(r for r, _ in values):.4f}, mean {sum(r for r, _ in values) / len(values):.4f},"
              f" {within}/{len(values)} within 1.01, {fast}/{len(values)} within 1.01 in <= 100 ms;"
              f" slowest {max(ms for _, ms in values):.1f} ms")
    print("(! = LKH broke a pass pair)")


if __name__ == "__main__":
    main()
