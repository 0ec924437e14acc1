"""The front ends call the library once and check only what the binding cannot take: the
column-wise smoothing spline, the k = 0 and k = 1 interpolants, the empty-column cases and
the checks that moved to the library (scipy's words, now from the library)."""

import numpy as np
import pytest
import scipy.interpolate as si

import spline


def words(fragment, f, *args, **kw):
    """``f`` raises a SplineError whose message contains scipy's ``fragment``."""
    with pytest.raises(spline.SplineError) as info:
        f(*args, **kw)
    assert fragment in str(info.value), str(info.value)


def test_smoothing_columns_are_the_one_column_fits(rng):
    x = np.sort(rng.uniform(-2, 2, 40))
    y = np.c_[x**2 * np.sin(4 * x), np.cos(3 * x), x**3] + rng.normal(0, 0.2, (40, 3))
    w = rng.uniform(0.5, 2.0, 40)
    for lam in (None, 0.0, 1e-3):
        whole = spline.make_smoothing_spline(x, y, w=w, lam=lam)
        for j in range(3):
            one = spline.make_smoothing_spline(x, y[:, j], w=w, lam=lam)
            np.testing.assert_array_equal(whole.t, one.t)
            np.testing.assert_array_equal(whole.c[:, j], one.c)
        theirs = si.make_smoothing_spline(x, y, w=w, lam=lam)
        np.testing.assert_allclose(whole(x), theirs(x), atol=1e-8)
    # axis: the same columns along axis 1.
    along = spline.make_smoothing_spline(x, y.T, lam=1e-2, axis=1)
    np.testing.assert_array_equal(along.c, spline.make_smoothing_spline(x, y, lam=1e-2).c)


def test_smoothing_checks_in_scipy_words(rng):
    x = np.sort(rng.uniform(-2, 2, 20))
    y = np.sin(x)
    words("``x`` should be an ascending array", spline.make_smoothing_spline, x[::-1], y)
    words("``x`` should be 1D", spline.make_smoothing_spline, x, y[1:])
    words("``x`` should be 1D", spline.make_smoothing_spline, x.reshape(1, -1), y)
    words("Invalid vector of weights", spline.make_smoothing_spline, x, y, w=-np.ones(20))
    words("``x`` and ``y`` length must be at least 5", spline.make_smoothing_spline, x[:4], y[:4])
    words("Regularization parameter should be non-negative", spline.make_smoothing_spline, x, y, lam=-1)


@pytest.mark.parametrize("k", [0, 1])
def test_degree_zero_and_one_are_scipys(rng, k):
    x = np.sort(rng.uniform(0, 1, 9))
    for y in (rng.normal(size=9), rng.normal(size=(9, 2, 3)), rng.normal(size=9) + 1j * rng.normal(size=9)):
        ours, theirs = spline.make_interp_spline(x, y, k=k), si.make_interp_spline(x, y, k=k)
        np.testing.assert_array_equal(ours.t, theirs.t)
        np.testing.assert_array_equal(ours.c, theirs.c)
        assert ours.c.dtype == theirs.c.dtype
        xx = np.linspace(-0.1, 1.1, 50)
        np.testing.assert_allclose(ours(xx), theirs(xx), atol=1e-14)
    # scipy's special cases accept a float degree.
    assert spline.make_interp_spline(x, x, k=float(k)).k == k
    words("Too much info for k=", spline.make_interp_spline, x, x, k=k, bc_type="clamped")
    with pytest.raises(TypeError):
        spline.make_interp_spline(x, x, k=2.5)


@pytest.mark.parametrize("bc_type", [None, "natural", "periodic"])
def test_empty_columns_have_scipys_knots(bc_type):
    x = np.linspace(0, 1, 8)
    ours = spline.make_interp_spline(x, np.zeros((8, 0)), bc_type=bc_type)
    theirs = si.make_interp_spline(x, np.zeros((8, 0)), bc_type=bc_type)
    np.testing.assert_array_equal(ours.t, theirs.t)
    assert ours.c.shape == theirs.c.shape
    t = np.r_[[0.0] * 4, 0.5, [1.0] * 4]
    assert spline.make_lsq_spline(x, np.zeros((8, 0)), t).c.shape == (5, 0)
    words("Shapes of x", spline.make_interp_spline, x, np.zeros((7, 0)), bc_type=bc_type)


def test_interp_and_lsq_checks_in_scipy_words():
    x = np.linspace(0, 1, 8)
    y = x**2
    words("Expect x to not have duplicates", spline.make_interp_spline, np.r_[x[:2], x[1:-1]], y)
    words("Expect x to be a 1D strictly", spline.make_interp_spline, x[::-1], y)
    words("Shapes of x", spline.make_interp_spline, x, y[1:])
    words("Bad boundary conditions at 0.", spline.make_interp_spline, x, y, bc_type=([(4, 0.0)], None))
    words("Bad boundary conditions at 0.", spline.make_interp_spline, x, y, bc_type=([(-1, 0.0)], None))
    words("The number of derivatives at boundaries does not match", spline.make_interp_spline, x, y,
          bc_type=([(1, 0.0)], None))
    words("Got 8 knots, need at least 12", spline.make_interp_spline, x, y, t=x)
    words("Out of bounds", spline.make_interp_spline, x, y, t=np.r_[[0.1] * 4, x[2:-2], [0.9] * 4])
    # scipy: the ends first, then NotImplementedError for a periodic t.
    words("First and last points does not match", spline.make_interp_spline, x, y, t=x, bc_type="periodic")
    with pytest.raises(NotImplementedError):
        spline.make_interp_spline(x, np.sin(2 * np.pi * x), t=x, bc_type="periodic")
    t = np.r_[[0.0] * 4, 0.5, [1.0] * 4]
    words("Need more x points", spline.make_lsq_spline, x[:3], y[:3], t)
    words("Expect t to be a 1D strictly increasing sequence", spline.make_lsq_spline, x, y, t[::-1])
    words("Shapes of x", spline.make_lsq_spline, x, y[1:], t)
    words("Out of bounds", spline.make_lsq_spline, 2 * x, y, t)
    words("Shapes of x (8,) and w (7,) are incompatible", spline.make_lsq_spline, x, y, t, w=np.ones(7))
    words("Expect x to be a 1D non-decreasing sequence", spline.make_lsq_spline, x[[0, 2, 1, 3, 4, 5, 6, 7]], y, t)


def test_other_checks_in_scipy_words():
    s = spline.BSpline([0, 0, 0, 0, 0.5, 1, 1, 1, 1], [0.0, 1.0, 2.0, 1.0, 0.0], 3)
    words("Cannot insert a knot at", s.insert_knot, 2.0)
    words("`m` must be positive", s.insert_knot, 0.5, 0)
    words("`m` must be positive", s.insert_knot, 0.5, -1)
    words("Expect t to be a 1-D sorted array_like", spline.BSpline.design_matrix, [0.5], [3, 2, 1, 0, 0, 0], 2)
    words("Length t is not enough for k=2", spline.BSpline.design_matrix, [0.5], [0.0, 0.0, 1.0], 2)
    words("Out of bounds w/ x", spline.BSpline.design_matrix, [1.0, 4.0], [0.0, 1, 2, 3, 4, 5], 2)
    words("There are 2 points in dimension 0, but order 3 requires at least 4 points",
          spline.make_ndbspl, (np.arange(2.0), np.arange(6.0)), np.zeros((2, 6)), k=3)
    x = np.linspace(0, 1, 20)
    words("`nest` too small: nest = 3 < 2*(k+1) = 8.", spline.make_splrep, x, x**2, s=0.1, nest=3)
    words("`nest` too small: nest = -3", spline.make_splrep, x, x**2, s=0.1, nest=-3)
    words("`nest` too small", lambda: list(spline.generate_knots(x, x**2, s=0.1, nest=3)))
    words("Either supply `t` or `nest`.", spline.make_splrep, x, x**2, s=0.1, nest=20,
          t=[0, 0, 0, 0, 1, 1, 1, 1.0])


def test_splrep_interval_defaults_are_the_data_ends(rng):
    x = np.linspace(0, 6, 50)
    y = np.sin(x) + rng.normal(0, 0.05, 50)
    default = spline.make_splrep(x, y, s=0.1)
    given = spline.make_splrep(x, y, s=0.1, xb=0.0, xe=6.0)
    np.testing.assert_array_equal(default.t, given.t)
    np.testing.assert_array_equal(default.c, given.c)


def test_rational_derivatives_and_surfaces_by_evaluators():
    # Derivatives against central differences of the order below, off the knots (0.25, 0.5,
    # 0.75, where the rational pieces meet with C¹ only).
    c = spline.NurbsCurve.circle([0.5, -1.0], 2.0)
    u = np.linspace(0.01, 0.99, 96)
    h = 1e-6
    for nu in (1, 2, 3):
        fd = (c(u + h, nu - 1) - c(u - h, nu - 1)) / (2 * h)
        np.testing.assert_allclose(c(u, nu), fd, rtol=1e-5, atol=1e-5 * np.abs(fd).max())
    with pytest.raises(spline.SplineError):
        c([1.5], 1)
    s = spline.NurbsSurface.torus([0, 0, 0], [0, 0, 1], 3.0, 1.0)
    uu, vv = np.meshgrid(np.linspace(0, 1, 7), np.linspace(0, 1, 5), indexing="ij")
    p = s(uu.ravel(), vv.ravel())
    ring = np.hypot(p[:, 0], p[:, 1]) - 3.0
    np.testing.assert_allclose(np.hypot(ring, p[:, 2]), 1.0, atol=1e-14)
