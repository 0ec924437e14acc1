"""Reference values of scipy 1.17's make_ndbspl for nd_interp/tests.rs.

Run from the workspace root:
    target/python-venv/bin/python crates/spline-fit/src/nd_interp/reference.py
and paste the printed arrays into the tests. The exact solver (spsolve) is used: scipy's
default gcrotmk stops at atol=1e-6.
"""
import numpy as np
import scipy.sparse.linalg as ssl
from scipy.interpolate._ndbspline import make_ndbspl  # not exported by scipy.interpolate

np.set_printoptions(precision=17)


def show(name, a):
    a = np.asarray(a, dtype=float).ravel()
    print(f"const {name}: [f64; {a.size}] = [" + ", ".join(repr(float(v)) for v in a) + "];")


x = np.array([0.0, 0.3, 0.5, 1.0, 1.2, 2.0])
y = np.array([-1.0, -0.5, 0.5, 1.0, 2.0])
z = np.array([0.0, 1.0, 1.5, 3.0])
X, Y, Z = np.meshgrid(x, y, z, indexing="ij")
# Two value columns: values[i, j, l, c] = cos(x + 2c) * exp(-y/3) + sin(x y z) + c z^2.
values = np.stack([np.cos(X + 2 * c) * np.exp(-Y / 3) + np.sin(X * Y * Z) + c * Z**2 for c in range(2)], axis=-1)
s = make_ndbspl((x, y, z), values, k=(3, 2, 1), solver=ssl.spsolve)
for d in range(3):
    show(f"KNOTS_{d}", s.t[d])
xi = np.array([[0.1, -0.9, 0.2], [0.7, 0.0, 1.2], [1.9, 1.7, 2.9], [2.0, 2.0, 3.0], [-0.5, 2.5, 3.5]])
show("VALUES", s(xi))
show("DX", s(xi, nu=(1, 0, 0)))
show("COEF_HEAD", s.c.ravel()[:12])
