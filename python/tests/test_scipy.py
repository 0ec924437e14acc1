"""The scipy-shaped API against scipy.interpolate on random cases: values, derivatives,
knot insertion, interpolation and least squares agree to ~1e-12."""

import numpy as np
import pytest
import scipy.interpolate as si

import spline
from conftest import random_knots

CASES = 40


def close(a, b, tol=1e-12):
    scale = max(1.0, float(np.max(np.abs(b))))
    assert np.max(np.abs(np.asarray(a) - np.asarray(b))) <= tol * scale


@pytest.mark.parametrize("dim", [0, 1, 2, 3])
def test_values_and_derivatives(rng, dim):
    for case in range(CASES):
        k = int(rng.integers(1, 6))
        n = int(rng.integers(k + 1, k + 15))
        t = random_knots(rng, k, n, clamped=case % 2 == 0)
        c = rng.normal(size=(n,) if dim == 0 else (n, dim))
        ours, theirs = spline.BSpline(t, c, k), si.BSpline(t, c, k)
        x = rng.uniform(t[k], t[n], 257)
        x[:2] = t[k], t[n]
        for nu in range(k + 2):
            close(ours(x, nu), theirs(x, nu))
        assert ours(x).shape == x.shape + c.shape[1:]
        X = x[:12].reshape(3, 4)
        assert ours(X, 1).shape == theirs(X, 1).shape
        assert ours(0.5).shape == theirs(0.5).shape  # a scalar gives shape c.shape[1:]
        close(ours(x[::3]), theirs(x[::3]))  # strided input
        np.testing.assert_array_equal(ours.t, t)
        np.testing.assert_array_equal(ours.c, c)
        assert ours.k == k


def test_derivative_spline(rng):
    for _ in range(CASES):
        k = int(rng.integers(2, 6))
        n = int(rng.integers(k + 1, k + 12))
        t = random_knots(rng, k, n, clamped=True, double=False)
        c = rng.normal(size=(n, 2))
        d, e = spline.BSpline(t, c, k).derivative(2), si.BSpline(t, c, k).derivative(2)
        assert d.k == e.k == k - 2
        x = rng.uniform(0, 1, 100)
        close(d(x), e(x), 1e-11)


def test_insert_knot(rng):
    for case in range(CASES):
        k = int(rng.integers(1, 6))
        n = int(rng.integers(k + 1, k + 12))
        t = random_knots(rng, k, n, clamped=case % 2 == 0)
        c = rng.normal(size=n)
        u, m = float(rng.uniform(0.1, 0.9)), int(rng.integers(1, k + 1))
        ours = spline.BSpline(t, c, k).insert_knot(u, m)
        theirs = si.BSpline(t, c, k).insert_knot(u, m)
        np.testing.assert_allclose(ours.t, theirs.t, rtol=0, atol=1e-15)
        close(ours.c, theirs.c[: len(ours.c)])
        x = rng.uniform(0, 1, 100)
        close(ours(x), si.BSpline(t, c, k)(x))


@pytest.mark.parametrize("k", [1, 2, 3, 4, 5])
def test_make_interp_spline(rng, k):
    for _ in range(10):
        m = int(rng.integers(k + 2, 40))
        x = np.sort(rng.uniform(0, 10, m))
        y = rng.normal(size=(m, 2))
        ours, theirs = spline.make_interp_spline(x, y, k), si.make_interp_spline(x, y, k)
        np.testing.assert_allclose(ours.t, theirs.t, rtol=0, atol=1e-14)
        close(ours.c, theirs.c, 1e-10)
        xx = rng.uniform(x[0], x[-1], 200)
        close(ours(xx), theirs(xx), 1e-10)
        close(ours(x), y, 1e-10)
        # On given knots, and a scalar function.
        t = theirs.t
        close(spline.make_interp_spline(x, y[:, 0], k, t=t)(xx), theirs(xx)[:, 0], 1e-10)


@pytest.mark.parametrize("k", [1, 2, 3, 5])
def test_make_lsq_spline(rng, k):
    for _ in range(10):
        m = int(rng.integers(30, 200))
        x = np.sort(rng.uniform(0, 1, m))
        x[0], x[-1] = 0.0, 1.0
        y = np.sin(6 * x) + 0.1 * rng.normal(size=m)
        inner = np.linspace(0, 1, int(rng.integers(3, 8)))[1:-1]
        t = np.r_[[0.0] * (k + 1), inner, [1.0] * (k + 1)]
        w = rng.uniform(0.5, 2.0, m)
        for weights in (None, w):
            ours = spline.make_lsq_spline(x, y, t, k, w=weights)
            theirs = si.make_lsq_spline(x, y, t, k, w=weights)
            close(ours.c, theirs.c, 1e-11)
        yy = np.c_[y, np.cos(3 * x)]
        close(spline.make_lsq_spline(x, yy, t, k).c, si.make_lsq_spline(x, yy, t, k).c, 1e-11)


def test_large_batch_matches_scipy(rng):
    t = np.r_[[0.0] * 4, np.linspace(0, 1, 98)[1:-1], [1.0] * 4]
    c = rng.normal(size=(100, 2))
    x = rng.uniform(0, 1, 100_000)
    close(spline.BSpline(t, c, 3)(x), si.BSpline(t, c, 3)(x))
