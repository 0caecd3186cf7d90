"""coatcontact.afm.fit (THEORY.md section 15): the README's call on the real JPK curve, agreement
with `coatcontact afm fit` (same estimates to the last digit printed), plain arrays and mappings
with the AFM tools' keys, recovery of a synthetic Hertz curve within 3 standard errors, and the
refusals (ValueError naming the keyword and what is allowed); on a coating, the homogeneous limit
(film = substrate) reproduces the half-space fit, and t of a coated curve made by the model comes
back within 3 standard errors."""
import os

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

DATA = os.path.join(SOURCE_DIR, "data", "afm")
SPOT = os.path.join(DATA, "fmt-jpk-fd_spot3-0192.jpk-force")


def header_value(header, key):
    line = [h for h in header if h.startswith(f"# {key}: ")][0]
    return float(line[len(f"# {key}: "):].split()[0])


def test_readme_call():
    curve = cc.afm.read("data/afm/fmt-jpk-fd_spot3-0192.jpk-force" if os.path.exists("data/afm") else SPOT)[0]
    r = cc.afm.fit(curve, model="hertz", radius=10e-6, halfspace=(1e3, 0.5),
                   free=("E", "contact_point", "baseline"), segment="approach")
    E, zc = r["estimates"]["E"], r["estimates"]["contact_point"]
    assert 1e3 < E < 1e5 and r["errors"]["E"] > 0
    approach = curve["tip position"][curve.segment("approach")]
    assert approach.min() < zc < approach.max()
    for key in ("names", "estimates", "errors", "units", "free", "residual_sigma", "chi2", "chi2_per_dof",
                "contact_point", "pulloff", "residual", "F_model", "points"):
        assert key in r, key
    assert r["pulloff"]["F"] < 0  # the retract's adhesion against its free-cantilever baseline
    assert np.allclose(r["residual"], r["F_model"] - r["F"])


def test_agrees_with_cli(cli):
    header, _, _ = cli("afm", "fit", "data/afm/fmt-jpk-fd_spot3-0192.jpk-force", "--radius", "10um",
                       "--halfspace", "1kPa,0.5", "--max-indentation", "100nm")
    r = cc.afm.fit(cc.afm.read(SPOT)[0], radius=10e-6, halfspace=(1e3, 0.5), max_indentation=100e-9)
    assert r["estimates"]["E"] == header_value(header, "E [Pa]")
    assert r["estimates"]["contact_point"] == header_value(header, "contact point [m]")
    assert r["estimates"]["baseline"] == header_value(header, "baseline [N]")
    assert r["chi2"] == header_value(header, "chi2")


def synthetic(seed, E=3e3, zc=2e-6, b=1e-10, sigma=2e-11, R=5e-6, n=800):
    z = np.linspace(4e-6, 0.0, n)
    d = np.clip(zc - z, 0, None)
    F = b + E / (1 - 0.25) * (4 / 3) * np.sqrt(R) * d ** 1.5  # nu = 0.5: E* = E/0.75, Hertz written here
    return z, F + np.random.default_rng(seed).normal(0, sigma, n)


def test_plain_arrays_recover_within_three_standard_errors():
    for seed in range(5):
        z, F = synthetic(seed)
        r = cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), noise=2e-11)
        for name, truth in (("E", 3e3), ("contact_point", 2e-6), ("baseline", 1e-10)):
            assert abs(r["estimates"][name] - truth) < 3 * r["errors"][name], (seed, name)
        assert 0.85 < r["chi2_per_dof"] < 1.15


def test_hertz_free_tilt_recovered():
    """free=("E", "contact_point", "baseline", "tilt"): a tilted baseline (THEORY.md section 15,
    "Free tilt") comes back with E, z_c and b within 3 standard errors."""
    tilt = 2e-4  # N/m: 8e-10 N over the curve, 40 noise sigmas
    for seed in range(4):
        z, F = synthetic(seed)
        F = F + tilt * (z - 2e-6)
        r = cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), noise=2e-11,
                       free=("E", "contact_point", "baseline", "tilt"))
        assert r["names"] == ["E", "contact_point", "baseline", "tilt"] and r["units"]["tilt"] == "N/m"
        for name, truth in (("E", 3e3), ("contact_point", 2e-6), ("baseline", 1e-10), ("tilt", tilt)):
            assert abs(r["estimates"][name] - truth) < 3 * r["errors"][name], (seed, name)
        assert 0.85 < r["chi2_per_dof"] < 1.15


def test_mapping_with_afm_tool_keys():
    z, F = synthetic(7)
    segment = np.zeros(len(z), dtype=int)
    mapping = {"tip position": np.concatenate([z, z[::-1]]), "force": np.concatenate([F, F[::-1] - 5e-10]),
               "segment": np.concatenate([segment, segment + 1])}
    r = cc.afm.fit(mapping, radius=5e-6, halfspace=(1.0, 0.5))
    plain = cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5))
    assert r["estimates"] == plain["estimates"]
    # The pull-off is measured against the retract's own free end (issue 35): this retract is the
    # approach reversed and shifted, with no adhesive dip, so only noise is below its baseline.
    assert r["pulloff"] is not None and -6 * 2e-11 < r["pulloff"]["F"] < 0
    assert r["chi2"] is None  # no heights: no preprocessing noise and none given


def test_refusals():
    z, F = synthetic(1)
    with pytest.raises(ValueError, match="model: 'lj' is not a model; allowed: 'hertz', 'jkr', 'md', 'dmt'"):
        cc.afm.fit((z, F), model="lj", radius=5e-6, halfspace=(1.0, 0.5))
    with pytest.raises(ValueError, match="spring_constant: the dmt model"):
        cc.afm.fit((z, F), model="dmt", radius=5e-6, halfspace=(1.0, 0.5))
    with pytest.raises(ValueError, match="spring_constant: the md model"):
        cc.afm.fit((z, F), model="md", radius=5e-6, halfspace=(1.0, 0.5))
    with pytest.raises(ValueError, match="spring_constant"):
        cc.afm.fit((z, F), model="jkr", radius=5e-6, halfspace=(1.0, 0.5))
    with pytest.raises(ValueError, match="model='jkr' or 'md' only"):
        cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), work=1e-3)
    with pytest.raises(ValueError, match="a coating takes a sphere"):
        cc.afm.fit((z, F), shape=("punch", 1e-6), film=(1e3, 0.5), substrate=(1e9, 0.3), thickness=1e-6)
    with pytest.raises(ValueError, match="one sample"):
        cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), film=(1e3, 0.5), substrate="rigid", thickness=1e-6)
    with pytest.raises(ValueError, match="free: 't' is not a parameter.*allowed: E, contact_point, baseline"):
        cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), free=("E", "t", "contact_point"))
    with pytest.raises(ValueError, match="free: 'w' is not a parameter.*allowed: E, contact_point, baseline"):
        cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), free=("E", "w", "contact_point"))
    with pytest.raises(ValueError, match="segment"):
        cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), segment="side")
    with pytest.raises(cc.NumericalError, match="no contact"):
        cc.afm.fit((z, F), radius=5e-6, halfspace=(1.0, 0.5), free=("E", "baseline"), contact_point=-1e-6)


def test_coating_thickness_recovered():
    """A 2 um film (5 kPa) on 1 MPa: the curve from the library's coating model + noise, t free
    (E1 fixed), back within 3 standard errors; the homogeneous limit (film = substrate) gives
    the half-space fit's contact point and residuals (E fixed) to the table's accuracy."""
    z = np.linspace(4e-6, 0.0, 300)
    # The homogeneous limit: Hertz data, a 'coating' of the same material as its substrate.
    _, F = synthetic(3, E=5e3, R=10e-6, n=300)
    half = cc.afm.fit((z, F), radius=10e-6, halfspace=(5e3, 0.5), free=("contact_point", "baseline"))
    same = cc.afm.fit((z, F), radius=10e-6, film=(5e3, 0.5), substrate=(5e3, 0.5), thickness=2e-6,
                      free=("contact_point", "baseline"))
    assert abs(same["estimates"]["contact_point"] - half["estimates"]["contact_point"]) < 1e-4 * half["errors"]["contact_point"]
    assert abs(same["residual_norm"] / half["residual_norm"] - 1) < 1e-6
    assert same["names"] == ["E1", "t", "contact_point", "baseline"]
    # A real coating: the model curve (t fixed at the truth, all else fixed) plus noise.
    truth = cc.afm.fit((z, F), radius=10e-6, film=(5e3, 0.5), substrate=(1e6, 0.3), thickness=2e-6,
                       free=("baseline",), contact_point=2e-6)
    model = truth["F_model"] - truth["estimates"]["baseline"] + 1e-10
    noisy = model + np.random.default_rng(5).normal(0, 2e-11, len(z))
    r = cc.afm.fit((z, noisy), radius=10e-6, film=(5e3, 0.5), substrate=(1e6, 0.3), thickness=5e-6,
                   free=("t", "contact_point", "baseline"), noise=2e-11)
    assert abs(r["estimates"]["t"] - 2e-6) < 3 * r["errors"]["t"]
    assert abs(r["estimates"]["contact_point"] - 2e-6) < 3 * r["errors"]["contact_point"]


def test_readme_section_runs_and_prints_what_the_cli_prints(cli):
    """The README's "Your AFM data": its Python block runs as printed (from the source folder),
    and the header lines it shows are the ones `afm fit` prints."""
    text = open(os.path.join(SOURCE_DIR, "README.md"), encoding="utf-8").read()
    section = text.split("## Your AFM data", 1)[1].split("\n## ", 1)[0]
    block = section.split("```python\n", 1)[1].split("```", 1)[0]
    here = os.getcwd()
    os.chdir(SOURCE_DIR)
    try:
        scope = {}
        exec(compile(block, "README.md", "exec"), scope)
    finally:
        os.chdir(here)
    E = scope["r"]["estimates"]["E"]
    header, _, _ = cli("afm", "fit", "data/afm/fmt-jpk-fd_spot3-0192.jpk-force", "--radius", "10um",
                       "--halfspace", "1kPa,0.5")
    shown = [line for line in section.splitlines() if line.startswith("# ")]
    assert shown and all(line in header for line in shown), (shown, header)
    assert E == header_value(header, "E [Pa]")


def jkr_retract(seed, R=10e-6, E=100e3, nu=0.5, w=10e-3, k=1.0, zc=1e-6, b=2e-9, m=0.01, sigma=5e-9, n=1500):
    """A retract written here: JKR of a sphere on a half-space, delta(a) = a^2/R - sqrt(2 pi a w/E*),
    F(a) = 4E* a^3/(3R) - sqrt(8 pi w E* a^3), on the branch a >= a_s (minimum of delta + F/k,
    THEORY.md section 10), for a uniform grid of piezo heights; past the jump the tip is off."""
    Es = E / (1 - nu**2)
    a = np.geomspace(1e-8, 12e-6, 200000)
    delta = a**2 / R - np.sqrt(2 * np.pi * a * w / Es)
    force = 4 * Es * a**3 / (3 * R) - np.sqrt(8 * np.pi * w * Es * a**3)
    Z = delta + force / k
    s = int(np.argmin(Z))
    a, delta, force, Z = a[s:], delta[s:], force[s:], Z[s:]
    top = int(np.searchsorted(delta, 1.2e-6))
    h = np.linspace(zc - Z[top], zc + 4e-6, n)
    target = zc - h
    on = target >= Z[0]
    d = np.where(on, np.interp(target, Z, delta), 0.0)
    f = np.where(on, np.interp(target, Z, force), 0.0)
    z = np.where(on, zc - d, h)
    rng = np.random.default_rng(seed)
    return z, f + b + m * (z - zc) + rng.normal(0.0, sigma, n)


def test_jkr_retract_recovered():
    """The adhesive retract fit (model="jkr") recovers E, w, the contact point, the baseline and
    its tilt within 3 standard errors from a JKR retract written here, for three seeds, and
    reports lambda with no warning (a soft adhesive sphere is deep in JKR's range)."""
    truth = {"E": 100e3, "w": 10e-3, "contact_point": 1e-6, "baseline": 2e-9, "tilt": 0.01}
    for seed in (1, 2, 3):
        z, F = jkr_retract(seed)
        r = cc.afm.fit((z, F), model="jkr", radius=10e-6, halfspace=(30e3, 0.5), spring_constant=1.0, noise=5e-9)
        assert r["names"] == ["E", "w", "contact_point", "baseline", "tilt"]
        assert r["units"]["w"] == "J/m2" and r["units"]["tilt"] == "N/m"
        for name, value in truth.items():
            assert abs(r["estimates"][name] - value) < 3 * r["errors"][name], (seed, name, r["estimates"][name])
        assert 0.85 < r["chi2_per_dof"] < 1.15
        assert r["maugis_lambda"] > 5 and r["warnings"] == []
        assert r["jump_off"]["F"] < 0 and r["jump_off"]["indentation"] < 0
    # A long surface-force range puts lambda below 5: a RuntimeWarning naming it.
    with pytest.warns(RuntimeWarning, match="lambda"):
        r = cc.afm.fit((z, F), model="jkr", radius=10e-6, halfspace=(30e3, 0.5), spring_constant=1.0,
                       surface_force_range=200e-9)
    assert r["maugis_lambda"] < 5


def test_jkr_real_retract():
    """The hydrogel retract of the data folder: the JKR fit runs with the file's spring constant,
    reports finite estimates, lambda and the tilt."""
    curve = cc.afm.read(os.path.join(DATA, "fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force"))[0]
    r = cc.afm.fit(curve, model="jkr", radius=10e-6, halfspace=(1e3, 0.5))
    assert r["spring_constant"] == curve.metadata["spring constant"]
    for name in ("E", "w", "contact_point", "baseline", "tilt"):
        assert np.isfinite(r["estimates"][name]) and r["errors"][name] > 0
    assert r["points"] == 3000 and np.isfinite(r["maugis_lambda"])


def test_md_real_retract_jkr_limit(cli):
    """model="md" on the Asylum retract (lambda ~ 400, inside JKR's range): the Maugis-Dugdale fit
    gives JKR's w and E to 1e-4 (the 1/lambda^2 approach and the zone table's ~1e-4, THEORY.md
    section 15), far inside their standard errors; the CLI's header has the same numbers."""
    path = os.path.join(DATA, "fmt-igor-fd_U3_3_p10004.ibw")
    curve = cc.afm.read(path)[0]
    md = cc.afm.fit(curve, model="md", radius=10e-6, halfspace=(10e3, 0.5))
    jkr = cc.afm.fit(curve, model="jkr", radius=10e-6, halfspace=(10e3, 0.5))
    assert md["model"] == "md" and 100 < md["maugis_lambda"] < 1e4
    for name in ("w", "E"):
        assert abs(md["estimates"][name] - jkr["estimates"][name]) < 1e-4 * jkr["estimates"][name], name
        assert abs(md["estimates"][name] - jkr["estimates"][name]) < 0.1 * jkr["errors"][name], name
    header, _, _ = cli("afm", "fit", path, "--model", "md", "--radius", "10um", "--halfspace", "10kPa,0.5")
    assert header_value(header, "w [J/m2]") == md["estimates"]["w"]
    assert header_value(header, "Maugis lambda") == md["maugis_lambda"]
