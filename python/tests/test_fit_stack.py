"""fit_stack: any named parameters of a layered coating, over the C API's cc_fit_stack.

The data are exact curves of the package's own SI contact (contact(), the adhesive model's
interpolant), a path independent of the fit's; the fit must give them back."""
import numpy as np
import pytest

import coatcontact as cc

E1, NU, E0 = 1e6, 0.25, 1e7          # Pa
RADIUS, WORK = 1e-3, 0.05            # m, J/m^2
H1, H2, E2 = 1e-5, 2e-5, 4e6         # m, m, Pa: the buried layer of the two-layer stack
POINTS = 40


def exact_curve(layers, thickness):
    c = cc.contact(cc.Stack(layers=layers, substrate=(E0, NU)), radius=RADIUS, thickness=thickness,
                   work=WORK, points=POINTS, tol=1e-10)
    return c["a"], c["F"]


def test_two_layers_recover_w_and_h2():
    a, F = exact_curve([(H1, E1, NU), (H2, E2, NU)], H1 + H2)
    # Start: h2 at half its value, w 30 % high.
    r = cc.fit_stack(a, F, layers=[(H1, E1, NU), (0.5 * H2, E2, NU)], substrate=(E0, NU),
                     radius=RADIUS, work=1.3 * WORK, free="w,h2")
    print("fit_stack w,h2: relative errors w %.2e h2 %.2e"
          % (r["estimates"]["w"] / WORK - 1, r["estimates"]["h2"] / H2 - 1))
    assert r["names"] == ("w", "h1", "h2", "E1", "E2")
    assert r["free"] == ("w", "h2")
    assert isinstance(r["value"], np.ndarray) and r["value"].shape == (5,)
    assert r["estimates"]["w"] == pytest.approx(WORK, rel=1e-6)
    assert r["estimates"]["h2"] == pytest.approx(H2, rel=1e-6)
    # Fixed parameters keep their values exactly and have no error.
    assert r["estimates"]["h1"] == H1 and r["estimates"]["E1"] == E1 and r["estimates"]["E2"] == E2
    assert r["errors"]["h1"] == 0 and r["errors"]["E1"] == 0 and r["errors"]["E2"] == 0
    assert r["errors"]["w"] >= 0 and r["errors"]["h2"] >= 0 and r["residual_sigma"] >= 0
    assert r["units"]["h2"] == "m" and r["units"]["E2"] == "Pa" and r["units"]["w"] == "J/m^2"
    assert r["start"]["h2"] == 0.5 * H2
    # The fitted curve passes through the data.
    assert np.abs(r["residual"]).max() <= 1e-6 * np.abs(F).max()


def test_one_layer_stack_equals_film_fit():
    a, F = exact_curve([(H1, E1, NU)], H1)
    film = cc.fit(a, F, radius=RADIUS, film=(E1, NU), substrate=(E0, NU), thickness=0.7 * H1,
                  work=1.3 * WORK, free=("w", "t"))
    stack = cc.fit_stack(a, F, layers=[(0.7 * H1, E1, NU)], substrate=(E0, NU), radius=RADIUS,
                         work=1.3 * WORK, free=("w", "h1"))
    assert stack["names"] == ("w", "t", "E1") and stack["free"] == ("w", "t")
    for name in ("w", "t", "E1"):
        assert stack["estimates"][name] == film["estimates"][name]
        assert stack["errors"][name] == pytest.approx(film["errors"][name], rel=1e-12, abs=0)
    assert stack["residual_sigma"] == pytest.approx(film["residual_sigma"], rel=1e-12)
    assert stack["estimates"]["w"] == pytest.approx(WORK, rel=1e-6)
    assert stack["estimates"]["t"] == pytest.approx(H1, rel=1e-6)


def test_a_stack_object_is_accepted():
    # w alone (the default) with its start from the pull-off. Noise of 0.1 uN: on the exact
    # curve a w-only fit stops at the right w but reports no convergence (cc.fit too).
    a, F = exact_curve([(H1, E1, NU)], H1)
    F = F + 1e-7 * np.random.default_rng(1).standard_normal(F.size)
    stack = cc.Stack(layers=[(H1, E1, NU)], substrate=(E0, NU))
    r = cc.fit_stack(a, F, stack, radius=RADIUS)
    assert r["free"] == ("w",) and r["estimates"]["t"] == H1
    assert abs(r["estimates"]["w"] - WORK) < 3 * r["errors"]["w"]


def test_bad_arguments_name_themselves():
    a, F = exact_curve([(H1, E1, NU)], H1)
    two = dict(layers=[(H1, E1, NU), (H2, E2, NU)], substrate=(E0, NU), radius=RADIUS, work=WORK)
    with pytest.raises(ValueError, match="free.*'h3'"):
        cc.fit_stack(a, F, free="w,h3", **two)
    with pytest.raises(ValueError, match="free.*'t'"):
        cc.fit_stack(a, F, free=("w", "t"), **two)
    with pytest.raises(ValueError, match="free.*twice"):
        cc.fit_stack(a, F, free="w,w", **two)
    with pytest.raises(ValueError, match="free"):
        cc.fit_stack(a, F, free=(), **two)
    with pytest.raises(ValueError, match="kind"):
        cc.fit_stack(a, F, kind="b", **two)
    with pytest.raises(ValueError, match="^F"):
        cc.fit_stack(a, F[:-1], **two)
    with pytest.raises(ValueError, match="radius"):
        cc.fit_stack(a, F, layers=two["layers"], substrate=(E0, NU), radius=-1e-3)
    with pytest.raises(ValueError, match="work"):
        cc.fit_stack(a, F, layers=two["layers"], substrate=(E0, NU), radius=RADIUS, free="h2")
    with pytest.raises(ValueError, match="layers"):
        cc.fit_stack(a, F, layers=[], substrate=(E0, NU), radius=RADIUS)
    with pytest.raises(ValueError, match="stack"):
        cc.fit_stack(a, F, cc.Stack(layers=two["layers"], substrate=(E0, NU)), substrate=(E0, NU),
                     radius=RADIUS)
    # Two-branch fits are not in the C API: w_load is not a name.
    with pytest.raises(ValueError, match="w_load"):
        cc.fit_stack(a, F, free="w_load,w_unload", **two)


def test_parameter_names():
    assert cc.stack_parameter_names(1) == ("w", "t", "E1")
    assert cc.stack_parameter_names(3) == ("w", "h1", "h2", "h3", "E1", "E2", "E3")
    with pytest.raises(ValueError, match="layers"):
        cc.stack_parameter_names(0)
