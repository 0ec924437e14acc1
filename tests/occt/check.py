"""Open CASCADE's second opinion on the tool's STEP and IGES files (`cargo xtask occt`, part
of `cargo xtask test`). See README.md beside this file.

    python check.py SPLINE_BINARY WORK_DIR [--cases N] [--seed S]

Prints one row per check (cases, agreed, largest relative error) and exits 1 on any
disagreement.
"""

import argparse
import json
import math
import os
import re
import resource
import subprocess
import sys
import time

import numpy as np
from OCP.BRep import BRep_Tool
from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge, BRepBuilderAPI_MakeFace
from OCP.BRepFilletAPI import BRepFilletAPI_MakeFillet
from OCP.BRepPrimAPI import (BRepPrimAPI_MakeBox, BRepPrimAPI_MakeCone,
                             BRepPrimAPI_MakeCylinder, BRepPrimAPI_MakeRevol,
                             BRepPrimAPI_MakeSphere, BRepPrimAPI_MakeTorus)
from OCP.Geom import Geom_BSplineCurve, Geom_BSplineSurface
from OCP.gp import gp_Ax1, gp_Dir, gp_Pnt, gp_Vec
from OCP.IFSelect import IFSelect_RetDone
from OCP.IGESControl import IGESControl_Reader, IGESControl_Writer
from OCP.Interface import Interface_Static
from OCP.OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int, Array2_double, Array2_gp_Pnt
from OCP.STEPControl import STEPControl_AsIs, STEPControl_Reader, STEPControl_Writer
from OCP.TopAbs import TopAbs_EDGE, TopAbs_FACE
from OCP.TopoDS import TopoDS
from OCP.OCP.collections import IndexedMap_TopoDS_Shape_TopTools_ShapeMapHasher as TopTools_IndexedMapOfShape
from OCP.TopExp import TopExp

TOLERANCE = 1e-12


def quiet():
    """Silences Open CASCADE's messages on standard output (its writers print progress)."""
    sys.stdout.flush()
    saved = os.dup(1)
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.close(devnull)
    return saved


def loud(saved):
    sys.stdout.flush()
    os.dup2(saved, 1)
    os.close(saved)


class Row:
    def __init__(self, name):
        self.name, self.cases, self.agreed, self.worst, self.failures = name, 0, 0, 0.0, []

    def add(self, ok, error, detail):
        self.cases += 1
        self.agreed += bool(ok)
        if math.isfinite(error):
            self.worst = max(self.worst, error)
        if not ok and len(self.failures) < 5:
            self.failures.append(detail)


# --- random B-splines ---------------------------------------------------------------------

def random_knots(rng, p, n, clamped=True):
    """n + p + 1 knots of degree p: interior multiplicities up to p, optionally unclamped."""
    while True:
        inner = n - p - 1 if clamped else n + p + 1
        values = []
        x = rng.uniform(-1, 1)
        while len(values) < inner:
            x += rng.uniform(0.05, 1.0)
            m = int(rng.integers(1, p + 1))
            values.extend([x] * min(m, inner - len(values)))
        if clamped:
            a, b = (values[0] if values else x) - rng.uniform(0.1, 1), x + rng.uniform(0.1, 1)
            knots = [a] * (p + 1) + values + [b] * (p + 1)
        else:
            knots = values
        if knots[p] < knots[n]:
            return knots


def random_object(rng, kind):
    if "curve" in kind:
        p = int(rng.integers(1, 8))
        n = p + 1 + int(rng.integers(0, 6))
        dim = 2 if kind.endswith("2") else 3
        obj = {
            "degree": p,
            "knots": random_knots(rng, p, n, clamped=rng.random() < 0.8),
            "control_points": (rng.normal(size=(n, dim)) * rng.choice([1e-3, 1, 1e3])).tolist(),
        }
        if "nurbs" in kind:
            obj["weights"] = rng.uniform(0.2, 3.0, n).tolist()
        return obj
    pu, pv = int(rng.integers(1, 6)), int(rng.integers(1, 6))
    nu, nv = pu + 1 + int(rng.integers(0, 4)), pv + 1 + int(rng.integers(0, 4))
    obj = {
        "degree": [pu, pv],
        "knots": [random_knots(rng, pu, nu), random_knots(rng, pv, nv)],
        "control_points": rng.normal(size=(nu, nv, 3)).tolist(),
    }
    if "nurbs" in kind:
        obj["weights"] = rng.uniform(0.2, 3.0, (nu, nv)).tolist()
    return obj


def distinct(knots):
    values, mults = [], []
    for k in knots:
        if values and values[-1] == k:
            mults[-1] += 1
        else:
            values.append(k)
            mults.append(1)
    return values, mults


def array1(values, kind=Array1_double):
    a = kind(1, len(values))
    for i, v in enumerate(values):
        a.SetValue(i + 1, v)
    return a


def occt_curve(obj):
    pts = [list(q) + [0.0] * (3 - len(q)) for q in obj["control_points"]]
    poles = Array1_gp_Pnt(1, len(pts))
    for i, q in enumerate(pts):
        poles.SetValue(i + 1, gp_Pnt(*q))
    values, mults = distinct(obj["knots"])
    if "weights" in obj:
        return Geom_BSplineCurve(poles, array1(obj["weights"]), array1(values), array1(mults, Array1_int), obj["degree"])
    return Geom_BSplineCurve(poles, array1(values), array1(mults, Array1_int), obj["degree"])


def occt_surface(obj):
    net = obj["control_points"]
    nu, nv = len(net), len(net[0])
    poles = Array2_gp_Pnt(1, nu, 1, nv)
    for i in range(nu):
        for j in range(nv):
            poles.SetValue(i + 1, j + 1, gp_Pnt(*net[i][j]))
    (uk, um), (vk, vm) = distinct(obj["knots"][0]), distinct(obj["knots"][1])
    args = [array1(uk), array1(vk), array1(um, Array1_int), array1(vm, Array1_int), obj["degree"][0], obj["degree"][1]]
    if "weights" in obj:
        w = Array2_double(1, nu, 1, nv)
        for i in range(nu):
            for j in range(nv):
                w.SetValue(i + 1, j + 1, obj["weights"][i][j])
        return Geom_BSplineSurface(poles, w, *args)
    return Geom_BSplineSurface(poles, *args)


def domain(knots, p):
    n = len(knots) - p - 1
    return knots[p], knots[n]


def size_of(obj):
    return float(np.max(np.abs(np.asarray(obj["control_points"], dtype=float)))) + 1e-300


# --- the tool -------------------------------------------------------------------------------

class Tool:
    def __init__(self, binary, work):
        self.binary, self.work, self.count = binary, work, 0

    def path(self, suffix):
        self.count += 1
        return os.path.join(self.work, f"o{self.count}{suffix}")

    def run(self, *args):
        out = subprocess.run([self.binary, *args], capture_output=True, text=True, timeout=60)
        if out.returncode != 0:
            raise RuntimeError(out.stderr.strip())
        return out.stdout

    def eval(self, obj, params):
        f = self.path(".json")
        with open(f, "w") as h:
            json.dump(obj, h)
        return json.loads(self.run("eval", f, "--at", json.dumps(params), "--derivatives", "1"))


def compare_curve(tool, obj, curve, rng, bound, within=None):
    p = obj["degree"]
    a, b = domain(obj["knots"], p)
    if within is not None:
        a, b = max(a, within[0]), min(b, within[1])
    # The ends of a piece of a curve split at a C0 knot have one-sided derivatives there:
    # only the interior of a piece is compared, the ends of a whole curve too.
    ends = [] if within is not None else [a, b]
    us = sorted(rng.uniform(a + 1e-3 * (b - a), b - 1e-3 * (b - a), 7).tolist() + ends)
    ours = tool.eval(obj, us)
    size = size_of(obj)
    dsize = size / (b - a)
    worst = 0.0
    for u, row in zip(us, ours):
        P, V = gp_Pnt(), gp_Vec()
        curve.D1(u, P, V)
        q = np.array(row[0] + [0.0] * (3 - len(row[0])))
        d = np.array(row[1] + [0.0] * (3 - len(row[1])))
        ep = np.linalg.norm(q - np.array([P.X(), P.Y(), P.Z()])) / max(size, np.linalg.norm(q))
        ed = np.linalg.norm(d - np.array([V.X(), V.Y(), V.Z()])) / max(dsize, np.linalg.norm(d))
        worst = max(worst, ep, ed)
    return worst <= bound, worst


def on_curve(tool, obj, curve, part, bound):
    """Whether points of Open CASCADE's curve on `part` lie on ours (closest points)."""
    pts = []
    for i in range(9):
        P = curve.Value(part[0] + (part[1] - part[0]) * i / 8)
        pts.append([P.X(), P.Y(), P.Z()][: len(obj["control_points"][0])])
    f = tool.path(".json")
    with open(f, "w") as h:
        json.dump(obj, h)
    hits = json.loads(tool.run("closest", f, "--points", json.dumps(pts)))
    worst = max(h["distance"] for h in hits) / size_of(obj)
    return worst <= bound, worst


def compare_surface(tool, obj, surface, rng, bound):
    (pu, pv), (ku, kv) = obj["degree"], obj["knots"]
    (a, b), (c, d) = domain(ku, pu), domain(kv, pv)
    uv = [[float(rng.uniform(a, b)), float(rng.uniform(c, d))] for _ in range(6)] + [[a, c], [b, d]]
    ours = tool.eval(obj, uv)
    size = size_of(obj)
    worst = 0.0
    for (u, v), row in zip(uv, ours):
        P, Du, Dv = gp_Pnt(), gp_Vec(), gp_Vec()
        surface.D1(u, v, P, Du, Dv)
        got = [(row[0][0], P, size), (row[1][0], Du, size / (b - a)), (row[0][1], Dv, size / (d - c))]
        for mine, theirs, scale in got:
            mine = np.array(mine)
            e = np.linalg.norm(mine - np.array([theirs.X(), theirs.Y(), theirs.Z()])) / max(scale, np.linalg.norm(mine))
            worst = max(worst, e)
    return worst <= bound, worst


# --- files ----------------------------------------------------------------------------------

def read_occt(path):
    saved = quiet()
    try:
        reader = STEPControl_Reader() if path.endswith(".step") else IGESControl_Reader()
        if reader.ReadFile(path) != IFSelect_RetDone:
            return None
        reader.TransferRoots()
        return reader.OneShape()
    finally:
        loud(saved)


def write_occt(shape, path):
    saved = quiet()
    try:
        if path.endswith(".step"):
            w = STEPControl_Writer()
            w.Transfer(shape, STEPControl_AsIs)
            w.Write(path)
        else:
            w = IGESControl_Writer("MM", 1)
            w.AddShape(shape)
            w.ComputeModel()
            w.Write(path)
    finally:
        loud(saved)


def shapes(shape, kind):
    m = TopTools_IndexedMapOfShape()
    TopExp.MapShapes_s(shape, kind, m)
    return [m.FindKey(i) for i in range(1, m.Extent() + 1)]


def ours_to_occt(tool, rng, cases, fmt, rows):
    kinds = ["curve2", "curve3", "nurbs curve2", "nurbs curve3", "surface", "nurbs surface"]
    for k in range(cases):
        kind = kinds[k % len(kinds)]
        row = rows[f"ours → OCCT, {fmt}, {'surfaces' if 'surface' in kind else 'curves'}"]
        obj = random_object(rng, kind)
        f = tool.path(".json")
        with open(f, "w") as h:
            json.dump(obj, h)
        out = tool.path("." + fmt)
        try:
            tool.run("export", out, f)
        except RuntimeError as e:
            row.add(False, math.inf, f"export failed: {e} ({f})")
            continue
        shape = read_occt(out)
        try:
            if "surface" in kind:
                faces = shapes(shape, TopAbs_FACE) if shape is not None else []
                if len(faces) != 1:
                    row.add(False, math.inf, f"{len(faces)} faces in {out}")
                    continue
                surface = BRep_Tool.Surface_s(TopoDS.Face(faces[0]))
                ok, err = compare_surface(tool, obj, surface, rng, TOLERANCE)
            else:
                edges = shapes(shape, TopAbs_EDGE) if shape is not None else []
                if not edges:
                    row.add(False, math.inf, f"no edge in {out}")
                    continue
                # Open CASCADE may split a curve at its C0 knots into several edges, each on
                # its part of the parameter range: each part is compared there.
                ok, err = True, 0.0
                for edge in edges:
                    curve = BRep_Tool.Curve_s(TopoDS.Edge(edge), 0.0, 0.0)
                    part = (curve.FirstParameter(), curve.LastParameter())
                    o, e = compare_curve(tool, obj, curve, rng, TOLERANCE, part)
                    if not o and len(edges) > 1:
                        # A piece of a curve split at its C0 knots may come with another
                        # parametrisation (rational pieces of degree 1 made polynomial):
                        # then its points must lie on our curve.
                        o, e = on_curve(tool, obj, curve, part, TOLERANCE)
                    ok, err = ok and o, max(err, e)
        except Exception as e:  # noqa: BLE001 (a check that cannot run is a failure)
            row.add(False, math.inf, f"{out}: {e}")
            continue
        row.add(ok, err, f"{out} ({f}): {err:.2e}")


def occt_to_ours(tool, rng, cases, fmt, rows):
    bound = TOLERANCE
    kinds = ["curve3", "nurbs curve3", "surface", "nurbs surface"]
    for k in range(cases):
        kind = kinds[k % len(kinds)]
        row = rows[f"OCCT → ours, {fmt}, {'surfaces' if 'surface' in kind else 'curves'}"]
        obj = random_object(rng, kind)
        # Open CASCADE writes clamped knot vectors of its own curves as they are; unclamped
        # ones are checked in the other direction.
        if "surface" in kind:
            geometry = occt_surface(obj)
            shape = BRepBuilderAPI_MakeFace(geometry, 1e-7).Face()
        else:
            obj["knots"] = random_knots(rng, obj["degree"], len(obj["control_points"]))
            geometry = occt_curve(obj)
            shape = BRepBuilderAPI_MakeEdge(geometry).Edge()
        out = tool.path("." + fmt)
        write_occt(shape, out)
        # The reference is Open CASCADE's own reading of the file it wrote: its writers keep
        # 13 (STEP) or fewer (IGES) significant digits, so the file, not the geometry in
        # memory, is what both readers must agree on.
        read_back = read_occt(out)
        if read_back is None:
            row.add(False, math.inf, f"Open CASCADE cannot read its own {out}")
            continue
        if "surface" in kind:
            geometry = BRep_Tool.Surface_s(TopoDS.Face(shapes(read_back, TopAbs_FACE)[0]))
        else:
            geometry = BRep_Tool.Curve_s(TopoDS.Edge(shapes(read_back, TopAbs_EDGE)[0]), 0.0, 0.0)
        try:
            records = json.loads(tool.run("import", out))
        except RuntimeError as e:
            row.add(False, math.inf, f"import failed: {e} ({out})")
            continue
        want = "surface" if "surface" in kind else "curve"
        found = [r for r in records if isinstance(r["object"]["degree"], list) == (want == "surface")]
        # The face's boundary curves come along: the surface is the one surface; the edge's
        # curve is the B-spline curve of the file.
        candidates = [r for r in found if r["object"]["degree"] == obj["degree"]] or found
        if not candidates:
            row.add(False, math.inf, f"no {want} in {out}")
            continue
        mine = candidates[0]["object"]
        try:
            if want == "surface":
                ok, err = compare_surface(tool, mine, geometry, rng, bound)
            else:
                # Open CASCADE splits curves at C0 knots into edges: the first edge's range.
                part = (geometry.FirstParameter(), geometry.LastParameter())
                ok, err = compare_curve(tool, mine, geometry, rng, bound, part)
        except Exception as e:  # noqa: BLE001
            row.add(False, math.inf, f"{out}: {e}")
            continue
        row.add(ok, err, f"{out}: {err:.2e}")


def solids(tool, rows):
    """Whole B-rep solids written by Open CASCADE: every face's surface and every edge's curve
    read, analytic surfaces on their closed forms."""
    box = BRepPrimAPI_MakeBox(10, 20, 30).Shape()
    fillet = BRepFilletAPI_MakeFillet(box)
    for edge in shapes(box, TopAbs_EDGE)[:4]:
        fillet.Add(2.0, TopoDS.Edge(edge))
    # A revolved profile: a B-spline curve in the xz plane about the z axis.
    profile = occt_curve({"degree": 3, "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1],
                          "control_points": [[1, 0, 0], [2, 0, 1], [1.5, 0, 2], [2.5, 0, 3], [1, 0, 4]]})
    revolved = BRepPrimAPI_MakeRevol(BRepBuilderAPI_MakeEdge(profile).Edge(), gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1))).Shape()
    cases = {
        "filleted box": (fillet.Shape(), None),
        "cylinder r = 3": (BRepPrimAPI_MakeCylinder(3, 7).Shape(), lambda p: abs(math.hypot(p[0], p[1]) - 3) / 3),
        "sphere r = 2": (BRepPrimAPI_MakeSphere(2).Shape(), lambda p: abs(np.linalg.norm(p) - 2) / 2),
        "torus (5, 1)": (BRepPrimAPI_MakeTorus(5, 1).Shape(), lambda p: abs(math.hypot(math.hypot(p[0], p[1]) - 5, p[2]) - 1) / 5),
        "cone r 3 → 1": (BRepPrimAPI_MakeCone(3, 1, 4).Shape(), None),
        "revolved profile": (revolved, None),
    }
    row = rows["OCCT → ours, step, B-rep solids"]
    for name, (shape, on_surface) in cases.items():
        out = tool.path(".step")
        write_occt(shape, out)
        with open(out) as h:
            text = h.read()
        # The file's faces and edges (a sphere's seam and poles have no EDGE_CURVE).
        faces, edges = text.count("ADVANCED_FACE("), text.count("EDGE_CURVE(")
        try:
            records = json.loads(tool.run("import", out))
        except RuntimeError as e:
            row.add(False, math.inf, f"{name}: {e}")
            continue
        surfaces = [r for r in records if isinstance(r["object"]["degree"], list)]
        curves = [r for r in records if not isinstance(r["object"]["degree"], list)]
        # Every face has its surface; every edge its curve (a seam shared by one face's two
        # sides, or a degenerate edge at a pole, has one curve or none).
        ok = len(surfaces) == faces and len(curves) == edges
        worst = 0.0
        if on_surface is not None:
            for r in surfaces:
                if r["entity"] not in ("CYLINDRICAL_SURFACE", "SPHERICAL_SURFACE", "TOROIDAL_SURFACE"):
                    continue
                o = r["object"]
                (pu, pv), (ku, kv) = o["degree"], o["knots"]
                (a, b), (c, d) = domain(ku, pu), domain(kv, pv)
                uv = [[a + (b - a) * i / 6, c + (d - c) * j / 6] for i in range(7) for j in range(7)]
                for row_ in tool.eval(o, uv):
                    worst = max(worst, on_surface(np.array(row_[0][0])))
            ok = ok and worst <= 1e-14
        row.add(ok, worst, f"{name}: {len(surfaces)} surfaces for {faces} faces, {len(curves)} curves for {edges} edges, off the surface by {worst:.1e}")


def malformed(tool, rng, rows):
    """Broken files: one line on standard error, exit status 2, quickly, in bounded memory."""
    good = {}
    obj = random_object(rng, "nurbs curve3")
    f = tool.path(".json")
    with open(f, "w") as h:
        json.dump(obj, h)
    for fmt in ("step", "igs"):
        out = tool.path("." + fmt)
        tool.run("export", out, f)
        with open(out, "rb") as h:
            good[fmt] = h.read()
    cases = []
    for fmt, text in good.items():
        cases.append((fmt, "truncated", text[: len(text) // 2]))
        cases.append((fmt, "empty", b""))
        cases.append((fmt, "non-ASCII", text.replace(b"0", "é".encode(), 1)))
        cases.append((fmt, "garbage", bytes(rng.integers(0, 256, 4000, dtype=np.uint8))))
    step = good["step"].decode()
    cases.append(("step", "huge multiplicity", step.replace("B_SPLINE_CURVE_WITH_KNOTS((", "B_SPLINE_CURVE_WITH_KNOTS((1000000000000,", 1).encode()))
    cases.append(("step", "reference cycle", step.replace("ENDSEC;\nEND", "#900001 = TRIMMED_CURVE('',#900002,(),(),.T.,.PARAMETER.);\n#900002 = TRIMMED_CURVE('',#900001,(),(),.T.,.PARAMETER.);\n#900003 = EDGE_CURVE('',#900004,#900004,#900001,.T.);\n#900004 = VERTEX_POINT('',#900005);\n#900005 = CARTESIAN_POINT('',(0.,0.,0.));\nENDSEC;\nEND", 1).encode()))
    cases.append(("step", "unknown entity for a point", step.replace("CARTESIAN_POINT", "CARTESIAN_POINTS", 1).encode()))
    row = rows["malformed files"]

    def limit():
        resource.setrlimit(resource.RLIMIT_AS, (1 << 30, 1 << 30))

    for fmt, what, data in cases:
        path = tool.path("." + fmt)
        with open(path, "wb") as h:
            h.write(data)
        start = time.time()
        out = subprocess.run([tool.binary, "import", path], capture_output=True, text=True, timeout=20, preexec_fn=limit)
        seconds = time.time() - start
        lines = out.stderr.strip().splitlines()
        # A reference cycle between wrappers is not an error: the cycle is skipped.
        fine = out.returncode == 0 if what == "reference cycle" else out.returncode == 2 and len(lines) == 1 and "panicked" not in out.stderr
        ok = fine and seconds < 2
        row.add(ok, 0.0, f"{fmt} {what}: status {out.returncode}, {seconds:.2f} s, {out.stderr.strip()[:200]!r}")


def report(rows, label):
    """Prints the table (one line per row; the column of confirmed Open CASCADE misses where
    the rows count them), the notes, every failure and the tool's known bugs the failures
    name (`TOOL BUG: ...`), then `LABEL: N passed, M failed`; returns the exit status."""
    rows = list(rows)
    misses = all(hasattr(r, "misses") for r in rows)
    extra = f" {'OCCT misses':>12}" if misses else ""
    print(f"{'check':<40} {'cases':>6} {'agreed':>7}{extra} {'largest relative error':>24}")
    for row in rows:
        extra = f" {row.misses:>12}" if misses else ""
        print(f"{row.name:<40} {row.cases:>6} {row.agreed:>7}{extra} {row.worst:>24.2e}")
    for row in rows:
        for note in getattr(row, "notes", []):
            print(f"  note, {row.name}: {note}")
        for note in getattr(row, "miss_notes", []):
            print(f"  OCCT miss confirmed, {row.name}: {note}")
    bugs = {}
    for row in rows:
        for detail in row.failures:
            print(f"  FAILED {row.name}: {detail}")
            for bug in re.findall(r"TOOL BUG: ([^)]*)", detail):
                bugs[bug] = bugs.get(bug, 0) + 1
    for bug, count in bugs.items():
        print(f"  tool bug ({count} failure(s)): {bug}")
    failed = sum(r.cases - r.agreed for r in rows)
    print(f"{label}: {sum(r.cases for r in rows) - failed} passed, {failed} failed")
    return 1 if failed else 0


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("work")
    parser.add_argument("--cases", type=int, default=240)
    parser.add_argument("--seed", type=int, default=20261202)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    Interface_Static.SetCVal_s("write.step.schema", "AP214IS")
    rng = np.random.default_rng(args.seed)
    tool = Tool(os.path.abspath(args.binary), args.work)
    names = []
    for direction in ("ours → OCCT", "OCCT → ours"):
        for fmt in ("step", "igs"):
            for what in ("curves", "surfaces"):
                names.append(f"{direction}, {fmt}, {what}")
    names += ["OCCT → ours, step, B-rep solids", "malformed files"]
    rows = {n: Row(n) for n in names}
    for fmt in ("step", "igs"):
        ours_to_occt(tool, rng, args.cases, fmt, rows)
        occt_to_ours(tool, rng, args.cases, fmt, rows)
    solids(tool, rows)
    malformed(tool, rng, rows)
    return report(rows.values(), "occt")


if __name__ == "__main__":
    sys.exit(main())
