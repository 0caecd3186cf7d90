#!/usr/bin/env python3
"""Slider updates of the explorer (python3 -m coatcontact.explore), per slider: what a user
waits for after moving a slider -- the slider set (Slider.set_val, what a drag does), the
library's computation and the drawing of the window (Agg) -- timed as one, and the drawing
part of it separately.

For each slider, `--moves` consecutive moves up from the start values:
  first visit, blocking  nothing cached, Explorer(block=True) (set(), --time, the Jupyter
                widget): the model (kernel table and interpolant) or the Maugis-Dugdale curve
                of the new value is built during the move;
  first visit, window    nothing cached, Explorer(block=False) (the window): the move asks the
                background for the model and draws the previous curves faded; `exact` is the
                time until the new setting is drawn (polled as the window's timer does);
  one step      the window: after each move the background thread builds the neighbours of
                the new position, and the next move comes once it is idle (a user pausing
                between moves); the move reads the cache;
  N steps       the same with jumps of explore.PREFETCH_STEPS grid steps (E1/E0, nu1, nu0:
                the farthest neighbours the background thread builds).
lambda is timed at lambda = 1 (finite: the Maugis-Dugdale curve is drawn), eta both at
lambda = inf and at lambda = 1, E1/E0 also at eta = 0.1. Medians and worst over the moves, in
ms of wall time, and the median CPU time of the update: of the main thread (Python,
matplotlib; the drawing) and of the whole process (with the library's OpenMP threads, and
any background build running meanwhile). On a machine shared with other work the wall time
is the longer; `full` counts the moves that redrew the whole figure
(their axis limits changed) instead of blitting the changed artists. A last row times the
Jupyter widget's update (the same blitted Agg canvas, smaller, plus its PNG encoding).

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
    explore._points.clear()
    explore._md_curves.clear()
    coatcontact._solver.cache_clear()
    coatcontact._model.cache_clear()


def run(name, base, count, prefetched, stride=1, block=False):
    """Times of `count` moves of slider `name` from `base` [ms]: whole update (wall), its
    CPU time in this thread, its drawing, the time until the setting is drawn exactly, and
    the number of moves that redrew the whole figure."""
    clear_caches()
    figure = plt.figure(figsize=(13, 8.5))
    explorer = explore.Explorer(figure, prefetch=prefetched, block=block, **base)
    explorer.wait()
    drawing = []
    redraw = explorer.redraw

    def timed_redraw():
        start = time.perf_counter()
        redraw()
        drawing.append(1e3 * (time.perf_counter() - start))

    explorer.redraw = timed_redraw
    out = {"update": [], "cpu": [], "cpu_all": [], "draw": [], "exact": [], "full": 0}
    slider = explorer.sliders[name]
    for value in moves(name, explorer.params[name], count, stride):
        if prefetched:
            wait_idle()
        position = explore._slider_position(name, value)
        del drawing[:]
        full_before = explorer.full_draws
        start, cpu, cpu_all = time.perf_counter(), time.thread_time(), time.process_time()
        slider.set_val(position)   # what a drag does: the slider moves, its callback updates
        out["update"].append(1e3 * (time.perf_counter() - start))
        out["cpu"].append(1e3 * (time.thread_time() - cpu))
        out["cpu_all"].append(1e3 * (time.process_time() - cpu_all))
        out["draw"].append(sum(drawing))
        explorer.wait()
        out["exact"].append(1e3 * (time.perf_counter() - start))
        out["full"] += explorer.full_draws - full_before
        assert math.isclose(explorer.data["params"][name], value, rel_tol=1e-12), (name, explorer.params[name], value)
    wait_idle()
    plt.close(figure)
    return out


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
    med = statistics.median
    if not args.tsv:
        print("slider\tat\tmoves\tupdate_median_ms\tupdate_max_ms\tcpu_main_median_ms\tcpu_all_median_ms\t"
              "draw_median_ms\tdraw_max_ms\tfull\texact_median_ms\texact_max_ms")
    for name, base in CASES:
        at = ",".join("%s=%g" % item for item in base.items()) or "start values"
        kinds = [("first visit, blocking", False, 1, True), ("first visit, window", False, 1, False),
                 ("one step", True, 1, False)]
        if name in MATERIAL:
            kinds.append(("%d steps" % explore.PREFETCH_STEPS, True, explore.PREFETCH_STEPS, False))
        for kind, prefetched, stride, block in kinds:
            r = run(name, base, args.moves, prefetched, stride, block)
            if args.tsv:
                task = "explore slider %s (%s), %s" % (name, at, kind)
                for column, label in (("update", "update"), ("cpu", "update, CPU of the main thread"),
                                      ("cpu_all", "update, CPU of the process"),
                                      ("draw", "draw"), ("exact", "until drawn exactly")):
                    if column == "exact" and kind != "first visit, window":
                        continue
                    v = r[column]
                    print("%s, %s\t%.4g\t%.4g\t%.4g\t%d\tpython" % (task, label, med(v), min(v), max(v), args.moves))
                print("%s, moves that redrew the whole figure (a count, not ms)\t%d\t\t\t%d\tpython"
                      % (task, r["full"], args.moves))
            else:
                print("%s\t%s\t%s\t%.1f\t%.1f\t%.1f\t%.1f\t%.1f\t%.1f\t%d\t%.1f\t%.1f" % (
                    name, at, kind, med(r["update"]), max(r["update"]), med(r["cpu"]), med(r["cpu_all"]), med(r["draw"]),
                    max(r["draw"]), r["full"], med(r["exact"]), max(r["exact"])))
    widget = run_widget(args.moves)
    if args.tsv:
        print("explore widget (Jupyter) eta one step, blit and PNG\t%.4g\t%.4g\t%.4g\t%d\tpython" % (
            med(widget), min(widget), max(widget), args.moves))
    else:
        print("widget\teta, cached\tone step\t%.1f\t%.1f" % (med(widget), max(widget)))


if __name__ == "__main__":
    main()
