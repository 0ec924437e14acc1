"""The exchange format (JSON) read into the package's classes: the library says which record
a text holds, the class of that kind reads it."""

from __future__ import annotations

from . import _core
from ._bspline import BSpline
from ._nurbs import NurbsCurve, NurbsSurface


def read_json(text: str):
    """A curve or surface from exchange-format JSON: ``BSpline``, ``NurbsCurve`` (with
    ``"weights"``) or ``NurbsSurface`` (two degrees); the library reads the record."""
    kind = _core.exchange_kind(text)
    if kind == "surface":
        return NurbsSurface.from_json(text)
    if kind == "nurbs":
        return NurbsCurve.from_json(text)
    return BSpline.from_json(text)
