"""The interactive explorer (python3 -m coatcontact.explore), headless: matplotlib's Agg backend
for the window, a real Jupyter kernel (nbclient) for the ipywidgets version. The plotted data
must be the library's own values for the slider settings."""
import math
import os
import subprocess
import sys
import time

import numpy as np
import pytest

matplotlib = pytest.importorskip("matplotlib")
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import coatcontact as cc  # noqa: E402
from coatcontact import explore  # noqa: E402


@pytest.fixture
def window():
    # No background builds: they would run on through the other tests.
    figure = plt.figure(figsize=(13, 8.5))
    yield explore.Explorer(figure, prefetch=False)
    plt.close(figure)


def check_plotted(e, ratio, nu1, nu0, eta, lam, k_bar):
    """The lines of Explorer e against direct library calls for these parameters."""
    stack = cc.Stack(film=(ratio, nu1), substrate=(1.0, nu0))
    curve = cc.adhesive_curve(stack, eta=eta, a_bar=explore.A_BAR)
    x, y = e.lines["coated_a"].get_data()
    np.testing.assert_array_equal(x, curve["a_bar"])
    np.testing.assert_array_equal(y, curve["P"])
    x, y = e.lines["coated_D"].get_data()
    np.testing.assert_array_equal(x, curve["D"])
    po = cc.pulloff(stack, eta=[eta])
    assert e.lines["load_a"].get_data() == ([po["a_bar_load"][0]], [po["P_load"][0]])
    assert e.lines["displacement_D"].get_data() == ([po["D_disp"][0]], [po["P_disp"][0]])
    sp = cc.pulloff_spring(stack, eta=eta, k_bar=[k_bar])
    assert e.lines["spring_D"].get_data() == ([sp["D"][0]], [sp["P"][0]])
    # The spring line through the jump has slope -k_bar.
    xs, ys = e.lines["spring_line_D"].get_data()
    assert (ys[1] - ys[0]) / (xs[1] - xs[0]) == pytest.approx(-k_bar, rel=1e-12)
    if math.isfinite(lam):
        md = cc.maugis_dugdale_pulloff(stack, eta=eta, lambda_=lam)
        assert e.lines["md_load_a"].get_data() == ([md["a_bar_load"]], [md["P_load"]])
        mc = cc.maugis_dugdale_curve(stack, eta=eta, lambda_=lam, a_bar=explore.A_BAR_MD)
        np.testing.assert_array_equal(e.lines["md_a"].get_data()[1], mc["P"])
    else:
        assert len(e.lines["md_a"].get_data()[0]) == 0
    return po


def test_start_values_are_the_library_values(window):
    p = window.params
    assert (p["ratio"], p["eta"], p["lam"]) == (0.1, 1.0, math.inf)
    po = check_plotted(window, 0.1, 0.25, 0.25, 1.0, math.inf, 1.0)
    # A soft film at eta = 1 enhances the load-controlled pull-off beyond JKR's -3/2 (THEORY.md
    # section 6, item 7): the explorer shows a curve that differs from the dashed reference.
    assert po["P_load"][0] < -1.6


def test_set_moves_the_sliders_and_the_curves(window):
    window.set(ratio=10.0, nu1=0.3, nu0=0.2, eta=0.3, lam=1.0, k_bar=0.1)
    check_plotted(window, 10.0, 0.3, 0.2, 0.3, 1.0, 0.1)
    assert window.sliders["ratio"].val == pytest.approx(1.0)
    assert window.sliders["lam"].val == pytest.approx(0.0)
    assert "E1/E0 = 10" in window.title.get_text()


def test_dragging_a_slider_redraws(window):
    # What a drag does: the Slider's value changes and its callback fires.
    # The slider stops on its grid (steps of 0.02 in log10 eta): 0.3 moves to 10^-0.52.
    window.sliders["eta"].set_val(math.log10(0.3))
    assert window.params["eta"] == pytest.approx(10 ** -0.52, rel=1e-11)
    check_plotted(window, 0.1, 0.25, 0.25, window.params["eta"], math.inf, 1.0)
    window.sliders["lam"].set_val(window.sliders["lam"].valmax)   # the top of lambda: JKR
    assert window.params["lam"] == math.inf


def test_a_move_by_one_step_reads_the_prefetched_model(window, monkeypatch):
    # After an update the background thread builds the neighbours on the sliders' grid; a drag
    # by one step lands on that grid value (bit for bit) and draws the library's values for it.
    monkeypatch.setattr(explore, "PREFETCH_STEPS", 1)   # the neighbours checked here, no more
    window.prefetch = True
    window.set(lam=1.0)
    deadline = time.monotonic() + 60
    while not explore.prefetch_idle():
        assert time.monotonic() < deadline, "the prefetch did not finish"
        time.sleep(0.01)
    up = explore._grid_value("ratio", explore._grid_index("ratio", 0.1) + 1)
    assert up == pytest.approx(10 ** -0.95, rel=1e-11)
    assert explore._points._entries[(up, 0.25, 0.25, 1.0)].done()
    assert explore._models._entries[(up, 0.25, 0.25)].done()
    assert explore._md_curves._entries[(0.1, 0.25, 0.25, 1.0, explore._grid_value("lam", 21))].done()
    window.sliders["ratio"].set_val(math.log10(up) + 1e-4)   # a drag a hair off the grid value
    assert window.params["ratio"] == up
    check_plotted(window, up, 0.25, 0.25, 1.0, 1.0, 1.0)


def pixels(figure):
    return np.asarray(figure.canvas.buffer_rgba()).copy()


def test_a_blitted_update_draws_what_a_full_draw_draws(window):
    # An update restores the figure drawn without its animated artists and draws those over
    # it; a full draw must give the same pixels, and a small move must not need one (the axis
    # limits are quantised and stay).
    full = window.full_draws
    window.sliders["eta"].set_val(window.sliders["eta"].val + explore.SLIDERS["eta"][4])
    window.sliders["k_bar"].set_val(window.sliders["k_bar"].val + explore.SLIDERS["k_bar"][4])
    assert window.full_draws == full
    check_plotted(window, 0.1, 0.25, 0.25, window.params["eta"], math.inf, window.params["k_bar"])
    blitted = pixels(window.figure)
    window.figure.canvas.draw()
    assert np.array_equal(blitted, pixels(window.figure))
    # A stiff film moves the limits: a full draw, and again the same pixels as drawing anew.
    window.set(ratio=10.0, lam=1.0)
    assert window.full_draws == full + 1
    assert window.ax_d.get_xlim() == explore.axis_limits(window.data)["D"][0]
    blitted = pixels(window.figure)
    window.figure.canvas.draw()
    assert np.array_equal(blitted, pixels(window.figure))


@pytest.mark.parametrize("mantissa", [1.0, 1.25, 2.5, 8.0])
def test_axis_limits_are_the_next_value_of_the_ladder(mantissa):
    for exponent in (-2, 0, 3):
        x = mantissa * 10.0 ** exponent
        assert explore._nice_above(x) == pytest.approx(x, rel=1e-12)
        above = explore._nice_above(x * 1.001)
        assert above > x and above / x <= 1.26


def test_a_window_that_does_not_block_draws_the_library_values_once_computed():
    # block=False (the window): an update needing a model not built yet returns at once with
    # the previous curves faded, and the setting is drawn when the background thread is done.
    figure = plt.figure(figsize=(13, 8.5))
    try:
        e = explore.Explorer(figure, block=False, prefetch=False)
        e.wait()
        check_plotted(e, 0.1, 0.25, 0.25, 1.0, math.inf, 1.0)
        ratio, nu1 = 0.37, 0.31   # off the grid: built by no other test
        e.set(ratio=ratio, nu1=nu1, lam=0.7)
        assert e.pending and e.title.get_text().startswith("computing E1/E0 = 0.37")
        assert e.data["params"]["ratio"] == 0.1                 # still the previous setting
        assert e.lines["coated_a"].get_alpha() == 0.3
        e.wait()
        assert not e.pending and e.lines["coated_a"].get_alpha() is None
        check_plotted(e, ratio, nu1, 0.25, 1.0, 0.7, 1.0)
        # A much thinner film extends the model's interpolant (hundreds of ms): not waited for
        # either, beyond Explorer.GRACE.
        e.set(eta=0.013, lam=math.inf)
        e.wait()
        check_plotted(e, ratio, nu1, 0.25, 0.013, math.inf, 1.0)
        blitted = pixels(figure)
        figure.canvas.draw()
        assert np.array_equal(blitted, pixels(figure))
    finally:
        plt.close(figure)


def test_a_failed_build_in_the_background_is_shown_and_raised(monkeypatch):
    # A setting the library cannot compute, asked for by a window: the error is the title's,
    # the previous curves stay faded, and wait() raises it.
    figure = plt.figure(figsize=(13, 8.5))
    try:
        e = explore.Explorer(figure, block=False, prefetch=False)
        e.wait()
        build = explore._points._build

        def failing(ratio, nu1, nu0, eta):
            if ratio == 0.41:
                raise cc.NumericalError("no result to tolerance at E1/E0 = 0.41")
            return build(ratio, nu1, nu0, eta)

        monkeypatch.setattr(explore._points, "_build", failing)
        e.set(ratio=0.41)
        with pytest.raises(cc.NumericalError, match="E1/E0 = 0.41"):
            e.wait()
        assert not e.pending and "no result to tolerance" in e.title.get_text()
        assert e.lines["coated_a"].get_alpha() == 0.3
        e.set(ratio=0.1)
        e.wait()
        check_plotted(e, 0.1, 0.25, 0.25, 1.0, math.inf, 1.0)
        assert e.lines["coated_a"].get_alpha() is None
    finally:
        plt.close(figure)


def test_bad_parameter_is_named(window):
    with pytest.raises(ValueError, match=r"eta = 1000 is outside \[0.01, 100\]"):
        window.set(eta=1000)
    with pytest.raises(ValueError, match="unknown parameter 'E1'"):
        explore.check_parameters({"E1": 1})


def run_module(*args, cwd):
    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "coatcontact.explore", *args], capture_output=True,
                          text=True, cwd=cwd, env=env)


def test_command_saves_a_screenshot(tmp_path):
    p = run_module("--set", "ratio=0.1", "--set", "eta=0.3", "--set", "lam=1", "--save", "shot.png", cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    image = plt.imread(str(tmp_path / "shot.png"))
    assert image.shape[0] > 500 and image.shape[1] > 800
    # Not blank: the curves' colours are present.
    assert np.unique(image.reshape(-1, image.shape[2]), axis=0).shape[0] > 50
    # The title (an animated artist, drawn by savefig) is there: dark pixels above the panels.
    assert image[: image.shape[0] // 20, :, :3].min() < 0.3
    assert sorted(os.listdir(tmp_path)) == ["shot.png"]


def test_command_rejects_bad_values(tmp_path):
    p = run_module("--set", "eta=0", "--save", "shot.png", cwd=tmp_path)
    assert p.returncode == 2
    assert "eta = 0 is outside [0.01, 100]" in p.stderr
    assert os.listdir(tmp_path) == []
    p = run_module(cwd=tmp_path)   # Agg: no window to open
    assert p.returncode == 2 and "--save" in p.stderr


def test_jupyter_widget_in_a_kernel(tmp_path):
    """The ipywidgets version inside a real kernel: moving a slider redraws with the library's
    values for the new setting."""
    pytest.importorskip("ipywidgets")
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    from notebook_runner import kernel_for_this_python
    code = "\n".join([
        "import math, coatcontact as cc, coatcontact.explore as ex",
        "w = ex.widget()",
        "before = w.image.value",
        "w.controls['eta'].value = math.log10(0.3)",
        "w.controls['ratio'].value = 1.0",
        "e = w.explorer",
        "assert abs(e.params['eta'] - 10 ** -0.52) < 1e-12 and abs(e.params['ratio'] - 10) < 1e-12, e.params",
        "po = cc.pulloff(film=(e.params['ratio'], 0.25), substrate=(1, 0.25), eta=[e.params['eta']])",
        "assert e.lines['load_a'].get_data()[1][0] == po['P_load'][0]",
        "assert w.image.value != before and w.image.value[:4] == b'\\x89PNG'",
        "print('widget ok', len(w.image.value))",
    ])
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell(code)])
    with kernel_for_this_python() as kernel_name:
        client = nbclient.NotebookClient(nb, timeout=120, kernel_name=kernel_name,
                                         resources={"metadata": {"path": str(tmp_path)}})
        # nbclient 0.7 parses the comm messages of ipywidgets >= 7 only (Debian bookworm has 6);
        # the widget state is not needed here.
        client.comm_open_handlers = {}
        client.store_widget_state = False
        client.execute()
    outputs = nb.cells[0].outputs
    assert any("widget ok" in o.get("text", "") for o in outputs), outputs


def test_legend_names_only_the_curves_drawn_and_sliders_say_log_scale(window):
    """Regression (issue 39): the legend listed the Maugis-Dugdale curve and pull-off while
    lambda = inf draws neither, and a logarithmic slider read "log10 E1/E0" beside the value
    itself (0.1, not -1)."""
    def legend_texts():
        shown = [legend for legend in window.figure.legends if legend.get_visible()]
        assert len(shown) == 1
        return [t.get_text() for t in shown[0].get_texts()]

    assert math.isinf(window.params["lam"])
    assert not any("Maugis" in t for t in legend_texts())
    window.set(lam=1.0)
    assert sum("Maugis" in t for t in legend_texts()) == 2
    window.set(lam=math.inf)
    assert not any("Maugis" in t for t in legend_texts())
    labels = {name: s.label.get_text() for name, s in window.sliders.items()}
    assert labels["ratio"] == "E1/E0 (log scale)" and not any("log10" in t for t in labels.values())
    assert window.sliders["ratio"].valtext.get_text() == "0.1"
