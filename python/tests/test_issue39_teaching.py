"""Issue 39 (ready for a paper and a lecture) on the Python side: the README's first call and
the default curves stay inside the model's validity, units as texts, a free-only correlation
matrix keyed by names with a warning above |r| = 0.99, and messages without C names or
17-digit reprs."""
import math
import os
import warnings

import numpy as np
import pytest

import coatcontact as cc

PAIR = dict(film=(1e6, 0.49), substrate=(70e9, 0.22))


def test_regression_default_contact_curve_inside_validity():
    # The README's showcase call: no ValidityWarning, 200 points, a <= 0.1 R, delta <= t, and
    # the curve reaches the pull-off it reports.
    with warnings.catch_warnings():
        warnings.simplefilter("error", cc.ValidityWarning)
        out = cc.contact(**PAIR, radius=2e-3, thickness=50e-6, work=0.04)
    assert out["a"].size == 200
    assert out["a"].max() <= 0.1 * 2e-3 * (1 + 1e-12)
    assert out["delta"].max() <= 50e-6
    assert out["a"].max() >= out["pulloff"]["a_load"]


def test_regression_default_shape_contact_inside_validity():
    with warnings.catch_warnings():
        warnings.simplefilter("error", cc.ValidityWarning)
        out = cc.shape_contact(**PAIR, shape=("sphere", 2e-3), thickness=50e-6, work=0.04)
    assert out["a"].max() <= 0.1 * 2e-3 * (1 + 1e-12)


def test_units_as_text_are_the_si_values():
    a = cc.contact(film=("1MPa", 0.49), substrate=("70GPa", 0.22), radius="2mm", thickness="50um",
                   work="40mJ/m2", a=[1e-5, 2e-5], strict=True)
    b = cc.contact(**PAIR, radius=2e-3, thickness=50e-6, work=0.04, a=[1e-5, 2e-5], strict=True)
    assert np.array_equal(a["F"], b["F"]) and np.array_equal(a["delta"], b["delta"])


def test_unknown_unit_is_a_clear_message():
    with pytest.raises(ValueError, match=r"film E: '1 MPx' is not a pressure.*MPa"):
        cc.Stack(film=("1 MPx", 0.49), substrate="rigid")


def _example_a_F(source):
    data = cc.read_curve(os.path.join(source, "data", "example_a_F.tsv"), "a,F")
    return data["a"], data["F"]


def test_regression_fit_correlation_free_only_keyed_by_name_and_warned(source_dir):
    a, F = _example_a_F(source_dir)
    with pytest.warns(cc.CorrelationWarning, match="correlation (t, E1|E1, t) = "):
        r = cc.fit(a, F, radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22), thickness=50e-6,
                   free=("w", "t", "E1"))
    assert r["free"] == ("w", "t", "E1")
    assert r["correlation"].shape == (3, 3)
    assert np.allclose(np.diag(r["correlation"]), 1.0)
    # The same number as the CLI reports for t-E1 on these data (~0.9996), by name and by index.
    assert abs(r["correlation_by_name"][("t", "E1")]) > 0.99
    assert r["correlation_by_name"][("t", "E1")] == r["correlation"][1, 2]
    assert r["covariance"][0, 0] == pytest.approx(r["errors"]["w"] ** 2)


def test_fit_one_free_parameter_is_quiet(source_dir):
    a, F = _example_a_F(source_dir)
    with warnings.catch_warnings():
        warnings.simplefilter("error", cc.CorrelationWarning)
        r = cc.fit(a, F, radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22), thickness=50e-6)
    assert r["correlation"].shape == (1, 1)


def test_messages_without_c_names_or_long_reprs():
    with pytest.raises(ValueError) as info:
        cc.reduced(film=(1e6, 0.6), substrate=(70e9, 0.22), a_over_t=[1.0])
    text = str(info.value)
    assert "cc_" not in text, text
    assert "0.59999999999999998" not in text, text
    assert cc._plain_message("cc_fit_run: nu = 0.59999999999999998 not allowed") == "nu = 0.6 not allowed"
    assert math.isclose(float(cc._plain_message("1.0000000000000001e-07")), 1e-7)
