"""coatcontact.afm.fit(..., depth_profile=True) and fit_map's weight_cp= (issue 36 items 4, 5):
the depth profile's keys and its last depth being the whole-range fit, on a synthetic Hertz
approach with heights (the one-curve pipeline); a real JPK curve's profile agrees with the
command line's `afm fit --depth-profile`; fit_map(weight_cp=) gives fit()'s weighted estimate
(one request field, one pipeline)."""
import os
import subprocess

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR, CLI

SPOT = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_spot3-0192.jpk-force")
E_TRUE, ZC, NU, R, K = 5e3, 2e-6, 0.5, 10e-6, 0.05


def synthetic(seed=1, n=400):
    """An approach with heights: F = (4/3) E* sqrt(R) delta^1.5 + noise, height = z - F/k."""
    z = np.linspace(5e-6, 0.0, n)
    F = 4 / 3 * E_TRUE / (1 - NU ** 2) * np.sqrt(R) * np.clip(ZC - z, 0, None) ** 1.5
    F = F + np.random.default_rng(seed).normal(0, 2e-12, n)
    return {"force": F, "height (piezo)": z - F / K, "segment": np.zeros(n, dtype=int),
            "metadata": {"spring constant": K, "path": "synthetic"}}


def test_depth_profile_keys_and_last_depth():
    r = cc.afm.fit(synthetic(), radius=R, halfspace=(1e4, NU), depth_profile=True)
    p = r["depth_profile"]
    for key in ("max_indentation", "E", "E_error", "depth", "flag", "points_in_contact"):
        assert key in p
    assert p["modulus_name"] == "E" and "E_apparent" not in p  # a half-space has no apparent modulus beside it
    n = len(p["depth"])
    assert n == 10 and all(len(p[k]) == n for k in ("max_indentation", "E", "E_error"))
    assert np.all(np.diff(p["depth"]) > 0)
    # The last depth is the whole range: the same fit as without the profile.
    assert p["E"][-1] == pytest.approx(r["estimates"]["E"], rel=1e-12)
    assert p["max_indentation"][-1] == pytest.approx(r["max_indentation"], rel=1e-12)
    # A half-space curve: E at every depth within 3 standard errors of the truth.
    assert np.all(np.abs(p["E"] - E_TRUE) < 3 * p["E_error"])


def test_depth_profile_refuses_arrays_and_adhesive_models():
    c = synthetic()
    z = c["height (piezo)"] + c["force"] / K
    with pytest.raises(ValueError, match="depth_profile"):
        cc.afm.fit((z, c["force"]), radius=R, halfspace=(1e4, NU), depth_profile=True)
    with pytest.raises(ValueError, match="modulus must be free"):
        cc.afm.fit(c, radius=R, halfspace=(1e4, NU), free=("contact_point", "baseline"), depth_profile=True)


def test_depth_profile_agrees_with_the_cli():
    out = subprocess.run([CLI, "afm", "fit", SPOT, "--radius", "5um", "--halfspace", "1kPa,0.5", "--depth-profile"],
                         capture_output=True, text=True, check=True).stdout
    rows = [line.split("\t") for line in out.splitlines() if line and not line.startswith("#")]
    curve = cc.afm.read(SPOT)[0]
    p = cc.afm.fit(curve, radius=5e-6, halfspace=(1e3, 0.5), depth_profile=True)["depth_profile"]
    assert len(rows) == len(p["E"])
    for row, E, dE, d in zip(rows, p["E"], p["E_error"], p["max_indentation"]):
        assert float(row[2]) == pytest.approx(E, rel=1e-12)
        assert float(row[3]) == pytest.approx(dE, rel=1e-12)
        assert float(row[1]) == pytest.approx(d, rel=1e-12)


def test_fit_map_weight_cp_is_fits():
    curves = [synthetic(seed) for seed in (1, 2)]
    rows = cc.afm.fit_map(curves, radius=R, halfspace=(1e4, NU), weight_cp=0.5e-6)
    plain = cc.afm.fit_map(curves, radius=R, halfspace=(1e4, NU))
    for curve, row, unweighted in zip(curves, rows, plain):
        one = cc.afm.fit(curve, radius=R, halfspace=(1e4, NU), weight_cp=0.5e-6)
        assert row["E"] == pytest.approx(one["estimates"]["E"], rel=1e-12)
        assert row["E"] != unweighted["E"]  # the weighting reached the batch
    with pytest.raises(ValueError, match="weight_cp"):
        cc.afm.fit_map(curves, radius=R, halfspace=(1e4, NU), weight_cp=-1.0)


def _pdf_pages(path):
    """Pages of a PDF: its page objects (matplotlib writes them uncompressed)."""
    data = open(path, "rb").read()
    return data.count(b"/Type /Page\n") + data.count(b"/Type /Page ") + data.count(b"/Type /Page/") \
        + data.count(b"/Type /Page>")


def test_fit_map_curve_plots_one_page_per_curve(tmp_path):
    pytest.importorskip("matplotlib")
    map2 = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_map2x2_extracted.jpk-force-map")
    out = tmp_path / "pages.pdf"
    rows = cc.afm.fit_map(map2, radius=5e-6, halfspace=(1e3, 0.5), curve_plots=out)
    assert len(rows) == 4 and _pdf_pages(out) == 4
    # Given curves, one without contact (flagged, no estimates): still one page each.
    flat = synthetic(4)
    flat["force"] = np.random.default_rng(4).normal(0, 2e-12, flat["force"].size)
    flat["height (piezo)"] = np.linspace(5e-6, 0.0, flat["force"].size) - flat["force"] / K
    out2 = tmp_path / "given.pdf"
    rows = cc.afm.fit_map([synthetic(1), flat], radius=R, halfspace=(1e4, NU), curve_plots=str(out2))
    assert list(rows["reason"]) == ["fitted", "no_contact"] and _pdf_pages(out2) == 2
    with pytest.raises(ValueError, match="curve_plots"):
        cc.afm.fit_map(map2, radius=5e-6, halfspace=(1e3, 0.5), curve_plots=tmp_path / "pages.png")
    assert not (tmp_path / "pages.png").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["given.pdf", "pages.pdf"]  # no temporary file left
