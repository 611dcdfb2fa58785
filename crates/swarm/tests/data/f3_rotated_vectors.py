"""Writes f3_rotated_vectors.json: CEC 2005 F3 (shifted rotated high-conditioned elliptic)
at D = 10 and 30, computed with NumPy from the official data in data/cec2005/, independently
of swarm's code: the oracle for crates/swarm/tests/engine.rs. Run from the repository root:
venv/bin/python crates/swarm/tests/data/f3_rotated_vectors.py
"""
import json

import numpy as np

shift = np.loadtxt("data/cec2005/data_high_cond_elliptic_rot.txt").ravel()
rng = np.random.default_rng(20)
out = {"numpy": np.__version__, "cases": []}
for d in (10, 30):
    m = np.loadtxt(f"data/cec2005/elliptic_M_D{d}.txt")
    weights = 1e6 ** (np.arange(d) / (d - 1))
    points = [np.zeros(d), shift[:d] + 1.0, rng.uniform(-100, 100, d), rng.uniform(-100, 100, d)]
    for x in points:
        z = (x - shift[:d]) @ m
        out["cases"].append({"point": x.tolist(), "value": float(weights @ (z * z) - 450.0)})
with open("crates/swarm/tests/data/f3_rotated_vectors.json", "w") as f:
    json.dump(out, f, indent=1)
