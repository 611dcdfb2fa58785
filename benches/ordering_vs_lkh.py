"""Swath ordering quality against LKH-3 (through elkai): best / LKH on the same instances.

The instances come from `cargo run --release -p agripath --example bench_sequence -- --export DIR`:
for each, the full eq. (8) cost matrix between pass ends (node 2p is pass p's first end, 2p+1
its last), the costs from the start point (or none for a free start, a closed tour), and our
`best` tour cost. A pass is two nodes kept adjacent by adding a large constant to every other
arc (as ../shared/peers/tsp_instances.py does); a fixed start is a depot node whose return
arcs cost 0, so the tour is an open path from it. Costs go to LKH as integers in centimetres;
the LKH tour is re-costed on the float matrix.

Run: .peers/bench/bin/python benches/ordering_vs_lkh.py DIR [RUNS]
"""
import json
import os
import sys
import time

import elkai

SCALE = 100  # centimetres


def lkh_cost(instance, runs):
    matrix = instance["matrix"]
    start = instance["start_costs"]
    ends = len(matrix)
    offset = 1 if start is not None else 0
    nodes = ends + offset
    max_edge = max(max(row) for row in matrix)
    if start is not None:
        max_edge = max(max_edge, max(start))
    big = int(round(20 * max_edge * SCALE)) + 1
    costs = [[0] * nodes for _ in range(nodes)]
    for i in range(nodes):
        for j in range(nodes):
            if i == j:
                continue
            if offset and i == 0:
                costs[i][j] = int(round(start[j - 1] * SCALE)) + big
            elif offset and j == 0:
                costs[i][j] = big  # the way back to the depot is free (open path)
            else:
                a, b = i - offset, j - offset
                costs[i][j] = 0 if a // 2 == b // 2 else int(round(matrix[a][b] * SCALE)) + big
    started = time.time()
    tour = elkai.DistanceMatrix(costs).solve_tsp(runs=runs)
    seconds = time.time() - started
    if tour[0] == tour[-1]:
        tour = tour[:-1]
    # Rotate to the depot (fixed start) and re-cost on the float matrix.
    if offset:
        k = tour.index(0)
        tour = tour[k:] + tour[:k]
    sequence = [node - offset for node in tour if not (offset and node == 0)]
    pairs_kept = all(sequence[i] // 2 == sequence[i + 1] // 2 for i in range(0, len(sequence), 2)) or \
        all(sequence[(i + 1) % len(sequence)] // 2 == sequence[(i + 2) % len(sequence)] // 2 for i in range(0, len(sequence), 2))
    if not offset:
        # Closed tour: align so that each pass's two ends are consecutive.
        if sequence[0] // 2 != sequence[1] // 2:
            sequence = sequence[1:] + sequence[:1]
    total = 0.0
    if offset:
        total += start[sequence[0]]
    for i in range(1, len(sequence) - 1, 2):
        total += matrix[sequence[i]][sequence[i + 1]]
    if not offset:
        total += matrix[sequence[-1]][sequence[0]]
    return total, seconds, pairs_kept


def main():
    folder = sys.argv[1]
    runs = int(sys.argv[2]) if len(sys.argv) > 2 else 3
    print(f"{'instance':<16} {'passes':>6} {'best m':>10} {'LKH m':>10} {'best/LKH':>9} {'LKH s':>7}")
    ratios = []
    for name in sorted(os.listdir(folder)):
        if not name.endswith(".json"):
            continue
        instance = json.load(open(os.path.join(folder, name)))
        lkh, seconds, kept = lkh_cost(instance, runs)
        ratio = instance["best_tour_cost_m"] / lkh
        ratios.append(ratio)
        flag = "" if kept else "  (LKH broke a pass pair)"
        print(f"{instance['name']:<16} {instance['passes']:>6} {instance['best_tour_cost_m']:>10.1f} {lkh:>10.1f} {ratio:>9.4f} {seconds:>7.1f}{flag}")
    print(f"worst best/LKH: {max(ratios):.4f}")


if __name__ == "__main__":
    main()
