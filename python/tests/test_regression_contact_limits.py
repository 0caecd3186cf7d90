"""Regressions of issue 29 on the Python contact path: tol = 0 was accepted (defect 9), and
cc.contact printed a curve far beyond the model's validity silently (defect 6). The warnings
are the library's (coatcontact/limits.hpp), the same text as the command line's."""
import warnings

import numpy as np
import pytest

import coatcontact as cc

PAIR = dict(film=(1e6, 0.49), substrate=(70e9, 0.22))


@pytest.mark.parametrize("tol", [0.0, -1e-8, 1.0, float("nan")])
def test_regression_python_tol_outside_range(tol):
    with pytest.raises(ValueError, match="tol"):
        cc.contact(**PAIR, radius=2e-3, thickness=50e-6, work=0.05, a=[1e-4], tol=tol)
    with pytest.raises(ValueError, match="tol"):
        cc.reduced(**PAIR, a_over_t=[1.0], tol=tol)


def test_regression_python_contact_validity_warnings():
    # a = 3 mm on a 2 mm sphere, delta ~ 2 mm on a 50 um film: the CLI's `contact` case.
    with pytest.warns(cc.ValidityWarning) as record:
        out = cc.contact(**PAIR, radius=2e-3, thickness=50e-6, work=0.05, a=[1e-4, 1e-3, 3e-3])
    messages = [str(w.message) for w in record]
    assert any("penetration reaches" in m for m in messages), messages
    assert any("past the sphere's own radius" in m for m in messages), messages
    assert np.all(np.isfinite(out["F"]))


def test_regression_python_contact_inside_limits_is_quiet():
    with warnings.catch_warnings():
        warnings.simplefilter("error", cc.ValidityWarning)
        cc.contact(**PAIR, radius=2e-3, thickness=50e-6, work=0.05, a=[1e-5, 2e-5])


def test_regression_python_shape_contact_validity_warnings():
    # The paraboloid of `contact --shape sphere:2mm`, and a cone pushed past a 1 um film.
    with pytest.warns(cc.ValidityWarning) as record:
        cc.shape_contact(**PAIR, shape=("sphere", 2e-3), thickness=50e-6, work=0.05, a=[1e-4, 3e-3])
    assert any("past the sphere's own radius" in str(w.message) for w in record)
    with pytest.warns(cc.ValidityWarning, match="penetration reaches"):
        cc.shape_contact(**PAIR, shape=("cone", 1.22), thickness=1e-6, work=0.05, a=[1e-5, 1e-4])
    with warnings.catch_warnings():
        warnings.simplefilter("error", cc.ValidityWarning)
        cc.shape_contact(**PAIR, shape=("sphere", 2e-3), thickness=50e-6, work=0.05, a=[1e-5, 2e-5])
