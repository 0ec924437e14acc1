"""The Dask example on a few airfoils: a LocalCluster of 2 workers gives the same summary
lines as smoothing the files one by one (``cargo xtask dask`` compares the whole database
with the tool's batch mode)."""

import importlib.util
import pathlib

import pytest

import spline

distributed = pytest.importorskip("dask.distributed")

ROOT = pathlib.Path(__file__).resolve().parents[1]
TABLE61 = ROOT.parent / "data" / "airfoils" / "table61"


def load_example():
    spec = importlib.util.spec_from_file_location("dask_smooth", ROOT / "examples" / "dask_smooth.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_dask_example_matches_serial(tmp_path):
    example = load_example()
    for name in ("2032c", "a18sm", "e377"):
        (tmp_path / f"{name}.dat").write_bytes((TABLE61 / f"{name}.dat").read_bytes())
    (tmp_path / "broken.dat").write_text("broken\n1 2\nnot a point\n")
    with distributed.LocalCluster(
        n_workers=2, threads_per_worker=1, dashboard_address=None
    ) as cluster, distributed.Client(cluster) as client:
        lines = example.smooth_directory(client, str(tmp_path), control_points=20)
    assert [line["name"] for line in lines] == ["2032c", "a18sm", "broken", "e377"]
    assert [line["error"] is None for line in lines] == [True, True, False, True]
    for line in lines:
        serial = spline.smooth_file(tmp_path / f"{line['name']}.dat", control_points=20)
        for key in ("control_points", "max_deviation", "max_deviation_to_data", "extrema", "error"):
            assert line[key] == serial[key], (line["name"], key)
