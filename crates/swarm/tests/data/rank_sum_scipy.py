"""Writes rank_sum_scipy.json: scipy's rank-sum test on samples shaped like Table 2's runs
(continuous values, exact ties such as F1's -450 reached in every run, one sample all tied),
the oracle for swarm::statistics::rank_sum (crates/swarm/tests/rank_sum.rs).

Run: python3 -m venv venv && venv/bin/pip install scipy && venv/bin/python rank_sum_scipy.py
"""
import json
import random

import scipy
from scipy.stats import mannwhitneyu

rng = random.Random(20)
cases = []
for n1, n2, tie_levels in [(50, 50, 0), (10, 10, 0), (50, 50, 3), (7, 12, 2), (30, 20, 1), (4, 4, 0)]:
    def sample(n, shift):
        if tie_levels:
            return [float(rng.randrange(tie_levels + 2)) + shift for _ in range(n)]
        return [rng.gauss(shift, 1.0) for _ in range(n)]
    first, second = sample(n1, 0.0), sample(n2, 0.4)
    cases.append((first, second))
# Table 2 like: one algorithm reaches -450 in every run, the other scatters above it.
cases.append(([-450.0] * 20, [-450.0] * 5 + [-450.0 + rng.expovariate(1.0) for _ in range(15)]))
out = []
for first, second in cases:
    result = mannwhitneyu(first, second, use_continuity=False, method="asymptotic")
    out.append({"first": first, "second": second, "p_value": float(result.pvalue)})
with open("rank_sum_scipy.json", "w") as f:
    json.dump({"scipy": scipy.__version__, "cases": out}, f, indent=1)
