"""Fitting with parameter correction, the eraser (``smooth``) and airfoil files."""

from __future__ import annotations

import os
import time
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

from . import _core
from ._bspline import ArrayLike, BSpline, FloatArray, _floats


@dataclass(frozen=True)
class CurveFit:
    """A least-squares curve with corrected parameters (``fit_curve``)."""

    curve: BSpline
    params: FloatArray
    max_deviation: float
    rms: float
    sweeps: int
    converged: bool


def fit_curve(
    points: ArrayLike,
    control_points: int,
    k: int = 3,
    parametrization: str = "centripetal",
    iterations: int = 20,
    angle_tolerance: float = 1e-3,
) -> CurveFit:
    """Least squares of ``points`` (shape ``(m, d)``) by a curve of degree ``k`` with
    ``control_points`` control points, then parameter correction (seed 003): each point's
    parameter moves to its closest point until the residuals are normal to the curve within
    ``angle_tolerance`` radians, at most ``iterations`` sweeps.

    ``parametrization``: ``"uniform"``, ``"chordal"`` or ``"centripetal"``; the knots are
    The NURBS Book's averaging knots for those parameters.
    """
    pts = _floats(points, "points")
    if pts.ndim != 2:
        raise _core.SplineError(f"points: expected shape (m, d), got {pts.shape}")
    curve, params, mx, rms, sweeps, converged = _core.fit(
        pts.reshape(-1),
        pts.shape[1],
        int(control_points),
        int(k),
        parametrization,
        int(iterations),
        float(angle_tolerance),
    )
    return CurveFit(BSpline._wrap(curve), params, mx, rms, sweeps, converged)


@dataclass(frozen=True)
class CurvatureExtremum:
    """A curvature extremum of a smoothed curve."""

    u: float
    point: Tuple[float, float]
    kind: str


@dataclass(frozen=True)
class SmoothedCurve:
    """The result of ``smooth`` (the fields of ``spline smooth``'s JSON output)."""

    curve: BSpline
    closed: bool
    first_point: int
    control_points: int
    max_deviation: float
    max_deviation_index: int
    max_deviation_to_data: float
    rms: float
    extrema: List[CurvatureExtremum]
    inflections: List[float]
    refinements: int
    conditions: int
    least_squares_curvature_extrema: int
    newton_steps: int
    opened_control_points: int


def smooth(
    points: ArrayLike,
    control_points: Optional[int] = None,
    *,
    max_deviation: Optional[float] = None,
    degree: int = 3,
    curvature_extrema: Optional[int] = None,
    extrema: Sequence[str] = (),
    objective: str = "max",
    thorough: bool = False,
    closed: bool = False,
    knot_exponents: Optional[Sequence[float]] = None,
) -> SmoothedCurve:
    """The selective eraser of curvature extrema (thesis ch. 6), as ``spline smooth``: the
    closest planar B-spline curve to ``points`` (shape ``(m, 2)``) whose curvature has only
    the allowed extrema. The options are the command's flags:

    - ``control_points`` or ``max_deviation`` (the fewest control points within it);
    - ``degree`` (at least 3);
    - ``curvature_extrema`` (alternating max, min, …) or ``extrema``: ``"max"``, ``"min"``,
      ``"max@U"``, ``"min@U"`` in the order of the data (default: one maximum);
    - ``objective``: ``"max"`` (largest deviation) or ``"least-squares"``;
    - ``thorough``: try every knot density; ``knot_exponents``: the exponents tried;
    - ``closed``: the data are a closed contour; the result is periodic, returned as its
      wrapped container (the last ``degree`` control points repeat the first ones).
    """
    pts = _floats(points, "points")
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise _core.SplineError(f"points: expected shape (m, 2), got {pts.shape}")
    curve, r = _core.smooth(
        pts.reshape(-1),
        None if control_points is None else int(control_points),
        None if max_deviation is None else float(max_deviation),
        int(degree),
        None if curvature_extrema is None else int(curvature_extrema),
        [str(e) for e in extrema],
        objective,
        bool(thorough),
        bool(closed),
        None if knot_exponents is None else [float(b) for b in knot_exponents],
    )
    (closed_, first, count, opened), mx, imx, to_data, rms, ext, infl = r[:7]
    refinements, conditions, start, newton = r[7:]
    return SmoothedCurve(
        curve=BSpline._wrap(curve),
        closed=closed_,
        first_point=first,
        control_points=count,
        max_deviation=mx,
        max_deviation_index=imx,
        max_deviation_to_data=to_data,
        rms=rms,
        extrema=[CurvatureExtremum(u, (x, y), kind) for (u, x, y, kind) in ext],
        inflections=list(infl),
        refinements=refinements,
        conditions=conditions,
        least_squares_curvature_extrema=start,
        newton_steps=newton,
        opened_control_points=opened,
    )


def read_airfoil(source: Union[str, os.PathLike]) -> Tuple[FloatArray, Optional[str]]:
    """The points of an airfoil coordinate file (Selig or Lednicer, as the UIUC database
    writes them) in Selig order, shape ``(m, 2)``, and its name line."""
    path = os.fspath(source)
    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
    except OSError as e:
        raise _core.SplineError(f"cannot read {path}: {e.strerror}") from None
    try:
        flat, name = _core.parse_airfoil_text(text)
    except _core.SplineError as e:
        raise _core.SplineError(f"{path}: {e}") from None
    return flat.reshape(-1, 2), name


def smooth_file(path: Union[str, os.PathLike], **options: Any) -> Dict[str, Any]:
    """Smooths one airfoil file and returns the line ``spline smooth DIR --out OUT`` writes
    for it in ``summary.jsonl``: ``name``, ``control_points``, ``max_deviation``,
    ``max_deviation_to_data``, ``extrema``, ``seconds``, ``error`` (the message when it
    failed, the other fields then ``None``). ``options`` are those of ``smooth``."""
    name = os.path.splitext(os.path.basename(os.fspath(path)))[0]
    started = time.perf_counter()
    try:
        points, _ = read_airfoil(path)
        r = smooth(points, **options)
        line: Dict[str, Any] = {
            "name": name,
            "control_points": r.opened_control_points,
            "max_deviation": r.max_deviation,
            "max_deviation_to_data": r.max_deviation_to_data,
            "extrema": len(r.extrema),
            "error": None,
        }
    except _core.SplineError as e:
        line = {
            "name": name,
            "control_points": None,
            "max_deviation": None,
            "max_deviation_to_data": None,
            "extrema": None,
            "error": str(e),
        }
    line["seconds"] = time.perf_counter() - started
    return line


__all__ = [
    "CurveFit",
    "CurvatureExtremum",
    "SmoothedCurve",
    "fit_curve",
    "smooth",
    "read_airfoil",
    "smooth_file",
]
