#!/usr/bin/env python3
"""scipy side of `cargo xtask bench surfaces`: the fitting workload of
crates/spline-fit/benches/surfaces.rs.

- lsq N: LSQBivariateSpline(x, y, z, tx, ty, kx=3, ky=3) on N scattered heights with 20 x 20
  coefficients on clamped uniform knots over [0, 1]^2 (16 interior knots i/17 each way),
  N = 10^4, 10^5. The data are those of the Rust benchmark: the Kronecker sequence with the
  plastic number, z = sin 3x cos 2y + 0.2 x y plus a deterministic wiggle.

Prints one JSON object: {"scipy": version, "numpy": version, "results": {id: {"median_s",
"runs", "residual"}}}; the residual is sum (s(x, y) - z)^2, as in the Rust benchmark.
"""
import json
import statistics
import time

import numpy as np
import scipy
from scipy.interpolate import LSQBivariateSpline


def height_data(n):
    g = 1.324717957244746
    a1, a2 = 1.0 / g, 1.0 / (g * g)
    j = np.arange(n, dtype=float)
    x = np.mod(0.5 + a1 * j, 1.0)
    y = np.mod(0.5 + a2 * j, 1.0)
    z = np.sin(3 * x) * np.cos(2 * y) + 0.2 * x * y + 0.01 * np.sin(12345.678 * j)
    return x, y, z


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
    interior = np.arange(1, 17, dtype=float) / 17.0
    for n in (10_000, 100_000):
        x, y, z = height_data(n)

        def fit():
            return LSQBivariateSpline(x, y, z, interior, interior, bbox=[0, 1, 0, 1], kx=3, ky=3)

        spl = fit()
        residual = float(np.sum((spl.ev(x, y) - z) ** 2))
        med, runs = median_time(fit)
        results[f"lsq/{n}"] = {"median_s": med, "runs": runs, "residual": residual}
    print(json.dumps({"scipy": scipy.__version__, "numpy": np.__version__, "results": results}))


if __name__ == "__main__":
    main()
