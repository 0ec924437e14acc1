#!/usr/bin/env python3
"""The scipy rows of `cargo xtask bench python`: the same calls through `spline` and through
scipy on the same data, medians of 7 runs after a warm-up. Before timing, each pair of
results is compared (the bench refuses to time functions that disagree).

Prints one JSON object: {"rows": [{"name", "spline_s", "scipy_s"}]}.
"""
import json
import statistics
import time

import numpy as np
import scipy.interpolate as si

import spline

RUNS = 7
rng = np.random.default_rng(11)


def median(f):
    f()
    times = []
    for _ in range(RUNS):
        start = time.perf_counter()
        f()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def close(a, b, tol):
    a, b = np.asarray(a), np.asarray(b)
    scale = max(1.0, float(np.max(np.abs(b))))
    assert float(np.max(np.abs(a - b))) <= tol * scale, float(np.max(np.abs(a - b)))


rows = []

# Evaluation with extrapolation: 10 columns, 10^5 points, a tenth outside the base interval.
x = np.sort(rng.uniform(0, 1, 200))
y = np.cumsum(rng.normal(size=(200, 10)), axis=0)
b_ours, b_theirs = spline.make_interp_spline(x, y), si.make_interp_spline(x, y)
xx = rng.uniform(-0.05, 1.05, 100_000)
close(b_ours(xx), b_theirs(xx), 1e-10)
rows.append({"name": "eval 10 cols, 1e5 pts", "spline_s": median(lambda: b_ours(xx)),
             "scipy_s": median(lambda: b_theirs(xx))})

# make_interp_spline: 10^4 points, cubic, not-a-knot and clamped.
x = np.sort(rng.uniform(0, 10, 10_000))
y = np.sin(x) + 0.1 * rng.normal(size=x.size)
for bc in (None, "clamped"):
    close(spline.make_interp_spline(x, y, bc_type=bc).c, si.make_interp_spline(x, y, bc_type=bc).c, 1e-8)
    rows.append({
        "name": f"make_interp_spline 1e4 ({bc or 'not-a-knot'})",
        "spline_s": median(lambda: spline.make_interp_spline(x, y, bc_type=bc)),
        "scipy_s": median(lambda: si.make_interp_spline(x, y, bc_type=bc)),
    })

# make_lsq_spline: 10^5 points, 200 knots, both methods.
x = np.sort(rng.uniform(0, 10, 100_000))
y = np.sin(x) + 0.1 * rng.normal(size=x.size)
t = np.r_[[0.0] * 4, np.linspace(0, 10, 200)[1:-1], [10.0] * 4]
for method in ("qr", "norm-eq"):
    close(spline.make_lsq_spline(x, y, t, method=method).c, si.make_lsq_spline(x, y, t, method=method).c, 1e-8)
    rows.append({
        "name": f"make_lsq_spline 1e5 ({method})",
        "spline_s": median(lambda: spline.make_lsq_spline(x, y, t, method=method)),
        "scipy_s": median(lambda: si.make_lsq_spline(x, y, t, method=method)),
    })

# make_smoothing_spline (GCV) on 2,000 points; make_splrep with s = m σ² on 2,000 points.
x = np.sort(rng.uniform(0, 10, 2_000))
y = np.sin(x) + 0.1 * rng.normal(size=x.size)
xx = np.linspace(0, 10, 1001)
close(spline.make_smoothing_spline(x, y)(xx), si.make_smoothing_spline(x, y)(xx), 1e-3)
rows.append({"name": "make_smoothing_spline 2e3 (GCV)",
             "spline_s": median(lambda: spline.make_smoothing_spline(x, y)),
             "scipy_s": median(lambda: si.make_smoothing_spline(x, y))})
s = x.size * 0.01
close(spline.make_splrep(x, y, s=s)(xx), si.make_splrep(x, y, s=s)(xx), 1e-6)
rows.append({"name": "make_splrep 2e3 (s = m σ²)",
             "spline_s": median(lambda: spline.make_splrep(x, y, s=s)),
             "scipy_s": median(lambda: si.make_splrep(x, y, s=s))})

print(json.dumps({"rows": rows}))
