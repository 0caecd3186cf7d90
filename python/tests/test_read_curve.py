"""coatcontact.read_curve reads a measured curve with the library's reader and unit table (the
CLI's, through cc_curve_read): the example data equal the file's numbers divided by the unit's
exact divisor (um: 1e6, mN: 1e3), as `coatcontact fit` reads them."""
import os

import numpy as np
import pytest

import coatcontact as cc


def test_example_in_si(source_dir):
    path = os.path.join(source_dir, "data", "example_a_F.tsv")
    raw_a, raw_F = np.loadtxt(path, unpack=True)
    d = cc.read_curve(path, "a,F")
    assert np.array_equal(d["a"], raw_a / 1e6) and np.array_equal(d["F"], raw_F / 1e3)
    assert "um" in d["units"] and "mN" in d["units"]
    assert "sigma_F" not in d and len(d["line"]) == len(raw_a)


def test_named_columns_and_sigma(tmp_path):
    path = tmp_path / "curve.tsv"
    path.write_text("# units: nm nN nN\n1.5\t7\t0.5\n3\t-2\t0.25\n")
    d = cc.read_curve(path, "delta=1,F=2,sigma_F=3")
    assert np.array_equal(d["delta"], np.array([1.5, 3]) / 1e9)
    assert np.array_equal(d["F"], np.array([7, -2]) / 1e9)
    assert np.array_equal(d["sigma_F"], np.array([0.5, 0.25]) / 1e9)


def test_bad_columns(tmp_path):
    path = tmp_path / "curve.tsv"
    path.write_text("1\t2\n3\t4\n")
    with pytest.raises(ValueError, match="columns: 'q' is not allowed"):
        cc.read_curve(path, "q")
    with pytest.raises(ValueError):
        cc.read_curve(tmp_path / "missing.tsv")
