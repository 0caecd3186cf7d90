"""Regressions of issue 40. Item 7: a Dask worker resolved relative paths in its own working folder,
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
