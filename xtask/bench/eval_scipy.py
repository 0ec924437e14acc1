#!/usr/bin/env python3
"""scipy side of `cargo xtask bench eval`: the workload of benches/curves.rs.

A cubic planar B-spline with 100 control points (clamped uniform knots on [0, 1]) evaluated
by BSpline.__call__ at 10^6 uniformly random parameters, in random order and sorted.
Prints one JSON object: {"scipy", "numpy", "results": {id: {"median_s", "runs"}}}.
"""
import json
import statistics
import time

import numpy as np
import scipy
from scipy.interpolate import BSpline

N_CTRL, DEGREE, POINTS, RUNS = 100, 3, 1_000_000, 9

knots = np.concatenate([[0.0] * DEGREE, np.linspace(0.0, 1.0, N_CTRL - DEGREE + 1), [1.0] * DEGREE])
rng = np.random.default_rng(7)
coefficients = np.stack([np.arange(N_CTRL) / N_CTRL, rng.uniform(size=N_CTRL)], axis=1)
spline = BSpline(knots, coefficients, DEGREE)
params = np.random.default_rng(42).uniform(size=POINTS)
workloads = {"random_order": params, "sorted": np.sort(params)}

results = {}
for name, x in workloads.items():
    spline(x)  # warm-up
    times = []
    for _ in range(RUNS):
        start = time.perf_counter()
        spline(x)
        times.append(time.perf_counter() - start)
    results[name] = {"median_s": statistics.median(times), "runs": RUNS}

print(json.dumps({"scipy": scipy.__version__, "numpy": np.__version__, "results": results}))
