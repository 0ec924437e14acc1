"""scipy's constructors of B-spline functions: ``make_interp_spline``, ``make_lsq_spline``
and ``make_smoothing_spline`` over the library's fits (one factorisation for all columns)."""

from __future__ import annotations

import operator
from math import prod
from typing import Optional, Tuple

import numpy as np
from numpy.lib.array_utils import normalize_axis_index

from . import _core
from ._bspline import ArrayLike, BSpline, _as_float_array, _from_columns, _real_columns


def _fit_input(y: ArrayLike, axis: int, check_finite: bool) -> Tuple[np.ndarray, int]:
    """``y`` with the interpolation axis first, and that axis normalised."""
    y = _as_float_array(y, check_finite)
    axis = normalize_axis_index(axis, y.ndim)
    return np.moveaxis(y, axis, 0), axis


def _solve_columns(y: np.ndarray, solve) -> np.ndarray:
    """Runs ``solve(flat, m)`` (a library fit on ``m`` real columns, returning row-major
    coefficients) on ``y`` (interpolation axis first, any trailing shape, maybe complex) and
    gives the coefficients with ``y``'s trailing shape and dtype."""
    cc, is_complex = _real_columns(y)
    flat = solve(np.ascontiguousarray(cc).reshape(-1), cc.shape[1])
    return _from_columns(flat, flat.size // cc.shape[1], y.shape[1:], is_complex)


def make_interp_spline(
    x: ArrayLike,
    y: ArrayLike,
    k: int = 3,
    t: Optional[ArrayLike] = None,
    bc_type=None,
    axis: int = 0,
    check_finite: bool = True,
) -> BSpline:
    """The interpolating B-spline of degree ``k`` (scipy's ``make_interp_spline``):
    ``f(x[j]) = y[j]`` along ``axis`` of ``y``, on the knots ``t`` or the not-a-knot knots;
    ``bc_type``: ``None``/``'not-a-knot'``, or ``'natural'`` for cubics."""
    if bc_type is None or bc_type == "not-a-knot" or bc_type == "periodic":
        deriv_l, deriv_r = None, None
    elif isinstance(bc_type, str):
        deriv_l, deriv_r = bc_type, bc_type
    else:
        try:
            deriv_l, deriv_r = bc_type
        except TypeError as e:
            raise _core.SplineError(f"Unknown boundary condition: {bc_type}") from e
    x = _as_float_array(x, check_finite)
    y, axis = _fit_input(y, axis, check_finite)
    if bc_type == "periodic" and not np.allclose(y[0], y[-1], atol=1e-15):
        raise _core.SplineError(
            "First and last points does not match while periodic case expected"
        )
    if x.size != y.shape[0]:
        raise _core.SplineError(f"Shapes of x {x.shape} and y {y.shape} are incompatible")
    if np.any(x[1:] == x[:-1]):
        raise _core.SplineError("Expect x to not have duplicates")
    if x.ndim != 1 or np.any(x[1:] < x[:-1]):
        raise _core.SplineError("Expect x to be a 1D strictly increasing sequence.")
    if k == 0:
        if any(v is not None for v in (t, deriv_l, deriv_r)):
            raise _core.SplineError("Too much info for k=0: t and bc_type can only be None.")
        t = np.r_[x, x[-1]]
        return BSpline.construct_fast(t, np.ascontiguousarray(y), k, axis=axis)
    if k == 1 and t is None:
        if not (deriv_l is None and deriv_r is None):
            raise _core.SplineError("Too much info for k=1: bc_type can only be None.")
        t = np.r_[x[0], x, x[-1]]
        return BSpline.construct_fast(t, np.ascontiguousarray(y), k, axis=axis)
    k = operator.index(k)
    if bc_type == "periodic" and t is not None:
        raise NotImplementedError(
            "For periodic case t is constructed automatically and can not be passed manually"
        )
    if k < 0:
        raise _core.SplineError("Expect non-negative k.")
    if t is not None:
        t = _as_float_array(t, check_finite)
        if t.ndim != 1 or np.any(t[1:] < t[:-1]):
            raise _core.SplineError("Expect t to be a 1-D sorted array_like.")
        if t.size < x.size + k + 1:
            raise _core.SplineError(f"Got {t.size} knots, need at least {x.size + k + 1}.")
        if (x[0] < t[k]) or (x[-1] > t[-k]):
            raise _core.SplineError(f"Out of bounds w/ x = {x}.")
    if bc_type == "periodic":
        bc, left, right = "periodic", [], []
    elif deriv_l is None and deriv_r is None:
        bc, left, right = "not-a-knot", [], []
    else:
        bc = "ends"
        left = _end_conditions(deriv_l, y, k, x[0])
        right = _end_conditions(deriv_r, y, k, x[-1])
        if t is not None:
            nt = t.size - k - 1
            if nt - x.size != len(left) + len(right):
                raise _core.SplineError(
                    "The number of derivatives at boundaries does not match: "
                    f"expected {nt - x.size}, got {len(left)}+{len(right)}"
                )
    if y.size == 0:
        if t is None:
            t = _core.not_a_knot(np.ascontiguousarray(x), k)
        c = np.zeros((t.size - k - 1,) + y.shape[1:], dtype=float)
        return BSpline.construct_fast(t, c, k, axis=axis)
    out = []

    def solve(flat, m):
        core = _core.interp_spline(x, flat, m, k, t, bc, left, right)
        out.append(core)
        return core.coefficients()

    c = _solve_columns(y, solve)
    return BSpline.construct_fast(out[0].knots(), c, k, axis=axis)


def _end_conditions(deriv, y: np.ndarray, k: int, where: float) -> list:
    """scipy's end conditions (``'clamped'``, ``'natural'``, ``None`` or a list of
    ``(order, value)``) as the library's: ``(order, values)`` with one real value per column
    of ``y`` (complex values are two)."""
    tail = y.shape[1:]
    if isinstance(deriv, str):
        if deriv == "clamped":
            deriv = [(1, np.zeros(tail))]
        elif deriv == "natural":
            deriv = [(2, np.zeros(tail))]
        else:
            raise _core.SplineError(f"Unknown boundary condition : {deriv}")
    if deriv is None:
        return []
    try:
        ords, vals = zip(*deriv)
    except TypeError as e:
        raise _core.SplineError(
            "Derivatives, `bc_type`, should be specified as a pair of iterables of pairs "
            "of (order, value)."
        ) from e
    ords = np.atleast_1d(ords)
    if not all(0 <= o <= k for o in ords):
        raise _core.SplineError(f"Bad boundary conditions at {where}.")
    dtype = np.result_type(y.dtype, *[np.asarray(v).dtype for v in vals])
    conditions = []
    for order, value in zip(ords, vals):
        v = np.asarray(value, dtype=dtype).reshape((1,) + tail)
        if np.iscomplexobj(y) and not np.iscomplexobj(v):
            v = v.astype(np.complex128)
        cc, _ = _real_columns(v)
        conditions.append((int(order), [float(a) for a in cc.reshape(-1)]))
    return conditions


def make_lsq_spline(
    x: ArrayLike,
    y: ArrayLike,
    t: ArrayLike,
    k: int = 3,
    w: Optional[ArrayLike] = None,
    axis: int = 0,
    check_finite: bool = True,
    *,
    method: str = "qr",
) -> BSpline:
    """The least-squares B-spline on the knots ``t`` (scipy's ``make_lsq_spline``):
    minimises ``sum((w[j] * (y[j] - f(x[j])))**2)`` along ``axis``; ``method``: ``'qr'``
    (Givens rotations) or ``'norm-eq'`` (banded normal equations)."""
    x = _as_float_array(x, check_finite)
    y = _as_float_array(y, check_finite)
    t = _as_float_array(t, check_finite)
    if w is not None:
        w = _as_float_array(w, check_finite)
    else:
        w = np.ones_like(x)
    k = operator.index(k)
    axis = normalize_axis_index(axis, y.ndim)
    y = np.moveaxis(y, axis, 0)
    if x.ndim != 1:
        raise _core.SplineError("Expect x to be a 1-D sequence.")
    if x.shape[0] < k + 1:
        raise _core.SplineError("Need more x points.")
    if k < 0:
        raise _core.SplineError("Expect non-negative k.")
    if t.ndim != 1 or np.any(t[1:] - t[:-1] < 0):
        raise _core.SplineError("Expect t to be a 1D strictly increasing sequence.")
    if x.size != y.shape[0]:
        raise _core.SplineError(f"Shapes of x {x.shape} and y {y.shape} are incompatible")
    if k > 0 and np.any((x < t[k]) | (x > t[-k])):
        raise _core.SplineError(f"Out of bounds w/ x = {x}.")
    if x.size != w.size:
        raise _core.SplineError(f"Shapes of x {x.shape} and w {w.shape} are incompatible")
    if method == "norm-eq" and np.any(x[1:] - x[:-1] <= 0):
        raise _core.SplineError("Expect x to be a 1D strictly increasing sequence.")
    if method == "qr" and any(x[1:] - x[:-1] < 0):
        raise _core.SplineError("Expect x to be a 1D non-decreasing sequence.")
    if method not in ("qr", "norm-eq"):
        raise _core.SplineError(f"Unknown {method = }.")
    n = t.size - k - 1
    if prod(y.shape[1:]) == 0:
        return BSpline.construct_fast(t, np.zeros((n,) + y.shape[1:]), k, axis=axis)
    ww = np.ascontiguousarray(w, dtype=np.float64)
    c = _solve_columns(
        y, lambda flat, m: _core.lsq_spline(x, flat, m, t, k, ww, method).coefficients()
    )
    return BSpline.construct_fast(t, np.ascontiguousarray(c), k, axis=axis)


def make_smoothing_spline(
    x: ArrayLike, y: ArrayLike, w: Optional[ArrayLike] = None, lam: Optional[float] = None, *, axis: int = 0
) -> BSpline:
    """The cubic smoothing spline (scipy's ``make_smoothing_spline``): minimises
    ``sum(w_j (y_j - f(x_j))**2) + lam * integral(f''**2)``, ``lam`` chosen by generalised
    cross-validation when ``None`` (per column)."""
    x = np.ascontiguousarray(x, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    if any(x[1:] - x[:-1] <= 0):
        raise _core.SplineError("``x`` should be an ascending array")
    if x.ndim != 1 or x.shape[0] != y.shape[axis]:
        raise _core.SplineError(f"``x`` should be 1D and {x.shape = } == {y.shape = }")
    if w is not None:
        w = np.ascontiguousarray(w, dtype=float)
        if any(w <= 0):
            raise _core.SplineError("Invalid vector of weights")
    if x.shape[0] <= 4:
        raise _core.SplineError("``x`` and ``y`` length must be at least 5")
    if lam is not None and lam < 0.0:
        raise _core.SplineError("Regularization parameter should be non-negative")
    axis = normalize_axis_index(axis, y.ndim)
    y = np.moveaxis(y, axis, 0)
    t_out = []

    def solve(flat, m):
        t, c = _core.smoothing_columns(x, flat, m, w, None if lam is None else float(lam))
        t_out.append(t)
        return c

    c = _solve_columns(y, solve)
    return BSpline.construct_fast(t_out[0], c, 3, axis=axis)
