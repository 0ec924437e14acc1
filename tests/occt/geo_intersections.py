"""The geometry suite's intersections (geometry.py): curve-curve (2-D, with overlaps),
curve-surface and surface-surface, against Open CASCADE.
"""

import json
import math

import numpy as np

from OCP.Geom2dAdaptor import Geom2dAdaptor_Curve
from OCP.Geom2dAPI import Geom2dAPI_ProjectPointOnCurve
from OCP.Geom2dInt import Geom2dInt_GInter
from OCP.GeomAPI import GeomAPI_IntCS, GeomAPI_IntSS, GeomAPI_ProjectPointOnSurf
from OCP.gp import gp_Pnt, gp_Pnt2d

from check import distinct, domain, occt_curve, occt_surface, random_knots, size_of
from geo_support import (ask, ask_or_fail, curve_json, curve_samples, EXACT, graph_surface, moved, occt_curve2d,
                         rotation, save, segment_distances, values, xyz)


def random_plane_curve(rng, scale, shift, rational=False):
    p = int(rng.integers(1, 5))
    n = p + 1 + int(rng.integers(0, 4))
    obj = {"degree": p, "knots": random_knots(rng, p, n),
           "control_points": (rng.uniform(-1, 1, (n, 2)) * scale + shift).tolist()}
    if rational:
        obj["weights"] = rng.uniform(0.3, 3.0, n).tolist()
    return obj


# The tool's bugs found by this script, as fixed cases (curve-curve intersections; each fails
# until the bug is fixed): (first curve, second curve, expected overlap or None, label).
REPRODUCERS = [
    # A transversal crossing missed: a quadratic against a rational polyline (found without
    # the weights); Open CASCADE and dense sampling find it at u = 0.94656, v = 0.48034.
    ({"degree": 2, "knots": [0, 0, 0, 0.5, 1, 1, 1], "control_points": [[-0.1, -0.3], [-0.8, -0.47], [-0.97, -0.06], [-0.85, -1.11]]},
     {"degree": 1, "knots": [0, 0, 0.4, 1, 1], "control_points": [[-1.13, -0.03], [-1.56, -0.95], [-0.19, -0.85]], "weights": [0.57, 0.36, 2.34]},
     None, "reproducer (missed crossing): "),
    # The command fails: "parameter 0.6752854320379084 is outside the domain [-0.640724881610729, 0.6752854320379083]".
    ({"degree": 2, "knots": [-0.640724881610729] * 3 + [-0.1496352764229789] + [0.6752854320379083] * 3,
      "control_points": [[364.0, -1116.0], [171.0, -1976.0], [43.0, -1519.0], [-996.0, -614.0]]},
     {"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[-160.0, -1587.0], [397.0, -1529.0]]},
     None, "reproducer (parameter outside the domain): "),
    # Collinear segments overlapping on u in [0.5, 1]: reported as one tangential point.
    ({"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0, 0], [1, 0]]},
     {"degree": 1, "knots": [0, 0, 1, 1], "control_points": [[0.5, 0], [1.5, 0]]},
     (0.5, 1.0, False), "reproducer (straight partial overlap): "),
    # A cubic with a sharp C0 corner at u = 1 against itself: two overlaps, [1, 1.0159] left out.
    ({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2], "control_points": [[0, 0], [1, 1], [2, 1], [3, 0], [2, 3], [4, 3], [5, 2]]},
     {"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2], "control_points": [[0, 0], [1, 1], [2, 1], [3, 0], [2, 3], [4, 3], [5, 2]]},
     (0.0, 2.0, False), "reproducer (overlap broken at a corner): "),
    # A curve with a loop (x = t² - 1, y = t³ - t, t in [-1.5, 1.5]) against its second half:
    # the overlap on u in [0.5, 1] is found, the crossing of the first half with the second
    # (u = 1/6, v = 5/6; `spline intersect` of the curve alone finds it) is dropped.
    ({"degree": 3, "knots": [0, 0, 0, 0, 1, 1, 1, 1], "control_points": [[1.25, -1.875], [-1.75, 3.875], [-1.75, -3.875], [1.25, 1.875]]},
     {"degree": 3, "knots": [0.5, 0.5, 0.5, 0.5, 1, 1, 1, 1], "control_points": [[-1.0, 0.0], [-1.0, -0.5], [-0.25, -1.0], [1.25, 1.875]]},
     (0.5, 1.0, False), "reproducer (crossing next to an overlap dropped): "),
]


def curve_curve(tool, rng, row, n):
    """`spline intersect` of two planar curves against Geom2dInt_GInter (the intersector of
    Geom2dAPI_InterCurveCurve): crossings of random curves, a curve against a piece of itself
    (possibly reversed, knots added), collinear segments overlapping in part; then the
    reproducers of the tool's known bugs (REPRODUCERS)."""
    cases = []
    for k in range(n):
        scale = float(10 ** rng.uniform(-3, 3))
        shift = rng.normal(size=2) * scale
        flavour = k % 4
        expected = None
        if flavour < 2:
            a = random_plane_curve(rng, scale, shift, rational=rng.random() < 0.5)
            b = random_plane_curve(rng, scale, shift, rational=rng.random() < 0.5)
        elif flavour == 2:
            a = random_plane_curve(rng, scale, shift, rational=rng.random() < 0.5)
            lo, hi = domain(a["knots"], a["degree"])
            c, d = sorted(rng.uniform(lo, hi, 2).tolist())
            piece = occt_curve(a)
            piece.Segment(c, d)
            reverse = rng.random() < 0.5
            if reverse:
                piece.Reverse()
            piece.InsertKnot(float(rng.uniform(piece.FirstParameter(), piece.LastParameter())), 1, 0.0, True)
            b = curve_json(piece, 2)
            expected = (c, d, reverse)
        else:
            p0, p1 = rng.normal(size=2) * scale + shift, rng.normal(size=2) * scale + shift
            s, t = float(rng.uniform(0.1, 0.9)), float(rng.uniform(1.1, 2))
            deg = int(rng.integers(1, 4))
            line = lambda x, y, m: [(x + (y - x) * i / m).tolist() for i in range(m + 1)]  # noqa: E731
            a = {"degree": deg, "knots": [0.0] * (deg + 1) + [1.0] * (deg + 1), "control_points": line(p0, p1, deg)}
            b = {"degree": 1, "knots": [0.0, 0.0, 1.0, 1.0], "control_points": line(p0 + s * (p1 - p0), p0 + t * (p1 - p0), 1)}
            expected = (s, 1.0, False)
        cases.append((a, b, expected, ""))
    cases += REPRODUCERS
    for a, b, expected, label in cases:
        fa, fb = save(tool, a), save(tool, b)
        detail = f"{label}spline intersect {fa} {fb}"
        size = max(size_of(a), size_of(b))
        mine = ask_or_fail(tool, row, detail, "intersect", fa, fb)
        if mine is None:
            continue
        ca, cb = occt_curve2d(a), occt_curve2d(b)
        tol = 1e-9 * size
        inter = Geom2dInt_GInter(Geom2dAdaptor_Curve(ca), Geom2dAdaptor_Curve(cb), tol, tol)
        theirs = [(inter.Point(i).ParamOnFirst(), inter.Point(i).ParamOnSecond(),
                   np.array(inter.Point(i).Value().Coord())) for i in range(1, inter.NbPoints() + 1)]
        segments = []
        for i in range(1, inter.NbSegments() + 1):
            sg = inter.Segment(i)
            if sg.HasFirstPoint() and sg.HasLastPoint():
                segments.append(sorted([sg.FirstPoint().ParamOnFirst(), sg.LastPoint().ParamOnFirst()]))
        segments = merged(segments, 1e-9 * (domain(a["knots"], a["degree"])[1] - domain(a["knots"], a["degree"])[0]))
        ok, err, misses, notes = compare_crossings(mine, theirs, segments, expected, ca, cb, size, a, touch_tolerance(a, b))
        row.add(ok, err, f"{detail}: {'; '.join(notes)}", miss=(f"{detail}: " + "; ".join(misses)) if misses else None)


def merged(segments, gap):
    """Parameter intervals joined where they touch (Open CASCADE splits an overlap at knots)."""
    out = []
    for s in sorted(segments):
        if out and s[0] <= out[-1][1] + gap:
            out[-1][1] = max(out[-1][1], s[1])
        else:
            out.append(list(s))
    return out


def touch_tolerance(a, b):
    """The tool's default curve-curve tolerance: 1e-9 of the larger side of the box of both
    curves' control points."""
    pts = np.concatenate([np.asarray(a["control_points"], float), np.asarray(b["control_points"], float)])
    return 1e-9 * float(np.max(pts.max(axis=0) - pts.min(axis=0)))


def on2d(c, u):
    P = c.Value(float(u))
    return np.array([P.X(), P.Y()])


def compare_crossings(mine, theirs, segments, expected, ca, cb, size, a, touch):
    """Matches the tool's intersections of two planar curves with Open CASCADE's. An overlap
    made by the construction must be the tool's one overlap; its ends may lie up to the
    touching distance `touch` beyond the true ones (the curves stay within it there): 2
    `touch` in space is accepted."""
    ok, err, misses, notes = True, 0.0, [], []
    match = 1e-7 * size
    points = [m for m in mine if not m.get("overlap")]
    overlaps = [m for m in mine if m.get("overlap")]
    length = domain(a["knots"], a["degree"])
    span = length[1] - length[0]
    # The construction: the overlap expected on the first curve.
    if expected is not None:
        c, d, reverse = expected
        good = [o for o in overlaps
                if max(np.linalg.norm(on2d(ca, o["u"][0]) - on2d(ca, c)), np.linalg.norm(on2d(ca, o["u"][1]) - on2d(ca, d)),
                       np.linalg.norm(on2d(cb, o["v"][0]) - on2d(ca, c)), np.linalg.norm(on2d(cb, o["v"][1]) - on2d(ca, d))) <= 2 * touch + EXACT * size
                and bool(o.get("reversed")) == reverse]
        if len(overlaps) != 1 or not good:
            ok = False
            notes.append(f"expected one overlap on u in [{c!r}, {d!r}] reversed={reverse}, the tool gives {overlaps}"
                         + known_overlap_bug(overlaps, a, c, d))
        for o in good:
            err = max(err, max(np.linalg.norm(on2d(ca, o["u"][0]) - on2d(ca, c)), np.linalg.norm(on2d(ca, o["u"][1]) - on2d(ca, d))) / size)
        theirs_ok = any(abs(s[0] - c) <= 1e-6 * span and abs(s[1] - d) <= 1e-6 * span for s in segments)
        if not theirs_ok:
            misses.append(f"Open CASCADE gives {len(segments)} segment(s) {segments} and {len(theirs)} point(s) for the overlap on [{c:.6g}, {d:.6g}]")
    else:
        for o in overlaps:
            # An overlap the construction did not make: the curves must coincide along it.
            ends = max(np.linalg.norm(on2d(ca, u) - on2d(cb, v)) for u, v in zip(o["u"], o["v"]))
            gap = max([ends] + [distance_to(cb, on2d(ca, u)) for u in np.linspace(o["u"][0], o["u"][1], 9)])
            if gap > 2 * touch + EXACT * size:
                ok = False
                notes.append(f"overlap {o} with a gap {gap:.2e} between the curves")
        for s in segments:
            # A segment of Open CASCADE's: real only if the curves coincide there.
            mid = 0.5 * (s[0] + s[1])
            if not any(o["u"][0] <= mid <= o["u"][1] for o in overlaps):
                gap = distance_to(cb, on2d(ca, mid))
                if gap > 1e-6 * size:
                    misses.append(f"Open CASCADE's segment {s} is no overlap (gap {gap:.2e} at its middle)")
                else:
                    ok = False
                    notes.append(f"the tool misses Open CASCADE's overlap {s}")
    inside = lambda u: any(o["u"][0] - 1e-9 * span <= u <= o["u"][1] + 1e-9 * span for o in overlaps)  # noqa: E731
    on_b = lambda v: any(min(o["v"]) - 1e-9 * span <= v <= max(o["v"]) + 1e-9 * span for o in overlaps)  # noqa: E731
    # Every tool crossing: matched by Open CASCADE, or verified on both curves.
    for m in points:
        q = np.array(m["point"])
        loose = math.sqrt(1e-9) * size if m.get("tangential") else match
        near = [np.linalg.norm(q - t[2]) for t in theirs]
        if near and min(near) <= loose:
            err = max(err, min(near) / size)
            continue
        gap = np.linalg.norm(on2d(ca, m["u"]) - on2d(cb, m["v"]))
        if gap <= 1e-9 * size and np.linalg.norm(on2d(ca, m["u"]) - q) <= 1e-9 * size:
            if not (expected is not None and inside(m["u"])):
                misses.append(f"Open CASCADE misses the crossing at u = {m['u']:.9g}, v = {m['v']:.9g} (|A(u) - B(v)| = {gap:.1e})")
        else:
            ok = False
            notes.append(f"the tool's {m} is not on both curves (gap {gap:.2e})")
    # Every Open CASCADE point: matched by the tool, inside its overlap, or not an intersection.
    for u, v, P in theirs:
        near = [np.linalg.norm(np.array(m["point"]) - P) for m in points]
        loose = max([math.sqrt(1e-9) * size if m.get("tangential") else match for m in points] or [match])
        # A point of an overlap (both parameters in it, or at one of its ends, which may lie
        # up to the touching distance off) is no crossing.
        at_end = any(np.linalg.norm(P - on2d(ca, x)) <= 4 * touch + EXACT * size for o in overlaps for x in o["u"])
        if (near and min(near) <= loose) or (inside(u) and on_b(v)) or at_end:
            continue
        gap = np.linalg.norm(on2d(ca, u) - on2d(cb, v))
        if gap <= 1e-9 * size:
            ok = False
            bug = "a crossing with an arc where the curves overlap is dropped" if inside(u) or on_b(v) else "a crossing is missed"
            notes.append(f"the tool misses Open CASCADE's crossing at u = {u!r}, v = {v!r} (gap {gap:.1e}) (TOOL BUG: {bug})")
        else:
            misses.append(f"Open CASCADE's point at u = {u:.9g} is no crossing (|A(u) - B(v)| = {gap:.1e})")
    notes.append(f"tool {len(points)} points {len(overlaps)} overlaps, OCCT {len(theirs)} points {len(segments)} segments")
    return ok, err, misses, notes


def distance_to(curve, point):
    """Distance from a point to a planar Open CASCADE curve: its projections and ends."""
    proj = Geom2dAPI_ProjectPointOnCurve(gp_Pnt2d(*point), curve)
    ends = [on2d(curve, curve.FirstParameter()), on2d(curve, curve.LastParameter())]
    found = [proj.LowerDistance()] if proj.NbPoints() else []
    return min(found + [float(np.linalg.norm(e - point)) for e in ends])


def known_overlap_bug(overlaps, a, c, d):
    """Names the tool's known overlap bugs when a failure looks like one of them (the overlap
    expected on u in [c, d])."""
    pts = np.asarray(a["control_points"], float)
    e = pts[-1] - pts[0]
    straight = bool(np.all(np.abs((pts - pts[0]) @ [e[1], -e[0]]) <= 1e-12 * np.dot(e, e)))
    if not overlaps and straight:
        return " (TOOL BUG: a partial overlap of two straight segments is reported as one touching point)"
    lo, hi = domain(a["knots"], a["degree"])
    small = 1e-6 * (hi - lo)
    corners = [v for v, m in zip(*distinct(a["knots"])) if m >= a["degree"] and lo < v < hi]
    ends = [c] + [x for o in sorted(o["u"] for o in overlaps) for x in o] + [d]
    gaps = [(g0, g1) for g0, g1 in zip(ends[::2], ends[1::2]) if g1 - g0 > small]
    if overlaps and not gaps:
        return f" (TOOL BUG: an overlap is reported as several contiguous pieces, not one maximal entry) split at {ends[2:-2:2]}"
    if any(g0 - small <= k <= g1 + small for g0, g1 in gaps for k in corners):
        return f" (TOOL BUG: an overlap is broken at a sharp C0 corner of the curve, a piece left out) leaving {gaps} out"
    if gaps:
        return f" (TOOL BUG: an overlap is cut short, a piece left out) leaving {gaps} out"
    return ""


def curve_surface(tool, rng, row, n):
    """`spline intersect CURVE SURFACE` against GeomAPI_IntCS: random curves through a random
    surface; iso-curves of the surface lying in it (an overlap along the whole curve)."""
    for k in range(n):
        R, scale = rotation(rng), float(10 ** rng.uniform(-3, 3))
        shift = rng.normal(size=3) * scale
        surface = graph_surface(rng, rational=rng.random() < 0.5)
        expected = None
        if k % 4 == 3:
            geom = occt_surface(surface)
            (pu, pv), (ku, kv) = surface["degree"], surface["knots"]
            if rng.random() < 0.5:
                iso = geom.UIso(float(rng.uniform(*domain(ku, pu))))
            else:
                iso = geom.VIso(float(rng.uniform(*domain(kv, pv))))
            curve = curve_json(iso, 3)
            expected = domain(curve["knots"], curve["degree"])
        else:
            p = int(rng.integers(1, 4))
            m = p + 1 + int(rng.integers(0, 4))
            pts = rng.uniform(-0.9, 0.9, (m, 3))
            pts[:, 2] = np.where(np.arange(m) % 2 == 0, -1.5, 1.5) * rng.uniform(0.5, 1.5, m)
            curve = {"degree": p, "knots": random_knots(rng, p, m), "control_points": pts.tolist()}
            if rng.random() < 0.4:
                curve["weights"] = rng.uniform(0.3, 3, m).tolist()
        surface, curve = moved(surface, R * scale, shift), moved(curve, R * scale, shift)
        fc, fs = save(tool, curve), save(tool, surface)
        detail = f"spline intersect {fc} {fs}"
        size = max(size_of(surface), size_of(curve))
        mine = ask_or_fail(tool, row, detail, "intersect", fc, fs)
        if mine is None:
            continue
        gc, gs = occt_curve(curve), occt_surface(surface)
        inter = GeomAPI_IntCS(gc, gs)
        if not inter.IsDone():
            row.add(False, math.inf, f"{detail}: GeomAPI_IntCS not done")
            continue
        theirs = []
        for i in range(1, inter.NbPoints() + 1):
            u, v, w = inter.Parameters(i)
            theirs.append((w, u, v, xyz(inter.Point(i))))
        segments = [(inter.Segment(i).FirstParameter(), inter.Segment(i).LastParameter()) for i in range(1, inter.NbSegments() + 1)]
        ok, err, misses, notes = True, 0.0, [], []
        points = [m for m in mine if not m.get("overlap")]
        overlaps = [m for m in mine if m.get("overlap")]
        t0, t1 = domain(curve["knots"], curve["degree"])
        span = t1 - t0
        inside = lambda t: any(o["t"][0] - 1e-9 * span <= t <= o["t"][1] + 1e-9 * span for o in overlaps)  # noqa: E731
        if expected is not None:
            if not (len(overlaps) == 1 and abs(overlaps[0]["t"][0] - t0) <= 1e-9 * span and abs(overlaps[0]["t"][1] - t1) <= 1e-9 * span):
                ok = False
                notes.append(f"the iso-curve lies in the surface on [{t0!r}, {t1!r}]; the tool gives {overlaps}")
            # Open CASCADE on a curve lying in the surface: whatever it reports must be on the
            # overlap; missing it is a miss (the construction is the third check).
            if not any(abs(s[0] - t0) <= 1e-6 * span and abs(s[1] - t1) <= 1e-6 * span for s in segments):
                misses.append(f"the iso-curve lies in the surface; Open CASCADE gives {len(segments)} segment(s), {len(theirs)} point(s)")
        for o in overlaps:
            for t, uv in zip(o["t"], o["uv"]):
                gap = np.linalg.norm(xyz(gc.Value(t)) - xyz(gs.Value(*uv)))
                if gap > 1e-9 * size:
                    ok = False
                    notes.append(f"overlap end t = {t!r} off the surface by {gap:.2e}")
        for m in points:
            q = np.array(m["point"])
            loose = 1e-5 * size if m.get("tangential") else 1e-7 * size
            near = [np.linalg.norm(q - t[3]) for t in theirs]
            if near and min(near) <= loose:
                err = max(err, min(near) / size)
                continue
            gap = np.linalg.norm(xyz(gc.Value(m["t"])) - xyz(gs.Value(m["u"], m["v"])))
            if gap <= 1e-9 * size and np.linalg.norm(xyz(gc.Value(m["t"])) - q) <= 1e-9 * size:
                if not inside(m["t"]) or expected is None:
                    misses.append(f"Open CASCADE misses the point at t = {m['t']:.9g} (|C(t) - S(u, v)| = {gap:.1e})")
            else:
                ok = False
                notes.append(f"the tool's {m} is not on both (gap {gap:.2e})")
        for w, u, v, P in theirs:
            near = [np.linalg.norm(np.array(m["point"]) - P) for m in points]
            if (near and min(near) <= 1e-5 * size) or inside(w):
                continue
            gap = np.linalg.norm(xyz(gc.Value(w)) - xyz(gs.Value(u, v)))
            if gap <= 1e-9 * size:
                ok = False
                notes.append(f"the tool misses Open CASCADE's point at t = {w!r}, (u, v) = ({u!r}, {v!r}) (gap {gap:.1e})"
                             " (TOOL BUG: an intersection point is missed)")
            else:
                misses.append(f"Open CASCADE's point at t = {w:.9g} is off (|C(t) - S(u, v)| = {gap:.1e})")
        notes.append(f"tool {len(points)} points {len(overlaps)} overlaps, OCCT {len(theirs)} points {len(segments)} segments")
        row.add(ok, err, f"{detail}: {'; '.join(notes)}", miss=(f"{detail}: " + "; ".join(misses)) if misses else None)


def surface_pair(rng, k):
    """Two surfaces that cross: graphs over different planes, a sphere or a torus against a
    graph surface."""
    flavour = k % 4
    if flavour == 0:
        return graph_surface(rng, (0, 1, 2), rng.random() < 0.5), graph_surface(rng, (0, 2, 1), rng.random() < 0.5)
    if flavour == 1:
        a = graph_surface(rng, (0, 1, 2), rng.random() < 0.5, amplitude=0.15)
        b = graph_surface(rng, (0, 1, 2), rng.random() < 0.5, amplitude=0.15)
        b["control_points"] = (np.asarray(b["control_points"]) * [0.6, 0.6, 1] + [0, 0, 0.1]).tolist()
        return a, b
    return None


def surface_surface(tool, rng, row, n):
    """`spline intersect SURFACE SURFACE` against GeomAPI_IntSS: samples of Open CASCADE's
    curves must lie on the tool's polylines and on its B-spline pieces, and the other way
    round, within the tolerance asked for (plus Open CASCADE's own distance from the
    surfaces). A point of one answer far from the other is checked on both surfaces (the
    tool's with its (u, v), Open CASCADE's by projection): on both, it is a miss of the other
    side (the tool's: a failure); off them, an error of its own side."""
    for k in range(n):
        R, scale = rotation(rng), float(10 ** rng.uniform(-3, 3))
        shift = rng.normal(size=3) * scale
        pair = surface_pair(rng, k)
        if pair is None:
            c = rng.normal(size=3) * 0.2
            if k % 4 == 2:
                out = ask(tool, "make", "sphere", "--center", json.dumps(c.tolist()), "--radius", float(rng.uniform(0.5, 0.9)),
                          "--axis", json.dumps(rng.normal(size=3).tolist()))
            else:
                major = float(rng.uniform(0.5, 0.8))
                out = ask(tool, "make", "torus", "--center", json.dumps(c.tolist()), "--major", major,
                          "--minor", float(rng.uniform(0.15, 0.4)) * major, "--axis", json.dumps(rng.normal(size=3).tolist()))
            pair = (out, graph_surface(rng, (0, 1, 2), rng.random() < 0.5, amplitude=0.2))
        compare_surface_pair(tool, row, *(moved(s, R * scale, shift) for s in pair))
    # The reproducer of a tool bug: a torus and a graph surface under a linear map (the same
    # pair unmapped, or mapped by R rounded to one decimal, is right): one intersection curve
    # comes out open, a piece of it (about 0.6 % of the size, where it crosses the torus's
    # two seams at once) missing.
    torus = ask(tool, "make", "torus", *SS_REPRODUCER["torus"])
    z = SS_REPRODUCER["z"]
    xs, ys = np.linspace(-1, 1, len(z)), np.linspace(-1, 1, len(z[0]))
    graph = {"degree": [3, 3], "knots": SS_REPRODUCER["knots"],
             "control_points": [[[float(x), float(y), h] for y, h in zip(ys, hs)] for x, hs in zip(xs, z)]}
    m = SS_REPRODUCER["map"]
    compare_surface_pair(tool, row, moved(torus, m, np.zeros(3)), moved(graph, m, np.zeros(3)),
                         "reproducer (a piece of a curve missed at a torus's seams): ")


SS_REPRODUCER = {
    "torus": ["--center", "[0.06, 0.084, -0.05]", "--major", "0.53", "--minor", "0.205", "--axis", "[0.614, -0.141, -0.33]"],
    "knots": [[0, 0, 0, 0, 1, 1, 1, 1], [0, 0, 0, 0, 0.76, 1.33, 1.7, 1.7, 1.7, 1.7]],
    "z": [[-0.1, 0.19, 0.15, 0.25, -0.12, 0.11], [0.06, 0.03, 0.12, 0.23, 0.11, 0.15],
          [-0.22, 0.05, -0.14, -0.02, 0.16, -0.55], [-0.14, 0.21, 0.2, -0.28, -0.15, -0.32]],
    "map": [[0.74, -0.44, -0.5], [-0.65, -0.65, -0.39], [0.15, -0.62, 0.77]],
}


def compare_surface_pair(tool, row, a, b, label=""):
    """One surface-surface case (see surface_surface)."""
    fa, fb = save(tool, a), save(tool, b)
    size = max(size_of(a), size_of(b))
    tolerance = 1e-6 * size
    detail = f"{label}spline intersect {fa} {fb} --tolerance {tolerance!r}"
    mine = ask_or_fail(tool, row, detail, "intersect", fa, fb, "--tolerance", repr(tolerance))
    if mine is None:
        return
    ga, gb = occt_surface(a), occt_surface(b)
    inter = GeomAPI_IntSS(ga, gb, 1e-7 * size)
    if not inter.IsDone():
        row.add(False, math.inf, f"{detail}: GeomAPI_IntSS not done")
        return
    lines = [inter.Line(i) for i in range(1, inter.NbLines() + 1)]
    ok, err, misses, notes = True, 0.0, [], []
    polylines = [np.array(c["points"]) for c in mine]
    # Open CASCADE's curves, densely: 2000 samples each.
    dense = [curve_samples(L, L.FirstParameter(), L.LastParameter(), 2000)[1] for L in lines]

    def off_surfaces(P):
        """How far Open CASCADE's point is from the two surfaces (its own error)."""
        worst = 0.0
        for g in (ga, gb):
            pr = GeomAPI_ProjectPointOnSurf(gp_Pnt(*P), g)
            worst = max(worst, pr.LowerDistance() if pr.IsDone() and pr.NbPoints() else math.inf)
        return worst

    # 1. Open CASCADE's curves on the tool's polylines.
    for L, samples in zip(lines, dense):
        pts = samples[::80]
        dist = np.min([segment_distances(pts, pl) for pl in polylines], axis=0) if polylines else np.full(len(pts), math.inf)
        for P, d in zip(pts, dist):
            if d <= tolerance + 1e-9 * size:
                err = max(err, d / size)
                continue
            e = off_surfaces(P)
            if d <= tolerance + 1e-9 * size + 20 * e:
                err = max(err, d / size)
            elif e <= 1e-8 * size:
                ok = False
                notes.append(f"Open CASCADE's point {P.tolist()} is on both surfaces ({e:.1e}) but {d:.2e} from the tool's curves"
                             " (TOOL BUG: part of an intersection curve is missed)")
                break
            else:
                misses.append(f"Open CASCADE's point {P.tolist()} is {e:.1e} off the surfaces")
                break
    # 2. The tool's polylines and pieces on Open CASCADE's curves. Open CASCADE's curves are
    # approximations: each one's own error, the largest distance of 25 of its points from
    # the surfaces, widens the bound (ten times, for the angle between the surfaces).
    own = [max(off_surfaces(P) for P in samples[::83]) for samples in dense]
    for c in mine:
        pts = np.array(c["points"])
        checks = [(pts, np.array(c["uv_a"]), np.array(c["uv_b"]), tolerance, "polyline")]
        for piece in c["pieces"]:
            ts = np.linspace(0, 1, 21).tolist()
            X = values(tool, piece["curve"], ts)
            pa = values(tool, piece["pcurve_a"], ts)[:, :2]
            pb = values(tool, piece["pcurve_b"], ts)[:, :2]
            if piece["max_error"] > tolerance * (1 + 1e-9):
                ok = False
                notes.append(f"a piece's max_error {piece['max_error']:.3e} > tolerance {tolerance:.3e}")
            checks.append((X, pa, pb, piece["max_error"], "piece"))
        for X, uva, uvb, bound, what in checks:
            each = np.array([segment_distances(X, d) for d in dense]) if dense else np.full((1, len(X)), math.inf)
            nearest = np.argmin(each, axis=0)
            dist = each[nearest, np.arange(len(X))]
            chord = max([float(np.max(np.linalg.norm(np.diff(d, axis=0), axis=1))) for d in dense] or [0.0])
            for X_, ua, ub, d, line in zip(X, uva, uvb, dist, nearest):
                # The chords of Open CASCADE's dense samples bend away from the curve by at
                # most chord² / (8 r): chord² / size is generous and small.
                if d <= bound + 1e-9 * size + chord * chord / size + 10 * (own[line] if own else 0.0):
                    err = max(err, d / size)
                    continue
                ea = np.linalg.norm(xyz(ga.Value(*ua)) - X_)
                eb = np.linalg.norm(xyz(gb.Value(*ub)) - X_)
                if max(ea, eb) <= bound + 1e-9 * size:
                    misses.append(f"Open CASCADE's curves pass {d:.2e} from the tool's {what} point {X_.tolist()}, which is on both "
                                  f"surfaces within {max(ea, eb):.1e} (their own error {own[line] if own else math.inf:.1e})")
                    break
                ok = False
                notes.append(f"the tool's {what} point {X_.tolist()} is {d:.2e} from Open CASCADE's curves and off the surfaces by {max(ea, eb):.2e}")
                break
    notes.append(f"tool {len(mine)} curves ({sum(len(c['pieces']) for c in mine)} pieces), OCCT {len(lines)} lines")
    row.add(ok, err, f"{detail}: {'; '.join(notes)}", miss=(f"{detail}: " + "; ".join(misses[:2])) if misses else None)
