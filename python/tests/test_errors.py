"""Errors become exceptions: ValueError with the library's message (the text the CLI prints
after the option names), NumericalError for a tolerance that cannot be met; never a crash,
never NaN."""
import numpy as np
import pytest

import coatcontact as cc

SOFT = dict(film=(0.1, 0.25), substrate=(1, 0.25))


def cli_message(stderr):
    # "coatcontact CMD: error: OPTIONS: MESSAGE" or "coatcontact CMD: numerical failure: MESSAGE"
    return stderr.splitlines()[-1]


def test_value_error_has_the_cli_message(cli):
    _, _, stderr = cli("sphere", "--radius", "1mm", "--thickness", "1000m", "--film", "1MPa,0.49",
                       "--substrate", "10MPa,0.49", "--work", "50mJ/m2", expect=2)
    with pytest.raises(ValueError) as e:
        cc.contact(film=(1e6, 0.49), substrate=(1e7, 0.49), radius=1e-3, thickness=1000.0, work=0.05)
    assert str(e.value) and cli_message(stderr).endswith(": " + str(e.value))


def test_numerical_error_has_the_cli_message(cli):
    # a/t = 1e6 at 1e-13: the discretization error stays near 1.5e-12.
    _, _, stderr = cli("reduced", "--film", "0.1,0.25", "--substrate", "1,0.25", "--a-over-t", "1e6",
                       "--tol", "1e-13", expect=3)
    with pytest.raises(cc.NumericalError) as e:  # strict: the first radius that fails fails the call
        cc.reduced(**SOFT, a_over_t=[1.0, 1e6], tol=1e-13, strict=True)
    assert isinstance(e.value, RuntimeError)
    assert cli_message(stderr) == "coatcontact reduced: numerical failure: " + str(e.value)


@pytest.mark.parametrize("kwargs,words", [
    (dict(film=(-1, 0.25), substrate=(1, 0.25), a_over_t=1), "Young's modulus"),
    (dict(film=(0.1, 0.6), substrate=(1, 0.25), a_over_t=1), "Poisson ratio"),
    (dict(film=(0.1, 0.25), substrate=(1, 0.25), indenter=(1, 0.6), a_over_t=1), "Poisson ratio"),
    (dict(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=0), "a/t 0 is not allowed"),
    (dict(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=1e9), "a/t"),
    (dict(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=np.nan), "a/t"),
    (dict(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=1, tol=1e-14), "tolerance"),
    (dict(film=(np.inf, 0.25), substrate=(1, 0.25), a_over_t=1), "Young's modulus"),
    (dict(film=(0.1, 0.25), substrate="steel", a_over_t=1), "rigid"),
    (dict(substrate=(1, 0.25), a_over_t=1), "film"),
    (dict(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=["x"]), None),
])
def test_bad_reduced_input(kwargs, words):
    with pytest.raises(ValueError) as e:
        cc.reduced(**kwargs)
    if words:
        assert words in str(e.value)


def test_bad_stack():
    with pytest.raises(ValueError, match="thickness"):
        cc.Stack(layers=[(1, 0.1, 0.25), (0, 1, 0.25)], substrate=(1, 0.25))
    with pytest.raises(ValueError, match="slip"):
        cc.Stack(layers=[(1, 0.1, 0.25, True, 3)], substrate=(1, 0.25))
    with pytest.raises(ValueError):
        cc.Stack(film=(0.1, 0.25))


def test_bad_adhesive_input():
    with pytest.raises(ValueError, match="eta"):
        cc.pulloff(**SOFT, eta=[1, -1])
    with pytest.raises(ValueError):
        cc.adhesive_curve(**SOFT, eta=1, a_bar=[0.5, -1])
    with pytest.raises(ValueError):
        cc.contact(**SOFT, radius=-1e-3, thickness=1e-6, work=0.05)
    with pytest.raises(ValueError):
        cc.contact(**SOFT, radius=1e-3, thickness=1e-6, work=0.05, points=0)


def test_bad_fit_input():
    a = np.linspace(1e-4, 2e-4, 10)
    with pytest.raises(ValueError):
        cc.fit(a, np.ones(9), radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22), thickness=5e-5)
    with pytest.raises(ValueError, match="free"):
        cc.fit(a, np.ones(10), radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22), thickness=5e-5,
               free=("w", "R"))
    with pytest.raises(ValueError):
        cc.fit(-a, np.ones(10), radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22), thickness=5e-5)


def test_fit_of_unrelated_data_is_a_numerical_error():
    # A straight line is no JKR curve: R^2 < 0.5 or no convergence, reported, not returned.
    a = np.linspace(1e-4, 2e-4, 20)
    F = np.where(np.arange(20) % 2 == 0, 1e-3, -1e-3)
    with pytest.raises((cc.NumericalError, ValueError)):
        cc.fit(a, F, radius=5e-3, film=(1e6, 0.49), substrate=(70e9, 0.22), thickness=5e-5)


def test_results_are_finite():
    # Every number (the per-point reasons are text: issue 25 item 6).
    r = cc.reduced(**SOFT, a_over_t=np.geomspace(1e-4, 1e3, 50))
    assert all(np.isfinite(v).all() for k, v in r.items() if k != "reason") and (r["status"] == 0).all()
    c = cc.adhesive_curve(**SOFT, eta=1)
    assert all(np.isfinite(v).all() for k, v in c.items() if k != "reason") and (c["status"] == 0).all()
