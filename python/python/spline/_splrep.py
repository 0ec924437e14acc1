"""scipy's FITPACK replicas with their signatures: ``make_splrep``, ``make_splprep`` and
``generate_knots`` (``scipy.interpolate``, ``bc_type`` ``"not-a-knot"`` or ``"periodic"``).
The fits run in the library (``spline_fit::make_splrep``: FITPACK's ``curfit`` and, periodic,
``percur``, with the defaults of ``xb``, ``xe`` and the checks of ``nest``); this module
converts the arguments and validates them with scipy's words where the library's differ."""

from __future__ import annotations

import operator
import warnings

import numpy as np

from . import _core
from ._bspline import BSpline
from ._make import make_interp_spline


def _validate_bc_type(bc_type):
    if bc_type is None:
        return "not-a-knot"
    if bc_type not in ("not-a-knot", "periodic"):
        raise _core.SplineError(
            "Only 'not-a-knot' and 'periodic' boundary conditions are recognised, "
            f"found {bc_type}"
        )
    return bc_type


def _validate_inputs(x, y, w, k, s, xb, xe, parametric):
    """scipy's ``_validate_inputs``: ``x, y (2-D), w, k, s, xb, xe``."""
    x = np.ascontiguousarray(x, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    if w is None:
        w = np.ones_like(x, dtype=float)
    else:
        w = np.ascontiguousarray(w, dtype=float)
        if w.ndim != 1:
            raise _core.SplineError(f"{w.ndim = } not implemented yet.")
        if (w < 0).any():
            raise _core.SplineError("Weights must be non-negative")
        if w.sum() == 0:
            raise _core.SplineError("All weights are zero.")
    if y.ndim == 0 or y.ndim > 2:
        raise _core.SplineError(f"{y.ndim = } not supported (must be 1 or 2.)")
    if parametric:
        if y.ndim != 2:
            raise _core.SplineError(f"{y.ndim = } != 2 not supported with {parametric =}.")
    else:
        if y.ndim != 1:
            raise _core.SplineError(f"{y.ndim = } != 1 not supported with {parametric =}.")
        y = y[:, None]
    if w.shape[0] != x.shape[0]:
        raise _core.SplineError(f"Weights is incompatible: {w.shape =} != {x.shape}.")
    if x.shape[0] != y.shape[0]:
        raise _core.SplineError(f"Data is incompatible: {x.shape = } and {y.shape = }.")
    if x.ndim != 1 or (x[1:] < x[:-1]).any():
        raise _core.SplineError("Expect `x` to be an ordered 1D sequence.")
    k = operator.index(k)
    if s < 0:
        raise _core.SplineError(f"`s` must be non-negative. Got {s = }")
    # xb, xe: None is scipy's min(x), max(x) in the library (x[0], x[-1] of the sorted x).
    xb = None if xb is None else float(xb)
    xe = None if xe is None else float(xe)
    return x, np.ascontiguousarray(y), w, k, float(s), xb, xe


def _fit(x, y, dim, w, xb, xe, k, s, t, nest, periodic):
    """The library's fit; warns as scipy does when the residual target was not met."""
    knots, c, converged = _core.splrep_fit(x, y, dim, w, xb, xe, k, s, t, nest, periodic)
    if not converged:
        warnings.warn(
            RuntimeWarning(
                "The maximal number of iterations for finding a smoothing spline with "
                "fp=s has been reached, or the iteration did not decrease fp: probably s "
                "too small. There is an approximation returned but the corresponding "
                "weighted sum of squared residuals does not satisfy the condition "
                "abs(fp-s)/s < tol."
            ),
            stacklevel=3,
        )
    return knots, c


def _nest(nest, k):
    """``nest`` for the binding; the library checks it (too small, or with ``t``) in
    scipy's words."""
    if nest is None:
        return None
    # The binding takes an unsigned count.
    if nest < 0:
        raise _core.SplineError(f"`nest` too small: {nest = } < 2*(k+1) = {2 * (k + 1)}.")
    return int(nest)


def generate_knots(x, y, *, w=None, xb=None, xe=None, k=3, s=0, nest=None, bc_type=None):
    """Yields the knot vectors of FITPACK's knot placement, ending with the one whose
    least-squares residual meets ``s`` (scipy's ``generate_knots``)."""
    periodic = _validate_bc_type(bc_type) == "periodic"
    if s == 0:
        if nest is not None or w is not None:
            raise _core.SplineError("s == 0 is interpolation only")
        k = operator.index(k)
        xf = np.ascontiguousarray(x, dtype=float)
        if periodic and k > 1:
            # scipy's _periodic_knots: floats whatever the data
            yield np.asarray(_core.splrep_knots(xf, xf, 0, None, None, None, k, 0.0, None, True)[0])
            return
        t = _core.not_a_knot(xf, k)
        x_dtype = np.asarray(x).dtype
        # scipy's knots keep the data's dtype where they are data (odd k)
        yield t.astype(x_dtype) if k % 2 == 1 and np.all(t == t.astype(x_dtype)) else t
        return
    parametric = np.ndim(y) == 2
    x, y, w, k, s, xb, xe = _validate_inputs(x, y, w, k, s, xb, xe, parametric=parametric)
    nest = _nest(nest, k)
    dim = y.shape[1] if parametric else 0
    for t in _core.splrep_knots(x, y.reshape(-1), dim, w, xb, xe, k, s, nest, periodic):
        yield np.asarray(t)


def make_splrep(x, y, *, w=None, xb=None, xe=None, k=3, s=0, t=None, nest=None, bc_type=None):
    """The smoothing spline of FITPACK's ``curfit`` (scipy's ``make_splrep``):
    ``sum((w * (y - g(x)))**2) <= s`` with the fewest knots, then the smoothest such spline;
    ``s = 0`` interpolates."""
    bc_type = _validate_bc_type(bc_type)
    if s == 0:
        if t is not None or w is not None or nest is not None:
            raise _core.SplineError("s==0 is for interpolation only")
        return make_interp_spline(x, y, k=k, bc_type=bc_type)
    x, y, w, k, s, xb, xe = _validate_inputs(x, y, w, k, s, xb, xe, parametric=False)
    tt = None if t is None else np.ascontiguousarray(t, dtype=float)
    nest = _nest(nest, k)
    knots, c = _fit(x, y.reshape(-1), 0, w, xb, xe, k, s, tt, nest, bc_type == "periodic")
    return BSpline.construct_fast(knots, c, k)


def make_splprep(x, *, w=None, u=None, ub=None, ue=None, k=3, s=0, t=None, nest=None, bc_type=None):
    """The parametric smoothing spline through the points ``x`` (a list of coordinate
    arrays; scipy's ``make_splprep``): returns the spline (coefficients of shape
    ``(ndim, n)``, ``axis=1``) and the parameters ``u`` (chord lengths on ``[0, 1]`` unless
    given; for ``s = 0`` scipy's not-a-knot interpolation, whatever ``bc_type``)."""
    periodic = _validate_bc_type(bc_type) == "periodic"
    x = np.stack([np.asarray(xi, dtype=float) for xi in x], axis=1)
    if u is None:
        u = _core.chord_lengths(np.ascontiguousarray(x).reshape(-1), x.shape[1])
    if s == 0:
        if t is not None or w is not None or nest is not None:
            raise _core.SplineError("s==0 is for interpolation only")
        return make_interp_spline(u, x.T, k=k, axis=1), u
    u, x, w, k, s, ub, ue = _validate_inputs(u, x, w, k, s, ub, ue, parametric=True)
    tt = None if t is None else np.ascontiguousarray(t, dtype=float)
    nest = _nest(nest, k)
    knots, c = _fit(u, x.reshape(-1), x.shape[1], w, ub, ue, k, s, tt, nest, periodic)
    cc = c.reshape(-1, x.shape[1]).T
    return BSpline(knots, cc, k, axis=1), u
