"""Tensor-product splines in any number of dimensions, as ``scipy.interpolate.NdBSpline``
and ``make_ndbspl``: the numerics run in the library (``NdSpline``); this module validates
the arguments with scipy's words and reshapes."""

from __future__ import annotations

import operator
from math import prod

import numpy as np
import scipy.sparse

from . import _core
from ._bspline import _float_dtype, _from_columns, _real_columns


def _preprocess(k, t_tpl):
    """scipy's checks of the degrees and knot vectors: ``(k as a list, t as float arrays)``.
    scipy raises at construction; the library's NdSpline is built at each call, so its
    checks of the knots are repeated here in scipy's words."""
    if not isinstance(t_tpl, tuple):
        raise _core.SplineError(f"Expect `t` to be a tuple of array-likes. Got {t_tpl} instead.")
    ndim = len(t_tpl)
    try:
        len(k)
    except TypeError:
        k = (k,) * ndim
    k = [operator.index(ki) for ki in k]
    if len(k) != ndim:
        raise _core.SplineError(f"len(t) = {len(t_tpl)} != {len(k) = }.")
    ts = []
    for d in range(ndim):
        td = np.asarray(t_tpl[d], dtype=float)
        kd = k[d]
        n = td.shape[0] - kd - 1
        if kd < 0:
            raise _core.SplineError(f"Spline degree in dimension {d} cannot be negative.")
        if td.ndim != 1:
            raise _core.SplineError(f"Knot vector in dimension {d} must be one-dimensional.")
        if n < kd + 1:
            raise _core.SplineError(
                f"Need at least {2 * kd + 2} knots for degree {kd} in dimension {d}."
            )
        if (np.diff(td) < 0).any():
            raise _core.SplineError(f"Knots in dimension {d} must be in a non-decreasing order.")
        if len(np.unique(td[kd : n + 1])) < 2:
            raise _core.SplineError(f"Need at least two internal knots in dimension {d}.")
        if not np.isfinite(td).all():
            raise _core.SplineError(f"Knots in dimension {d} should not have nans or infs.")
        ts.append(np.ascontiguousarray(td))
    return k, ts


class NdBSpline:
    r"""A tensor-product spline in ``N`` dimensions (scipy's ``NdBSpline``):

    .. math:: s(x) = \sum c_{i_1 \dots i_N} B(x_1; i_1, t_1) \cdots B(x_N; i_N, t_N)

    ``t`` a tuple of knot vectors, ``c`` of shape ``(n_1, …, n_N, …)`` (trailing dimensions
    are value columns, complex values two real ones), ``k`` an int or one per dimension.
    """

    def __init__(self, t, c, k, *, extrapolate=None):
        self._k, self._t = _preprocess(k, t)
        self.extrapolate = True if extrapolate is None else bool(extrapolate)
        self._c = np.asarray(c)
        ndim = len(self._t)
        # scipy raises at construction (the library's NdSpline is built at each call).
        if self._c.ndim < ndim:
            raise _core.SplineError(f"Coefficients must be at least {ndim}-dimensional.")
        for d in range(ndim):
            td, kd = self._t[d], self._k[d]
            n = td.shape[0] - kd - 1
            if self._c.shape[d] != n:
                raise _core.SplineError(
                    f"Knots, coefficients and degree in dimension {d} are inconsistent:"
                    f" got {self._c.shape[d]} coefficients for {len(td)} knots,"
                    f" need at least {n} for k={k}."
                )
        self._c = np.ascontiguousarray(self._c, dtype=_float_dtype(self._c.dtype))

    @property
    def k(self):
        """The degrees, one per dimension."""
        return tuple(self._k)

    @property
    def t(self):
        """The knot vectors."""
        return tuple(self._t)

    @property
    def c(self):
        """The coefficients."""
        return self._c

    def _core(self):
        ndim = len(self._t)
        tail = self._c.shape[ndim:]
        cc, is_complex = _real_columns(self._c.reshape(prod(self._c.shape[:ndim]), *tail))
        core = _core.NdColumns(
            [list(map(float, t)) for t in self._t], cc.reshape(-1), list(self._k),
            cc.shape[1], self.extrapolate,
        )
        return core, is_complex, tail

    def __call__(self, xi, *, nu=None, extrapolate=None):
        """The values (or partial derivatives of orders ``nu``) at the points ``xi`` of shape
        ``(..., ndim)``: shape ``xi.shape[:-1] + c.shape[ndim:]``."""
        ndim = len(self._t)
        if extrapolate is None:
            extrapolate = self.extrapolate
        extrapolate = bool(extrapolate)
        if nu is None:
            nu = np.zeros((ndim,), dtype=np.int64)
        else:
            nu = np.asarray(nu, dtype=np.int64)
            # scipy's words (the library accepts an empty nu and words the count otherwise);
            # the binding takes unsigned orders.
            if nu.ndim != 1 or nu.shape[0] != ndim:
                raise _core.SplineError(
                    f"invalid number of derivative orders {nu = } for ndim = {len(self.t)}."
                )
            if any(nu < 0):
                raise _core.SplineError(f"derivatives must be positive, got {nu = }")
        xi = np.asarray(xi, dtype=float)
        xi_shape = xi.shape
        xi = np.ascontiguousarray(xi.reshape(-1, xi_shape[-1]))
        # numpy shapes: the library sees the coordinates flat.
        if xi_shape[-1] != ndim:
            raise _core.SplineError(f"Shapes: xi.shape={xi_shape} and ndim={ndim}")
        core, is_complex, tail = self._core()
        flat = core.eval(xi.reshape(-1), [int(v) for v in nu], extrapolate)
        out = _from_columns(flat, xi.shape[0], tail, is_complex)
        return out.reshape(xi_shape[:-1] + tail)

    @classmethod
    def design_matrix(cls, xvals, t, k, extrapolate=True):
        """The tensor-product collocation matrix at the points ``xvals`` (shape
        ``(npts, ndim)``) as a ``scipy.sparse.csr_array``."""
        xvals = np.asarray(xvals, dtype=float)
        # numpy shapes: the library sees the coordinates flat.
        if xvals.ndim != 2:
            raise _core.SplineError(f"Expect xvals of shape (npts, ndim), got {xvals.shape}.")
        ndim = xvals.shape[-1]
        if len(t) != ndim:
            raise _core.SplineError(
                f"Data and knots are inconsistent: len(t) = {len(t)} for  {ndim = }."
            )
        k, ts = _preprocess(k, t)
        data, indices, indptr, shape = _core.nd_design_matrix(
            np.ascontiguousarray(xvals.reshape(-1)), [list(map(float, td)) for td in ts],
            k, bool(extrapolate),
        )
        return scipy.sparse.csr_array(
            (data, np.asarray(indices, dtype=np.int64), np.asarray(indptr, dtype=np.int64)),
            shape=shape,
        )

    def derivative(self, nu):
        """The partial derivative of orders ``nu`` (one per dimension) as an ``NdBSpline``."""
        nu_arr = np.asarray(nu, dtype=np.int64)
        ndim = len(self.t)
        # As in __call__: scipy's words; the binding takes unsigned orders.
        if nu_arr.ndim != 1 or nu_arr.shape[0] != ndim:
            raise _core.SplineError(
                f"invalid number of derivative orders {nu = } for ndim = {len(self.t)}."
            )
        if any(nu_arr < 0):
            raise _core.SplineError(f"derivative orders must be positive, got {nu = }")
        core, is_complex, tail = self._core()
        d = core.derivative([int(v) for v in nu_arr])
        t = tuple(np.asarray(tt) for tt in d.knots())
        k = tuple(d.degrees())
        shape = tuple(len(tt) - kk - 1 for tt, kk in zip(t, k))
        flat = d.coefficients()
        c = _from_columns(flat, prod(shape), tail, is_complex).reshape(shape + tail)
        return NdBSpline(t, c, k, extrapolate=self.extrapolate)


def _solve_with(solver, matrix, rhs, solver_args):
    """scipy's way of solving the collocation system with a given solver: ``spsolve``
    directly, an iterative solver column by column, its ``info`` checked."""
    import scipy.sparse.linalg as ssl

    if solver is ssl.spsolve:
        return solver(matrix, rhs, **solver_args)
    solver_args.setdefault("atol", 1e-6)
    out = np.empty_like(rhs)
    for j in range(rhs.shape[1]):
        out[:, j], info = solver(matrix, rhs[:, j], **solver_args)
        if info != 0:
            raise _core.SplineError(f"{solver = } returns {info = } for column {j}.")
    return out


def make_ndbspl(points, values, k=3, *, solver=None, **solver_args):
    """The tensor-product interpolant of ``values`` on the grid ``points`` (scipy's
    ``make_ndbspl``, not-a-knot in every dimension).

    Without ``solver`` and solver arguments the library solves the Kronecker-structured
    system dimension by dimension (exact, and much faster than scipy's default iterative
    solver). With a ``solver`` (a ``scipy.sparse.linalg`` function) or solver arguments
    (``maxiter=…``: scipy's default ``gcrotmk`` then), the sparse collocation matrix is solved
    by that solver as scipy does, with its failure to converge raised as a ``ValueError``."""
    ndim = len(points)
    xi_shape = tuple(len(x) for x in points)
    try:
        len(k)
    except TypeError:
        k = (k,) * ndim
    values = np.asarray(values)
    tail = values.shape[ndim:]
    cc, is_complex = _real_columns(values.reshape(prod(xi_shape), *tail))
    core = _core.make_ndbspl_columns(
        [list(map(float, p)) for p in points], cc.reshape(-1), [int(v) for v in k], cc.shape[1]
    )
    t = tuple(np.asarray(tt) for tt in core.knots())
    kk = tuple(core.degrees())
    shape = tuple(len(tt) - kd - 1 for tt, kd in zip(t, kk))
    if solver is not None or solver_args:
        import itertools

        import scipy.sparse.linalg as ssl

        xvals = np.asarray(list(itertools.product(*points)), dtype=float)
        matrix = NdBSpline.design_matrix(xvals, t, kk)
        flat = _solve_with(solver or ssl.gcrotmk, matrix, cc, dict(solver_args))
        c = _from_columns(flat.reshape(-1), prod(shape), tail, is_complex).reshape(shape + tail)
        return NdBSpline(t, c, kk)
    c = _from_columns(core.coefficients(), prod(shape), tail, is_complex).reshape(shape + tail)
    return NdBSpline(t, c, kk)
