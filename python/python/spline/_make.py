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
    ``bc_type``: ``None``/``'not-a-knot'``, ``'periodic'``, ``'clamped'``, ``'natural'`` or
    a pair of lists of ``(order, value)``. The library checks the data, the knots and the
    conditions with scipy's words."""
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
    # The binding takes a 1-D x (the library checks its order, duplicates and length).
    if x.ndim != 1:
        raise _core.SplineError("Expect x to be a 1D strictly increasing sequence.")
    # scipy's cases k = 0 and k = 1 without t come before its operator.index(k): 0.0 and
    # 1.0 are accepted there.
    if k == 0 or (k == 1 and t is None):
        k = int(k)
    k = operator.index(k)
    # scipy raises NotImplementedError for a periodic t (the library a ValueError), after
    # its first check, of the ends (the library's too), and not for k = 0 (t refused first).
    if bc_type == "periodic" and t is not None and k != 0:
        if not np.allclose(y[0], y[-1], atol=1e-15):
            raise _core.SplineError(
                "First and last points does not match while periodic case expected"
            )
        raise NotImplementedError(
            "For periodic case t is constructed automatically and can not be passed manually"
        )
    # The binding takes an unsigned degree.
    if k < 0:
        raise _core.SplineError("Expect non-negative k.")
    if t is not None:
        t = _as_float_array(t, check_finite)
        # The binding takes a 1-D t (the library checks its order, length and bounds).
        if t.ndim != 1:
            raise _core.SplineError("Expect t to be a 1-D sorted array_like.")
    if bc_type == "periodic":
        bc, left, right = "periodic", [], []
    elif deriv_l is None and deriv_r is None:
        bc, left, right = "not-a-knot", [], []
    else:
        bc = "ends"
        ends = (x[0], x[-1]) if x.size else (None, None)
        left = _end_conditions(deriv_l, y, ends[0])
        right = _end_conditions(deriv_r, y, ends[1])
    if prod(y.shape[1:]) == 0:
        # No value columns: the library fits one zero column for the knots (and checks the
        # arguments as scipy does before it returns zeros; for k <= 1 scipy returns y).
        zero = [(order, [0.0]) for order, _ in left], [(order, [0.0]) for order, _ in right]
        core = _core.interp_spline(x, np.zeros(y.shape[0]), 1, k, t, bc, *zero)
        rows = core.coefficients().size
        dtype = y.dtype if k <= 1 and t is None else float
        c = np.zeros((rows,) + y.shape[1:], dtype=dtype)
        return BSpline.construct_fast(core.knots(), c, k, axis=axis)
    out = []

    def solve(flat, m):
        core = _core.interp_spline(x, flat, m, k, t, bc, left, right)
        out.append(core)
        return core.coefficients()

    c = _solve_columns(y, solve)
    return BSpline.construct_fast(out[0].knots(), c, k, axis=axis)


def _end_conditions(deriv, y: np.ndarray, where: Optional[float]) -> list:
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
    # The binding takes unsigned orders (the library refuses orders above k in these words).
    if not all(o >= 0 for o in ords):
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
    (Givens rotations) or ``'norm-eq'`` (banded normal equations). The library checks the
    data, the knots and the weights with scipy's words."""
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
    # The binding takes a 1-D x, an unsigned k and a 1-D t.
    if x.ndim != 1:
        raise _core.SplineError("Expect x to be a 1-D sequence.")
    if k < 0:
        raise _core.SplineError("Expect non-negative k.")
    if t.ndim != 1:
        raise _core.SplineError("Expect t to be a 1D strictly increasing sequence.")
    # Any object is a method here (the binding takes a name).
    if method not in ("qr", "norm-eq"):
        raise _core.SplineError(f"Unknown {method = }.")
    ww = np.ascontiguousarray(w, dtype=np.float64)

    def fit(flat, m):
        return _core.lsq_spline(x, flat, m, t, k, ww, method)

    if prod(y.shape[1:]) == 0:
        # No value columns: the library fits one zero column (and checks the arguments).
        rows = fit(np.zeros(y.shape[0]), 1).coefficients().size
        return BSpline.construct_fast(t, np.zeros((rows,) + y.shape[1:]), k, axis=axis)
    c = _solve_columns(y, lambda flat, m: fit(flat, m).coefficients())
    return BSpline.construct_fast(t, np.ascontiguousarray(c), k, axis=axis)


def make_smoothing_spline(
    x: ArrayLike, y: ArrayLike, w: Optional[ArrayLike] = None, lam: Optional[float] = None, *, axis: int = 0
) -> BSpline:
    """The cubic smoothing spline (scipy's ``make_smoothing_spline``): minimises
    ``sum(w_j (y_j - f(x_j))**2) + lam * integral(f''**2)``, ``lam`` chosen by generalised
    cross-validation when ``None`` (per column). The library checks the data, the weights
    and ``lam`` with scipy's words."""
    x = np.ascontiguousarray(x, dtype=float)
    y = np.ascontiguousarray(y, dtype=float)
    # The binding takes a 1-D x.
    if x.ndim != 1:
        raise _core.SplineError(f"``x`` should be 1D and {x.shape = } == {y.shape = }")
    if w is not None:
        w = np.ascontiguousarray(w, dtype=float)
    axis = normalize_axis_index(axis, y.ndim)
    y = np.moveaxis(y, axis, 0)
    out = []

    def solve(flat, m):
        core = _core.smoothing_columns(x, flat, m, w, None if lam is None else float(lam))
        out.append(core)
        return core.coefficients()

    c = _solve_columns(y, solve)
    return BSpline.construct_fast(out[0].knots(), c, 3, axis=axis)
