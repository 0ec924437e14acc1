"""STEP and IGES files from Python: what is written reads back as the same geometry, names
travel, bad files and bad objects raise SplineError with one line."""

import numpy as np
import pytest

import spline


def objects():
    circle = spline.NurbsCurve.circle([0.5, -1.0], 2.0)
    torus = spline.NurbsSurface.torus([0.0, 0.0, 1.0], [0.0, 0.3, 1.0], 3.0, 0.7)
    rng = np.random.default_rng(7)
    t = np.r_[[0.0] * 4, 0.3, 0.3, 0.7, [1.0] * 4]
    space = spline.BSpline(t, rng.normal(size=(7, 3)), 3)
    return [circle, torus, space], ["circle", "a torus", "space curve"]


@pytest.mark.parametrize("suffix", [".step", ".igs"])
def test_round_trip(tmp_path, suffix):
    objs, names = objects()
    path = tmp_path / f"model{suffix}"
    write = spline.write_step if suffix == ".step" else spline.write_iges
    read = spline.read_step if suffix == ".step" else spline.read_iges
    write(path, objs, names)
    items = read(path)
    assert len(items) == 3
    by_kind = {type(i.geometry).__name__: i for i in items}
    circle, torus, space = objs
    u = np.linspace(0.0, 1.0, 17)
    # The planar circle comes back in the plane z = 0.
    c = by_kind["NurbsCurve"].geometry
    assert np.allclose(c(u)[:, :2], circle(u), rtol=0, atol=1e-14) and np.all(c(u)[:, 2] == 0)
    s = by_kind["NurbsSurface"].geometry
    uu, vv = np.meshgrid(u, u)
    assert np.allclose(s(uu, vv), torus(uu, vv), rtol=0, atol=1e-13)
    b = by_kind["BSpline"].geometry
    assert np.allclose(b(u), space(u), rtol=0, atol=1e-14)
    if suffix == ".step":
        assert {i.name for i in items} == set(names)
    else:
        # IGES labels hold 8 characters; longer names travel in a name property.
        assert {i.name for i in items} == set(names)


def test_errors(tmp_path):
    bad = tmp_path / "bad.step"
    bad.write_text("ISO-10303-21;\nHEADER;\nENDSEC;\nDATA;\n#1 = CARTESIAN_POINT('',(0.,0.);\nENDSEC;\nEND-ISO-10303-21;\n")
    with pytest.raises(spline.SplineError, match="STEP line 5") as e:
        spline.read_step(bad)
    assert "\n" not in str(e.value)
    with pytest.raises(spline.SplineError, match="expected a file ending"):
        spline.read_step(tmp_path / "model.igs")
    with pytest.raises(spline.SplineError, match="not a curve or surface"):
        spline.write_iges(tmp_path / "x.igs", [42])
    with pytest.raises(spline.SplineError, match="names for"):
        spline.write_step(tmp_path / "x.step", objects()[0], ["one"])
    with pytest.raises(spline.SplineError):
        spline.read_iges(tmp_path / "missing.igs")
