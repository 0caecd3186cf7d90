"""The peers' adhesionless AFM models through coatcontact.afm.fit (THEORY.md section 15):
shape=("pyramid3", theta) and ("sneddon-sphere", R) and weight_cp= against nanite's formulas
written here (hertz_pyr3s, sneddon_spher, weight.weight_cp): a noise-free synthetic curve of
each comes back to its truth, a weighted fit solves nanite's weighted normal equations, and
the CLI's --shape/--weight-cp give the Python estimates on the real spot3 curve."""
import os

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

SPOT = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_spot3-0192.jpk-force")
E_TRUE, ZC, B, NU = 5e3, 0.3e-6, 1e-10, 0.5


def pyr3(alpha, d):  # nanite hertz_pyr3s per E/(1 - nu^2)
    return 0.8887 * np.tan(alpha) * d ** 2


def sphere(R, d):  # nanite sneddon_spher per E/(1 - nu^2): invert delta(a) by bisection on a in (0, R)
    lo, hi = np.zeros_like(d), np.full_like(d, R * (1 - 1e-12))
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        low = mid / 2 * np.log((R + mid) / (R - mid)) < d
        lo, hi = np.where(low, mid, lo), np.where(low, hi, mid)
    a = 0.5 * (lo + hi)
    return np.where(d > 0, (R ** 2 + a ** 2) / 2 * np.log((R + a) / (R - a)) - a * R, 0.0)


def curve(g):
    z = np.linspace(1e-6, -2e-6, 600)
    return z, B + E_TRUE / (1 - NU ** 2) * g(np.clip(ZC - z, 0, None))


@pytest.mark.parametrize("shape,g", [(("pyramid3", np.radians(35)), lambda d: pyr3(np.radians(35), d)),
                                     (("sneddon-sphere", 5e-6), lambda d: sphere(5e-6, d))])
@pytest.mark.parametrize("weight_cp", [None, 0.5e-6])
def test_noise_free_curve_returns_the_truth(shape, g, weight_cp):
    z, F = curve(g)
    r = cc.afm.fit((z, F), shape=shape, halfspace=(1.0, NU), weight_cp=weight_cp)
    assert r["estimates"]["E"] == pytest.approx(E_TRUE, rel=1e-6)  # z_c to ~sqrt(eps): see the C++ test
    assert r["estimates"]["contact_point"] == pytest.approx(ZC, abs=1e-12)
    # The model force at the truth is nanite's to 1e-10 (the bisection above is to ~1e-16 in a).
    assert np.allclose(r["F_model"], F, rtol=1e-6, atol=1e-6 * F.max())


def test_weighted_fit_solves_nanites_weighted_problem():
    z, F = curve(lambda d: sphere(5e-6, d))
    F = F + np.random.default_rng(3).normal(0, 2e-10, F.size)
    r = cc.afm.fit((z, F), shape=("sneddon-sphere", 5e-6), halfspace=(1.0, NU), weight_cp=0.5e-6)
    plain = cc.afm.fit((z, F), shape=("sneddon-sphere", 5e-6), halfspace=(1.0, NU))
    E, zc, b = (r["estimates"][k] for k in ("E", "contact_point", "baseline"))
    w = np.minimum(np.abs(z - zc) / 0.5e-6, 1.0)  # nanite weight.weight_cp
    g = sphere(5e-6, np.clip(zc - z, 0, None))
    res = F - b - E / (1 - NU ** 2) * g
    assert abs(np.sum(w ** 2 * res * g)) < 1e-8 * np.sum(np.abs(w ** 2 * F * g))
    assert abs(np.sum(w ** 2 * res)) < 1e-8 * np.sum(np.abs(w ** 2 * F))
    assert r["estimates"]["E"] != pytest.approx(plain["estimates"]["E"], rel=1e-6)


def test_refusals():
    z, F = curve(lambda d: pyr3(0.6, d))
    with pytest.raises(ValueError, match="pyramid3"):
        cc.afm.fit((z, F), shape=("pyramid3", 1.0, 2.0), halfspace=(1.0, NU))
    with pytest.raises(ValueError, match="weighting"):
        cc.afm.fit((z, F), shape=("pyramid3", 0.6), halfspace=(1.0, NU), weight_cp=1e-7,
                   free=("E", "contact_point", "baseline", "tilt"))


def test_cli_agrees_on_spot3(cli):
    for spec, shape in (("sneddon-sphere:10um", ("sneddon-sphere", 10e-6)), ("pyramid3:35deg", ("pyramid3", np.radians(35)))):
        header, _, _ = cli("afm", "fit", "data/afm/fmt-jpk-fd_spot3-0192.jpk-force", "--shape", spec,
                           "--halfspace", "1kPa,0.5", "--weight-cp", "500nm")
        r = cc.afm.fit(cc.afm.read(SPOT)[0], shape=shape, halfspace=(1e3, 0.5), weight_cp=500e-9)
        line = [h for h in header if h.startswith("# E [Pa]: ")][0]
        assert r["estimates"]["E"] == pytest.approx(float(line.split(": ")[1].split()[0]), rel=1e-12)


def paraboloid(R, d):  # nanite hertz_paraboloidal per E/(1 - nu^2)
    return 4.0 / 3.0 * np.sqrt(R) * d ** 1.5


@pytest.mark.parametrize("shape,g,weight_cp", [
    (("pyramid3", np.radians(35)), lambda d: pyr3(np.radians(35), d), None),
    (("sneddon-sphere", 5e-6), lambda d: sphere(5e-6, d), None),
    (("sphere", 5e-6), lambda d: paraboloid(5e-6, d), 500e-9),  # the paraboloid tip
])
def test_spot3_estimates_are_nanites_optimum(shape, g, weight_cp):
    """On the real spot3 approach (the offset baseline, nanite's convention), our estimates are
    the optimum of nanite's own residuals (model.residuals.residual: force - model, times
    compute_contact_point_weights at the trial contact point): the weighted normal equations in
    E and b hold, and moving the contact point by 0.1 nm either way (a third of its standard
    error) with E and b re-solved raises nanite's weighted sum of squares."""
    r = cc.afm.fit(SPOT, shape=shape, halfspace=(1e3, NU), baseline_model="offset", weight_cp=weight_cp)
    z, F = np.asarray(r["tip_position"]), np.asarray(r["F"])

    def solved(zc):  # nanite's weighted problem at a fixed contact point: linear in (E*, b)
        w = np.ones_like(z) if weight_cp is None else np.minimum(np.abs(z - zc) / weight_cp, 1.0)
        gz = g(np.clip(zc - z, 0, None))
        scale = np.array([gz.max(), 1.0])  # columns of one magnitude for lstsq's cut-off
        A = np.column_stack([gz, np.ones_like(z)]) * w[:, None] / scale
        x, *_ = np.linalg.lstsq(A, F * w, rcond=None)
        return x / scale, np.sum((F * w - A @ x) ** 2)

    E, zc, b = (r["estimates"][k] for k in ("E", "contact_point", "baseline"))
    x, rss = solved(zc)
    assert x[0] * (1 - NU ** 2) == pytest.approx(E, rel=1e-9)
    assert x[1] == pytest.approx(b, rel=1e-9)
    assert solved(zc - 1e-10)[1] > rss and solved(zc + 1e-10)[1] > rss


def test_fit_reads_a_path_of_one_curve():
    from_path = cc.afm.fit(SPOT, radius=5e-6, halfspace=(1e3, NU))
    from_curve = cc.afm.fit(cc.afm.read(SPOT)[0], radius=5e-6, halfspace=(1e3, NU))
    assert from_path["estimates"] == from_curve["estimates"]
    with pytest.raises(ValueError, match="holds 4 curves"):
        cc.afm.fit(os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_map2x2_extracted.jpk-force-map"),
                   radius=5e-6, halfspace=(1e3, NU))
    with pytest.raises(TypeError, match="a float is not allowed"):
        cc.afm.fit(3.0, radius=5e-6, halfspace=(1e3, NU))
