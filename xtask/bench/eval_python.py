#!/usr/bin/env python3
"""Python side of `cargo xtask bench python`: the workload of benches/curves.rs and
eval_scipy.py evaluated through the `spline` package and through scipy in the same run.

A cubic planar B-spline with 100 control points (clamped uniform knots on [0, 1]) at 10^6
uniformly random parameters, in random order and sorted; medians of 9 runs after a warm-up.
Prints one JSON object: {"scipy", "numpy", "results": {id: {"median_s", "runs"}}} with ids
`spline_random_order`, `spline_sorted`, `scipy_random_order`, `scipy_sorted`.
"""
import json
import statistics
import time

import numpy as np
import scipy
import scipy.interpolate

import spline

N_CTRL, DEGREE, POINTS, RUNS = 100, 3, 1_000_000, 9

knots = np.concatenate([[0.0] * DEGREE, np.linspace(0.0, 1.0, N_CTRL - DEGREE + 1), [1.0] * DEGREE])
rng = np.random.default_rng(7)
coefficients = np.stack([np.arange(N_CTRL) / N_CTRL, rng.uniform(size=N_CTRL)], axis=1)
ours = spline.BSpline(knots, coefficients, DEGREE)
theirs = scipy.interpolate.BSpline(knots, coefficients, DEGREE)
params = np.random.default_rng(42).uniform(size=POINTS)
workloads = {"random_order": params, "sorted": np.sort(params)}

results = {}
for name, x in workloads.items():
    difference = float(np.max(np.abs(ours(x) - theirs(x))))
    assert difference < 1e-12, difference
    for who, f in (("spline", ours), ("scipy", theirs)):
        f(x)  # warm-up
        times = []
        for _ in range(RUNS):
            start = time.perf_counter()
            f(x)
            times.append(time.perf_counter() - start)
        results[f"{who}_{name}"] = {"median_s": statistics.median(times), "runs": RUNS}

print(json.dumps({"scipy": scipy.__version__, "numpy": np.__version__, "results": results}))
