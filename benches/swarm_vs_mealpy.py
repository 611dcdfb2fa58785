"""Speed and quality of our BA, PSO and GA against mealpy 3.0.3 at the same budget.

Same problem, population and iterations on both sides: seed 000's settings (D = 50,
population 500, 300 iterations) on f1 (CEC 2005 shifted sphere, official shift) and f8
(generalized penalized 1). mealpy runs single-threaded ("single" mode); our time is the mean
wall time of one run on one core (`agripath bench functions`, runs are independent). Each
side keeps its own algorithm parameters, except PSO, set to seed 000's c1 = c2 = 2,
w = 0.729 on both.

Run: .peers/bench/bin/python benches/swarm_vs_mealpy.py [MEALPY_RUNS] [OUR_RUNS]
(needs `pip install numpy==1.26.0 mealpy` in that venv, and `cargo build --release`).
"""
import csv
import os
import subprocess
import sys
import tempfile
import time

import numpy as np
from mealpy import FloatVar
from mealpy.evolutionary_based.GA import BaseGA
from mealpy.swarm_based.BA import OriginalBA
from mealpy.swarm_based.PSO import OriginalPSO

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
D, POP, ITERS = 50, 500, 300
MEALPY_RUNS = int(sys.argv[1]) if len(sys.argv) > 1 else 3
OUR_RUNS = int(sys.argv[2]) if len(sys.argv) > 2 else 10

SHIFT = np.loadtxt(os.path.join(ROOT, "data/cec2005/data_sphere.txt"))[:D]


def f1(x):
    z = x - SHIFT
    return float(np.dot(z, z) - 450.0)


def f8(x):
    y = 1 + (x + 1) / 4
    u = np.where(x > 10, 100 * (x - 10) ** 4, np.where(x < -10, 100 * (-x - 10) ** 4, 0.0))
    body = 10 * np.sin(np.pi * y[0]) ** 2 + np.sum((y[:-1] - 1) ** 2 * (1 + 10 * np.sin(np.pi * y[1:]) ** 2)) + (y[-1] - 1) ** 2
    return float(np.pi / D * body + np.sum(u))


FUNCTIONS = {"f1": (f1, -100.0, 100.0), "f8": (f8, -50.0, 50.0)}
ALGORITHMS = {
    "BA": ("ba", lambda: OriginalBA(epoch=ITERS, pop_size=POP)),
    "PSO": ("pso", lambda: OriginalPSO(epoch=ITERS, pop_size=POP, c1=2.0, c2=2.0, w=0.729)),
    "GA": ("ga", lambda: BaseGA(epoch=ITERS, pop_size=POP)),
}


def ours():
    with tempfile.TemporaryDirectory() as folder:
        out = os.path.join(folder, "bench")
        subprocess.run(
            [os.path.join(ROOT, "target/release/agripath"), "bench", "functions",
             "--dim", str(D), "--pop", str(POP), "--iters", str(ITERS), "--runs", str(OUR_RUNS),
             "--algorithms", ",".join(key for key, _ in ALGORITHMS.values()),
             "--functions", ",".join(FUNCTIONS), "--out", out],
            check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(out, "table.csv")) as handle:
            return {(row["function"], row["algorithm"]): row for row in csv.DictReader(handle)}


def main():
    table = ours()
    print(f"D = {D}, population {POP}, {ITERS} iterations; mealpy {MEALPY_RUNS} runs, ours {OUR_RUNS} runs")
    print(f"{'function':8} {'algorithm':9} {'mealpy s/run':>12} {'ours s/run':>10} {'speed-up':>9} "
          f"{'mealpy mean best':>17} {'our mean best':>14}")
    for name, (function, low, high) in FUNCTIONS.items():
        problem = {"bounds": FloatVar(lb=(low,) * D, ub=(high,) * D), "obj_func": function,
                   "minmax": "min", "log_to": None}
        for label, (key, make) in ALGORITHMS.items():
            seconds, bests = [], []
            for run in range(MEALPY_RUNS):
                model = make()
                started = time.perf_counter()
                best = model.solve(problem, seed=run + 1)
                seconds.append(time.perf_counter() - started)
                bests.append(best.target.fitness)
            row = table[(name, label)]
            mealpy_time = sum(seconds) / len(seconds)
            our_time = float(row["mean_time_s"])
            print(f"{name:8} {label:9} {mealpy_time:12.3f} {our_time:10.4f} {mealpy_time / our_time:8.0f}x "
                  f"{np.mean(bests):17.6e} {float(row['mean']):14.6e}", flush=True)


if __name__ == "__main__":
    main()
