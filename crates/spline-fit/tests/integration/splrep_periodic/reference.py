"""Reference values of scipy 1.17's periodic FITPACK replica (make_splrep, make_splprep,
generate_knots with bc_type="periodic"; scipy/interpolate/_fitpack_repro.py) for
splrep_periodic/mod.rs. FITPACK itself (splrep/splprep with per=1, Dierckx's fpperi) places
knots slightly differently when it adds several at once (it splits the residual sums in
proportion where scipy fits again); the comments say for which cases the two agree.

Run from the workspace root:
    target/python-venv/bin/python crates/spline-fit/tests/integration/splrep_periodic/reference.py \
        > crates/spline-fit/tests/integration/splrep_periodic/reference.rs
The data are written out in full (`X`, `Y`, ...), so the Rust test needs no Python.
"""
import textwrap
import warnings

import numpy as np
import scipy
from scipy.interpolate import (generate_knots, make_interp_spline, make_splprep,
                               make_splrep, splprep, splrep)

warnings.simplefilter("ignore", RuntimeWarning)


def show(name, a):
    a = np.asarray(a, dtype=float).ravel()
    body = ", ".join(repr(float(v)) for v in a)
    lines = textwrap.wrap(body, 96, initial_indent="    ", subsequent_indent="    ")
    print("#[rustfmt::skip]")
    print(f"pub const {name}: [f64; {a.size}] = [\n" + "\n".join(lines) + "\n];")


print("//! Printed by reference.py (next to this file): scipy's periodic FITPACK replica on the")
print(f"//! data below, scipy {scipy.__version__}, numpy {np.__version__}. Do not edit by hand.")
print()
print("// The period is 2π: printed as the data have it.")
print("#![allow(clippy::approx_constant)]")
print()
# Data: 40 abscissae on [0, 2π], unevenly spaced; a 2π-periodic function with a bump,
# rounded to 6 decimals (so the same numbers in Rust); y[-1] = y[0] exactly.
rng = np.random.default_rng(20260723)
x = np.r_[0.0, np.sort(rng.uniform(0, 2 * np.pi, 38)), 2 * np.pi]
y = np.sin(x) + 0.5 * np.cos(2 * x) + 0.3 * np.exp(-4 * (x - 3.0) ** 2)
y = np.round(y + 0.02 * rng.standard_normal(40), 6)
y[-1] = y[0]
w = np.round(rng.uniform(0.5, 2.0, 40), 3)
show("X", x)
show("Y", y)
show("W", w)

for tag, s, k, weights in [("S1", 1.0, 3, None), ("S01", 0.1, 3, None), ("S001", 0.01, 3, None),
                           ("K2", 0.05, 2, None), ("K5", 0.02, 5, None), ("W", 0.2, 3, w),
                           ("K1", 0.05, 1, None)]:
    spl = make_splrep(x, y, w=weights, k=k, s=s, bc_type="periodic")
    t, c, _ = splrep(x, y, w=weights, k=k, s=s, per=1)
    same = len(t) == len(spl.t) and np.allclose(t, spl.t, atol=1e-15)
    print(f"// {tag}: FITPACK's splrep(per=1) places {'the same' if same else 'other'} knots")
    show(f"KNOTS_{tag}", spl.t)
    show(f"COEF_{tag}", spl.c)
    ww = np.ones(40) if weights is None else weights
    print(f"pub const FP_{tag}: f64 = {float(np.sum((ww[:-1] * (spl(x[:-1]) - y[:-1])) ** 2))!r};")

# k = 6: above FITPACK's degrees (scipy's replica only).
spl = make_splrep(x, y, k=6, s=0.05, bc_type="periodic")
show("KNOTS_K6", spl.t)
show("COEF_K6", spl.c)

# Not periodic, k = 6 (scipy's replica accepts any degree; FITPACK 1 to 5).
spl = make_splrep(x, y, k=6, s=0.05)
show("KNOTS_NP_K6", spl.t)
show("COEF_NP_K6", spl.c)

# Given knots: FITPACK's own, s = 0.03.
t, c, _ = splrep(x, y, k=3, s=0.03, per=1)
spl = make_splrep(x, y, k=3, s=0.03, t=t, bc_type="periodic")
show("GIVEN_T", t)
show("GIVEN_COEF", spl.c)

# The sequence of knot vectors.
seq = list(generate_knots(x, y, k=3, s=0.01, bc_type="periodic"))
print(f"pub const SEQ_LENGTHS: [usize; {len(seq)}] = [{', '.join(str(len(t)) for t in seq)}];")
show("SEQ_SECOND", seq[1])
seq = list(generate_knots(x, y, k=3, s=0, bc_type="periodic"))
show("INTERP_KNOTS_K3", seq[0])
seq = list(generate_knots(x, y, k=4, s=0, bc_type="periodic"))
show("INTERP_KNOTS_K4", seq[0])

# Large s: the least-squares constant (the weighted mean of y[:-1]).
spl = make_splrep(x, y, w=w, k=3, s=100.0, bc_type="periodic")
show("KNOTS_CONST", spl.t)
show("COEF_CONST", spl.c)

# s = 0: scipy's periodic interpolation.
spl = make_splrep(x, y, k=3, s=0, bc_type="periodic")
show("INTERP_COEF_K3", spl.c)

# A closed curve in the plane through 30 points (chord-length parameters).
th = np.linspace(0, 2 * np.pi, 30)
r = 1.0 + 0.25 * np.cos(3 * th)
px = np.round(r * np.cos(th), 6)
py = np.round(r * np.sin(th), 6)
px[-1], py[-1] = px[0], py[0]
show("CURVE_X", px)
show("CURVE_Y", py)
spl, u = make_splprep([px, py], k=3, s=0.002, bc_type="periodic")
(t, c, _), u2 = splprep([px, py], k=3, s=0.002, per=1)
assert np.allclose(u, u2, atol=1e-15)
same = len(t) == len(spl.t) and np.allclose(t, spl.t, atol=1e-15)
print(f"// CURVE: FITPACK's splprep(per=1) places {'the same' if same else 'other'} knots")
show("CURVE_U", u)
show("CURVE_KNOTS", spl.t)
show("CURVE_COEF", spl.c)  # (n, 2): x, y of each coefficient
