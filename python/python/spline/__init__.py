"""``spline``: B-splines, NURBS and spline algebra with Jacobians, from Rust.

numpy arrays in, numpy arrays out; every loop over points runs in the compiled library with
the GIL released; errors are ``SplineError`` (a ``ValueError``) carrying the library's message.

Where scipy has the same thing, the same names: ``BSpline(t, c, k)``, ``s(x, nu)``,
``s.derivative()``, ``s.insert_knot(x, m)``, ``make_interp_spline``, ``make_lsq_spline``.
Beyond: NURBS curves and surfaces with their constructions, fitting with parameter
correction (``fit_curve``), the eraser of curvature extrema (``smooth``), inflections and
curvature extrema (``features``), products and structural operations with their Jacobians as
``scipy.sparse`` arrays, and the JSON exchange format (``to_json``, ``read_json``).

>>> import numpy as np, spline
>>> x = np.linspace(0, 1, 11)
>>> s = spline.make_interp_spline(x, np.sin(x))
>>> bool(abs(s(0.55) - np.sin(0.55)) < 1e-6)
True
"""

from ._core import SplineError
from ._bspline import BSpline, Features, product
from ._make import make_interp_spline, make_lsq_spline, make_smoothing_spline
from ._exchange import read_json
from ._nd import NdBSpline, make_ndbspl
from ._splrep import generate_knots, make_splprep, make_splrep
from ._nurbs import NurbsCurve, NurbsSurface
from ._cad import CadItem, read_iges, read_step, write_iges, write_step
from ._fit import (
    CurvatureExtremum,
    CurveFit,
    SmoothedCurve,
    fit_curve,
    read_airfoil,
    smooth,
    smooth_file,
)

__all__ = [
    "SplineError",
    "BSpline",
    "Features",
    "make_interp_spline",
    "make_lsq_spline",
    "make_smoothing_spline",
    "product",
    "read_json",
    "NdBSpline",
    "make_ndbspl",
    "generate_knots",
    "make_splrep",
    "make_splprep",
    "NurbsCurve",
    "NurbsSurface",
    "CadItem",
    "read_step",
    "write_step",
    "read_iges",
    "write_iges",
    "CurvatureExtremum",
    "CurveFit",
    "SmoothedCurve",
    "fit_curve",
    "read_airfoil",
    "smooth",
    "smooth_file",
]
