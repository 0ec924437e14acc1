"""scipy's own B-spline tests, run against this package.

``scipy/interpolate/tests/test_bsplines.py`` of the installed scipy, unmodified, runs in a
subprocess pytest with the plugin ``_scipy_swap`` (the package's names bound in scipy's
place), scipy's ``conftest`` (the ``xp`` fixture) and a junit report; this test prints the
passes per class and fails when they fall below the bar below. Raise the bar as the package
catches up: scipy 1.17 itself passes 186 of the 187 tests of the six core classes (one is
an expected failure) and all but that one of the file.
"""

import collections
import os
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

scipy = pytest.importorskip("scipy")

#: The classes of the issue's first bar.
CORE = (
    "TestBSpline",
    "TestInsert",
    "TestInterop",
    "TestInterp",
    "TestLSQ",
    "TestSmoothingSpline",
)

#: Passes that must not be lost (core classes, whole file); missing names are stubs, so
#: these count only what the package does. The issue's goal: 183 and 505.
BAR_CORE = 187
BAR_ALL = 520

HERE = Path(__file__).resolve().parent


def run_suite(tmp_path):
    """Runs scipy's file; returns ``{class: Counter(status)}``."""
    test_file = Path(scipy.__file__).parent / "interpolate" / "tests" / "test_bsplines.py"
    report = tmp_path / "junit.xml"
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(HERE), env.get("PYTHONPATH", "")])
    env["PYTHONDONTWRITEBYTECODE"] = "1"
    run = subprocess.run(
        [
            sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
            "-p", "_scipy_swap", "-p", "scipy.conftest",
            # scipy's conftest is loaded by name above; without the cut pytest would also
            # load it by path when the venv and the working directory share an ancestor
            # (both under /tmp), and refuse the same plugin under two names.
            f"--confcutdir={test_file.parent}",
            f"--junitxml={report}", "-o", "junit_family=xunit2",
            str(test_file),
        ],
        cwd=tmp_path, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
        text=True, timeout=1800,
    )
    if not report.exists():
        pytest.fail(f"scipy's suite did not run:\n{run.stderr[-3000:]}")
    counts = collections.defaultdict(collections.Counter)
    for case in ET.parse(report).iter("testcase"):
        cls = case.get("classname", "").rsplit(".", 1)[-1]
        tags = {child.tag for child in case}
        status = (
            "failed" if tags & {"failure", "error"}
            else "skipped" if "skipped" in tags
            else "passed"
        )
        counts[cls][status] += 1
    return counts


def test_scipy_bsplines_suite(tmp_path):
    counts = run_suite(tmp_path)
    lines = [f"{'class':<28}{'passed':>8}{'failed':>8}{'skipped':>8}"]
    for cls in sorted(counts):
        c = counts[cls]
        lines.append(f"{cls:<28}{c['passed']:>8}{c['failed']:>8}{c['skipped']:>8}")
    core = sum(counts[c]["passed"] for c in CORE)
    core_total = sum(sum(counts[c].values()) for c in CORE)
    passed = sum(c["passed"] for c in counts.values())
    total = sum(sum(c.values()) for c in counts.values())
    lines.append(f"core classes: {core} of {core_total}; whole file: {passed} of {total}")
    print("\n".join(lines))
    assert core >= BAR_CORE, "\n".join(lines)
    assert passed >= BAR_ALL, "\n".join(lines)
