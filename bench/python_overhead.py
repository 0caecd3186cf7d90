#!/usr/bin/env python3
"""Overhead of the Python package over the C++ library: the reduced solver of the soft film
(E1/E0 = 0.1, nu = 0.25, tolerance 1e-8) at one radius (a/t = 1 and 100) and on the standard sweep
(200 log-spaced a/t in [0.01, 100]), as bench/bench_solver.cpp times them.

For each task: the C API call timed inside the compiled module (the library's own cost on
this machine), cc.ReducedSolver.solve and cc.reduced (argument handling, arrays, dict);
medians over the runs. With BUILD/bench/results.tsv from `make bench` its C++ rows are shown
too. usage: PYTHONPATH=build/python python3 bench/python_overhead.py [--runs N]
[--large N (also time one sweep of N radii, e.g. 100000)] [--build build]
"""
import argparse
import os
import statistics
import time

import numpy as np

import coatcontact as cc
from coatcontact import _core


def median_seconds(call, runs):
    call()  # warm-up (FFTW plans, caches)
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=21)
    parser.add_argument("--large", type=int, default=0)
    parser.add_argument("--build", default="build")
    args = parser.parse_args()

    stack = cc.Stack(film=(0.1, 0.25), substrate=(1, 0.25))
    solver = cc.ReducedSolver(stack)
    tasks = {"one radius (a/t = 1)": np.array([1.0]),
             "one radius (a/t = 100)": np.array([100.0]),
             "200 radii (a/t 0.01..100)": np.geomspace(0.01, 100, 200)}
    print("task\tC_API_ms\tReducedSolver.solve_ms\tcc.reduced_ms\toverhead_ms\toverhead_%")
    for name, radii in tasks.items():
        runs = args.runs if radii.size == 1 else max(3, args.runs // 2)
        c_api = solver._core.time_c_call(radii, 1e-8, runs)
        method = median_seconds(lambda: solver.solve(radii, 1e-8), runs)
        function = median_seconds(lambda: cc.reduced(stack, a_over_t=radii), runs)
        over = function - c_api
        print("%s\t%.4g\t%.4g\t%.4g\t%.3g\t%.2g" % (name, 1e3 * c_api, 1e3 * method, 1e3 * function,
                                                  1e3 * over, 100 * over / c_api))
    if args.large:
        radii = np.geomspace(0.01, 100, args.large)
        start = time.perf_counter()
        r = cc.reduced(stack, a_over_t=radii)
        seconds = time.perf_counter() - start
        print("%d radii in one call: %.3g s (%.3g ms per radius), max error estimate %.2g"
              % (args.large, seconds, 1e3 * seconds / args.large, r["error_estimate"].max()))

    results = os.path.join(args.build, "bench", "results.tsv")
    if os.path.exists(results):
        print("\nC++ benchmarks (%s):" % results)
        with open(results) as f:
            for line in f:
                if "SolvePerRadius/100\t" in line or "StandardSweep" in line or "reduced" in line:
                    print("  " + line.rstrip())
    else:
        print("\n(no %s: `make bench` adds the C++ benchmark library's numbers)" % results)
    print("threads: %s cores; C++ sweep parallel when built with OpenMP" % os.cpu_count())


if __name__ == "__main__":
    main()
