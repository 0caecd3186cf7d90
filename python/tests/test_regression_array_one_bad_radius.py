"""Issue 29, defect 3: one radius the solver refused (exit 3 at a/t = 262.87 for PDMS on glass)
made `reduced` raise for a whole array and return nothing. The refusals are gone at their root
(the refinement skips an unresolved level, THEORY.md section 6 and docs/solver.md); an array
holding every radius the issue reported, between ordinary ones, returns a value for each, each
within the requested tolerance by its own estimate and within that estimate of an independent
solve of the same radius at a tighter tolerance."""
import numpy as np

import coatcontact as cc

PDMS_ON_GLASS = dict(film=(1e6, 0.49), substrate=(70e9, 0.22))
# The radii of the issue (a 1500-point scan over 1..1000 failed at the last three), between
# neighbours that always passed.
REPORTED = [250.0, 262.87057444622462, 270.0, 564.722, 636.604, 878.947]


def test_regression_array_aborted_by_one_radius():
    r = cc.reduced(**PDMS_ON_GLASS, a_over_t=np.array(REPORTED))
    assert len(r["E_eq"]) == len(REPORTED)
    for name in ("Pi_s", "Delta_s", "E_eq", "Gamma1", "error_estimate"):
        assert np.all(np.isfinite(r[name])), name
    assert np.all(r["error_estimate"] <= 1e-8)
    # Tier: an independent solve at tolerance 1e-10 of the same radii (1e-11 is below the kernel
    # table's own accuracy at these radii, ~2e-11); the default-tolerance
    # values must lie within their own estimates of it (the estimate is an upper bound).
    fine = cc.reduced(**PDMS_ON_GLASS, a_over_t=np.array(REPORTED), tol=1e-10)
    for name in ("Pi_s", "Delta_s", "E_eq", "Gamma1"):
        rel = np.abs(r[name] - fine[name]) / np.abs(fine[name])
        assert np.all(rel <= r["error_estimate"] + fine["error_estimate"]), (name, rel)


def test_regression_array_incompressible_film_on_glass():
    # The second pair, 2 MPa nu = 0.5 on glass, failed near a/t = 717.
    radii = np.linspace(700.0, 735.0, 15) + 0.123
    r = cc.reduced(film=(2e6, 0.5), substrate=(70e9, 0.22), a_over_t=radii)
    assert np.all(np.isfinite(r["E_eq"])) and np.all(r["error_estimate"] <= 1e-8)
