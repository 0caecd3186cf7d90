#!/usr/bin/env python3
"""Slider updates of the explorer (python3 -m coatcontact.explore), per slider: the library's
computation behind one move (explore.compute) and matplotlib's redraw of the window (Agg),
timed separately.

For each slider, `--moves` consecutive moves of one grid step up from the start values:
  cold     nothing cached: the model (kernel table and interpolant) or the Maugis-Dugdale
           curve of the new value is built during the move;
  prefetched  as the window works: after each move the background thread builds the
           neighbours of the new position, and the next move comes once it is idle (a user
           pausing between moves); the move then reads the cache.
lambda is timed at lambda = 1 (finite: the Maugis-Dugdale curve is drawn), eta both at
lambda = inf and at lambda = 1, E1/E0 also at eta = 0.1. Medians over the moves, in ms. Rows for bench/run.sh's
results.tsv with --tsv. usage: PYTHONPATH=build/python python3 bench/explore_sliders.py
[--moves N] [--tsv]
"""
import argparse
import math
import statistics
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from coatcontact import explore  # noqa: E402

CASES = [("ratio", {}), ("ratio", {"eta": 0.1}), ("nu1", {}), ("nu0", {}), ("eta", {}), ("eta", {"lam": 1.0}),
         ("lam", {"lam": 1.0}), ("k_bar", {})]


def moves(name, start, count):
    """`count` grid values one step apart, up from the start value of slider `name`."""
    index = explore._grid_index(name, start) if name in explore.GRID else None
    _, lo, hi, _, step, log = explore.SLIDERS[name]
    out, value = [], start
    for i in range(1, count + 1):
        if index is not None:
            value = explore._grid_value(name, index + i)
        else:
            value = 10.0 ** (math.log10(start) + i * step) if log else start + i * step
        out.append(value)
    return out


def wait_idle(limit=60.0):
    end = time.perf_counter() + limit
    while not explore.prefetch_idle():
        if time.perf_counter() > end:
            raise RuntimeError("explore_sliders: the background prefetch did not finish in %g s" % limit)
        time.sleep(0.005)


def run(name, base, count, prefetched):
    """Median compute and draw times [ms] over `count` moves of slider `name` from `base`."""
    explore._models.clear()
    explore._md_curves.clear()
    figure = plt.figure(figsize=(13, 8.5))
    explorer = explore.Explorer(figure, prefetch=prefetched, **base)
    figure.canvas.draw()
    computes, draws = [], []
    for value in moves(name, explorer.params[name], count):
        if prefetched:
            wait_idle()
        params = {**explorer.params, name: value}
        start = time.perf_counter()
        explore.compute(params)
        computed = time.perf_counter()
        explorer.set(**{name: value})   # compute again (now cached) and set the lines
        figure.canvas.draw()
        drawn = time.perf_counter()
        computes.append(1e3 * (computed - start))
        draws.append(1e3 * (drawn - computed))
    wait_idle()
    plt.close(figure)
    return statistics.median(computes), max(computes), statistics.median(draws)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moves", type=int, default=5)
    parser.add_argument("--tsv", action="store_true", help="rows task, median_ms, min, max, runs, kind")
    args = parser.parse_args()
    if not args.tsv:
        print("slider\tat\tcold_compute_ms\tprefetched_compute_ms\tprefetched_max_ms\tdraw_ms")
    for name, base in CASES:
        at = ",".join("%s=%g" % item for item in base.items()) or "start values"
        cold, cold_max, _ = run(name, base, args.moves, False)
        warm, warm_max, draw = run(name, base, args.moves, True)
        if args.tsv:
            task = "explore slider %s (%s)" % (name, at)
            print("%s, compute cold\t%.4g\t\t%.4g\t%d\tpython" % (task, cold, cold_max, args.moves))
            print("%s, compute prefetched\t%.4g\t\t%.4g\t%d\tpython" % (task, warm, warm_max, args.moves))
            print("%s, draw\t%.4g\t\t\t%d\tpython" % (task, draw, args.moves))
        else:
            print("%s\t%s\t%.1f\t%.1f\t%.1f\t%.1f" % (name, at, cold, warm, warm_max, draw))


if __name__ == "__main__":
    main()
