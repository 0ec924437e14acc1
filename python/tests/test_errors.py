"""Bad input raises SplineError (a ValueError) with the library's one-line message."""

import numpy as np
import pytest

import spline

T = [0, 0, 0, 0, 0.5, 1, 1, 1, 1]
C = [0.0, 1.0, 2.0, 1.0, 0.0]


def raises(fragment, f, *args, **kw):
    with pytest.raises(spline.SplineError) as info:
        f(*args, **kw)
    message = str(info.value)
    assert fragment in message, message
    assert "\n" not in message
    assert isinstance(info.value, ValueError)
    return info.value


def test_constructor_errors():
    # scipy's checks and words (its tests match them), raised as SplineError.
    raises("inconsistent", spline.BSpline, T, C[:-1], 3)
    raises("non-decreasing", spline.BSpline, [0, 0, 0, 0, 0.7, 0.5, 1, 1, 1, 1], C + [1.0], 3)
    raises("nans or infs", spline.BSpline, [0, 0, 0, 0, 0.5, 1, 1, 1, np.inf], C, 3)
    raises("two internal knots", spline.BSpline, [0] * 9, C, 3)
    raises("at least 8 knots", spline.BSpline, T[:7], C[:3], 3)
    with pytest.raises(TypeError):
        spline.BSpline(T, C, 1.5)


def test_evaluation_errors():
    s = spline.BSpline(T, C, 3)
    # Outside the base interval: the end polynomials (scipy's default), NaN without
    # extrapolation; a NaN point gives NaN.
    x = np.array([-0.5, 1.5])
    left = np.polyval([s(0.0, 3) / 6, s(0.0, 2) / 2, s(0.0, 1), s(0.0)], -0.5)
    assert abs(s(-0.5) - left) < 1e-12
    assert np.isnan(s(x, extrapolate=False)).all()
    assert np.isnan(spline.BSpline(T, C, 3, extrapolate=False)(x)).all()
    assert np.isnan(s([0.2, np.nan])[1])
    raises("non-negative", s, 0.5, -1)
    raises("Cannot insert", s.insert_knot, 2.0)
    raises("positive", s.insert_knot, 0.5, 0)
    raises("planar", s.features)
    np.testing.assert_array_equal(s([0.1, 0.9], 4), [0.0, 0.0])


def test_fitting_errors():
    x = np.linspace(0, 1, 6)
    raises("", spline.make_interp_spline, x[::-1], x)
    raises("", spline.make_interp_spline, x[:3], x[:3], 3)
    raises("", spline.make_lsq_spline, x, x, [0, 0, 0, 0, 0.5, 0.6, 0.7, 0.8, 1, 1, 1, 1], 3)
    raises("parametrization", spline.fit_curve, np.c_[x, x], 4, 3, "bogus")
    pts = np.c_[np.cos(x), np.sin(x)]
    raises("control_points or max_deviation", spline.smooth, pts)
    raises("objective", spline.smooth, pts, 8, objective="bogus")
    raises("extrema", spline.smooth, pts, 8, extrema=["sideways"])
    raises("(m, 2)", spline.smooth, np.zeros((5, 3)), 8)


def test_io_errors(tmp_path):
    raises("cannot read", spline.read_airfoil, tmp_path / "missing.dat")
    bad = tmp_path / "bad.dat"
    bad.write_text("name\n1 2 3\nhello\n")
    raises(str(bad), spline.read_airfoil, bad)
    raises("not JSON", spline.read_json, "{")
    raises("exchange-format", spline.BSpline.from_json, '{"degree": 1}')
    raises("weights", spline.BSpline.from_json, spline.NurbsCurve.circle([0, 0], 1).to_json())
    raises("radius", spline.NurbsCurve.circle, [0, 0], -1.0)
    raises("center", spline.NurbsCurve.circle, [0.0], 1.0)
    raises("", spline.NurbsSurface.torus, [0, 0, 0], [0, 0, 1], 1.0, 2.0)
