"""Reference values for the `columns` modules of spline-geom and spline-fit.

Run with scipy 1.17 in the workspace's virtual environment:

    target/python-venv/bin/python crates/spline-fit/src/columns/reference.py

Every section prints the values pasted into the unit tests (the test names the section).
With `--rust FILE` it also writes the sections as Rust constants (named after the section,
upper case): that is how `crates/spline-fit/src/columns/reference_values.rs` was made.
"""
import re
import sys
import numpy as np
from scipy.interpolate import BSpline

np.set_printoptions(precision=17, linewidth=120)


SECTIONS = {}


def show(name, value):
    values = np.asarray(value, dtype=float).ravel().tolist()
    SECTIONS[name] = values
    print(f"// {name}")
    print(repr(values))


def write_rust(path):
    with open(path, "w") as f:
        f.write("//! scipy 1.17 reference values, written by `reference.py --rust` (do not edit).\n\n")
        f.write("#![allow(clippy::approx_constant, clippy::unreadable_literal)]\n\n")
        for name, values in SECTIONS.items():
            ident = re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_").upper()
            body = ", ".join("f64::NAN" if v != v else repr(v) for v in values)
            f.write(f"/// `{name}`\n#[rustfmt::skip]\npub(super) const {ident}: &[f64] = &[{body}];\n")


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

# derivative / antiderivative of the cubic above (knots and coefficients).
d = b.derivative(2)
show("derivative(2) t", d.t)
show("derivative(2) c", d.c)
a2 = b.antiderivative(2)
show("antiderivative(2) t", a2.t)
show("antiderivative(2) c", a2.c)
# integrals
show("integrate(-1.5, 4.0) extrapolate=True", b.integrate(-1.5, 4.0))
show("integrate(0.5, 1.8)", b.integrate(0.5, 1.8))
show("integrate(1.8, 0.5)", b.integrate(1.8, 0.5))
show("integrate(-1.5, 4.0) extrapolate=False", b.integrate(-1.5, 4.0, extrapolate=False))
show("integrate(-3.3, 7.9) periodic", b.integrate(-3.3, 7.9, extrapolate="periodic"))
show("integrate(1.9, 2.1) periodic", b.integrate(1.9, 2.1, extrapolate="periodic"))
# roots of column 1 (PPoly with discontinuity=True, extrapolate=False).
from scipy.interpolate import PPoly
pp = PPoly.from_spline(BSpline(t, c[:, 1], 3), extrapolate=False)
show("roots column 1", pp.roots())
# a discontinuous linear spline (double knot) that jumps across zero at 1
tl = [0.0, 0.0, 1.0, 1.0, 2.0, 2.0]
cl = [-1.0, -0.5, 0.5, 2.0]
ppl = PPoly.from_spline(BSpline(tl, cl, 1), extrapolate=False)
show("roots linear jump", ppl.roots())
# a quintic with roots
t5 = np.r_[[0.0] * 6, 0.5, 1.1, 2.0, [3.0] * 6]
c5 = np.array([1.0, -2.0, 0.5, 3.0, -1.0, 0.2, 0.7, -0.4, 1.0])
pp5 = PPoly.from_spline(BSpline(t5, c5, 5), extrapolate=False)
show("roots quintic", pp5.roots())
# insert_knot
bi = b.insert_knot(1.2, 2)
show("insert_knot(1.2, 2) t", bi.t)
show("insert_knot(1.2, 2) c", bi.c)
tp = np.arange(-3.0, 11.0)  # uniform knots, cubic periodic on [0, 7]
cp = np.array([1.0, 2.0, -1.0, 0.5, 3.0, 0.0, 1.5, 1.0, 2.0, -1.0])
bp = BSpline(tp, cp, 3, extrapolate="periodic")
for xv in (0.5, 6.5, 3.2):
    bq = bp.insert_knot(xv)
    show(f"periodic insert_knot({xv}) t", bq.t)
    show(f"periodic insert_knot({xv}) c", bq.c)
# basis_element
e = BSpline.basis_element([0.0, 1.0, 1.0, 3.0])
show("basis_element [0,1,1,3] t", e.t)
show("basis_element values", e(np.array([-0.5, 0.5, 1.0, 2.0, 3.5])))
# design_matrix
xd = np.array([-0.5, 0.3, 1.0, 1.5, 2.0, 2.5])
dm = BSpline.design_matrix(xd, t, 3, extrapolate=True)
show("design_matrix extrapolate=True data", dm.data)
show("design_matrix extrapolate=True indices", dm.indices)
dmp = BSpline.design_matrix(xd, t, 3, extrapolate="periodic")
show("design_matrix periodic data", dmp.data)
show("design_matrix periodic indices", dmp.indices)
# from_power_basis
from scipy.interpolate import CubicSpline
xs = np.array([0.0, 0.7, 1.5, 2.0, 3.2, 4.0])
ys = np.sin(xs) + np.cos(2 * xs)  # scipy accepts one column only
for bc in ("not-a-knot", "natural", "clamped"):
    cs = CubicSpline(xs, ys, bc_type=bc)
    bb = BSpline.from_power_basis(cs, bc_type=bc)
    show(f"from_power_basis {bc} pp.c", cs.c)
    show(f"from_power_basis {bc} t", bb.t)
    show(f"from_power_basis {bc} c", bb.c)
ysp = np.sin(xs * 2 * np.pi / 4.0)
ysp[-1] = ysp[0]
cs = CubicSpline(xs, ysp, bc_type="periodic")
bb = BSpline.from_power_basis(cs, bc_type="periodic")
show("from_power_basis periodic pp.c", cs.c)
show("from_power_basis periodic t", bb.t)
show("from_power_basis periodic c", bb.c)

# ---- spline-fit columns ----
from scipy.interpolate import make_interp_spline, make_lsq_spline
xi = np.array([0.0, 0.4, 1.0, 1.7, 2.1, 3.0, 3.6, 4.5, 5.0])
yi = np.c_[np.sin(xi), np.cos(xi) + xi]
for k in range(1, 6):
    s = make_interp_spline(xi, yi, k=k)
    show(f"interp k={k} not-a-knot t", s.t)
    show(f"interp k={k} not-a-knot c", s.c)
for k in (3,):
    for bc in ("natural", "clamped"):
        s = make_interp_spline(xi, yi, k=k, bc_type=bc)
        show(f"interp k={k} {bc} t", s.t)
        show(f"interp k={k} {bc} c", s.c)
s = make_interp_spline(xi, yi, k=2, bc_type=([(1, [0.5, -1.0])], None))
show("interp k=2 ([(1, [0.5, -1])], None) t", s.t)
show("interp k=2 ([(1, [0.5, -1])], None) c", s.c)
s = make_interp_spline(xi, yi, k=4, bc_type=([(1, [0.5, -1.0]), (2, [0.0, 1.0])], [(3, [1.0, 1.0])]))
show("interp k=4 two derivatives each end t", s.t)
show("interp k=4 two derivatives each end c", s.c)
yp = np.c_[np.sin(xi * 2 * np.pi / 5.0), np.cos(xi * 2 * np.pi / 5.0)]
yp[-1] = yp[0]
for k in range(1, 6):
    s = make_interp_spline(xi, yp, k=k, bc_type="periodic")
    show(f"interp k={k} periodic t", s.t)
    show(f"interp k={k} periodic c", s.c)
# least squares
rng = np.random.default_rng(1234)
xl = np.sort(rng.uniform(0, 4, 40))
yl = np.c_[np.sin(xl) + 0.1 * rng.standard_normal(40), xl ** 2, np.exp(-xl), np.cos(3 * xl), xl]
wl = rng.uniform(0.5, 2.0, 40)
tl = np.r_[[0.0] * 4, 0.5, 1.3, 2.0, 2.2, 3.1, [4.0] * 4]
tl[:4] = xl[0]; tl[-4:] = xl[-1]
show("lsq x", xl)
show("lsq y", yl)
show("lsq w", wl)
show("lsq t", tl)
for method in ("qr", "norm-eq"):
    s = make_lsq_spline(xl, yl, tl, k=3, w=wl, method=method)
    show(f"lsq k=3 weighted {method} c", s.c)
s = make_lsq_spline(xl, yl[:, 0], tl, k=3)
show("lsq k=3 unweighted column 0 c", s.c)

if len(sys.argv) == 3 and sys.argv[1] == "--rust":
    write_rust(sys.argv[2])
