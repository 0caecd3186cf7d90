"""Interactive explorer of the adhesive contact on a coating: python3 -m coatcontact.explore

A matplotlib window with six sliders -- film over substrate modulus E1/E0, the Poisson ratios
nu1 and nu0, the film thickness eta = t/(pi w R^2/E1*)^(1/3), the Maugis-Dugdale parameter
lambda (top of the slider: infinity, the JKR limit) and the spring stiffness k_bar -- and the
normalized curves P(a_bar) and P(D) (docs/THEORY.md section 5, the paper's [EqSolNormF,
EqSolNormD]) with the pull-offs under load, displacement and spring control (sections 5, 10)
and, for finite lambda, the Maugis-Dugdale curve and its pull-off (section 13). The dashed
curve is JKR on a solid of film material: where the coated curve dips below it, the film
enhances the pull-off.

In Jupyter, `coatcontact.explore.widget()` gives the same plot with ipywidgets sliders (when
ipywidgets is installed). Without a display, `--save FILE.png` draws the window into a file.

    python3 -m coatcontact.explore                       # the window
    python3 -m coatcontact.explore --set ratio=10 --set eta=0.3 --save explorer.png
    python3 -m coatcontact.explore --time                # time one update per slider

Moving eta or k_bar only reads the interpolated reduced variables of the current stack (about
a millisecond); moving E1/E0, nu1 or nu0 builds the kernel table and the interpolant of a new
stack, and a finite lambda solves the cohesive zone at each radius (tens to hundreds of ms).
The sliders stop on a fixed grid of values (their steps), and while the window waits a
background thread builds the models, curves and pull-offs of the grid values up to
PREFETCH_STEPS steps either side for E1/E0, nu1, nu0 and eta (and, with a finite lambda, the Maugis-Dugdale curves of the neighbouring
lambda and eta): such a move then reads a cache. A move to a setting not built yet does not
hold the window: it shows the previous curves faded while a second background thread builds
the new one, then draws it. Drawing blits: only the artists that change are drawn over a kept
copy of the figure (Explorer). Values given to Explorer.set() are used as they are.
`bench/explore_sliders.py` measures the updates.
"""
import argparse
import atexit
import collections
import concurrent.futures
import functools
import math
import os
import queue
import sys
import threading
import time

import numpy as np

from . import AdhesiveModel, Stack, _core, maugis_dugdale_curve, maugis_dugdale_pulloff

#: The sliders: name -> (label, lowest, highest, start, step, logarithmic). Logarithmic
#: sliders move log10 of the value. The top of the lambda slider means lambda = inf (JKR).
SLIDERS = {
    "ratio": ("E1/E0", 0.01, 100.0, 0.1, 0.05, True),
    "nu1": ("ν1", 0.0, 0.5, 0.25, 0.01, False),
    "nu0": ("ν0", 0.0, 0.5, 0.25, 0.01, False),
    "eta": ("η = t/l", 0.01, 100.0, 1.0, 0.02, True),
    "lam": ("λ (Maugis)", 0.1, 100.0, math.inf, 0.05, True),
    "k_bar": ("k̄ (spring)", 0.001, 1000.0, 1.0, 0.05, True),
}
DEFAULTS = {name: spec[3] for name, spec in SLIDERS.items()}
#: Contact radii a_bar of the JKR curves and of the Maugis-Dugdale curve (0: its end, a -> 0).
A_BAR = np.geomspace(1e-3, 3.5, 400)
A_BAR_MD = np.concatenate(([0.0], np.geomspace(0.01, 0.25, 8), np.linspace(0.3, 3.0, 46)))
JKR_LOAD, JKR_DISP = -1.5, -5.0 / 6.0


def _slider_position(name, value):
    """Slider coordinate of a value (log10 for logarithmic sliders; inf -> the top)."""
    _, lo, hi, _, _, log = SLIDERS[name]
    if math.isinf(value):
        value = hi
    return math.log10(value) if log else value


def _slider_value(name, position):
    """The value at a slider coordinate: the inverse of _slider_position. Lambda at the top
    of its slider is inf (JKR)."""
    _, lo, hi, _, step, log = SLIDERS[name]
    if name == "lam" and position >= math.log10(hi) - 1e-9:
        return math.inf
    return 10.0 ** position if log else position


#: Sliders whose values stop on their grid (the models and Maugis-Dugdale curves of these
#: values are cached and built ahead for the neighbours of the current value).
GRID = ("ratio", "nu1", "nu0", "eta", "lam")


def _grid_index(name, value):
    """The index of the grid value of slider `name` nearest to `value` (0 at the bottom)."""
    _, lo, _, _, step, _ = SLIDERS[name]
    return int(round((_slider_position(name, value) - _slider_position(name, lo)) / step))


def _grid_value(name, index):
    """The value at grid index `index` of slider `name`, or None outside the slider. One
    function makes every grid value, so a cached model is found again bit for bit."""
    _, lo, hi, _, step, log = SLIDERS[name]
    position = round(_slider_position(name, lo) + index * step, 10)
    if index < 0 or position > _slider_position(name, hi) + 1e-9:
        return None
    value = _slider_value(name, position)
    if name == "lam" and math.isinf(value):
        return value
    return float("%.12g" % value)


def _snap(name, value):
    """A value of a GRID slider moved onto its grid (lambda = inf stays inf)."""
    if name not in GRID or math.isinf(value):
        return value
    return _grid_value(name, _grid_index(name, value))


def check_parameters(params):
    """The parameters, completed with DEFAULTS; ValueError naming a wrong one and its range."""
    out = dict(DEFAULTS)
    for name, value in params.items():
        if name not in SLIDERS:
            raise ValueError("explore: unknown parameter %r (allowed: %s)" % (name, ", ".join(SLIDERS)))
        value = float(value)
        label, lo, hi = SLIDERS[name][:3]
        if not (lo <= value <= hi or (name == "lam" and value == math.inf)):
            raise ValueError("explore: %s = %g is outside [%g, %g]%s" % (
                name, value, lo, hi, " (or inf)" if name == "lam" else ""))
        out[name] = value
    return out


class _Cache:
    """Results of `build` by key, each computed once: in the caller's thread (get), ahead of
    need in one background thread (prefetch), or on request in a second background thread
    (request: the key wanted now, without waiting for it). A key being built is waited for,
    not built twice. Keeps the `size` most recently used results."""

    def __init__(self, build, size):
        self._build, self._size = build, size
        self._lock = threading.Lock()
        self._entries = collections.OrderedDict()   # key -> concurrent.futures.Future
        self._queue = queue.Queue()
        self._worker = None
        self._wanted = None                          # the latest requested key not yet started
        self._wake = threading.Condition(self._lock)
        self._requester = None
        self._failed = {}                            # key -> the error of its requested build

    def request(self, *key):
        """The result for `key` if it is ready, else None, and then the key is being built:
        by the request thread, which starts on the latest requested key (a request replaces
        one not yet started) while the prefetch thread goes on, or already elsewhere. The
        prefetch keys still waiting are dropped (they were for an earlier position). A failed
        build raises here, as in get()."""
        with self._lock:
            if key in self._failed:   # raised once; a later request builds the key again
                raise self._failed.pop(key)
            future = self._entries.get(key)
            if future is not None:
                self._entries.move_to_end(key)
                if future.done():
                    return future.result()
                return None
            self._wanted = key
            self._wake.notify()
            if self._requester is None:
                self._requester = threading.Thread(target=self._serve_requests, daemon=True,
                                                   name="coatcontact.explore request")
                self._requester.start()
                atexit.register(self.stop)
        self._drain()
        return None

    def _serve_requests(self):
        while True:
            with self._lock:
                while self._wanted is None:
                    self._wake.wait()
                key, self._wanted = self._wanted, None
                if key == ():   # stop()
                    return
                if key in self._entries:
                    continue
                future = self._entries[key] = concurrent.futures.Future()
                self._trim()
            self._run(key, future)
            if future.exception() is not None:
                with self._lock:
                    self._failed[key] = future.exception()

    def get(self, *key):
        with self._lock:
            future = self._entries.get(key)
            mine = future is None
            if mine:
                future = self._entries[key] = concurrent.futures.Future()
                self._trim()
            self._entries.move_to_end(key)
        if mine:
            self._run(key, future)
        return future.result()

    def prefetch(self, keys):
        """Builds `keys` in the background thread, replacing the keys still waiting there
        (those of an earlier position are no longer the neighbours)."""
        self._drain()
        for key in keys:
            self._queue.put(key)
        if self._worker is None:
            self._worker = threading.Thread(target=self._work, name="coatcontact.explore prefetch", daemon=True)
            self._worker.start()
            # At exit: drop the waiting keys and let the thread finish the build in hand (a
            # thread still inside the library while the interpreter ends would abort it).
            atexit.register(self.stop)

    def stop(self):
        """Drops the keys waiting for the background threads and waits for them to end."""
        if self._requester is not None:
            with self._lock:
                self._wanted = ()
                self._wake.notify()
            self._requester.join()
            self._requester = None
        if self._worker is None:
            return
        self._drain()
        self._queue.put(None)
        self._worker.join()
        self._worker = None

    def _drain(self):
        while True:
            try:
                self._queue.get_nowait()
            except queue.Empty:
                return

    def idle(self):
        """True when nothing waits or is being built in the background."""
        with self._lock:
            busy = self._wanted is not None or any(not f.done() for f in self._entries.values())
        return self._queue.empty() and not busy

    def clear(self):
        with self._lock:
            for key in [k for k, f in self._entries.items() if f.done()]:
                del self._entries[key]

    def _work(self):
        while True:
            key = self._queue.get()
            if key is None:
                return
            with self._lock:
                if key in self._entries:
                    continue
                future = self._entries[key] = concurrent.futures.Future()
                self._trim()
            self._run(key, future)

    def _run(self, key, future):
        try:
            future.set_result(self._build(*key))
        except BaseException as error:   # handed to whoever asks for the key
            with self._lock:
                self._entries.pop(key, None)
            future.set_exception(error)

    def _trim(self):
        for key in [k for k, f in self._entries.items() if f.done()][:max(0, len(self._entries) - self._size)]:
            del self._entries[key]


def _stack(ratio, nu1, nu0):
    # Substrate E0 = 1 and film E1 = ratio: every normalized result depends on ratios only.
    return Stack(film=(ratio, nu1), substrate=(1.0, nu0))


def _build_model(ratio, nu1, nu0):
    return AdhesiveModel(_stack(ratio, nu1, nu0), tol=1e-8)


def _build_point(ratio, nu1, nu0, eta):
    """The model of the stack and its JKR curve and pull-offs at one eta. The first call at an
    eta fills the model's interpolant over the radii it needs (built lazily: the costly part,
    most of all for a new stack or a much thinner film)."""
    model = _models.get(ratio, nu1, nu0)
    pulloff = model.pulloff([eta])   # its scan reaches further than the curve's radii
    return model, model.curve(eta, A_BAR), pulloff


def _pulloff_spring(model, eta, k_bar):
    """coatcontact.pulloff_spring on this model: the package's function builds (and caches)
    a model of its own per stack, whose interpolant would cost a second build on a first visit."""
    rows = _core.pulloff_spring(model._core, float(eta), np.atleast_1d(np.asarray(k_bar, dtype=float)))
    return {"P": rows[:, 0], "a_bar": rows[:, 1], "D": rows[:, 2]}


def _build_maugis_dugdale(ratio, nu1, nu0, eta, lam):
    stack = _stack(ratio, nu1, nu0)
    curve = maugis_dugdale_curve(stack, eta=eta, lambda_=lam, a_bar=A_BAR_MD)
    return curve, maugis_dugdale_pulloff(stack, eta=eta, lambda_=lam)


_models = _Cache(_build_model, 48)
_points = _Cache(_build_point, 64)   # each holds its model: a cached point never rebuilds it
_md_curves = _Cache(_build_maugis_dugdale, 64)


def _point(ratio, nu1, nu0, eta):
    return _points.get(ratio, nu1, nu0, eta)


def _maugis_dugdale(ratio, nu1, nu0, eta, lam):
    return _md_curves.get(ratio, nu1, nu0, eta, lam)


#: How many grid steps either side of the current value the background thread builds the
#: models, curves and pull-offs of E1/E0, nu1, nu0 and eta for (nearest first); one step for
#: lambda and eta under a finite lambda (their Maugis-Dugdale curves).
PREFETCH_STEPS = 3


def _neighbours(name, value, steps=1):
    """The grid values within `steps` steps either side of `value` (which may lie between
    two), nearest first."""
    index = _grid_index(name, value)
    out = []
    for i in [index] + [index + sign * d for d in range(1, steps + 1) for sign in (-1, 1)]:
        v = _grid_value(name, i)
        if v is not None and v != value and v not in out and not (name == "lam" and math.isinf(v)):
            out.append(v)
    return out


def prefetch(params):
    """Starts building, in the background, what moves of up to PREFETCH_STEPS grid steps from
    `params` need, nearest first: the models, curves and pull-offs of the neighbouring E1/E0,
    nu1, nu0 and eta and, with a finite lambda, the Maugis-Dugdale curves of the neighbouring
    lambda and eta."""
    p = check_parameters(params)
    point = (p["ratio"], p["nu1"], p["nu0"], p["eta"])
    rings = []   # per slider: its neighbouring keys, nearest first
    for i, name in enumerate(("ratio", "nu1", "nu0", "eta")):
        ring = []
        for v in _neighbours(name, p[name], PREFETCH_STEPS):
            key = list(point)
            key[i] = v
            ring.append(tuple(key))
        rings.append(ring)
    # Interleaved: every slider's nearest neighbours before anybody's second ones.
    keys = [ring[j] for j in range(max(map(len, rings))) for ring in rings if j < len(ring)]
    _points.prefetch(keys)
    if math.isfinite(p["lam"]):
        material = point[:3]
        md = [material + (p["eta"], v) for v in _neighbours("lam", p["lam"])]
        md += [material + (v, p["lam"]) for v in _neighbours("eta", p["eta"])]
        _md_curves.prefetch(md)


def prefetch_idle():
    """True when the background threads have built every neighbour asked for."""
    return _points.idle() and _models.idle() and _md_curves.idle()


def compute(params):
    """Everything the explorer draws for one set of parameters (see SLIDERS), as a dict:
    a_bar, P, D (JKR on the coating), P_jkr, D_jkr (homogeneous JKR, film material),
    pulloff (P, a_bar, D under load, displacement and spring control), and md (curve a_bar,
    P, D and load-controlled pull-off P, a_bar, D) when lambda is finite, else None."""
    p = check_parameters(params)
    model, curve, po = _point(p["ratio"], p["nu1"], p["nu0"], p["eta"])
    sp = _pulloff_spring(model, p["eta"], [p["k_bar"]])
    out = {
        "params": p,
        "a_bar": curve["a_bar"], "P": curve["P"], "D": curve["D"],
        "P_jkr": 4.0 / 3.0 * A_BAR ** 3 - 2.0 * math.sqrt(2.0) * A_BAR ** 1.5,
        "D_jkr": A_BAR ** 2 - np.sqrt(2.0 * A_BAR),
        "pulloff": {
            "load": (float(po["P_load"][0]), float(po["a_bar_load"][0]), float(po["D_load"][0])),
            "displacement": (float(po["P_disp"][0]), float(po["a_bar_disp"][0]), float(po["D_disp"][0])),
            "spring": (float(sp["P"][0]), float(sp["a_bar"][0]), float(sp["D"][0])),
        },
        "md": None,
    }
    if math.isfinite(p["lam"]):
        md_curve, md_pulloff = _maugis_dugdale(p["ratio"], p["nu1"], p["nu0"], p["eta"], p["lam"])
        out["md"] = {"a_bar": md_curve["a_bar"], "P": md_curve["P"], "D": md_curve["D"],
                     "load": (md_pulloff["P_load"], md_pulloff["a_bar_load"], md_pulloff["D_load"])}
    return out


def _format(name, value):
    if name == "lam" and math.isinf(value):
        return "∞ (JKR)"
    return "%.3g" % value


def _setting(p):
    """The parameters as the title shows them."""
    return "E1/E0 = %s, ν1 = %s, ν0 = %s, η = %s, λ = %s, k̄ = %s" % tuple(
        _format(name, p[name]) for name in ("ratio", "nu1", "nu0", "eta", "lam", "k_bar"))


#: Mantissas of the axis limits: a limit is the first of these times a power of ten that holds
#: the data, so that most moves keep the limits and redraw by blitting (see Explorer.redraw).
_NICE = (1.0, 1.25, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0)


def _nice_above(x):
    """The smallest number of the ladder _NICE x 10^k that is >= x > 0."""
    exponent = math.floor(math.log10(x))
    for mantissa in _NICE:
        value = float("%.12g" % (mantissa * 10.0 ** exponent))
        if value >= x:
            return value
    return float("%.12g" % (10.0 ** (exponent + 1)))


def axis_limits(data):
    """The axis limits for the result of compute(): {"a": (xlim, ylim), "D": (xlim, ylim)}.
    P runs from below the lowest pull-off (15 % margin, at least -2.1) to 3; D over the
    curves' part with P <= 3. Each moving limit is rounded outward onto the ladder _NICE."""
    po, md = data["pulloff"], data["md"]
    p_low = min([po["load"][0], po["spring"][0]] + ([md["load"][0]] if md else []))
    bottom = -2.1 if -1.15 * p_low <= 2.1 else -_nice_above(-1.15 * p_low)
    top = 3.0
    d_values = np.concatenate([data["D"][data["P"] <= top], data["D_jkr"][data["P_jkr"] <= top]]
                              + ([md["D"][md["P"] <= top]] if md else []))
    left = -1.5 if 0.1 - d_values.min() <= 1.5 else -_nice_above(0.1 - d_values.min())
    right = 2.0 if d_values.max() <= 2.0 else _nice_above(d_values.max())
    return {"a": ((0.0, 3.0), (bottom, top)), "D": ((left, right), (bottom, top))}


class Explorer:
    """The two panels P(a_bar), P(D) on a matplotlib Figure, redrawn by set(**params).

    Explorer(figure, sliders=True) also puts one matplotlib Slider per parameter under the
    panels (the window of `python3 -m coatcontact.explore`); sliders=False leaves them out
    (the Jupyter widget draws its own). `lines` holds the plotted Line2D objects by name,
    `data` the result of compute() that they show.

    Redrawing blits: what changes from one setting to the next (curves, markers, title, the
    sliders' bars and values) is animated; a full draw of the figure (the first, after a
    resize, or when the axis limits change) keeps a copy of the figure without them, and an
    update restores that copy and draws only the animated artists over it. The limits are
    quantised (axis_limits), so most moves keep them. `full_draws` counts the updates that
    had to redraw the whole figure.

    block=True computes what a setting needs during the update (set() returns with the
    library's values drawn). block=False (the window) never waits for a model or
    Maugis-Dugdale curve not built yet: the update asks a background thread for it, draws
    the previous curves faded under a "computing" title, and a timer of the canvas draws the
    new setting once it is there (`pending` is True meanwhile; wait() does the same without
    an event loop). A drag over settings not visited yet thus stays as quick as the drawing.
    """

    def __init__(self, figure, sliders=True, prefetch=True, block=True, **params):
        self.figure = figure
        self.prefetch = prefetch
        self.block = block
        self.pending = False
        self.error = None   # the library's error for the setting shown (block=False)
        self.params = check_parameters(params)
        bottom = 0.36 if sliders else 0.12
        width = 0.40 if sliders else 0.31   # the widget keeps the right for the legend
        top = 0.88 if sliders else 0.80   # below the two-line title and the panels' own titles
        self.ax_a = figure.add_axes([0.07, bottom, width, top - bottom])
        self.ax_d = figure.add_axes([0.07 + width + 0.09, bottom, width, top - bottom])
        styles = {
            "coated": dict(color="#1f77b4", lw=2.2, label="JKR on the coating"),
            "jkr": dict(color="0.35", lw=1.2, ls="--", label="JKR, solid of film material"),
            "md": dict(color="#ff7f0e", lw=1.8, label="Maugis–Dugdale on the coating (λ)"),
            "load": dict(color="#2ca02c", marker="o", ms=8, ls="none", label="pull-off, load control"),
            "displacement": dict(color="#9467bd", marker="^", ms=8, ls="none", label="pull-off, displacement control"),
            "spring": dict(color="#d62728", marker="s", ms=7, ls="none", label="pull-off through the spring k̄"),
            "md_load": dict(color="#ff7f0e", marker="o", ms=8, ls="none", mfc="none", mew=2,
                            label="Maugis–Dugdale pull-off, load control"),
            "spring_line": dict(color="#d62728", lw=1, ls=":", label="spring line, slope −k̄"),
        }
        self.lines = {}
        for ax, panel in ((self.ax_a, "a"), (self.ax_d, "D")):
            for name in ("jkr", "coated", "md", "load", "displacement", "spring", "md_load"):
                style = dict(styles[name])
                if panel == "D":
                    style.pop("label")
                self.lines[name + "_" + panel], = ax.plot([], [], **style)
            ax.axhline(0.0, color="0.6", lw=0.8)
            ax.grid(True, color="0.92")
            ax.set_ylabel("P = F / (π w R)")
        style = dict(styles["spring_line"])
        self.lines["spring_line_D"], = self.ax_d.plot([], [], **style)
        self.ax_a.set_xlabel("ā = a / (π w R²/E₁*)^(1/3)")
        self.ax_d.set_xlabel("D = δ / (π² w² R/E₁*²)^(1/3)")
        self.ax_a.set_title("force against contact radius")
        self.ax_d.set_title("force against penetration")
        # The legend copies the lines' styles now, before they are made animated (a legend
        # entry copied from an animated line would be animated too, and left out of a draw).
        # Two legends, with and without the Maugis-Dugdale entries: the one shown names only the
        # curves drawn (lambda = inf draws none of them).
        self.legends = {}
        for md_drawn in (False, True):
            names = ("coated", "jkr", "md", "load", "displacement", "spring", "md_load") if md_drawn else \
                ("coated", "jkr", "load", "displacement", "spring")
            handles = [self.lines[n + "_a"] for n in names] + [self.lines["spring_line_D"]]
            if sliders:   # beside the sliders, off the curves
                legend = figure.legend(handles=handles, loc="lower right", bbox_to_anchor=(0.995, 0.01), fontsize=8)
            else:         # the widget has no room below: to the right of the two panels
                legend = figure.legend(handles=handles, loc="center right", fontsize=8)
            legend.set_visible(md_drawn == math.isfinite(self.params["lam"]))
            self.legends[md_drawn] = legend
        # The title belongs to an Axes, not the Figure: a Figure leaves its animated artists
        # out of savefig, an Axes draws them when saving.
        self.title = self.ax_a.text(0.5, 0.98, "", transform=figure.transFigure, ha="center", va="top",
                                    fontsize="large", clip_on=False)
        self.sliders = {}
        if sliders:
            from matplotlib.widgets import Slider
            for i, (name, (label, lo, hi, _, step, log)) in enumerate(SLIDERS.items()):
                ax = figure.add_axes([0.14, 0.25 - 0.04 * i, 0.50, 0.025])
                s = Slider(ax, label + (" (log scale)" if log else ""), _slider_position(name, lo),
                           _slider_position(name, hi), valinit=_slider_position(name, self.params[name]),
                           valstep=step)
                s.valtext.set_text(_format(name, self.params[name]))
                s.drawon = False   # redraw() draws the slider's bar and value, not the whole figure
                s.on_changed(functools.partial(self._moved, name))
                self.sliders[name] = s
        self._animated = list(self.lines.values()) + [self.title]
        for s in self.sliders.values():
            self._animated += [a for a in (s.poly, getattr(s, "_handle", None), s.valtext) if a is not None]
        for artist in self._animated:
            artist.set_animated(True)
        self._background = None   # (canvas size, the figure without its animated artists)
        self._limits = None
        self.full_draws = 0
        figure.canvas.mpl_connect("draw_event", self._drawn)
        self._timer = figure.canvas.new_timer(interval=20)
        self._timer.add_callback(self._poll)
        self.update()

    def _moved(self, name, position):
        value = _snap(name, _slider_value(name, position))
        self.sliders[name].valtext.set_text(_format(name, value))
        if value != self.params[name]:
            self.params[name] = value
            self.update()
        else:
            self.redraw()   # the slider's bar moved within one grid step

    def set(self, **params):
        """Moves the named sliders (values, not slider positions) and redraws once."""
        old = self.params
        self.params = check_parameters({**self.params, **params})
        for name, s in self.sliders.items():
            if self.params[name] == old[name]:
                continue
            s.eventson = False
            s.set_val(_slider_position(name, self.params[name]))
            s.valtext.set_text(_format(name, self.params[name]))
            s.eventson = True
        self.update()

    def update(self):
        """Recomputes (compute()) and redraws the curves, markers, title and, when they
        change, the limits. With block=False and the setting's models not built yet: asks
        for them and draws the previous curves faded (see the class)."""
        if not self.block:
            try:
                ready = self._ready(self.params, self.GRACE)
            except Exception as error:
                self._failed(error)
                return
            if not ready:
                self._show_pending()
                return
        self.error = None
        d = self.data = compute(self.params)
        if self.pending:
            self.pending = False
            self._timer.stop()
        for line in self.lines.values():
            line.set_alpha(None)   # faded while pending or after a failed setting
        p, po = d["params"], d["pulloff"]
        L = self.lines
        L["coated_a"].set_data(d["a_bar"], d["P"])
        L["coated_D"].set_data(d["D"], d["P"])
        L["jkr_a"].set_data(A_BAR, d["P_jkr"])
        L["jkr_D"].set_data(d["D_jkr"], d["P_jkr"])
        for name in ("load", "displacement", "spring"):
            P, a_bar, D = po[name]
            L[name + "_a"].set_data([a_bar], [P])
            L[name + "_D"].set_data([D], [P])
        P_s, _, D_s = po["spring"]
        span = np.array([-0.6, 0.6])
        L["spring_line_D"].set_data(D_s + span, P_s - p["k_bar"] * span)
        md = d["md"]
        if self.legends[md is not None].get_visible() is False:
            self.legends[md is None].set_visible(False)
            self.legends[md is not None].set_visible(True)
            self._background = None   # the legend is part of the background: a full draw
        if md is None:
            for name in ("md_a", "md_D", "md_load_a", "md_load_D"):
                L[name].set_data([], [])
        else:
            L["md_a"].set_data(md["a_bar"], md["P"])
            L["md_D"].set_data(md["D"], md["P"])
            L["md_load_a"].set_data([md["load"][1]], [md["load"][0]])
            L["md_load_D"].set_data([md["load"][2]], [md["load"][0]])
        limits = axis_limits(d)
        if limits != self._limits:
            for ax, panel in ((self.ax_a, "a"), (self.ax_d, "D")):
                ax.set_xlim(*limits[panel][0])
                ax.set_ylim(*limits[panel][1])
            self._limits = limits
            self._background = None   # ticks and grid move: a full draw
        self.title.set_text(
            "%s\npull-off P: load %.4f (JKR −3/2), displacement %.4f (JKR −5/6), spring %.4f%s"
            % (_setting(p), po["load"][0], po["displacement"][0], po["spring"][0],
               ", Maugis–Dugdale (load) %.4f" % md["load"][0] if md else ""))
        self.redraw()
        if self.prefetch:
            prefetch(p)

    #: How long [s] an update of a window (block=False) waits for what it asked the background
    #: for before drawing the previous curves faded: most curves at a new eta of a stack
    #: already built take about a millisecond.
    GRACE = 0.015

    @staticmethod
    def _ready(p, grace=0.0):
        """True when compute(p) reads caches only, at once or within `grace` seconds; else the
        missing models and curves are being built in the background."""
        material = (p["ratio"], p["nu1"], p["nu0"])
        deadline = time.monotonic() + grace
        while True:
            ready = _points.request(*material, p["eta"]) is not None
            if math.isfinite(p["lam"]):
                ready = _md_curves.request(*material, p["eta"], p["lam"]) is not None and ready
            if ready or time.monotonic() >= deadline:
                return ready
            time.sleep(0.001)

    def _show_pending(self):
        self.pending = True
        for line in self.lines.values():
            line.set_alpha(0.3)
        self.title.set_text("computing %s …\n(faded: the curves of the previous setting)" % _setting(self.params))
        self.redraw()
        self._timer.start()

    def _poll(self):
        # The canvas timer's callback while pending: draws the setting once its models are built.
        if not self.pending:
            self._timer.stop()
            return
        try:
            ready = self._ready(self.params)
        except Exception as error:
            self._failed(error)
            return
        if ready:
            self.update()

    def _failed(self, error):
        # A window's setting the library could not compute: its message in the title (not a
        # traceback from a GUI callback), the previous curves faded; wait() raises it.
        self._timer.stop()
        self.pending = False
        self.error = error
        for line in self.lines.values():
            line.set_alpha(0.3)
        self.title.set_text("%s\n%s (faded: the curves of the previous setting)" % (_setting(self.params), error))
        self.redraw()

    def wait(self, timeout=60.0):
        """Polls (as the canvas timer does) until the pending setting is drawn; for a canvas
        without an event loop. Raises the library's error if the setting could not be
        computed, RuntimeError after `timeout` seconds."""
        end = time.monotonic() + timeout
        while self.pending:
            if time.monotonic() > end:
                raise RuntimeError("explore: the setting %r was not computed in %g s" % (self.params, timeout))
            time.sleep(0.002)
            self._poll()
        if self.error is not None:
            error, self.error = self.error, None
            raise error

    def redraw(self):
        """Draws the animated artists over the kept copy of the figure (a full draw when there
        is none, or the canvas changed size) and blits the figure to the screen."""
        canvas = self.figure.canvas
        if self._background is None or self._background[0] != self._canvas_size():
            self.full_draws += 1
            canvas.draw()   # _drawn keeps the copy and draws the animated artists
        else:
            canvas.restore_region(self._background[1])
            self._draw_animated()
        canvas.blit(self.figure.bbox)

    def _canvas_size(self):
        return self.figure.canvas.get_width_height() + (self.figure.dpi,)

    def _draw_animated(self):
        for artist in self._animated:
            self.figure.draw_artist(artist)

    def _drawn(self, event):
        # After every full draw (ours, the window's first, a resize): keep the figure without
        # the animated artists, then draw them. savefig draws them itself (see the title).
        if self.figure.canvas.is_saving():
            return
        self._background = (self._canvas_size(), self.figure.canvas.copy_from_bbox(self.figure.bbox))
        self._draw_animated()


def png_of_canvas(canvas):
    """The pixels of an Agg canvas, as they are (no redraw), as PNG bytes."""
    import io
    from PIL import Image
    buffer = io.BytesIO()
    Image.fromarray(np.asarray(canvas.buffer_rgba())).save(buffer, format="png", compress_level=1)
    return buffer.getvalue()


def widget(**params):
    """The explorer in Jupyter: ipywidgets sliders over a picture of the two panels.

    Returns an ipywidgets.VBox; its attribute `explorer` is the Explorer it redraws (for
    tests: set a slider's value and read explorer.data). Needs ipywidgets (Debian
    python3-ipywidgets); ImportError with that hint otherwise. A move blits the Explorer's
    Agg canvas and sends its pixels as PNG (no redraw of the whole figure).
    """
    try:
        import ipywidgets
    except ImportError:
        raise ImportError("coatcontact.explore.widget needs ipywidgets (Debian: python3-ipywidgets; "
                          "pip: ipywidgets); without it use python3 -m coatcontact.explore") from None
    from matplotlib.figure import Figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    figure = Figure(figsize=(12, 5.2), dpi=80)
    canvas = FigureCanvasAgg(figure)
    explorer = Explorer(figure, sliders=False, **params)
    image = ipywidgets.Image(format="png")

    def draw():
        image.value = png_of_canvas(canvas)

    controls = {}

    def moved(change):
        values = {n: _snap(n, _slider_value(n, c.value)) for n, c in controls.items()}
        for n, c in controls.items():
            c.description = "%s = %s" % (SLIDERS[n][0], _format(n, values[n]))
        explorer.set(**values)
        draw()

    for name, (label, lo, hi, _, step, log) in SLIDERS.items():
        c = ipywidgets.FloatSlider(value=_slider_position(name, explorer.params[name]),
                                   min=_slider_position(name, lo), max=_slider_position(name, hi),
                                   step=step, readout=False, continuous_update=False,
                                   description="%s = %s" % (label, _format(name, explorer.params[name])))
        c.layout.width = "420px"
        c.style = {"description_width": "150px"} if hasattr(c, "style") else None
        c.observe(moved, names="value")
        controls[name] = c
    draw()
    box = ipywidgets.VBox([image] + list(controls.values()))
    box.explorer = explorer
    box.controls = controls
    box.image = image
    return box


def _parse_set(text):
    name, sep, value = text.partition("=")
    if not sep:
        raise ValueError("--set: expected NAME=VALUE, got %r" % text)
    return name.strip(), (math.inf if value.strip() in ("inf", "∞") else float(value))


def _time_updates(explorer):
    """One move per slider to a value not seen before (no cache hit), timed as a whole (the
    library's computation and the drawing) and its drawing alone (bench/explore_sliders.py
    times many moves, and the moves that read the background thread's models)."""
    steps = {"ratio": 0.2, "nu1": 0.3, "nu0": 0.3, "eta": 0.5, "lam": 1.0, "k_bar": 3.0}
    print("explorer update times (one move per slider, from the start values):")
    for name, value in steps.items():
        full = explorer.full_draws
        start = time.perf_counter()
        explorer.set(**{name: value})
        done = time.perf_counter()
        explorer.redraw()
        drawn = time.perf_counter()
        print("  %-6s -> %-6g update %7.1f ms (%s), of which drawing about %5.1f ms"
              % (name, value, 1e3 * (done - start),
                 "axis limits changed: whole figure drawn" if explorer.full_draws > full else "blitted",
                 1e3 * (drawn - done)))
        explorer.set(**{name: DEFAULTS[name]})


def main(argv=None):
    parser = argparse.ArgumentParser(prog="python3 -m coatcontact.explore",
                                     description="Sliders over the adhesive contact of a sphere on a coating "
                                                 "(normalized curves and pull-offs, docs/THEORY.md sections 5, 10, 13).")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="start value of a slider: %s (lam=inf is JKR)" % ", ".join(SLIDERS))
    parser.add_argument("--save", metavar="FILE.png", help="draw the window into FILE.png and exit (no display needed)")
    parser.add_argument("--time", action="store_true", help="time one update per slider and exit")
    args = parser.parse_args(argv)
    try:
        params = check_parameters(dict(_parse_set(s) for s in args.set))
    except ValueError as error:
        print("coatcontact.explore: %s" % error, file=sys.stderr)
        return 2
    import matplotlib
    if args.save or args.time:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    interactive = matplotlib.get_backend().lower() not in ("agg", "pdf", "svg", "ps", "cairo", "template")
    if not (args.save or args.time or interactive):
        print("coatcontact.explore: no interactive matplotlib backend (no display?); "
              "use --save FILE.png, or run with a display", file=sys.stderr)
        return 2
    figure = plt.figure(figsize=(13, 8.5))
    # Models of the neighbouring slider values are built ahead, and models not built yet are
    # waited for in the background, only in a window one can drag.
    window = not (args.save or args.time)
    explorer = Explorer(figure, prefetch=window, block=not window, **params)
    if args.time:
        _time_updates(explorer)
    if args.save:
        # Atomic: a temporary file next to the target, renamed over it.
        temporary = "%s.tmp%d.png" % (args.save, os.getpid())
        try:
            figure.savefig(temporary, dpi=80)
            os.replace(temporary, args.save)
        finally:
            if os.path.exists(temporary):
                os.remove(temporary)
        print("wrote %s" % args.save)
    if not (args.save or args.time):
        plt.show()
    return 0


if __name__ == "__main__":
    sys.exit(main())
