"""B-spline curves and functions with a scipy-like face: ``BSpline(t, c, k)``."""

from __future__ import annotations

import operator
from math import prod
from typing import NamedTuple, Optional, Tuple

import numpy as np
import numpy.typing as npt
import scipy.sparse
from numpy.lib.array_utils import normalize_axis_index

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


def _float_dtype(dtype: np.dtype) -> type:
    """scipy's rule: complex coefficients stay complex (``complex128``), others ``float64``."""
    return np.complex128 if np.issubdtype(dtype, np.complexfloating) else np.float64


def _as_float_array(x: ArrayLike, check_finite: bool = False) -> FloatArray:
    """``x`` as a contiguous float64 array (scipy's ``_as_float_array``)."""
    x = np.ascontiguousarray(x)
    x = x.astype(_float_dtype(x.dtype), copy=False)
    if check_finite and not np.isfinite(x).all():
        raise _core.SplineError("Array must not contain infs or nans.")
    return x


def _mode(extrapolate) -> str:
    """scipy's ``extrapolate`` (``True``, ``False`` or ``'periodic'``) as the library's name."""
    if isinstance(extrapolate, str) and extrapolate == "periodic":
        return "periodic"
    return "on" if extrapolate else "off"


def _real_columns(c: np.ndarray) -> Tuple[FloatArray, bool]:
    """The coefficients as a row-major ``(rows, m)`` float64 matrix (trailing dimensions
    flattened, a complex value as two real columns) and whether they were complex."""
    is_complex = np.iscomplexobj(c)
    c = np.ascontiguousarray(c, dtype=np.complex128 if is_complex else np.float64)
    cc = c.view(np.float64) if is_complex else c
    if is_complex and c.ndim == 1:
        cc = cc.reshape(c.shape[0], 2)
    # (Not reshape(rows, -1): that fails for zero rows.)
    return np.ascontiguousarray(cc.reshape(cc.shape[0], prod(cc.shape[1:]))), is_complex


def _from_columns(flat: FloatArray, rows: int, tail: tuple, is_complex: bool) -> np.ndarray:
    """The inverse of ``_real_columns`` for a flat row-major result of ``rows`` rows."""
    out = np.ascontiguousarray(flat, dtype=np.float64).reshape(rows, -1)
    if is_complex:
        out = out.view(np.complex128)
    return out.reshape((rows,) + tail)


class BSpline:
    r"""A univariate spline in the B-spline basis, as ``scipy.interpolate.BSpline``:

    .. math:: S(x) = \sum_{j=0}^{n-1} c_j B_{j,k;t}(x)

    ``t`` are the ``n + k + 1`` knots, ``c`` the coefficients (any shape whose axis ``axis``
    has at least ``n`` entries: the trailing dimensions are columns evaluated together;
    complex coefficients are two real columns), ``k`` the degree. ``extrapolate``: ``True``
    (the end polynomials continue outside the base interval ``[t[k], t[n]]``), ``False``
    (NaN there) or ``'periodic'``. The numerics run in the library (``ColumnSpline``); this
    class moves axes and validates arguments with scipy's messages.

    Beyond scipy: Jacobians of structural operations (``insertion_matrix``…), planar curve
    features and curvature, refinement and degree elevation, the JSON exchange format.

    >>> import numpy as np, spline
    >>> s = spline.BSpline([0, 0, 0, 1, 2, 2, 2], [0.0, 1.0, 3.0, 4.0], 2)
    >>> float(s(1.0))
    2.0
    """

    #: scipy's functions that accept a ``BSpline`` (``PPoly.from_spline``) convert arrays
    #: with the spline's array namespace; this package is numpy only.
    _asarray = staticmethod(np.asarray)

    def __init__(self, t: ArrayLike, c: ArrayLike, k: int, extrapolate=True, axis: int = 0):
        self.k = operator.index(k)
        self._c = np.asarray(c)
        self._t = np.ascontiguousarray(t, dtype=np.float64)
        if isinstance(extrapolate, str) and extrapolate == "periodic":
            self.extrapolate = extrapolate
        else:
            self.extrapolate = bool(extrapolate)
        n = self._t.shape[0] - self.k - 1
        axis = normalize_axis_index(axis, self._c.ndim)
        self.axis = axis
        if axis != 0:
            self._c = np.moveaxis(self._c, axis, 0)
        # scipy raises at construction; the library's ColumnSpline is built lazily (at the
        # first evaluation), so its checks of the knots and coefficients are repeated here.
        if k < 0:
            raise _core.SplineError("Spline order cannot be negative.")
        if self._t.ndim != 1:
            raise _core.SplineError("Knot vector must be one-dimensional.")
        if n < self.k + 1:
            raise _core.SplineError(f"Need at least {2 * k + 2} knots for degree {k}")
        if (np.diff(self._t) < 0).any():
            raise _core.SplineError("Knots must be in a non-decreasing order.")
        if len(np.unique(self._t[k : n + 1])) < 2:
            raise _core.SplineError("Need at least two internal knots.")
        if not np.isfinite(self._t).all():
            raise _core.SplineError("Knots should not have nans or infs.")
        if self._c.ndim < 1:
            raise _core.SplineError("Coefficients must be at least 1-dimensional.")
        if self._c.shape[0] < n:
            raise _core.SplineError("Knots, coefficients and degree are inconsistent.")
        self._c = np.ascontiguousarray(self._c, dtype=_float_dtype(self._c.dtype))

    @classmethod
    def construct_fast(cls, t, c, k, extrapolate=True, axis=0) -> "BSpline":
        """A spline without checks: ``t`` and ``c`` must have the right shape and dtype."""
        self = object.__new__(cls)
        self._t, self._c, self.k = np.asarray(t), np.asarray(c), k
        self.extrapolate = extrapolate
        self.axis = axis
        return self

    @classmethod
    def _wrap(cls, core: "_core.Curve") -> "BSpline":
        """A spline from the library's ``Curve`` (the package's own operations)."""
        flat = core.coefficients()
        c = flat if core.dim == 0 else flat.reshape(-1, core.dim)
        return cls.construct_fast(core.knots(), c, core.degree)

    @property
    def tck(self):
        """``(t, c, k)`` (read-only)."""
        return self.t, self.c, self.k

    @property
    def t(self) -> FloatArray:
        """The knots."""
        return self._t

    @t.setter
    def t(self, t) -> None:
        self._t = np.asarray(t)

    @property
    def c(self) -> np.ndarray:
        """The coefficients, interpolation axis first."""
        return self._c

    @c.setter
    def c(self, c) -> None:
        self._c = np.asarray(c)

    @property
    def _s(self) -> "_core.Curve":
        """The library's ``Curve`` (scalar or points of dimension 1 to 4) for the package's
        own operations (Jacobians, features, refinement, elevation, JSON)."""
        n = self._t.shape[0] - self.k - 1
        c = np.asarray(self._c)[:n]
        if np.iscomplexobj(c) or c.ndim > 2:
            raise _core.SplineError(
                "this operation needs real coefficients of shape (n,) or (n, d)"
            )
        flat, dim = _flat_rows(c, "c")
        return _core.Curve(int(self.k), _floats(self._t, "t"), flat, dim)

    def _columns(self) -> Tuple["_core.Columns", bool]:
        cc, is_complex = _real_columns(self._c)
        t = np.ascontiguousarray(self._t, dtype=np.float64)
        return _core.Columns(t, cc.reshape(-1), int(self.k), cc.shape[1]), is_complex

    @property
    def domain(self) -> Tuple[float, float]:
        """The base interval ``(t[k], t[n])``."""
        n = self._t.shape[0] - self.k - 1
        return float(self._t[self.k]), float(self._t[n])

    def __repr__(self) -> str:
        return f"BSpline(k={self.k}, n={len(self._t) - self.k - 1}, c.shape={self._c.shape})"

    def __call__(self, x: ArrayLike, nu: int = 0, extrapolate=None) -> np.ndarray:
        """The ``nu``-th derivative at ``x``: shape ``x.shape`` in place of the
        interpolation axis of ``c``. ``extrapolate`` defaults to ``self.extrapolate``."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        x = np.asarray(x)
        x_shape, x_ndim = x.shape, x.ndim
        x = np.ascontiguousarray(x.ravel(), dtype=np.float64)
        nu = operator.index(nu)
        # The binding takes an unsigned order.
        if nu < 0:
            raise _core.SplineError(f"Derivative order must be non-negative, got nu = {nu}.")
        tail = self._c.shape[1:]
        if prod(tail) == 0:
            out = np.zeros((x.size,) + tail, dtype=_float_dtype(self._c.dtype))
        else:
            columns, is_complex = self._columns()
            flat = columns.eval(x, nu, _mode(extrapolate))
            out = _from_columns(flat, x.size, tail, is_complex)
        out = out.reshape(x_shape + tail)
        if self.axis != 0:
            order = list(range(out.ndim))
            order = order[x_ndim : x_ndim + self.axis] + order[:x_ndim] + order[x_ndim + self.axis :]
            out = out.transpose(order)
        return out

    def _columns_result(self, core: "_core.Columns", is_complex: bool, extrapolate) -> "BSpline":
        """A ``BSpline`` from a library result with this spline's trailing shape."""
        t = core.knots()
        flat = core.coefficients()
        rows = flat.size // core.columns
        c = _from_columns(flat, rows, self._c.shape[1:], is_complex)
        return self.construct_fast(t, c, core.degree, extrapolate, self.axis)

    def derivative(self, nu: int = 1) -> "BSpline":
        """The derivative of order ``nu`` as a spline of degree ``k − nu`` (scipy's
        convention: knots ``t[nu:-nu]``, ``c`` padded with zeros to the knots' length)."""
        columns, is_complex = self._columns()
        return self._columns_result(columns.derivative(int(nu)), is_complex, self.extrapolate)

    def antiderivative(self, nu: int = 1) -> "BSpline":
        """The antiderivative of order ``nu`` (zero at ``t[k]``), degree ``k + nu``; a periodic
        spline's antiderivative does not extrapolate (``extrapolate=False``)."""
        columns, is_complex = self._columns()
        extrapolate = False if _mode(self.extrapolate) == "periodic" else self.extrapolate
        return self._columns_result(columns.antiderivative(int(nu)), is_complex, extrapolate)

    def integrate(self, a: float, b: float, extrapolate=None) -> np.ndarray:
        """The integral over ``[a, b]``: outside the base interval the end polynomials
        (``extrapolate=True``), zero (``False``) or the periodic continuation."""
        if extrapolate is None:
            extrapolate = self.extrapolate
        columns, is_complex = self._columns()
        flat = columns.integrate(float(a), float(b), _mode(extrapolate))
        return np.asarray(_from_columns(flat, 1, self._c.shape[1:], is_complex)[0])

    def insert_knot(self, x: float, m: int = 1) -> "BSpline":
        """The same spline with the knot ``x`` inserted ``m`` times (Boehm); a periodic spline
        (``extrapolate='periodic'``) keeps its periodic form."""
        x = float(x)
        # The binding takes an unsigned count (the library refuses x outside the base
        # interval and m = 0 in scipy's words).
        if m < 0:
            raise _core.SplineError(f"`m` must be positive, got {m = }.")
        columns, is_complex = self._columns()
        periodic = _mode(self.extrapolate) == "periodic"
        return self._columns_result(
            columns.insert_knot(x, int(m), periodic), is_complex, self.extrapolate
        )

    @classmethod
    def basis_element(cls, t: ArrayLike, extrapolate=True) -> "BSpline":
        """The B-spline basis element ``B(x | t[0], ..., t[k+1])``, ``k = len(t) − 2``."""
        core = _core.Columns.basis_element(_floats(t, "t"))
        return cls.construct_fast(core.knots(), core.coefficients(), core.degree, extrapolate)

    @classmethod
    def design_matrix(cls, x: ArrayLike, t: ArrayLike, k: int, extrapolate=False) -> scipy.sparse.csr_array:
        """The ``len(x) × (len(t) − k − 1)`` collocation matrix ``B_j(x_i)`` as a
        ``scipy.sparse.csr_array``; points outside the base interval raise unless
        ``extrapolate`` (``True`` or ``'periodic'``)."""
        x = _as_float_array(x, True)
        t = _as_float_array(t, True)
        if not (isinstance(extrapolate, str) and extrapolate == "periodic"):
            extrapolate = bool(extrapolate)
        # The binding takes an unsigned degree and a 1-D t (the library checks the order and
        # number of the knots and, without extrapolation, the bounds in scipy's words).
        if k < 0:
            raise _core.SplineError("Spline order cannot be negative.")
        if t.ndim != 1:
            raise _core.SplineError(f"Expect t to be a 1-D sorted array_like, but got t={t}.")
        data, indices, indptr, shape = _core.design_matrix(
            np.ascontiguousarray(x.ravel()), t, int(k), _mode(extrapolate)
        )
        int_dtype = np.int32 if len(data) < np.iinfo(np.int32).max else np.int64
        return scipy.sparse.csr_array(
            (data, np.asarray(indices, dtype=int_dtype), np.asarray(indptr, dtype=int_dtype)),
            shape=shape,
        )

    @classmethod
    def from_power_basis(cls, pp, bc_type: str = "not-a-knot") -> "BSpline":
        """A ``scipy.interpolate.CubicSpline`` in the B-spline basis (knots by ``bc_type``:
        ``'not-a-knot'``, ``'natural'``, ``'clamped'`` or ``'periodic'``)."""
        from scipy.interpolate import CubicSpline

        if not isinstance(pp, CubicSpline):
            raise NotImplementedError(
                f"Only CubicSpline objects are accepted for now. Got {type(pp)} instead."
            )
        if bc_type not in ("not-a-knot", "natural", "clamped", "periodic"):
            raise TypeError(f"Unknown boundary condition: {bc_type}")
        x = np.ascontiguousarray(pp.x, dtype=np.float64)
        coef = np.asarray(pp.c)
        order, pieces, tail = coef.shape[0], coef.shape[1], coef.shape[2:]
        cc, is_complex = _real_columns(coef.reshape(order * pieces, -1))
        core = _core.Columns.from_power_basis(x, cc.reshape(-1), order, cc.shape[1], bc_type)
        t = core.knots()
        flat = core.coefficients()
        c = _from_columns(flat, flat.size // core.columns, tail, is_complex)
        return cls.construct_fast(t, c, core.degree, pp.extrapolate, pp.axis)

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
        """The Jacobian of differentiation: ``derivative(nu).c[:m] == M @ c`` (``m`` the
        matrix's rows; the rest of scipy's padded ``c`` is zero)."""
        return _csr(self._s.derivative_map(int(nu)))

    def features(self, accuracy: Optional[float] = None) -> Features:
        """Inflections and curvature extrema of a planar curve, located exactly (root
        isolation of the curvature numerators) to ``accuracy`` in the parameter."""
        return Features(
            *self._s.features(None if accuracy is None else float(accuracy))
        )

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


def product(a: BSpline, b: BSpline) -> Tuple[BSpline, scipy.sparse.csr_array, scipy.sparse.csr_array]:
    """The product ``a(x) b(x)`` of two B-spline functions in its minimal B-spline space,
    with the Jacobians of its coefficients: ``J_a = ∂c/∂a.c``, ``J_b = ∂c/∂b.c``."""
    p, ja, jb = _core.product(a._s, b._s)
    return BSpline._wrap(p), _csr(ja), _csr(jb)

