"""B-spline curves and functions with a scipy-like face: ``BSpline(t, c, k)``."""

from __future__ import annotations

import json
from typing import NamedTuple, Optional, Sequence, Tuple

import numpy as np
import numpy.typing as npt
import scipy.sparse

from . import _core

ArrayLike = npt.ArrayLike
FloatArray = npt.NDArray[np.float64]


def _floats(values: ArrayLike, what: str) -> FloatArray:
    """A contiguous float64 copy-if-needed of ``values``."""
    try:
        a = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError) as e:
        raise _core.SplineError(f"{what}: expected numbers ({e})") from None
    # (np.ascontiguousarray would turn a scalar into shape (1,).)
    return a if a.flags.c_contiguous else np.ascontiguousarray(a)


def _flat_rows(values: ArrayLike, what: str) -> Tuple[FloatArray, int]:
    """``values`` of shape ``(n,)`` or ``(n, d)`` as a flat array and ``d`` (0 for ``(n,)``)."""
    a = _floats(values, what)
    if a.ndim == 1:
        return a, 0
    if a.ndim == 2:
        return a.reshape(-1), a.shape[1]
    raise _core.SplineError(
        f"{what}: expected shape (n,) or (n, d), got {a.shape}"
    )


def _csr(parts: tuple) -> scipy.sparse.csr_array:
    """A ``scipy.sparse.csr_array`` from the CSR parts the extension returns."""
    data, indices, indptr, shape = parts
    return scipy.sparse.csr_array(
        (data, np.asarray(indices, dtype=np.int64), np.asarray(indptr, dtype=np.int64)),
        shape=shape,
    )


class Features(NamedTuple):
    """Inflections and curvature extrema of a planar curve (parameters, sorted)."""

    inflections: FloatArray
    curvature_extrema: FloatArray
    constant_curvature: Optional[float]


class BSpline:
    """A B-spline function or curve, as ``scipy.interpolate.BSpline``.

    ``t`` are the ``n + k + 1`` knots, ``c`` the ``n`` coefficients — shape ``(n,)`` for a
    function, ``(n, d)`` with ``1 ≤ d ≤ 4`` for a curve — and ``k`` the degree. The base
    interval is ``[t[k], t[n]]``.

    Differences from scipy: parameters outside the base interval raise ``SplineError``
    (the library does not extrapolate), and ``c`` must have exactly ``n`` rows.

    >>> import numpy as np, spline
    >>> s = spline.BSpline([0, 0, 0, 1, 2, 2, 2], [0.0, 1.0, 3.0, 4.0], 2)
    >>> float(s(1.0))
    2.0
    """

    __slots__ = ("_s",)

    def __init__(self, t: ArrayLike, c: ArrayLike, k: int, extrapolate: bool = False) -> None:
        if extrapolate:
            raise _core.SplineError(
                "extrapolate=True: the library evaluates inside the base interval only"
            )
        flat, dim = _flat_rows(c, "c")
        self._s = _core.Curve(int(k), _floats(t, "t"), flat, dim)

    @classmethod
    def _wrap(cls, core: "_core.Curve") -> "BSpline":
        obj = cls.__new__(cls)
        obj._s = core
        return obj

    @property
    def t(self) -> FloatArray:
        """The knots (a copy)."""
        return self._s.knots()

    @property
    def c(self) -> FloatArray:
        """The coefficients, ``(n,)`` or ``(n, d)`` (a copy)."""
        flat = self._s.coefficients()
        return flat if self._s.dim == 0 else flat.reshape(-1, self._s.dim)

    @property
    def k(self) -> int:
        """The degree."""
        return self._s.degree

    @property
    def domain(self) -> Tuple[float, float]:
        """The base interval ``(t[k], t[n])``."""
        return self._s.domain()

    def __repr__(self) -> str:
        return f"BSpline(k={self.k}, n={len(self.t) - self.k - 1}, dim={self._s.dim or 'scalar'})"

    def __call__(self, x: ArrayLike, nu: int = 0) -> FloatArray:
        """The ``nu``-th derivative at ``x`` (any shape): shape ``x.shape + c.shape[1:]``.

        One batch call into the library (GIL released); derivatives above the degree are 0.
        """
        xa = _floats(x, "x")
        flat = xa.reshape(-1)
        tail = () if self._s.dim == 0 else (self._s.dim,)
        if nu < 0:
            raise _core.SplineError(f"nu must be non-negative, got {nu}")
        if nu > self.k:
            # Checked like any other parameter, then zero (the exchange format's convention).
            self._s.eval(flat, 0)
            return np.zeros(xa.shape + tail)
        return self._s.eval(flat, int(nu)).reshape(xa.shape + tail)

    def derivative(self, nu: int = 1) -> "BSpline":
        """The derivative of order ``nu`` as a B-spline of degree ``k − nu``."""
        return BSpline._wrap(self._s.derivative(int(nu)))

    def insert_knot(self, x: float, m: int = 1) -> "BSpline":
        """The same curve with the knot ``x`` inserted ``m`` times (Boehm)."""
        return BSpline._wrap(self._s.insert_knot(float(x), int(m)))

    def refine(self, knots: ArrayLike) -> "BSpline":
        """The same curve with every knot of ``knots`` inserted (Oslo algorithm)."""
        return BSpline._wrap(self._s.refine(_floats(knots, "knots")))

    def elevate_degree(self, times: int = 1) -> "BSpline":
        """The same curve as a B-spline of degree ``k + times``."""
        return BSpline._wrap(self._s.elevate_degree(int(times)))

    def insertion_matrix(self, x: float, m: int = 1) -> scipy.sparse.csr_array:
        """The Jacobian of knot insertion: ``insert_knot(x, m).c == M @ c``."""
        return _csr(self._s.insertion_map(float(x), int(m)))

    def refinement_matrix(self, knots: ArrayLike) -> scipy.sparse.csr_array:
        """The Jacobian of refinement: ``refine(knots).c == M @ c``."""
        return _csr(self._s.refinement_map(_floats(knots, "knots")))

    def elevation_matrix(self, times: int = 1) -> scipy.sparse.csr_array:
        """The Jacobian of degree elevation: ``elevate_degree(times).c == M @ c``."""
        return _csr(self._s.elevation_map(int(times)))

    def derivative_matrix(self, nu: int = 1) -> scipy.sparse.csr_array:
        """The Jacobian of differentiation: ``derivative(nu).c == M @ c``."""
        return _csr(self._s.derivative_map(int(nu)))

    def features(self, accuracy: float = 1e-12) -> Features:
        """Inflections and curvature extrema of a planar curve, located exactly (root
        isolation of the curvature numerators) to ``accuracy`` in the parameter."""
        return Features(*self._s.features(float(accuracy)))

    def curvature(self, x: ArrayLike) -> FloatArray:
        """The signed curvature of a planar curve at ``x``."""
        xa = _floats(x, "x")
        return self._s.curvature(xa.reshape(-1)).reshape(xa.shape)

    def to_json(self) -> str:
        """The curve in the exchange format (``docs/exchange-format.md``)."""
        return self._s.to_json()

    @classmethod
    def from_json(cls, text: str) -> "BSpline":
        """A curve from exchange-format JSON (a 1-D curve becomes a scalar function)."""
        return cls._wrap(_core.Curve.from_json(text))


def make_interp_spline(
    x: ArrayLike, y: ArrayLike, k: int = 3, t: Optional[ArrayLike] = None
) -> BSpline:
    """The interpolating B-spline of degree ``k`` (as scipy's): ``f(x[j]) = y[j]`` on the
    not-a-knot knots, or on ``t``; ``y`` of shape ``(m,)`` or ``(m, d)``."""
    flat, dim = _flat_rows(y, "y")
    tt = None if t is None else _floats(t, "t")
    return BSpline._wrap(_core.interpolate(_floats(x, "x"), flat, dim, int(k), tt))


def make_lsq_spline(
    x: ArrayLike, y: ArrayLike, t: ArrayLike, k: int = 3, w: Optional[ArrayLike] = None
) -> BSpline:
    """The least-squares B-spline on the knots ``t`` (as scipy's): minimises
    ``sum((w[j] * (y[j] - f(x[j])))**2)``."""
    flat, dim = _flat_rows(y, "y")
    ww = None if w is None else _floats(w, "w")
    return BSpline._wrap(
        _core.least_squares(_floats(x, "x"), flat, dim, _floats(t, "t"), int(k), ww)
    )


def product(a: BSpline, b: BSpline) -> Tuple[BSpline, scipy.sparse.csr_array, scipy.sparse.csr_array]:
    """The product ``a(x) b(x)`` of two B-spline functions in its minimal B-spline space,
    with the Jacobians of its coefficients: ``J_a = ∂c/∂a.c``, ``J_b = ∂c/∂b.c``."""
    p, ja, jb = _core.product(a._s, b._s)
    return BSpline._wrap(p), _csr(ja), _csr(jb)


def read_json(text: str):
    """A curve or surface from exchange-format JSON: ``BSpline``, ``NurbsCurve`` (with
    ``"weights"``) or ``NurbsSurface`` (two degrees)."""
    from ._nurbs import NurbsCurve, NurbsSurface

    try:
        obj = json.loads(text)
    except json.JSONDecodeError as e:
        raise _core.SplineError(f"not JSON: {e}") from None
    if isinstance(obj, dict) and isinstance(obj.get("degree"), Sequence):
        return NurbsSurface.from_json(text)
    if isinstance(obj, dict) and "weights" in obj:
        return NurbsCurve.from_json(text)
    return BSpline.from_json(text)
