"""coatcontact.indent.analyse and film (THEORY.md section 16): Oliver-Pharr on the shared
fused-silica file against the vendor's per-test averages (E within 0.5 %, H within 1 %) and the
CLI's `indent analyse --all`; the film's modulus from synthetic CSM data made here with
coatcontact.reduced's exact E_eq of the stack (diamond tip), per depth and fitted, and its thickness with the modulus given;
every empirical model runs; a layer below the film equal to the substrate changes nothing; bad options raise
ValueError naming the option."""
import os
import subprocess

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

DATA = os.path.join(SOURCE_DIR, "data", "indentation")
XLS = os.path.join(DATA, "FS_Calibration.xls")
DIAMOND = (1141e9, 0.07)


class Synthetic:
    """A CSM test of a film from the exact coated flat-punch stiffness (perfect Berkovich)."""

    def __init__(self, film, thickness, substrate, hc, hardness=8e9, beta=1.0, eps=0.75):
        area = 24.5 * (hc * 1e9) ** 2 * 1e-18
        a = np.sqrt(area / np.pi)
        stack = cc.Stack(film, substrate=substrate, indenter=DIAMOND)
        e_eq = cc.reduced(stack, a_over_t=a / thickness)["E_eq"]
        self.stiffness = 2 * beta * a * stack.reference_modulus * e_eq
        self.load = hardness * area
        self.depth = hc + eps * self.load / self.stiffness
        self.hardness = None
        self.metadata = {"area coefficients": [24.5], "poisson": film[1], "range": None}


def test_analyse_against_the_vendor():
    for t in cc.indent.read(XLS):
        r = cc.indent.analyse(t)
        assert r["E_mean"] == pytest.approx(t.vendor_results["E_mean"], rel=0.005), t.name
        assert r["H_mean"] == pytest.approx(t.vendor_results["H_mean"], rel=0.01), t.name
        assert r["points"] == int(r["in_range"].sum()) > 100
        assert r["E_mean"] == pytest.approx(r["E"][r["in_range"]].mean(), rel=1e-12)


def test_analyse_equals_the_cli():
    cli = os.environ.get("COATCONTACT_CLI")
    if not cli:
        pytest.skip("COATCONTACT_CLI not set")
    out = subprocess.run([cli, "indent", "analyse", XLS, "--all"], check=True, capture_output=True, text=True).stdout
    rows = [line.split("\t") for line in out.splitlines() if not line.startswith("#")]
    for t, row in zip(cc.indent.read(XLS), rows):
        r = cc.indent.analyse(t)
        assert row[0] == t.name
        assert float(row[1]) == pytest.approx(r["E_mean"], rel=1e-15)
        assert float(row[3]) == pytest.approx(r["H_mean"], rel=1e-15)


def test_film_recovers_its_modulus():
    hc = np.linspace(10e-9, 200e-9, 12)
    t = Synthetic((70e9, 0.17), 500e-9, (162e9, 0.22), hc)
    f = cc.indent.film(t, thickness=500e-9, film_poisson=0.17, substrate=(162e9, 0.22))
    assert f["delivered"].all()
    # The roots are interpolated between stacks on a grid of ln E1 (du = 0.05): 1e-6.
    np.testing.assert_allclose(f["E_film"], 70e9, rtol=1e-6)
    assert f["E_film_mean"] == pytest.approx(70e9, rel=1e-6)
    assert f["E_apparent"][-1] > 1.1 * 70e9  # the substrate shows in Oliver-Pharr
    np.testing.assert_allclose(f["a_over_t"], f["contact_radius"] / 500e-9, rtol=1e-15)


def test_layer_equal_to_the_substrate():
    hc = np.linspace(10e-9, 150e-9, 8)
    t = Synthetic((70e9, 0.17), 300e-9, (162e9, 0.22), hc)
    one = cc.indent.film(t, thickness=300e-9, film_poisson=0.17, substrate=(162e9, 0.22))
    two = cc.indent.film(t, thickness=300e-9, film_poisson=0.17, substrate=(162e9, 0.22),
                         layers=[(200e-9, 162e9, 0.22)])
    np.testing.assert_allclose(two["E_film"], one["E_film"], rtol=1e-6)


def test_film_thickness_and_models():
    hc = np.linspace(20e-9, 200e-9, 10)
    t = Synthetic((70e9, 0.17), 500e-9, (162e9, 0.22), hc)
    f = cc.indent.film(t, film_modulus=70e9, film_poisson=0.17, substrate=(162e9, 0.22), thickness=300e-9)
    np.testing.assert_allclose(f["t_film"], 500e-9, rtol=1e-6)
    for model in cc.indent.MODELS[1:]:  # over a range where every model holds (a < t, h_c < t)
        m = cc.indent.film(t, thickness=500e-9, film_poisson=0.17, substrate=(162e9, 0.22), model=model,
                           depth_range=(20e-9, 200e-9))
        assert m["model"] == model and np.isfinite(m["E_film_mean"])


def test_bad_options():
    t = cc.indent.read(XLS)[0]
    with pytest.raises(ValueError, match="beta"):
        cc.indent.analyse(t, beta=-1)
    with pytest.raises(ValueError, match="model"):
        cc.indent.film(t, thickness=1e-6, film_poisson=0.18, substrate=(162e9, 0.22), model="nix")
    with pytest.raises(ValueError, match="area"):
        cc.indent.analyse(t, area="magic")
    with pytest.raises(ValueError, match="substrate"):
        cc.indent.film(t, thickness=1e-6, film_poisson=0.18)
