"""NURBS constructions against closed forms, the exchange format round trip, features
against dense sampling, parameter correction and the eraser on an airfoil."""

import json
import pathlib

import numpy as np
import scipy.interpolate as si

import spline

AIRFOILS = pathlib.Path(__file__).resolve().parents[2] / "data" / "airfoils"


def test_circle_and_arc():
    for triangle in (False, True):
        c = spline.NurbsCurve.circle([1.0, -2.0], 3.0, triangle=triangle)
        u = np.linspace(0, 1, 101)
        np.testing.assert_allclose(np.linalg.norm(c(u) - [1, -2], axis=1), 3.0, atol=1e-14)
        # The tangent is normal to the radius.
        d = c(u, 1)
        np.testing.assert_allclose(np.sum(d * (c(u) - [1, -2]), axis=1), 0.0, atol=1e-12)
    a = spline.NurbsCurve.arc([0, 0, 1], 2.0, 0.0, np.pi / 3, normal=[0, 0, 1])
    p = a(np.linspace(0, 1, 11))
    np.testing.assert_allclose(np.linalg.norm(p - [0, 0, 1], axis=1), 2.0, atol=1e-14)
    np.testing.assert_allclose(p[-1], [1.0, np.sqrt(3.0), 1.0], atol=1e-14)
    # Insertion and elevation keep the curve.
    u = np.linspace(0, 1, 33)
    np.testing.assert_allclose(a.insert_knot(0.3, 2)(u), a(u), atol=1e-14)
    np.testing.assert_allclose(a.elevate_degree(1)(u), a(u), atol=1e-14)


def test_sphere_and_torus():
    rng = np.random.default_rng(1)
    u, v = rng.uniform(0, 1, 200), rng.uniform(0, 1, 200)
    s = spline.NurbsSurface.sphere([1, 2, 3], 2.0)
    np.testing.assert_allclose(np.linalg.norm(s(u, v) - [1, 2, 3], axis=1), 2.0, atol=1e-13)
    t = spline.NurbsSurface.torus([0, 0, 0], [0, 0, 1], 3.0, 1.0)
    p = t(u, v)
    ring = np.hypot(p[:, 0], p[:, 1]) - 3.0
    np.testing.assert_allclose(np.hypot(ring, p[:, 2]), 1.0, atol=1e-13)
    assert s(u.reshape(20, 10), 0.5).shape == (20, 10, 3)


def test_exchange_format_round_trip():
    rng = np.random.default_rng(2)
    t = [0, 0, 0, 0, 0.3, 0.6, 1, 1, 1, 1]
    for c in (rng.normal(size=6), rng.normal(size=(6, 3))):
        s = spline.BSpline(t, c, 3)
        back = spline.read_json(s.to_json())
        assert isinstance(back, spline.BSpline)
        np.testing.assert_array_equal(back.c, s.c)
        np.testing.assert_array_equal(back.t, s.t)
        assert json.loads(s.to_json())["degree"] == 3
    circle = spline.NurbsCurve.circle([0, 0], 1.0)
    back = spline.read_json(circle.to_json())
    assert isinstance(back, spline.NurbsCurve)
    np.testing.assert_array_equal(back.w, circle.w)
    sphere = spline.NurbsSurface.sphere([0, 0, 0], 1.0)
    again = spline.read_json(sphere.to_json())
    assert isinstance(again, spline.NurbsSurface)
    np.testing.assert_array_equal(again(0.3, 0.7), sphere(0.3, 0.7))


def sampled_turning_points(values):
    d = np.diff(values)
    return np.nonzero(d[:-1] * d[1:] < 0)[0] + 1


def test_features_against_dense_sampling():
    rng = np.random.default_rng(3)
    for _ in range(10):
        t = np.r_[[0.0] * 4, np.sort(rng.uniform(0.1, 0.9, 4)), [1.0] * 4]
        c = np.c_[np.linspace(0, 1, 8), 0.3 * rng.normal(size=8)]
        s = spline.BSpline(t, c, 3)
        f = s.features()
        u = np.linspace(0, 1, 200_001)
        kappa = s.curvature(u)
        # Every sign change of the curvature is an inflection found within the sampling step.
        changes = u[np.nonzero(np.sign(kappa[:-1]) != np.sign(kappa[1:]))[0]]
        assert len(changes) == len(f.inflections)
        np.testing.assert_allclose(f.inflections, changes, atol=1e-5)
        turning = u[sampled_turning_points(kappa)]
        assert len(turning) == len(f.curvature_extrema)
        np.testing.assert_allclose(f.curvature_extrema, turning, atol=1e-4)


def test_fit_curve_with_parameter_correction():
    theta = np.linspace(0, np.pi, 40)
    pts = np.c_[np.cos(theta), np.sin(theta)]
    fit = spline.fit_curve(pts, 8, 3, iterations=30)
    uncorrected = spline.fit_curve(pts, 8, 3, iterations=0)
    # Correction lowers the sum of squares (the residuals become normal to the curve).
    assert fit.rms < 0.95 * uncorrected.rms
    assert fit.max_deviation < 1e-3 and uncorrected.sweeps == 0
    on_curve = fit.curve(fit.params)
    np.testing.assert_allclose(
        np.linalg.norm(on_curve - pts, axis=1).max(), fit.max_deviation, rtol=1e-12
    )


def test_smooth_airfoil():
    pts, _ = spline.read_airfoil(AIRFOILS / "clarkv.dat")
    assert pts.shape == (33, 2)
    r = spline.smooth(pts, 20)
    assert r.control_points == 20
    assert [e.kind for e in r.extrema] == ["maximum"]
    # One turning point of the curvature, by dense sampling (the eraser's promise).
    u = np.linspace(0, 1, 100_001)
    kappa = r.curve.curvature(u)
    assert len(sampled_turning_points(kappa)) == 1
    assert 0 < r.max_deviation < 1e-3
    line = spline.smooth_file(AIRFOILS / "clarkv.dat", control_points=20)
    assert line["error"] is None and line["max_deviation"] == r.max_deviation


def test_interpolation_reproduces_cubics():
    x = np.linspace(-1, 2, 9)
    s = spline.make_interp_spline(x, x**3 - x)
    xx = np.linspace(-1, 2, 50)
    np.testing.assert_allclose(s(xx), xx**3 - xx, atol=1e-12)
    np.testing.assert_allclose(s(xx, 1), 3 * xx**2 - 1, atol=1e-11)
    assert isinstance(si.BSpline(s.t, s.c, s.k), si.BSpline)


def test_smooth_closed_contour():
    # An ellipse 2 × 1 with a deterministic jitter: four vertices round the closed curve.
    k = np.arange(80)
    t = 0.3 + 2 * np.pi * k / 80
    noise = 1e-3 * (((k * 7919) % 13) / 6.0 - 1.0)
    pts = np.c_[2 * np.cos(t) + noise, np.sin(t) - noise]
    r = spline.smooth(pts, 16, closed=True, extrema=["min", "max", "min", "max"])
    assert r.closed and r.control_points == 16
    assert sorted(e.kind for e in r.extrema) == ["maximum", "maximum", "minimum", "minimum"]
    assert r.max_deviation < 6e-3
    # The wrapped container closes: it starts and ends at the same point with the same tangent.
    lo, hi = r.curve.domain
    np.testing.assert_allclose(r.curve(lo), r.curve(hi), atol=1e-12)
    np.testing.assert_allclose(r.curve(lo, 1), r.curve(hi, 1), rtol=1e-9, atol=1e-9)


def test_smooth_auto_extrema_as_the_tool():
    # The fewest curvature extrema within the default tolerance: two on this plate (as
    # `spline smooth --curvature-extrema auto`), with the warning-free answer and its summary.
    pts, _ = spline.read_airfoil(AIRFOILS / "plates" / "goe417a.dat")
    r = spline.smooth(pts, 20, curvature_extrema="auto")
    assert len(r.extrema) == 2 and r.max_deviation < 2e-3
    assert not r.warnings
    assert r.summary["control_points"] == 20 and r.summary["error"] is None
    # One maximum only: the plate's camber line turns, the tool warns and so does Python.
    one = spline.smooth(pts, 20)
    assert one.warnings and one.max_deviation > 8e-3
    try:
        spline.smooth(pts, 20, curvature_extrema="many")
    except spline.SplineError as e:
        assert "auto" in str(e)
    else:
        raise AssertionError("an unknown count was accepted")
