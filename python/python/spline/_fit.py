"""Fitting with parameter correction, the eraser (``smooth``) and airfoil files."""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, field
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


#: The numbers of a ``summary.jsonl`` line, in the order of the library's record
#: (``spline.shape.SmoothSummary``); ``error`` and ``warnings`` follow them.
_SUMMARY_KEYS = ("control_points", "max_deviation", "max_deviation_to_data", "extrema")


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
    #: Sentences for the caller, empty when all is well (as ``spline smooth`` prints them).
    warnings: List[str] = field(default_factory=list)
    #: The fields of the line ``spline smooth DIR --out OUT`` writes for the result in
    #: ``summary.jsonl``, but its name, input and seconds.
    summary: Dict[str, Any] = field(default_factory=dict, repr=False)


def smooth(
    points: ArrayLike,
    control_points: Optional[int] = None,
    *,
    max_deviation: Optional[float] = None,
    degree: int = 3,
    curvature_extrema: Union[int, str, None] = None,
    extrema: Sequence[str] = (),
    objective: str = "max",
    thorough: bool = False,
    knot_search: bool = False,
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
      ``curvature_extrema="auto"``: the fewest (1, 2, …; closed 2, 4, …, up to 8) that bring
      every point within ``max_deviation`` (default 0.2 % of the diagonal of the points'
      bounding box), with ``control_points``;
    - ``objective``: ``"max"`` (largest deviation) or ``"least-squares"``;
    - ``thorough``: try every knot density; ``knot_exponents``: the exponents tried;
      ``knot_search``: then move the interior knots one at a time while the curve comes
      closer (open data; tens to hundreds of times slower);
    - ``closed``: the data are a closed contour; the result is periodic, returned as its
      wrapped container (the last ``degree`` control points repeat the first ones).
    """
    pts = _floats(points, "points")
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise _core.SplineError(f"points: expected shape (m, 2), got {pts.shape}")
    if curvature_extrema is None or isinstance(curvature_extrema, str):
        extrema_count = curvature_extrema
    else:
        extrema_count = str(int(curvature_extrema))
    curve, r = _core.smooth(
        pts.reshape(-1),
        None if control_points is None else int(control_points),
        None if max_deviation is None else float(max_deviation),
        int(degree),
        extrema_count,
        [str(e) for e in extrema],
        objective,
        bool(thorough),
        bool(knot_search),
        bool(closed),
        None if knot_exponents is None else [float(b) for b in knot_exponents],
    )
    (closed_, first, count, opened), mx, imx, to_data, rms, ext, infl = r[:7]
    refinements, conditions, start, newton, line = r[7:]
    summary = dict(zip(_SUMMARY_KEYS, line[:4]))
    summary["error"] = line[4]
    if line[5]:
        summary["warnings"] = list(line[5])
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
        warnings=list(line[5]),
        summary=summary,
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
    ``max_deviation_to_data``, ``extrema``, ``warnings`` (only when there are any),
    ``error`` (the message when it failed, the numbers then ``None``), ``seconds``.
    ``options`` are those of ``smooth``."""
    name = os.path.splitext(os.path.basename(os.fspath(path)))[0]
    started = time.perf_counter()
    try:
        points, _ = read_airfoil(path)
        line: Dict[str, Any] = {"name": name, **smooth(points, **options).summary}
    except _core.SplineError as e:
        line = {"name": name, **dict.fromkeys(_SUMMARY_KEYS), "error": str(e)}
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
