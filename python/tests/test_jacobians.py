"""Jacobians as scipy.sparse arrays: each structural map reproduces the operation
(``M @ c``) and equals central finite differences; the product's Jacobians too."""

import numpy as np
import scipy.sparse

import spline
from conftest import random_knots


def fd_jacobian(f, c, h=1e-6):
    """Central differences of ``f`` (flat output) with respect to the flat ``c``."""
    cols = []
    for i in range(c.size):
        e = np.zeros_like(c)
        e.flat[i] = h
        cols.append((np.ravel(f(c + e)) - np.ravel(f(c - e))) / (2 * h))
    return np.stack(cols, axis=1)


def test_structural_maps_match_finite_differences(rng):
    for case in range(20):
        k = int(rng.integers(1, 5))
        n = int(rng.integers(k + 1, k + 10))
        t = random_knots(rng, k, n, clamped=case % 2 == 0)
        c = rng.normal(size=n)
        s = spline.BSpline(t, c, k)
        u = float(rng.uniform(0.1, 0.9))
        new = np.sort(rng.uniform(0.1, 0.9, 3))
        ops = [
            (s.insertion_matrix(u, 1), lambda b: spline.BSpline(t, b, k).insert_knot(u, 1).c),
            (s.refinement_matrix(new), lambda b: spline.BSpline(t, b, k).refine(new).c),
            (s.elevation_matrix(1), lambda b: spline.BSpline(t, b, k).elevate_degree(1).c),
            # The library's derivative (scipy's refuses knots repeated k times and pads c).
            (s.derivative_matrix(1), lambda b: spline.BSpline(t, b, k)._s.derivative(1).coefficients()),
        ]
        for matrix, op in ops:
            assert isinstance(matrix, scipy.sparse.csr_array)
            np.testing.assert_allclose(matrix @ c, op(c), atol=1e-12)
            np.testing.assert_allclose(matrix.toarray(), fd_jacobian(op, c), atol=1e-7)
        # Vector coefficients: the same matrix acts on every coordinate.
        cc = rng.normal(size=(n, 3))
        inserted = spline.BSpline(t, cc, k).insert_knot(u, 1)
        np.testing.assert_allclose(s.insertion_matrix(u, 1) @ cc, inserted.c, atol=1e-12)


def test_product_jacobians(rng):
    for _ in range(20):
        k1, k2 = int(rng.integers(1, 4)), int(rng.integers(1, 4))
        n1, n2 = int(rng.integers(k1 + 1, k1 + 6)), int(rng.integers(k2 + 1, k2 + 6))
        t1, t2 = random_knots(rng, k1, n1, True), random_knots(rng, k2, n2, True)
        a, b = rng.normal(size=n1), rng.normal(size=n2)
        p, ja, jb = spline.product(spline.BSpline(t1, a, k1), spline.BSpline(t2, b, k2))
        x = rng.uniform(0, 1, 50)
        np.testing.assert_allclose(
            p(x), spline.BSpline(t1, a, k1)(x) * spline.BSpline(t2, b, k2)(x), atol=1e-12
        )
        fa = fd_jacobian(
            lambda v: spline.product(spline.BSpline(t1, v, k1), spline.BSpline(t2, b, k2))[0].c, a
        )
        fb = fd_jacobian(
            lambda v: spline.product(spline.BSpline(t1, a, k1), spline.BSpline(t2, v, k2))[0].c, b
        )
        np.testing.assert_allclose(ja.toarray(), fa, atol=1e-7)
        np.testing.assert_allclose(jb.toarray(), fb, atol=1e-7)
