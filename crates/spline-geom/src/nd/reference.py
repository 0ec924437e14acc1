"""Reference values of scipy 1.17's NdBSpline for the tests in nd/tests.rs.

Run from the workspace root:
    target/python-venv/bin/python crates/spline-geom/src/nd/reference.py
and paste the printed arrays into the tests. Coefficients are c[i] = sin(1 + 0.7 i) over
the row-major flat index i (the tests compute them the same way).
"""
import numpy as np
from scipy.interpolate import NdBSpline

np.set_printoptions(precision=17)


def coeffs(shape):
    n = int(np.prod(shape))
    return np.sin(1.0 + 0.7 * np.arange(n)).reshape(shape)


def show(name, a):
    a = np.asarray(a, dtype=float).ravel()
    print(f"const {name}: [f64; {a.size}] = [" + ", ".join(repr(float(v)) if np.isfinite(v) else "f64::NAN" for v in a) + "];")


# 1-D, cubic, two interior knots, one double.
t1 = np.array([0, 0, 0, 0, 0.3, 0.3, 0.7, 1, 1, 1, 1.0])
s1 = NdBSpline((t1,), coeffs((7,)), 3)
x1 = np.array([[0.0], [0.1], [0.3], [0.55], [0.7], [1.0], [-0.2], [1.3]])
show("ONE_D", s1(x1))
show("ONE_D_NU1", s1(x1, nu=(1,)))
show("ONE_D_NU2", s1(x1, nu=(2,)))
show("ONE_D_NOEXT", s1(x1, extrapolate=False))

# 2-D, degrees (2, 3), 2 value columns.
ta = np.array([0, 0, 0, 0.5, 1.5, 2, 2, 2.0])
tb = np.array([-1, -1, -1, -1, 0, 1, 1, 1, 1.0])
s2 = NdBSpline((ta, tb), coeffs((5, 5, 2)), (2, 3))
x2 = np.array([[0.2, -0.5], [0.5, 0.0], [1.9, 0.99], [2.0, 1.0], [-0.3, 0.4], [1.0, 1.5]])
show("TWO_D", s2(x2))
show("TWO_D_NU12", s2(x2, nu=(1, 2)))
show("TWO_D_NOEXT", s2(x2, extrapolate=False))
m = NdBSpline.design_matrix(x2[:3], (ta, tb), (2, 3))
show("TWO_D_DM_DATA", m.data)
print("const TWO_D_DM_INDICES: [usize; %d] = [%s];" % (m.indices.size, ", ".join(map(str, m.indices))))

# 3-D, degrees (1, 2, 3), unclamped third knot vector.
tx = np.array([0, 0, 0.4, 1, 1.0])
ty = np.array([0, 0, 0, 0.25, 0.5, 1, 1, 1.0])
tz = np.array([-0.3, -0.2, -0.1, 0, 0.4, 0.6, 1, 1.1, 1.2, 1.3])
s3 = NdBSpline((tx, ty, tz), coeffs((3, 5, 6)), (1, 2, 3))
x3 = np.array([[0.1, 0.2, 0.3], [0.4, 0.5, 0.0], [0.9, 0.95, 1.0], [1.0, 1.0, 0.5], [1.2, -0.1, 0.7]])
show("THREE_D", s3(x3))
show("THREE_D_NU102", s3(x3, nu=(1, 0, 2)))
show("THREE_D_NU011", s3(x3, nu=(0, 1, 1)))

# Equal degrees (the fixed-size kernels): 2-D cubic with 2 columns, 3-D quadratic.
tc = np.array([0, 0, 0, 0, 0.2, 0.5, 0.9, 1, 1, 1, 1.0])
s4 = NdBSpline((tc, tc), coeffs((7, 7, 2)), 3)
x4 = np.array([[0.1, 0.3], [0.5, 0.5], [1.0, 0.95], [1.2, -0.3], [0.0, 1.0]])
show("CUBIC_2D", s4(x4))
show("CUBIC_2D_NOEXT", s4(x4, extrapolate=False))
tq = np.array([0, 0, 0, 0.3, 0.6, 1, 1, 1.0])
s5 = NdBSpline((tq, tq, tq), coeffs((5, 5, 5)), 2)
x5 = np.array([[0.1, 0.3, 0.7], [0.6, 0.6, 0.0], [1.0, 0.95, 0.2], [1.2, -0.3, 0.5]])
show("QUAD_3D", s5(x5))
show("CUBIC_2D_NU21", s4(x4, nu=(2, 1)))
show("QUAD_3D_NU101", s5(x5, nu=(1, 0, 1)))
