#!/usr/bin/env python3
"""scipy side of `cargo xtask bench fit`: the workloads of crates/spline-fit/benches/fit.rs.

- interp N: make_interp_spline(x, y, k=3) on N planar points (default not-a-knot knots),
  N = 10^4, 10^5, 10^6;
- lsq_qr / lsq_norm_eq: make_lsq_spline(x, y, t, k=3) on 10^5 planar points with 200
  coefficients on clamped uniform knots, method="qr" (the default) and method="norm-eq".

Prints one JSON object: {"scipy": version, "numpy": version, "results": {id: {"median_s",
"runs", "residual"}}}; residuals are max |s(x) - y| (interpolation) and sum |s(x) - y|^2
(least squares), as in the Rust benchmark.
"""
import json
import math
import statistics
import sys
import time

import numpy as np
import scipy
from scipy.interpolate import make_interp_spline, make_lsq_spline


def abscissae(n):
    j = np.arange(n, dtype=float)
    x = (j + 0.3 * np.sin(j)) / (n - 1)
    x[0], x[-1] = 0.0, 1.0
    return x


def ordinates(x):
    j = np.arange(len(x), dtype=float)
    noise = 0.05 * np.sin(12345.678 * j)
    return np.stack([
        np.sin(6 * math.pi * x) + 0.1 * np.cos(50 * x) + noise,
        np.cos(4 * math.pi * x) * x - noise,
    ], axis=1)


def median_time(fn, budget_s=3.0, min_runs=5, max_runs=50):
    fn()  # warm up
    times = []
    start = time.perf_counter()
    while len(times) < max_runs and (len(times) < min_runs or time.perf_counter() - start < budget_s):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), len(times)


def main():
    results = {}
    for n in (10_000, 100_000, 1_000_000):
        x = abscissae(n)
        y = ordinates(x)
        spl = make_interp_spline(x, y, k=3)
        residual = float(np.max(np.abs(spl(x) - y)))
        med, runs = median_time(lambda: make_interp_spline(x, y, k=3))
        results[f"interp/{n}"] = {"median_s": med, "runs": runs, "residual": residual}
    m = 100_000
    x = abscissae(m)
    y = ordinates(x)
    interior = np.linspace(0.0, 1.0, 200 - 3 + 1)[1:-1]
    t = np.r_[[0.0] * 4, interior, [1.0] * 4]
    for name, method in (("lsq_qr", "qr"), ("lsq_norm_eq", "norm-eq")):
        spl = make_lsq_spline(x, y, t, k=3, method=method)
        residual = float(np.sum((spl(x) - y) ** 2))
        med, runs = median_time(lambda: make_lsq_spline(x, y, t, k=3, method=method))
        results[f"{name}/{m}"] = {"median_s": med, "runs": runs, "residual": residual}
    json.dump({"scipy": scipy.__version__, "numpy": np.__version__, "results": results}, sys.stdout)
    print()


if __name__ == "__main__":
    main()
