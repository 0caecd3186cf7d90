"""coatcontact.indent.read on the real files of data/indentation/: channels against a
decoding written here (NumPy on the text files' lines, zipfile on the Micromaterials archive),
the metadata keys of the issue ("test", "area coefficients", "poisson", "frame stiffness",
"tip") as the files state them, and bad files raising ValueError with the file and line."""
import os
import zipfile

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

DATA = os.path.join(SOURCE_DIR, "data", "indentation")


def test_nanosuite_metadata_and_vendor_results():
    tests = cc.indent.read(os.path.join(DATA, "FS_Calibration.xls"))
    assert [t.name for t in tests] == ["Test %03d" % k for k in range(1, 17)]
    t = tests[0]
    assert t.metadata["test"] == "Test 001"
    np.testing.assert_array_equal(t.metadata["area coefficients"], [27.3136, 152.6988585, -494.1823171])
    assert t.metadata["poisson"] == 0.18
    assert t.metadata["frame stiffness"] is None  # the file states a correction (0), not the stiffness
    assert t.metadata["Frame Stiffness Correction [N/m]"] == "0"
    assert t.metadata["tip"] == "Berk40_20210907_MarilaineSP"
    assert t.metadata["range"] == pytest.approx((100e-9, 200e-9), rel=1e-15)
    assert t.vendor_results["E_mean"] == pytest.approx(76.318e9, rel=1e-15)
    assert t.vendor_results["H_mean"] == pytest.approx(9.784e9, rel=1e-15)
    for name in ("depth", "load", "time", "stiffness", "hardness", "modulus", "segment"):
        assert len(t[name]) == len(t) == 1211
    assert t.segment.dtype.kind == "i" and t.segment[0] == 1 and t.segment[-1] == 4
    # the software's "no value" (1.797e308) is NaN, never a number
    assert np.isnan(t.hardness[0]) and np.nanmax(t.hardness) < 1e12


def test_hysitron_text_channels_against_the_lines():
    path = os.path.join(DATA, "RobinSteel0000LC.txt")
    (t,) = cc.indent.read(path)
    raw = np.loadtxt(path, skiprows=4, encoding="latin-1")  # blank lines between segments skipped
    np.testing.assert_array_equal(t.depth, raw[:, 0] / 1e9)
    np.testing.assert_array_equal(t.load, raw[:, 1] / 1e6)
    np.testing.assert_array_equal(t.time, raw[:, 2])
    np.testing.assert_array_equal(t["Depth [V]"], raw[:, 3])
    assert t.stiffness is None and t.metadata["area coefficients"] is None and t.metadata["poisson"] is None
    assert t.metadata["date"] == "Mon Apr 29 10:41:06 2019"


def test_micromaterials_entries_against_zipfile():
    path = os.path.join(DATA, "multipleIndentations.zip")
    tests = cc.indent.read(path)
    with zipfile.ZipFile(path) as archive:
        names = [n for n in archive.namelist() if n.endswith(".txt")]
        assert [t.name + ".txt" for t in tests] == names
        for t in tests[:5]:
            raw = np.loadtxt(archive.open(t.name + ".txt"))
            np.testing.assert_array_equal(t.time, raw[:, 0])
            np.testing.assert_array_equal(t.depth, raw[:, 1] / 1e9)
            np.testing.assert_array_equal(t.load, raw[:, 2] / 1e3)


def test_fischerscope_decimal_commas():
    path = os.path.join(DATA, "FS1.txt")
    tests = cc.indent.read(path)
    assert len(tests) == 10 and tests[1].name == "Block 1 Value 2"
    with open(path, encoding="latin-1") as f:
        lines = f.read().splitlines()
    start = lines.index("F\th\tt") + 1
    rows = np.array([[float(v.replace(",", ".")) for v in line.split("\t")] for line in lines[start:start + len(tests[0])]])
    np.testing.assert_array_equal(tests[0].load, rows[:, 0] / 1e3)
    np.testing.assert_array_equal(tests[0].depth, rows[:, 1] / 1e6)
    assert tests[0].metadata["epsilon"] == 0.75


def test_bad_files(tmp_path):
    path = os.path.join(DATA, "RobinSteel0000LC.txt")
    with open(path, "rb") as f:
        text = f.read()
    bad = tmp_path / "bad.txt"
    bad.write_bytes(text.replace(b"0.558046", b"0.55x046", 1))
    with pytest.raises(ValueError, match=r"bad\.txt: line 6: field 1 is not a number"):
        cc.indent.read(bad)
    with pytest.raises(ValueError, match="no such file"):
        cc.indent.read(tmp_path / "none.hld")
    other = tmp_path / "other.dat"
    other.write_text("hello\n")
    with pytest.raises(ValueError, match="unknown indentation file format"):
        cc.indent.read(other)
