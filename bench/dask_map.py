#!/usr/bin/env python3
"""coatcontact.afm.fit_map on a synthetic 64 x 64 JPK force map (tests/afm/make_afm_map, 100
points per segment): jobs=1, jobs=2 and a dask.distributed LocalCluster of 2 worker processes
(one thread each) on the same map, and the ratio Dask / jobs=2 (issue 25: within 10 %).

The cluster is started before any timing; each way is called once to warm up (imports on the
workers, the page cache of the map), then --runs rounds call the ways in turn (a shared
machine's load falls on all alike). Wall time and CPU time (this process and the workers')
medians are printed, as rows "task median_ms min_ms max_ms runs kind" of bench/run.sh's
results.tsv (--tsv) or as text.
The rows of every way are checked to be those of jobs=1.
usage: PYTHONPATH=build/python python3 bench/dask_map.py MAKE_AFM_MAP [--runs N] [--size N] [--tsv]
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

import coatcontact as cc


def worker_cpu(client):
    """CPU seconds used so far by the cluster's worker processes (all their threads)."""
    return sum(client.run(time.process_time).values()) if client is not None else 0.0


def timed_rounds(ways, runs, client):
    """Each way called once (warm-up), then `runs` rounds calling every way in turn (the rounds
    interleave the ways, so that a shared machine's load falls on all of them alike): wall and
    CPU seconds (this process and the workers) of each call, and each way's last rows."""
    rows = {name: call() for name, call in ways.items()}
    wall = {name: [] for name in ways}
    cpu = {name: [] for name in ways}
    for _ in range(runs):
        for name, call in ways.items():
            cpu0, work0 = time.process_time(), worker_cpu(client)
            start = time.perf_counter()
            rows[name] = call()
            wall[name].append(time.perf_counter() - start)
            cpu[name].append(time.process_time() - cpu0 + worker_cpu(client) - work0)
    return wall, cpu, rows


def same_rows(a, b):
    return a.dtype == b.dtype and all(a[n].tobytes() == b[n].tobytes() for n in a.dtype.names)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("make_map")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--size", type=int, default=64)
    parser.add_argument("--tsv", action="store_true")
    args = parser.parse_args()
    try:
        import distributed
    except ImportError:
        print("bench/dask_map.py: no python3-distributed (scripts/install-deps.sh): Dask timings left out",
              file=sys.stderr)
        return 0
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "map.jpk-force-map")
        subprocess.run([args.make_map, path, str(args.size), str(args.size), "--points", "100", "--seed", "4",
                        "--clean"], check=True, stdout=subprocess.DEVNULL)
        model = dict(radius=10e-6, halfspace=(5e3, 0.5))
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") \
                as cluster, distributed.Client(cluster) as client:
            client.wait_for_workers(2)
            ways = {"jobs=1": lambda: cc.afm.fit_map(path, **model, jobs=1),
                    "jobs=2": lambda: cc.afm.fit_map(path, **model, jobs=2),
                    "Dask LocalCluster 2 workers": lambda: cc.afm.fit_map(path, **model, client=client)}
            wall, cpu, rows = timed_rounds(ways, args.runs, client)
    label = f"afm.fit_map {args.size}x{args.size} map (100 points)"
    for name in ways:
        if not same_rows(rows["jobs=1"], rows[name]):
            print(f"bench/dask_map.py: {name} rows differ from jobs=1", file=sys.stderr)
    dask = "Dask LocalCluster 2 workers"
    ratio = statistics.median(wall[dask]) / statistics.median(wall["jobs=2"])
    cpu_ratio = statistics.median(cpu[dask]) / statistics.median(cpu["jobs=2"])
    if args.tsv:
        for name in ways:
            for what, times in (("wall", wall[name]), ("CPU of all processes", cpu[name])):
                print(f"{label}, {name} ({what})\t{1e3 * statistics.median(times):.4g}\t{1e3 * min(times):.4g}\t"
                      f"{1e3 * max(times):.4g}\t{args.runs}\tpython")
        print(f"{label}, Dask / jobs=2 (wall medians)\t{ratio:.3g}\t\t\t{args.runs}\tratio")
        print(f"{label}, Dask / jobs=2 (CPU medians)\t{cpu_ratio:.3g}\t\t\t{args.runs}\tratio")
    else:
        for name in ways:
            print(f"{label}, {name}: wall median {statistics.median(wall[name]):.3f} s (min {min(wall[name]):.3f}, "
                  f"max {max(wall[name]):.3f}), CPU median {statistics.median(cpu[name]):.3f} s, {args.runs} runs")
        print(f"Dask / jobs=2: wall {ratio:.3f} (target <= 1.10), CPU {cpu_ratio:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
