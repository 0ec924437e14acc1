#!/usr/bin/env python3
"""Smooth a directory of airfoil files (the UIUC database) with Dask.

Each file is one task of a ``dask.bag``: ``spline.smooth_file`` reads it and runs the
selective eraser of curvature extrema (the library releases the GIL), and the result is the
line that ``spline smooth DIR --out OUT`` writes for it in ``summary.jsonl`` — so the two
summaries can be compared line by line.

    python dask_smooth.py DIR --out summary.jsonl [--workers 2] [--control-points 20]

Here the cluster is a ``LocalCluster`` of worker processes. On several machines (each with
``pip install ./python`` done and the files at the same path), start ``dask scheduler`` on one
and ``dask worker tcp://SCHEDULER:8786`` on every machine, then pass
``--scheduler tcp://SCHEDULER:8786``: the client connects to that cluster instead.
"""

import argparse
import json
import os
import sys
import time

import dask.bag as db
from dask.distributed import Client, LocalCluster

import spline


def smooth_directory(client, directory, **options):
    """The summary lines of every ``.dat`` file of ``directory``, in file-name order."""
    files = sorted(
        os.path.join(directory, f) for f in os.listdir(directory) if f.lower().endswith(".dat")
    )
    partitions = max(1, min(len(files), 8 * len(client.scheduler_info()["workers"])))
    bag = db.from_sequence(files, npartitions=partitions)
    return bag.map(spline.smooth_file, **options).compute()


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("directory")
    parser.add_argument("--out", required=True, help="summary.jsonl to write")
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--control-points", type=int, default=20)
    parser.add_argument("--scheduler", help="address of a running Dask scheduler")
    args = parser.parse_args()

    # The cluster: a LocalCluster of worker processes, one thread each (the library does
    # the work with the GIL released). For a multi-machine cluster, see the module docstring.
    if args.scheduler:
        cluster, client = None, Client(args.scheduler)
    else:
        cluster = LocalCluster(
            n_workers=args.workers, threads_per_worker=1, dashboard_address=None
        )
        client = Client(cluster)

    started = time.perf_counter()
    lines = smooth_directory(client, args.directory, control_points=args.control_points)
    wall = time.perf_counter() - started
    with open(args.out, "w", encoding="utf-8") as f:
        for line in lines:
            f.write(json.dumps(line) + "\n")
    failed = sum(line["error"] is not None for line in lines)
    print(
        f"dask: smoothed {len(lines) - failed} of {len(lines)} files in {wall:.1f} s "
        f"on {len(client.scheduler_info()['workers'])} workers; summary in {args.out}",
        file=sys.stderr,
    )
    client.close()
    if cluster is not None:
        cluster.close()


if __name__ == "__main__":
    main()
