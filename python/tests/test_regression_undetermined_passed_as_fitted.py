"""Regression of issue 36 ("Undetermined results pass as fitted"): a retract that never detaches
and an adhesion w whose standard error exceeds it were rows flagged 0. Python shows the flags
(undetermined, no_detachment, estimates kept), the batch columns rating, tabor_mu,
maugis_lambda and warnings, and sorts by rating (docs/afm.md). The synthetic force is Hertz's
paraboloid written here (THEORY.md section 15)."""
import warnings

import numpy as np
import pytest

import coatcontact as cc

E, NU, R, K, ZC = 1e4, 0.5, 10e-6, 0.05, 1e-6


def hertz(d):
    return np.where(d > 0, 4.0 / 3.0 * E / (1 - NU**2) * np.sqrt(R) * np.clip(d, 0, None) ** 1.5, 0.0)


def curve(sigma, stuck=0.0, dip=0.0, seed=1, n=1000):
    """Approach 3 -> 0.5 um and retract back; the retract past the contact point is `stuck`
    (0: the free cantilever) less `dip` over its first 20 nm, plus Gaussian noise."""
    rng = np.random.default_rng(seed)
    u = np.linspace(0.0, 1.0, n)
    z = np.concatenate([3e-6 - 2.5e-6 * u, 0.5e-6 + 2.5e-6 * u])
    d = ZC - z
    f = hertz(d)
    retract = np.arange(2 * n) >= n
    f = np.where(retract & (d <= 0), stuck, f)
    f = f - np.where(retract & (d <= 0) & (d > -20e-9), dip, 0.0)
    f = f + rng.normal(0.0, sigma, f.size)
    return {"force": f, "height (piezo)": z - f / K, "segment": retract.astype(int)}


F_MAX = float(hertz(ZC - 0.5e-6))


def test_retract_without_detachment_is_flagged():
    rows = cc.afm.fit_map([curve(1e-11, stuck=-0.3 * F_MAX), curve(1e-11)], radius=R, halfspace=(E, NU),
                          segment="retract", spring_constant=K, jobs=1)
    assert list(rows["flag"]) == [11, 0] and list(rows["reason"]) == ["no_detachment", "fitted"]
    assert np.all(np.isfinite(rows["E"])), "the estimates are kept"
    assert "never detached" in rows["warnings"][0] and rows["warnings"][1] == ""
    assert np.all(np.isnan(rows["tabor_mu"])) and np.all(np.isnan(rows["maugis_lambda"])), "Hertz: no mu, lambda"


def test_undetermined_w_is_flagged():
    """JKR with w and the tilt free on a retract whose adhesive dip is 4 noise sigmas: whenever
    w's error exceeds w the curve is undetermined (estimates kept), never fitted."""
    curves = [curve(1e-11, dip=4e-11, seed=s) for s in range(1, 5)]
    rows = cc.afm.fit_map(curves, model="jkr", radius=R, halfspace=(E, NU), spring_constant=K, jobs=1)
    # A draw may be not identifiable at all (no_convergence, 3: no estimates); the others keep theirs.
    kept = np.isin(rows["flag"], (0, 10))
    assert np.all(kept | (rows["flag"] == 3)), rows["reason"]
    loose = kept & (rows["w_error"] > np.abs(rows["w"]))
    assert np.any(loose), "some draw leaves w undetermined"
    assert np.all(rows["flag"][loose] == 10) and np.all(rows["flag"][kept & ~loose] == 0)
    assert all("undetermined: w" in w for w in rows["warnings"][loose])
    assert np.all(np.isfinite(rows["tabor_mu"][kept])) and np.all(np.isfinite(rows["maugis_lambda"][kept]))
    # The one-curve fit says the same, with a RuntimeWarning.
    first = int(np.flatnonzero(loose)[0])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        r = cc.afm.fit(curves[first], model="jkr", radius=R, halfspace=(E, NU), spring_constant=K)
    assert r["flag"] == "undetermined" and any("undetermined: w" in str(c.message) for c in caught)


def test_batch_columns_and_rating_order():
    clean, loud = curve(2e-11, seed=3), curve(2e-10, seed=3)
    rows = cc.afm.fit_map([loud, clean, loud], radius=R, halfspace=(E, NU), spring_constant=K, jobs=1)
    for name in ("rating", "tabor_mu", "maugis_lambda", "warnings"):
        assert name in rows.dtype.names
    assert rows["rating"][1] > rows["rating"][0] == rows["rating"][2] > 0 and rows["rating"][1] <= 10
    ranked = cc.afm.fit_map([loud, clean, loud], radius=R, halfspace=(E, NU), spring_constant=K, jobs=1,
                            sort_by="rating")
    assert list(ranked["curve"]) == [1, 0, 2], "descending, equal ratings in curve order (stable)"
    with pytest.raises(ValueError, match="sort_by: 'chi2' is not allowed"):
        cc.afm.fit_map([clean], radius=R, halfspace=(E, NU), spring_constant=K, sort_by="chi2")
