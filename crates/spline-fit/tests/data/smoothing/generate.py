"""Reference cases for the smoothing splines of spline-fit, computed by scipy.

Run once (any Python with scipy >= 1.15; the project's bench venv has it):

    python3 generate.py [SEED]      # writes gcv.json, lambda.json, residual.json, curves.json

Every case is random held-out data drawn from SEED (default 20261201): sorted abscissae
(uniform or clustered), values of a smooth function plus Gaussian noise, sometimes weights.
The Rust tests read the JSON files and need no Python.
"""
import json
import sys

import numpy as np
import scipy
from scipy.interpolate import make_smoothing_spline, make_splrep, make_splprep


def smooth_function(rng):
    a, b, c = rng.uniform(0.5, 3.0, 3)
    return lambda x: np.sin(a * x) + 0.3 * np.cos(b * x * x) + 0.1 * c * x


def abscissae(rng, n):
    if rng.random() < 0.5:
        x = np.sort(rng.uniform(-2.0, 3.0, n))
    else:
        x = np.sort(np.concatenate([rng.normal(0.0, 0.4, n // 2), rng.uniform(-2.0, 3.0, n - n // 2)]))
    # Distinct abscissae (make_smoothing_spline needs them increasing).
    x = np.unique(np.round(x, 12))
    return x


def case_common(rng, n, weighted):
    x = abscissae(rng, n)
    f = smooth_function(rng)
    sigma = rng.uniform(0.02, 0.3)
    y = f(x) + rng.normal(0.0, sigma, x.size)
    w = rng.uniform(0.3, 2.0, x.size) if weighted else None
    return x, y, w, sigma


def spline_record(spl):
    c = np.asarray(spl.c)
    return {"degree": int(spl.k), "knots": spl.t.tolist(), "coefficients": c.tolist()}


def gcv_cases(rng):
    cases = []
    for i, n in enumerate([5, 6, 9, 17, 30, 60, 120, 250, 40, 75]):
        x, y, w, _ = case_common(rng, n, weighted=(i % 3 == 2))
        spl = make_smoothing_spline(x, y, w=w)
        lam = _lambda_of(x, y, w)
        check = np.linspace(x[0], x[-1], 37)
        cases.append({
            "name": f"gcv-{i}", "x": x.tolist(), "y": y.tolist(),
            "weights": None if w is None else w.tolist(), "lambda": float(lam),
            "spline": spline_record(spl), "at": check.tolist(), "values": spl(check).tolist(),
        })
    return cases


def _lambda_of(x, y, w):
    """The lambda make_smoothing_spline picks (it does not return it): rerun its search."""
    import scipy.interpolate._bsplines as b
    captured = {}
    original = b._compute_optimal_gcv_parameter

    def spy(*args):
        lam = original(*args)
        captured["lam"] = lam
        return lam

    b._compute_optimal_gcv_parameter = spy
    try:
        b.make_smoothing_spline(x, y, w=w)
    finally:
        b._compute_optimal_gcv_parameter = original
    return captured["lam"]


def lambda_cases(rng):
    cases = []
    for i, n in enumerate([5, 12, 33, 80]):
        x, y, w, _ = case_common(rng, n, weighted=(i % 2 == 1))
        for lam in [0.0, 1e-4, 0.05, 3.0]:
            spl = make_smoothing_spline(x, y, w=w, lam=lam)
            check = np.linspace(x[0], x[-1], 23)
            cases.append({
                "name": f"lambda-{i}-{lam}", "x": x.tolist(), "y": y.tolist(),
                "weights": None if w is None else w.tolist(), "lambda": lam,
                "spline": spline_record(spl), "at": check.tolist(), "values": spl(check).tolist(),
            })
    return cases


def residual(spl, x, y, w):
    r = (spl(x) - y) if w is None else w * (spl(x) - y)
    return float(np.sum(r * r))


def residual_cases(rng):
    cases = []
    for i, (n, k) in enumerate([(20, 3), (50, 3), (50, 1), (80, 2), (80, 4), (120, 5), (200, 3), (35, 3), (300, 3), (60, 2)]):
        x, y, w, sigma = case_common(rng, n, weighted=(i % 4 == 3))
        m = x.size
        ww = np.ones(m) if w is None else w
        for factor in [0.3, 1.0, 4.0]:
            s = float(factor * np.sum((ww * sigma) ** 2))
            spl = make_splrep(x, y, w=w, k=k, s=s)
            cases.append({
                "name": f"residual-{i}-{factor}", "x": x.tolist(), "y": y.tolist(),
                "weights": None if w is None else w.tolist(), "degree": k, "s": s,
                "spline": spline_record(spl), "residual": residual(spl, x, y, w),
            })
    return cases


def curve_cases(rng):
    cases = []
    for i, n in enumerate([25, 60, 140]):
        t = np.sort(rng.uniform(0.0, 1.5 * np.pi, n))
        r = 1.0 + 0.3 * np.sin(3 * t)
        sigma = rng.uniform(0.005, 0.05)
        pts = np.stack([r * np.cos(t), r * np.sin(t)]) + rng.normal(0.0, sigma, (2, n))
        for factor in [0.5, 2.0]:
            s = float(factor * n * sigma ** 2 * 2)
            spl, u = make_splprep(pts, k=3, s=s)
            c = np.asarray(spl.c)
            cases.append({
                "name": f"curve-{i}-{factor}", "points": pts.T.tolist(), "s": s, "degree": 3,
                "params": np.asarray(u).tolist(),
                "spline": {"degree": int(spl.k), "knots": spl.t.tolist(), "coefficients": c.tolist()},
            })
    return cases


def main():
    seed = int(sys.argv[1]) if len(sys.argv) > 1 else 20261201
    rng = np.random.default_rng(seed)
    meta = {"generator": f"scipy {scipy.__version__}, numpy {np.__version__}, seed {seed}"}
    for name, make in [("gcv", gcv_cases), ("lambda", lambda_cases),
                       ("residual", residual_cases), ("curves", curve_cases)]:
        with open(f"{name}.json", "w") as f:
            json.dump({**meta, "cases": make(rng)}, f)


if __name__ == "__main__":
    main()
