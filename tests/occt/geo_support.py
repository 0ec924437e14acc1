"""Shared pieces of the geometry suite (geometry.py): the table row with confirmed Open CASCADE
misses, the tool's JSON in and out, random smooth curves and graph surfaces, and the third
opinions (dense sampling, Gauss-Legendre length).
"""

import json
import math

import numpy as np

from OCP.Geom2d import Geom2d_BSplineCurve
from OCP.gp import gp_Pnt, gp_Pnt2d, gp_Vec
from OCP.OCP.collections import Array1_gp_Pnt2d, Array1_int

from check import array1, distinct, domain, Row, size_of


# Exact operations (evaluation, insertion, elevation, exact constructions): relative to the
# object's size, the rounding of a few hundred operations.
EXACT = 1e-12


class Check(Row):
    """A row of the table: check.py's Row plus the Open CASCADE misses confirmed by a third
    check (counted as agreed) and notes for the footnotes."""

    def __init__(self, name):
        super().__init__(name)
        self.misses, self.miss_notes, self.notes = 0, [], []

    def add(self, ok, error, detail, miss=None):
        self.cases += 1
        self.agreed += bool(ok)
        if math.isfinite(error):
            self.worst = max(self.worst, error)
        if not ok:
            self.failures.append(detail)  # every failure is listed, with its reproducer
        if ok and miss:
            self.misses += 1
            if len(self.miss_notes) < 3:
                self.miss_notes.append(miss)


# --- helpers ----------------------------------------------------------------------------------

def save(tool, obj):
    f = tool.path(".json")
    with open(f, "w") as h:
        json.dump(obj, h)
    return f


def ask(tool, *args):
    return json.loads(tool.run(*[str(a) for a in args]))


def ask_or_fail(tool, row, detail, *args):
    """The tool's answer to `args`, or None after the row records its error (with the known
    bug it shows named) as a failure of the case `detail`."""
    try:
        return ask(tool, *args)
    except RuntimeError as e:
        row.add(False, math.inf, f"{detail}: {failed(e)}")
        return None


def failed(e):
    """The tool's error message, with the known bug it shows named."""
    if "outside the domain" in str(e):
        return f"{e} (TOOL BUG: the command fails on a parameter one rounding step past the end of the curve's domain)"
    if "did not reach the accuracy" in str(e):
        return f"{e} (TOOL BUG: arclength --at-length fails at a tight relative tolerance, asking an absolute accuracy below rounding)"
    return str(e)


def values(tool, obj, params):
    """The tool's points at the parameters (numpy rows, padded to 3-D)."""
    rows = ask(tool, "eval", save(tool, obj), "--at", json.dumps(params))
    return np.array([pad(r[0] if not isinstance(r[0][0], list) else r[0][0]) for r in rows])


def pad(q):
    q = list(q)
    return np.array(q + [0.0] * (3 - len(q)), dtype=float)


def xyz(P):
    return np.array([P.X(), P.Y(), P.Z()])


def flat_knots(knot, mult, count):
    out = []
    for i in range(1, count + 1):
        out += [knot(i)] * mult(i)
    return out


def curve_json(c, dim):
    """An Open CASCADE B-spline curve (3-D) in the exchange format, `dim` coordinates."""
    obj = {
        "degree": c.Degree(),
        "knots": flat_knots(c.Knot, c.Multiplicity, c.NbKnots()),
        "control_points": [list(c.Pole(i).Coord())[:dim] for i in range(1, c.NbPoles() + 1)],
    }
    if c.IsRational():
        obj["weights"] = [c.Weight(i) for i in range(1, c.NbPoles() + 1)]
    return obj


def surface_json(s):
    nu, nv = s.NbUPoles(), s.NbVPoles()
    obj = {
        "degree": [s.UDegree(), s.VDegree()],
        "knots": [flat_knots(s.UKnot, s.UMultiplicity, s.NbUKnots()), flat_knots(s.VKnot, s.VMultiplicity, s.NbVKnots())],
        "control_points": [[list(s.Pole(i, j).Coord()) for j in range(1, nv + 1)] for i in range(1, nu + 1)],
    }
    if s.IsURational() or s.IsVRational():
        obj["weights"] = [[s.Weight(i, j) for j in range(1, nv + 1)] for i in range(1, nu + 1)]
    return obj


def occt_curve2d(obj):
    pts = obj["control_points"]
    poles = Array1_gp_Pnt2d(1, len(pts))
    for i, q in enumerate(pts):
        poles.SetValue(i + 1, gp_Pnt2d(*q))
    v, m = distinct(obj["knots"])
    if "weights" in obj:
        return Geom2d_BSplineCurve(poles, array1(obj["weights"]), array1(v), array1(m, Array1_int), obj["degree"])
    return Geom2d_BSplineCurve(poles, array1(v), array1(m, Array1_int), obj["degree"])


def structure_error(mine, theirs):
    """Relative difference of two objects in the exchange format with the same knots:
    knots (to the domain's length), control points (to the size), weights; inf when the knot
    vectors or nets differ in length."""
    surface = isinstance(mine["degree"], list)
    if mine["degree"] != theirs["degree"]:
        return math.inf
    kms = mine["knots"] if surface else [mine["knots"]]
    kts = theirs["knots"] if surface else [theirs["knots"]]
    err = 0.0
    for a, b in zip(kms, kts):
        if len(a) != len(b):
            return math.inf
        err = max(err, float(np.max(np.abs(np.subtract(a, b)))) / (max(a) - min(a)))
    pa, pb = np.asarray(mine["control_points"], float), np.asarray(theirs["control_points"], float)
    if pa.shape != pb.shape:
        return math.inf
    err = max(err, float(np.max(np.abs(pa - pb))) / size_of(mine))
    wa = np.asarray(mine.get("weights", np.ones(pa.shape[:-1])), float)
    wb = np.asarray(theirs.get("weights", np.ones(pb.shape[:-1])), float)
    return max(err, float(np.max(np.abs(wa - wb) / np.abs(wb))))


def simple_knots(rng, p, n, a=0.0):
    """Clamped knots with simple interior knots at random spacing."""
    inner = np.cumsum(rng.uniform(0.3, 1.0, n - p))
    knots = [a] * (p + 1) + list(a + inner[:-1]) + [a + inner[-1]] * (p + 1)
    return [float(k) for k in knots]


def smooth_curve(rng, dim, rational=False, degrees=(2, 5), scale=None):
    """A clamped curve with simple knots (C^{p-1}): no corner, for offsets and arc length."""
    p = int(rng.integers(degrees[0], degrees[1] + 1))
    n = p + 1 + int(rng.integers(0, 5))
    scale = scale if scale is not None else float(rng.choice([1e-3, 1, 1e3]))
    # A wandering polygon (not a random cloud): no near-cusps of the curve itself.
    steps = rng.normal(size=(n, dim))
    steps[:, 0] += 1.5
    pts = np.cumsum(steps, axis=0) * scale
    obj = {"degree": p, "knots": simple_knots(rng, p, n, float(rng.uniform(-1, 1))), "control_points": pts.tolist()}
    if rational:
        obj["weights"] = rng.uniform(0.5, 2.0, n).tolist()
    return obj


def rotation(rng):
    q, r = np.linalg.qr(rng.normal(size=(3, 3)))
    return q * np.sign(np.diag(r))


def graph_surface(rng, axes=(0, 1, 2), rational=False, amplitude=0.3, degrees=(2, 3)):
    """A surface over a square: coordinate axes[2] = f(axes[0], axes[1]), simple knots."""
    pu, pv = (int(rng.integers(degrees[0], degrees[1] + 1)) for _ in range(2))
    nu, nv = pu + 1 + int(rng.integers(0, 3)), pv + 1 + int(rng.integers(0, 3))
    xs, ys = np.linspace(-1, 1, nu), np.linspace(-1, 1, nv)
    net = np.zeros((nu, nv, 3))
    net[:, :, axes[0]] = xs[:, None]
    net[:, :, axes[1]] = ys[None, :]
    net[:, :, axes[2]] = rng.normal(size=(nu, nv)) * amplitude
    obj = {"degree": [pu, pv], "knots": [simple_knots(rng, pu, nu), simple_knots(rng, pv, nv)], "control_points": net.tolist()}
    if rational:
        obj["weights"] = rng.uniform(0.5, 2.0, (nu, nv)).tolist()
    return obj


def moved(obj, matrix, shift):
    """The object under x -> matrix x + shift (3-D)."""
    out = dict(obj)
    out["control_points"] = (np.asarray(obj["control_points"], float) @ np.asarray(matrix).T + shift).tolist()
    return out


def curve_samples(curve, a, b, count):
    us = np.linspace(a, b, count)
    return us, np.array([xyz(curve.Value(float(u))) for u in us])


def segment_distances(points, polyline):
    """Distance from each point to a polyline (its segments), vectorised."""
    if len(polyline) == 1:
        return np.linalg.norm(points - polyline[0], axis=1)
    a, b = polyline[:-1], polyline[1:]
    d = b - a
    dd = np.maximum(np.einsum("ij,ij->i", d, d), 1e-300)
    t = np.clip(np.einsum("kij,ij->ki", points[:, None, :] - a[None], d) / dd, 0.0, 1.0)
    nearest = a[None] + t[..., None] * d[None]
    return np.min(np.linalg.norm(points[:, None, :] - nearest, axis=2), axis=1)


def dense_curve_min(curve, knots, p, point, per_span=200):
    """Smallest distance from the point to samples of the curve, per_span per knot span, then
    refined by golden-section search around the best samples (an upper bound of the true
    minimum, close to it)."""
    a, b = domain(knots, p)
    breaks = sorted({k for k in knots if a <= k <= b})
    us = np.concatenate([np.linspace(s, t, per_span) for s, t in zip(breaks, breaks[1:]) if t > s])
    d = np.array([np.linalg.norm(xyz(curve.Value(float(u))) - point) for u in us])
    best = float(d.min())
    for i in np.argsort(d)[:3]:
        lo, hi = us[max(i - 1, 0)], us[min(i + 1, len(us) - 1)]
        f = lambda u: float(np.linalg.norm(xyz(curve.Value(u)) - point))  # noqa: E731
        g = 0.6180339887498949
        c, e = hi - g * (hi - lo), lo + g * (hi - lo)
        fc, fe = f(c), f(e)
        for _ in range(60):
            if fc < fe:
                hi, e, fe = e, c, fc
                c = hi - g * (hi - lo)
                fc = f(c)
            else:
                lo, c, fc = c, e, fe
                e = lo + g * (hi - lo)
                fe = f(e)
        best = min(best, fc, fe)
    return best


def dense_surface_min(surface, obj, point, count=90):
    (pu, pv), (ku, kv) = obj["degree"], obj["knots"]
    (a, b), (c, d) = domain(ku, pu), domain(kv, pv)
    best = math.inf
    for u in np.linspace(a, b, count):
        for v in np.linspace(c, d, count):
            best = min(best, float(np.linalg.norm(xyz(surface.Value(float(u), float(v))) - point)))
    return best


def gauss_length(curve, knots, p, pieces=48):
    """Composite 24-point Gauss-Legendre length, `pieces` per knot span (the third opinion)."""
    x, w = np.polynomial.legendre.leggauss(24)
    a, b = domain(knots, p)
    breaks = sorted({k for k in knots if a <= k <= b})
    total = 0.0
    for s, t in zip(breaks, breaks[1:]):
        for lo, hi in zip(np.linspace(s, t, pieces + 1)[:-1], np.linspace(s, t, pieces + 1)[1:]):
            for xi, wi in zip(x, w):
                P, V = gp_Pnt(), gp_Vec()
                curve.D1(float((hi - lo) / 2 * xi + (hi + lo) / 2), P, V)
                total += wi * (hi - lo) / 2 * V.Magnitude()
    return total
