#!/usr/bin/env python3
"""Slider updates of the explorer (python3 -m coatcontact.explore), per slider: what a user
waits for after moving a slider -- the slider set (Slider.set_val, what a drag does), the
library's computation and the drawing of the window (Agg) -- timed as one, and the drawing
part of it separately.

For each slider, `--moves` consecutive moves up from the start values:
  first visit   nothing cached: the model (kernel table and interpolant) or the
                Maugis-Dugdale curve of the new value is built during the move;
  one step      as the window works: after each move the background thread builds the
                neighbours of the new position, and the next move comes once it is idle (a
                user pausing between moves); the move reads the cache;
  three steps   the same with jumps of explore.PREFETCH_STEPS grid steps (E1/E0, nu1, nu0:
                the farthest neighbours the background thread builds).
lambda is timed at lambda = 1 (finite: the Maugis-Dugdale curve is drawn), eta both at
lambda = inf and at lambda = 1, E1/E0 also at eta = 0.1. Medians and worst over the moves, in
ms; `full` counts the moves that redrew the whole figure (their axis limits changed) instead
of blitting the changed artists. A last row times the Jupyter widget's update (the same
blitted Agg canvas, smaller, plus its PNG encoding).

Not measured: a GUI backend's event loop and its copy of the blitted region to the screen
(on Agg, canvas.blit does nothing; TkAgg copies the figure's pixels into a Tk photo image),
and in Jupyter the transfer of the PNG to the browser.

Rows for bench/run.sh's results.tsv with --tsv. usage: PYTHONPATH=build/python python3
bench/explore_sliders.py [--moves N] [--tsv]
"""
import argparse
import math
import statistics
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import coatcontact  # noqa: E402
from coatcontact import explore  # noqa: E402

CASES = [("ratio", {}), ("ratio", {"eta": 0.1}), ("nu1", {}), ("nu0", {}), ("eta", {}), ("eta", {"lam": 1.0}),
         ("lam", {"lam": 1.0}), ("k_bar", {})]
MATERIAL = ("ratio", "nu1", "nu0")


def moves(name, start, count, stride):
    """`count` values `stride` grid steps apart, up from the start value of slider `name`."""
    index = explore._grid_index(name, start) if name in explore.GRID else None
    _, lo, hi, _, step, log = explore.SLIDERS[name]
    out, value = [], start
    for i in range(1, count + 1):
        if index is not None:
            value = explore._grid_value(name, index + i * stride)
        else:
            value = 10.0 ** (math.log10(start) + i * stride * step) if log else start + i * stride * step
        out.append(value)
    return out


def wait_idle(limit=120.0):
    end = time.perf_counter() + limit
    while not explore.prefetch_idle():
        if time.perf_counter() > end:
            raise RuntimeError("explore_sliders: the background prefetch did not finish in %g s" % limit)
        time.sleep(0.005)


def clear_caches():
    explore._models.clear()
    explore._md_curves.clear()
    coatcontact._solver.cache_clear()
    coatcontact._model.cache_clear()


def run(name, base, count, prefetched, stride=1):
    """Whole-update and drawing times [ms] of `count` moves of slider `name` from `base`, and
    the number of moves that redrew the whole figure."""
    clear_caches()
    figure = plt.figure(figsize=(13, 8.5))
    explorer = explore.Explorer(figure, prefetch=prefetched, **base)
    drawing = []
    redraw = explorer.redraw

    def timed_redraw():
        start = time.perf_counter()
        redraw()
        drawing.append(1e3 * (time.perf_counter() - start))

    explorer.redraw = timed_redraw
    whole, draws, full = [], [], 0
    slider = explorer.sliders[name]
    for value in moves(name, explorer.params[name], count, stride):
        if prefetched:
            wait_idle()
        position = explore._slider_position(name, value)
        del drawing[:]
        full_before = explorer.full_draws
        start = time.perf_counter()
        slider.set_val(position)   # what a drag does: the slider moves, its callback updates
        whole.append(1e3 * (time.perf_counter() - start))
        draws.append(sum(drawing))
        full += explorer.full_draws - full_before
        assert math.isclose(explorer.params[name], value, rel_tol=1e-12), (name, explorer.params[name], value)
    wait_idle()
    plt.close(figure)
    return whole, draws, full


def run_widget(count):
    """Whole-update times [ms] of the Jupyter widget's figure: blit plus PNG encoding, for
    `count` one-step moves of eta (cached models: the drawing and encoding are timed)."""
    from matplotlib.figure import Figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    figure = Figure(figsize=(12, 5.2), dpi=80)
    canvas = FigureCanvasAgg(figure)
    explorer = explore.Explorer(figure, sliders=False, prefetch=False)
    out = []
    for value in moves("eta", explorer.params["eta"], count, 1):
        start = time.perf_counter()
        explorer.set(eta=value)
        explore.png_of_canvas(canvas)
        out.append(1e3 * (time.perf_counter() - start))
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--moves", type=int, default=5)
    parser.add_argument("--tsv", action="store_true", help="rows task, median_ms, min, max, runs, kind")
    args = parser.parse_args()
    if not args.tsv:
        print("slider\tat\tmoves\tupdate_median_ms\tupdate_max_ms\tdraw_median_ms\tdraw_max_ms\tfull")
    for name, base in CASES:
        at = ",".join("%s=%g" % item for item in base.items()) or "start values"
        kinds = [("first visit", False, 1), ("one step", True, 1)]
        if name in MATERIAL:
            kinds.append(("%d steps" % explore.PREFETCH_STEPS, True, explore.PREFETCH_STEPS))
        for kind, prefetched, stride in kinds:
            whole, draws, full = run(name, base, args.moves, prefetched, stride)
            if args.tsv:
                task = "explore slider %s (%s), %s" % (name, at, kind)
                print("%s, update\t%.4g\t%.4g\t%.4g\t%d\tpython" % (task, statistics.median(whole), min(whole),
                                                                   max(whole), args.moves))
                print("%s, draw (%d of %d full)\t%.4g\t%.4g\t%.4g\t%d\tpython" % (
                    task, full, args.moves, statistics.median(draws), min(draws), max(draws), args.moves))
            else:
                print("%s\t%s\t%s\t%.1f\t%.1f\t%.1f\t%.1f\t%d" % (name, at, kind, statistics.median(whole), max(whole),
                                                               statistics.median(draws), max(draws), full))
    widget = run_widget(args.moves)
    if args.tsv:
        print("explore widget (Jupyter) eta one step, blit and PNG\t%.4g\t%.4g\t%.4g\t%d\tpython" % (
            statistics.median(widget), min(widget), max(widget), args.moves))
    else:
        print("widget\teta, cached\tone step\t%.1f\t%.1f\t\t\t" % (statistics.median(widget), max(widget)))


if __name__ == "__main__":
    main()
