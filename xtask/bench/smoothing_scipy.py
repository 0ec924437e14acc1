#!/usr/bin/env python3
"""scipy side of `cargo xtask bench smoothing`: the workloads of
crates/spline-fit/benches/smoothing.rs on N = 10^5 data
x_j = j + 0.3 sin j, y_j = sin(x_j/3000) + 0.5 cos(x_j/700) + 0.1 sin(12345.678 j):

- lambda: make_smoothing_spline(x, y, lam=1);
- gcv: make_smoothing_spline(x, y) (lambda by GCV; scipy's search is in Python, one run);
- residual: splrep(x, y, s=N/200) (FITPACK, Fortran) and make_splrep(x, y, s=N/200)
  (scipy's Python replica of FITPACK, which spline-fit follows step for step; one run).

Prints one JSON object {"scipy", "numpy", "results": {id: {"median_s", "runs", "check"}}}: the
check is lambda for gcv, the residual sum of squares otherwise, as the Rust benchmark prints.
"""
import json
import statistics
import time

import numpy as np
import scipy
import scipy.interpolate._bsplines as bsplines
from scipy.interpolate import make_smoothing_spline, make_splrep, splev, splrep

N = 100_000


def data(n):
    j = np.arange(n, dtype=float)
    x = j + 0.3 * np.sin(j)
    return x, np.sin(x / 3000) + 0.5 * np.cos(x / 700) + 0.1 * np.sin(12345.678 * j)


def median_time(fn, budget_s=10.0, min_runs=3, max_runs=20):
    times = []
    start = time.perf_counter()
    while len(times) < max_runs and (len(times) < min_runs or time.perf_counter() - start < budget_s):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), len(times)


def gcv_lambda(x, y):
    """make_smoothing_spline does not return lambda: read it off its search."""
    seen = {}
    original = bsplines._compute_optimal_gcv_parameter

    def spy(*args):
        seen["lam"] = original(*args)
        return seen["lam"]

    bsplines._compute_optimal_gcv_parameter = spy
    try:
        t0 = time.perf_counter()
        bsplines.make_smoothing_spline(x, y)
        elapsed = time.perf_counter() - t0
    finally:
        bsplines._compute_optimal_gcv_parameter = original
    return seen["lam"], elapsed


def main():
    x, y = data(N)
    results = {}
    spl = make_smoothing_spline(x, y, lam=1.0)
    med, runs = median_time(lambda: make_smoothing_spline(x, y, lam=1.0))
    results[f"lambda/{N}"] = {"median_s": med, "runs": runs, "check": float(np.sum((spl(x) - y) ** 2))}
    lam, elapsed = gcv_lambda(x, y)
    results[f"gcv/{N}"] = {"median_s": elapsed, "runs": 1, "check": float(lam)}
    s = N / 200
    tck = splrep(x, y, s=s)
    med, runs = median_time(lambda: splrep(x, y, s=s))
    results[f"splrep/{N}"] = {"median_s": med, "runs": runs,
                              "check": float(np.sum((splev(x, tck) - y) ** 2)), "knots": len(tck[0])}
    t0 = time.perf_counter()
    spl = make_splrep(x, y, s=s)
    elapsed = time.perf_counter() - t0
    results[f"make_splrep/{N}"] = {"median_s": elapsed, "runs": 1,
                                   "check": float(np.sum((spl(x) - y) ** 2)), "knots": len(spl.t)}
    print(json.dumps({"scipy": scipy.__version__, "numpy": np.__version__, "results": results}))


if __name__ == "__main__":
    main()
