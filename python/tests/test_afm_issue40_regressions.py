"""Regressions of issue 40. Item 7: one corrupt curve failed the read of its whole map; a Dask worker resolved relative paths in its own working folder,
so `fit_map(["data/afm/map"], client=...)` read nothing (or another file) on a worker started
elsewhere. The workers now get absolute paths and the rows keep the names the caller gave. A
stand-in client runs each task in another folder, as a worker process would; the rows must equal
the serial run's bit for bit, unreadable-file rows included."""
import os
import re

import pytest

import coatcontact as cc

from conftest import SOURCE_DIR


class ElsewhereClient:
    """The three calls fit_map makes of a dask.distributed Client, each task run in `folder`."""

    def __init__(self, folder, workers=2):
        self.folder = folder
        self.workers = workers

    def scheduler_info(self):
        return {"workers": {i: {} for i in range(self.workers)}}

    def submit(self, function, *args, pure=True):
        here = os.getcwd()
        os.chdir(self.folder)
        try:
            return function(*args)
        finally:
            os.chdir(here)

    def gather(self, futures):
        return list(futures)


def same_rows(a, b):
    assert a.dtype == b.dtype
    for name in a.dtype.names:
        assert a[name].tobytes() == b[name].tobytes(), name


def test_dask_workers_resolve_relative_paths_in_callers_folder(monkeypatch, tmp_path):
    monkeypatch.chdir(SOURCE_DIR)
    elsewhere = tmp_path / "worker"
    elsewhere.mkdir()
    bad = os.path.relpath(tmp_path / "notes.jpk-force")
    with open(bad, "w") as f:
        f.write("not a force curve\n")
    files = ["data/afm/fmt-jpk-fd_map2x2_extracted.jpk-force-map", bad]
    keywords = dict(radius=10e-6, halfspace=(1e3, 0.5))
    with pytest.warns(UserWarning, match="notes.jpk-force"):
        serial = cc.afm.fit_map(files, jobs=1, **keywords)
    with pytest.warns(UserWarning, match="notes.jpk-force"):
        spread = cc.afm.fit_map(files, client=ElsewhereClient(str(elsewhere)), **keywords)
    same_rows(serial, spread)
    assert list(spread["file"][:4]) == [files[0]] * 4
    assert list(spread["flag"][:4]) == [0] * 4 and spread["flag"][4] == 8


@pytest.mark.parametrize("key", ["segment", "height (piezo)"])
def test_column_of_wrong_length_named_not_no_contact(key):
    """Regression (issue 40, item 8): a mapping whose segment (or height) column has another
    length than its force was fitted and explained as "no contact"; now a ValueError names it."""
    import numpy as np
    z = np.linspace(0, 2e-6, 200)
    curve = {"force": np.zeros(200), "height (piezo)": z, "segment": np.zeros(200, dtype=int),
             "metadata": {"spring constant": 0.05}}
    curve[key] = curve[key][:150]
    for call in (lambda: cc.afm.fit(curve, radius=10e-6, halfspace=(1e3, 0.5)),
                 lambda: cc.afm.fit_map([curve], radius=10e-6, halfspace=(1e3, 0.5))):
        with pytest.raises(ValueError, match=re.escape(f"'{key}' has 150 values for 200 forces")):
            call()


def test_one_corrupt_curve_does_not_fail_read_of_map(tmp_path):
    """Regression (issue 40, item 7): one corrupt curve of a map (curve 1's deflection channel cut
    to 3 bytes) made cc.afm.read of the whole map fail. The others are read, the corrupt one is
    left out with a warning naming it, and each keeps its curve index; a map whose every curve
    is corrupt, or a single corrupt curve, is still a ValueError."""
    import zipfile
    source = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_map2x2_extracted.jpk-force-map")

    def corrupt(target, curves):
        with zipfile.ZipFile(source) as src, zipfile.ZipFile(target, "w", zipfile.ZIP_DEFLATED) as dst:
            for info in src.infolist():
                data = src.read(info.filename)
                if any(info.filename == f"index/{c}/segments/0/channels/vDeflection.dat" for c in curves):
                    data = data[:3]
                dst.writestr(info.filename, data)

    one_bad = tmp_path / "one_bad.jpk-force-map"
    corrupt(one_bad, [1])
    with pytest.warns(UserWarning, match=r"curve 1: .*truncated channel"):
        curves = cc.afm.read(one_bad)
    whole = cc.afm.read(source)
    assert [c.metadata["curve index"] for c in curves] == [0, 2, 3]
    for c in curves:
        original = whole[c.metadata["curve index"]]
        assert c["force"].tobytes() == original["force"].tobytes()
    all_bad = tmp_path / "all_bad.jpk-force-map"
    corrupt(all_bad, [0, 1, 2, 3])
    with pytest.raises(ValueError, match="no curve of the file can be read"):
        cc.afm.read(all_bad)
