"""NURBS curves and surfaces, and their constructions (circles, arcs, spheres, tori)."""

from __future__ import annotations

from typing import Optional, Sequence, Tuple

import numpy as np

from . import _core
from ._bspline import ArrayLike, Features, FloatArray, _floats


class NurbsCurve:
    """A NURBS curve in the plane or in space: knots ``t``, Cartesian control points ``c``
    of shape ``(n, 2)`` or ``(n, 3)``, positive weights ``w``, degree ``k``.

    >>> import numpy as np, spline
    >>> circle = spline.NurbsCurve.circle([0.0, 0.0], 2.0)
    >>> float(np.linalg.norm(circle(0.3)))
    2.0
    """

    __slots__ = ("_s",)

    def __init__(self, t: ArrayLike, c: ArrayLike, w: ArrayLike, k: int) -> None:
        pts = _floats(c, "c")
        if pts.ndim != 2:
            raise _core.SplineError(f"c: expected shape (n, 2) or (n, 3), got {pts.shape}")
        self._s = _core.NurbsCurveCore(
            int(k), _floats(t, "t"), pts.reshape(-1), _floats(w, "w"), pts.shape[1]
        )

    @classmethod
    def _wrap(cls, core: "_core.NurbsCurveCore") -> "NurbsCurve":
        obj = cls.__new__(cls)
        obj._s = core
        return obj

    @classmethod
    def circle(
        cls,
        center: Sequence[float],
        radius: float,
        normal: Optional[Sequence[float]] = None,
        triangle: bool = False,
    ) -> "NurbsCurve":
        """The full circle about ``center`` (2 or 3 coordinates; in space, in the plane
        normal to ``normal``, default z): 9 control points on a square (or 7 on a triangle),
        domain ``[0, 1]``."""
        n = None if normal is None else [float(v) for v in normal]
        return cls._wrap(
            _core.NurbsCurveCore.circle([float(v) for v in center], float(radius), n, triangle)
        )

    @classmethod
    def arc(
        cls,
        center: Sequence[float],
        radius: float,
        start: float,
        sweep: float,
        normal: Optional[Sequence[float]] = None,
    ) -> "NurbsCurve":
        """The arc from angle ``start`` sweeping ``sweep`` radians (negative: clockwise),
        rational quadratic pieces of at most 90°, domain ``[0, 1]``."""
        n = None if normal is None else [float(v) for v in normal]
        return cls._wrap(
            _core.NurbsCurveCore.arc(
                [float(v) for v in center], float(radius), float(start), float(sweep), n
            )
        )

    @property
    def t(self) -> FloatArray:
        """The knots."""
        return self._s.knots()

    @property
    def c(self) -> FloatArray:
        """The Cartesian control points, ``(n, d)``."""
        return self._s.control_points().reshape(-1, self._s.dim)

    @property
    def w(self) -> FloatArray:
        """The weights."""
        return self._s.weights()

    @property
    def k(self) -> int:
        """The degree."""
        return self._s.degree

    def __repr__(self) -> str:
        return f"NurbsCurve(k={self.k}, n={len(self.w)}, dim={self._s.dim})"

    def __call__(self, x: ArrayLike, nu: int = 0) -> FloatArray:
        """The ``nu``-th derivative at ``x``: shape ``x.shape + (d,)``."""
        xa = _floats(x, "x")
        if nu < 0:
            raise _core.SplineError(f"nu must be non-negative, got {nu}")
        return self._s.eval(xa.reshape(-1), int(nu)).reshape(xa.shape + (self._s.dim,))

    def insert_knot(self, x: float, m: int = 1) -> "NurbsCurve":
        """The same curve with the knot ``x`` inserted ``m`` times."""
        return NurbsCurve._wrap(self._s.insert_knot(float(x), int(m)))

    def elevate_degree(self, times: int = 1) -> "NurbsCurve":
        """The same curve with its degree raised by ``times`` (exact)."""
        return NurbsCurve._wrap(self._s.elevate_degree(int(times)))

    def features(self, accuracy: Optional[float] = None) -> Features:
        """Inflections and curvature extrema of a planar NURBS curve."""
        return Features(
            *self._s.features(None if accuracy is None else float(accuracy))
        )

    def to_json(self) -> str:
        """The curve in the exchange format."""
        return self._s.to_json()

    @classmethod
    def from_json(cls, text: str) -> "NurbsCurve":
        """A NURBS curve from exchange-format JSON (unit weights when it has none)."""
        return cls._wrap(_core.NurbsCurveCore.from_json(text))


class NurbsSurface:
    """A NURBS surface in space: knots ``(tu, tv)``, the net ``c`` of shape
    ``(n_u, n_v, 3)``, weights ``w`` of shape ``(n_u, n_v)``, degrees ``(p, q)``."""

    __slots__ = ("_s",)

    def __init__(
        self, t: Tuple[ArrayLike, ArrayLike], c: ArrayLike, w: ArrayLike, k: Tuple[int, int]
    ) -> None:
        net = _floats(c, "c")
        if net.ndim != 3 or net.shape[2] != 3:
            raise _core.SplineError(f"c: expected shape (n_u, n_v, 3), got {net.shape}")
        self._s = _core.NurbsSurfaceCore(
            (int(k[0]), int(k[1])),
            _floats(t[0], "tu"),
            _floats(t[1], "tv"),
            net.reshape(-1),
            _floats(w, "w").reshape(-1),
        )

    @classmethod
    def _wrap(cls, core: "_core.NurbsSurfaceCore") -> "NurbsSurface":
        obj = cls.__new__(cls)
        obj._s = core
        return obj

    @classmethod
    def sphere(cls, center: Sequence[float], radius: float) -> "NurbsSurface":
        """The sphere: a 5 × 9 net of degrees (2, 2), normals outwards."""
        return cls._wrap(_core.NurbsSurfaceCore.sphere(list(map(float, center)), float(radius)))

    @classmethod
    def torus(
        cls, center: Sequence[float], axis: Sequence[float], major: float, minor: float
    ) -> "NurbsSurface":
        """The torus about the axis through ``center`` along ``axis``, ``major > minor > 0``."""
        return cls._wrap(
            _core.NurbsSurfaceCore.torus(
                list(map(float, center)), list(map(float, axis)), float(major), float(minor)
            )
        )

    @property
    def t(self) -> Tuple[FloatArray, FloatArray]:
        """The knots in ``u`` and ``v``."""
        return self._s.knots()

    @property
    def k(self) -> Tuple[int, int]:
        """The degrees ``(p, q)``."""
        return self._s.degrees

    def __repr__(self) -> str:
        return f"NurbsSurface(k={self.k}, net={self._s.net_size})"

    def __call__(self, u: ArrayLike, v: ArrayLike) -> FloatArray:
        """The points at ``(u, v)`` (broadcast together): shape ``broadcast.shape + (3,)``."""
        ua, va = np.broadcast_arrays(_floats(u, "u"), _floats(v, "v"))
        out = self._s.eval(
            np.ascontiguousarray(ua).reshape(-1), np.ascontiguousarray(va).reshape(-1)
        )
        return out.reshape(ua.shape + (3,))

    def to_json(self) -> str:
        """The surface in the exchange format."""
        return self._s.to_json()

    @classmethod
    def from_json(cls, text: str) -> "NurbsSurface":
        """A NURBS surface from exchange-format JSON (unit weights when it has none)."""
        return cls._wrap(_core.NurbsSurfaceCore.from_json(text))
