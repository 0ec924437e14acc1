"""Reference cases for periodic interpolation: scipy's make_interp_spline(x, y, k,
bc_type="periodic") on random data (functions and planar curves), with the spline's wrapped
knots and control points and its values (periodic extrapolation included) at random points.

    python3 generate.py SEED > interpolate_periodic.json
"""
import json
import sys

import numpy as np
import scipy
from scipy.interpolate import make_interp_spline


def case(rng, name, k, n, dim):
    x = np.cumsum(rng.uniform(0.05, 1.0, n)) + rng.uniform(-2.0, 2.0)
    y = rng.uniform(-1.0, 1.0, (n, dim)) if dim > 1 else rng.uniform(-1.0, 1.0, n)
    y[-1] = y[0]
    spl = make_interp_spline(x, y, k=k, bc_type="periodic")
    period = x[-1] - x[0]
    at = np.sort(rng.uniform(x[0] - period, x[-1] + period, 25))
    values = spl(at)
    return {
        "name": name,
        "degree": k,
        "x": x.tolist(),
        "y": y.tolist(),
        "at": at.tolist(),
        "expected": {
            "knots": spl.t.tolist(),
            "control_points": np.asarray(spl.c).tolist(),
            "values": np.asarray(values).tolist(),
        },
    }


def main():
    seed = int(sys.argv[1]) if len(sys.argv) > 1 else 12
    rng = np.random.default_rng(seed)
    cases = []
    for k in range(1, 6):
        for n in (k + 2, 9, 30):
            for dim in (1, 2):
                cases.append(case(rng, f"k{k}-n{n}-d{dim}", k, n, dim))
    json.dump(
        {
            "operation": "interpolate_periodic",
            "generator": f"scipy {scipy.__version__}, generate.py seed {seed}",
            "cases": cases,
        },
        sys.stdout,
    )


main()
