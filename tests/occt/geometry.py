"""Open CASCADE's second opinion on the tool's geometry (`cargo xtask test occt`, after
check.py). See README.md beside this file.

    python geometry.py SPLINE_BINARY WORK_DIR [--cases N] [--seed S]

Random cases (N per check, default 30, fixed seed) of evaluation, knot insertion, degree
elevation, knot removal, closest points, intersections (with overlaps), offsets, arc length
and the constructions of `spline make`, each against Open CASCADE 8. Prints one row per check
(cases, agreed, Open CASCADE misses confirmed by a third check, largest relative error) and
exits 1 on any disagreement. A disagreement counts as agreed only where an independent third
check (dense sampling, evaluating both answers, or the construction of the case) shows that
Open CASCADE, not the tool, missed; those are the "OCCT misses" column, explained below the
table.
"""

import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.dont_write_bytecode = True  # no __pycache__ beside the scripts
from check import Tool, report  # noqa: E402
from geo_intersections import curve_curve, curve_surface, surface_surface  # noqa: E402
from geo_offsets import arclength, circles, offsets, revolutions, spheres_tori  # noqa: E402
from geo_structural import closest, elevation, evaluation, insertion, removal  # noqa: E402
from geo_support import Check  # noqa: E402

NAMES = [
    "evaluation, curves", "evaluation, surfaces", "knot insertion", "degree elevation", "knot removal, exact",
    "knot removal, within a tolerance",
    "closest points, curves", "closest points, surfaces", "intersections, curve-curve (2-D)",
    "intersections, curve-surface", "intersections, surface-surface",
    "offsets, planar polynomial", "offsets, planar rational (NURBS, arcs)", "offsets, space curves",
    "offsets, surfaces", "arc length", "constructions, circles and arcs", "constructions, spheres and tori",
    "constructions, revolved surfaces",
]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("work")
    parser.add_argument("--cases", type=int, default=30)
    parser.add_argument("--seed", type=int, default=20261204)
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rng = np.random.default_rng(args.seed)
    tool = Tool(os.path.abspath(args.binary), args.work)
    rows = {name: Check(name) for name in NAMES}
    n = args.cases
    evaluation(tool, rng, rows, n)
    insertion(tool, rng, rows["knot insertion"], n)
    elevation(tool, rng, rows["degree elevation"], n)
    removal(tool, rng, rows, n)
    closest(tool, rng, rows, n)
    curve_curve(tool, rng, rows["intersections, curve-curve (2-D)"], n)
    curve_surface(tool, rng, rows["intersections, curve-surface"], n)
    surface_surface(tool, rng, rows["intersections, surface-surface"], max(4, n * 2 // 3))
    offsets(tool, rng, rows, n)
    arclength(tool, rng, rows["arc length"], n)
    circles(tool, rng, rows["constructions, circles and arcs"], n)
    spheres_tori(tool, rng, rows["constructions, spheres and tori"], n)
    revolutions(tool, rng, rows["constructions, revolved surfaces"], max(4, n // 2))
    return report(rows.values(), "occt geometry")


if __name__ == "__main__":
    sys.exit(main())
