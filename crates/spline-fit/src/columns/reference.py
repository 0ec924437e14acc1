"""Reference values for the `columns` modules of spline-geom and spline-fit.

Run with scipy 1.17 in the workspace's virtual environment:

    target/python-venv/bin/python crates/spline-fit/src/columns/reference.py

Every section prints the values pasted into the unit tests (the test names the section).
"""
import numpy as np
from scipy.interpolate import BSpline

np.set_printoptions(precision=17, linewidth=120)


def show(name, value):
    print(f"// {name}")
    print(repr(np.asarray(value, dtype=float).ravel().tolist()))


# eval: a cubic with 2 columns on non-uniform unclamped knots.
t = [-1.0, -0.5, 0.0, 0.3, 1.0, 1.7, 2.0, 2.6, 3.0, 3.1]
c = np.array([[1.0, -2.0], [0.5, 0.0], [2.0, 1.0], [-1.0, 3.0], [0.25, 0.5], [1.5, -1.0]])
b = BSpline(t, c, 3)
x = np.array([-2.0, 0.3, 0.3, 1.0, 1.35, 2.0, 2.2, 5.0])
show("eval extrapolate=True nu=0", b(x))
show("eval extrapolate=True nu=1", b(x, nu=1))
show("eval extrapolate=True nu=2", b(x, nu=2))
show("eval extrapolate=True nu=3", b(x, nu=3))
show("eval extrapolate=periodic nu=0", b(x, extrapolate="periodic"))
show("eval extrapolate=periodic nu=1", b(x, nu=1, extrapolate="periodic"))
show("eval extrapolate=False nu=0", b(x, extrapolate=False))
# degree 7 (general kernel), one column.
t7 = np.linspace(0, 1, 20)
c7 = np.sin(np.arange(12.0))
b7 = BSpline(t7, c7, 7)
x7 = np.array([-0.1, 0.4, 0.5, 0.61, 0.65, 1.2])
show("eval k=7 nu=0", b7(x7))
show("eval k=7 nu=2", b7(x7, nu=2))
