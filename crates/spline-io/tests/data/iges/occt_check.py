"""Reads the file our writer produced (`IGES_OUT=dir cargo test -p spline-io --test integration
write_files_for_occt -- --ignored`) with Open CASCADE and compares poles, knots and weights
with the values the test wrote next to it (ours.json).

    target/python-venv/bin/python crates/spline-io/tests/data/iges/occt_check.py dir
"""
import json, sys
from OCP.IGESControl import IGESControl_Reader
from OCP.TopExp import TopExp_Explorer
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE, TopAbs_WIRE
from OCP.TopoDS import TopoDS
from OCP.BRep import BRep_Tool

d = sys.argv[1]
want = json.load(open(f"{d}/ours.json"))
r = IGESControl_Reader()
r.ReadFile(f"{d}/ours.igs")
r.TransferRoots()
shape = r.OneShape()
worst = 0.0

def close(a, b, what):
    global worst
    assert len(a) == len(b), (what, len(a), len(b))
    for x, y in zip(a, b):
        if isinstance(x, list):
            close(x, y, what)
        else:
            worst = max(worst, abs(x - y) / max(1.0, abs(y)))
            assert abs(x - y) <= 1e-12 * max(1.0, abs(y)), (what, x, y)

roots = [r.Shape(k) for k in range(1, r.NbShapes() + 1)]

def joined(shape):
    """OCCT splits a curve at its C0 knots into the edges of a wire: join them back (the
    knot of the junction with multiplicity p, the shared pole once)."""
    knots, poles, weights = [], [], []
    ex = TopExp_Explorer(shape, TopAbs_EDGE)
    while ex.More():
        c = BRep_Tool.Curve_s(TopoDS.Edge(ex.Current()), 0.0, 0.0)
        assert c.DynamicType().Name() == "Geom_BSplineCurve"
        p = c.Degree()
        k = [c.Knot(i) for i in range(1, c.NbKnots() + 1) for _ in range(c.Multiplicity(i))]
        ps = [[c.Pole(i).X(), c.Pole(i).Y(), c.Pole(i).Z()] for i in range(1, c.NbPoles() + 1)]
        ws = [c.Weight(i) for i in range(1, c.NbPoles() + 1)]
        if knots:
            knots = knots[: -(p + 1)] + [k[0]] * p + k[p + 1 :]
            poles += ps[1:]
            weights += ws[1:]
        else:
            knots, poles, weights = k, ps, ws
        ex.Next()
    return knots, poles, weights

curves = [joined(x) for x in roots if x.ShapeType() in (TopAbs_EDGE, TopAbs_WIRE)]
assert len(curves) == 3, len(curves)
for (k, p, w), (knots, poles, weights) in zip(curves, want["curves"]):
    close(k, knots, "knots")
    close(p, poles, "poles")
    if weights is not None:
        close(w, weights, "weights")
faces = []
for x in roots:
    ex = TopExp_Explorer(x, TopAbs_FACE)
    while ex.More():
        faces.append(BRep_Tool.Surface_s(TopoDS.Face(ex.Current())))
        ex.Next()
assert len(faces) == 2, len(faces)
for s, (ku, kv, (nu, nv), poles, weights) in zip(faces, want["surfaces"]):
    assert s.DynamicType().Name() == "Geom_BSplineSurface"
    assert (s.NbUPoles(), s.NbVPoles()) == (nu, nv)
    close([s.UKnot(i) for i in range(1, s.NbUKnots() + 1) for _ in range(s.UMultiplicity(i))], ku, "u knots")
    close([s.VKnot(i) for i in range(1, s.NbVKnots() + 1) for _ in range(s.VMultiplicity(i))], kv, "v knots")
    occt = [[s.Pole(i + 1, j + 1).X(), s.Pole(i + 1, j + 1).Y(), s.Pole(i + 1, j + 1).Z()] for i in range(nu) for j in range(nv)]
    close(occt, poles, "poles (row-major, i along u)")
    if weights is not None:
        close([s.Weight(i + 1, j + 1) for i in range(nu) for j in range(nv)], weights, "weights")
print("OK: 3 curves and 2 surfaces agree with Open CASCADE, largest relative difference", worst)
