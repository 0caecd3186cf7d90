"""Every model beyond the paper is reachable from Python, with the numbers of THEORY.md:
stacks of layers (section 12), spring control (section 10), Maugis-Dugdale (section 13) and
indenter shapes (section 11)."""
import math

import numpy as np
import pytest

import coatcontact as cc


def test_stack_of_layers_matches_the_cli(cli):
    """Two layers on a stiff base: the reduced variables equal `coatcontact reduced --layer`."""
    stack = cc.Stack(layers=[(1, 10, 0.3), (2, 1, 0.45)], substrate=(100, 0.2))
    a = np.array([0.01, 1.0, 100.0])
    r = cc.reduced(stack, a_over_t=a)
    _, rows, _ = cli("reduced", "--layer", "1,10,0.3", "--layer", "2,1,0.45", "--substrate", "100,0.2",
                     "--a-over-t", "0.01,1,100")
    for i, row in enumerate(rows):
        assert r["E_eq"][i] == float(row[5])
        assert r["Gamma1"][i] == float(row[6])


def test_sliding_interface_changes_the_answer():
    """A frictionless interface between identical materials is not invisible (section 12)."""
    bonded = cc.reduced(film=(1, 0.3), substrate=(1, 0.3), a_over_t=3.0)
    sliding = cc.reduced(cc.Stack(layers=[(1, 1, 0.3, True)], substrate=(1, 0.3)), a_over_t=3.0)
    assert bonded["E_eq"] == pytest.approx(1.0, rel=1e-12)
    assert abs(sliding["E_eq"] - 1.0) > 1e-3


def test_spring_pulloff_solves_the_jkr_quintic():
    """Homogeneous JKR at k_bar = 1 (section 10): P = -1.410238343649, a_bar = 0.862633136333."""
    r = cc.pulloff_spring(film=(1, 0.25), substrate=(1, 0.25), eta=1.0, k_bar=[0.0, 1.0, math.inf],
                          tol=1e-10)
    assert r["P"][1] == pytest.approx(-1.410238343649, rel=1e-9)
    assert r["a_bar"][1] == pytest.approx(0.862633136333, rel=1e-9)
    assert r["P"][0] == pytest.approx(-1.5, rel=1e-9)       # load control
    assert r["P"][2] == pytest.approx(-5.0 / 6.0, rel=1e-9)  # displacement control


def test_maugis_dugdale_pulloff_homogeneous():
    """Maugis (1992): -1.60073 at lambda = 1 (section 13)."""
    r = cc.maugis_dugdale_pulloff(film=(1, 0.25), substrate=(1, 0.25), eta=1.0, lambda_=1.0)
    assert r["P_load"] == pytest.approx(-1.60073, abs=5e-6)
    assert r["m_load"] > 1.0
    curve = cc.maugis_dugdale_curve(film=(1, 0.25), substrate=(1, 0.25), eta=1.0, lambda_=1.0,
                                    a_bar=[0.0, 0.5, 1.0])
    assert math.isinf(curve["m"][0]) and np.all(np.isfinite(curve["P"]))


@pytest.mark.parametrize("film, lam", [((0.1, 0.25), 0.3), ((0.1, 0.25), 3.0), ((10.0, 0.25), 1.0)])
def test_maugis_dugdale_pulloff_table_within_its_estimate_of_the_direct_solve(film, lam):
    """Section 13 "Checks": the pull-off from the reduced table of the cohesive zone (the
    default) lies within its error estimate (plus the direct solve's) of the direct solve
    (direct_solve=True); the estimates are the table's (above the direct solve's ~1e-11) and
    informative, below 5 % of the value (measured at pull-offs: estimates 2.7e-5 to 1.2e-2
    relative, errors at most 3.4e-4 relative; tests/capi/test_capi.c)."""
    stack = cc.Stack(film=film, substrate=(1.0, 0.25))
    table = cc.maugis_dugdale_pulloff(stack, eta=1.0, lambda_=lam)
    direct = cc.maugis_dugdale_pulloff(stack, eta=1.0, lambda_=lam, direct_solve=True)
    assert abs(table["P_load"] - direct["P_load"]) <= table["P_load_err"] + direct["P_load_err"]
    assert abs(table["D_disp"] - direct["D_disp"]) <= table["D_disp_err"] + direct["D_disp_err"]
    assert direct["P_load_err"] < table["P_load_err"] < 0.05 * abs(table["P_load"])
    assert 0.0 < direct["D_disp_err"] < table["D_disp_err"] < 0.05 * abs(table["D_disp"])
    assert table["end_of_curve"] == direct["end_of_curve"]
    # Every value carries its estimate (the minimum's location included): under load control,
    # an interior minimum in these cases, a_bar, D and m lie within theirs.
    for key in ("a_bar_load", "D_load", "m_load"):
        assert 0.0 < table[key + "_err"]
        assert abs(table[key] - direct[key]) <= table[key + "_err"] + direct[key + "_err"]


def test_paraboloid_shape_equals_the_sphere():
    """Section 11: the shape path of a paraboloid reproduces the sphere's pull-off."""
    film, substrate = (1e6, 0.25), (1e7, 0.25)
    sphere = cc.contact(film=film, substrate=substrate, radius=1e-3, thickness=1e-5, work=0.05)
    shaped = cc.shape_contact(film=film, substrate=substrate, shape=("sphere", 1e-3), thickness=1e-5,
                              work=0.05, points=20)
    assert shaped["pulloff"]["F_load"] == pytest.approx(sphere["pulloff"]["F_load"], rel=1e-7)
    assert np.all(np.isfinite(shaped["F"])) and np.all(shaped["F_H"] >= shaped["F"])


def test_bad_shape_raises():
    with pytest.raises(ValueError, match="half included angle"):
        cc.shape_contact(film=(1e6, 0.3), substrate=(1e9, 0.3), shape=("cone", 2.0), thickness=1e-6,
                         work=0.05)
