"""Shared helpers of the pytest suite: random B-splines drawn from a seeded generator."""

import numpy as np
import pytest


def random_knots(rng, k, n, clamped, double=True):
    """``n + k + 1`` sorted knots of degree ``k`` on ``[0, 1]`` (some interior knots
    repeated), clamped or not."""
    interior = np.sort(rng.uniform(0.05, 0.95, n - k - 1))
    if double and interior.size > 1 and rng.uniform() < 0.5:
        interior[1] = interior[0]  # a double knot
    if clamped:
        return np.r_[[0.0] * (k + 1), interior, [1.0] * (k + 1)]
    lo = np.sort(rng.uniform(-0.3, 0.0, k))
    hi = np.sort(rng.uniform(1.0, 1.3, k))
    return np.r_[lo, 0.0, interior, 1.0, hi]


@pytest.fixture
def rng():
    return np.random.default_rng(20261201)
