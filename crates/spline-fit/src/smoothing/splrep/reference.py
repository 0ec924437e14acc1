"""Reference values of scipy 1.17's make_splrep, make_splprep and generate_knots
(scipy/interpolate/_fitpack_repro.py) for smoothing/splrep/tests.rs.

Run from the workspace root:
    target/python-venv/bin/python crates/spline-fit/src/smoothing/splrep/reference.py
and paste the printed arrays into the tests. The data are computed the same way there.
"""
import numpy as np
from scipy.interpolate import make_splrep, make_splprep, generate_knots

np.set_printoptions(precision=17)


def arr(a):
    a = np.asarray(a, dtype=float).ravel()
    return "[" + ", ".join(repr(float(v)) for v in a) + "]"


def show(name, a):
    a = np.asarray(a, dtype=float).ravel()
    print(f"const {name}: [f64; {a.size}] = {arr(a)};")


# Data: x_i = i / 39 (i < 40), y_i = sin(6 x) + 0.1 sin(37 x^2 + 1).
x = np.arange(40) / 39.0
y = np.sin(6 * x) + 0.1 * np.sin(37 * x**2 + 1)
w = 1.0 + 0.5 * np.cos(3 * x)
xs = np.array([0.0, 0.13, 0.5, 0.77, 1.0])

for tag, s, k in [("S05", 0.5, 3), ("S01", 0.1, 3), ("S001", 0.01, 3), ("S1E4", 1e-4, 3), ("K2", 0.05, 2), ("K5", 0.02, 5)]:
    spl = make_splrep(x, y, k=k, s=s)
    show(f"KNOTS_{tag}", spl.t)
    show(f"VALUES_{tag}", spl(xs))

# Weights and a wider interval.
spl = make_splrep(x, y, w=w, xb=-0.1, xe=1.2, k=3, s=0.2)
show("KNOTS_W", spl.t)
show("VALUES_W", spl(xs))

# Given knots.
t = np.r_[[0.0] * 4, 0.25, 0.5, 0.6, [1.0] * 4]
spl = make_splrep(x, y, k=3, s=0.05, t=t)
show("VALUES_T", spl(xs))

# nest caps the knots.
spl = make_splrep(x, y, k=3, s=1e-6, nest=14)
show("KNOTS_NEST", spl.t)
show("VALUES_NEST", spl(xs))

# s = 0: not-a-knot interpolation.
spl = make_splrep(x, y, k=3, s=0)
show("VALUES_S0", spl(xs))

# The sequence of generate_knots.
seq = list(generate_knots(x, y, k=3, s=1e-3))
print(f"const SEQ_LENGTHS: [usize; {len(seq)}] = [{', '.join(str(len(t)) for t in seq)}];")
show("SEQ_LAST", seq[-1])
show("SEQ_THIRD", seq[2])

# A 3-D curve: a helix with a wobble, 30 points.
th = np.linspace(0, 3 * np.pi, 30)
pts = [np.cos(th) + 0.02 * np.sin(7 * th), np.sin(th), 0.3 * th]
spl, u = make_splprep(pts, k=3, s=0.01)
show("CURVE_U", u)
show("CURVE_KNOTS", spl.t)
show("CURVE_VALUES", spl(np.array([0.0, 0.3, 0.71, 1.0])).T)
