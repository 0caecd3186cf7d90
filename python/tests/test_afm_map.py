"""coatcontact.afm.fit_map (THEORY.md section 15, "Many curves"): the README's call on the real
JPK map, the same numbers as `coatcontact afm fit MAP` (the CLI's table), curves given instead of
paths, a synthetic JPK map (tests/afm/make_afm_map) with its bad curves flagged as the truth says,
jobs=2 identical to jobs=1, and a dask.distributed LocalCluster of 2 worker processes identical to
the serial run; refusals name the keyword."""
import os
import subprocess

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR, run_cli

MAP = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_map2x2_extracted.jpk-force-map")
BUILD_DIR = os.environ.get("COATCONTACT_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
MAKE_MAP = os.path.join(BUILD_DIR, "tests", "afm", "make_afm_map")


def same_rows(a, b):
    """Bit for bit: every column's bytes (NaN where both have no value)."""
    assert a.dtype == b.dtype
    for name in a.dtype.names:
        assert a[name].tobytes() == b[name].tobytes(), name


def test_readme_call(monkeypatch):
    monkeypatch.chdir(SOURCE_DIR)
    rows = cc.afm.fit_map(["data/afm/fmt-jpk-fd_map2x2_extracted.jpk-force-map"],
                          model="hertz", radius=10e-6, halfspace=(1e3, 0.5),
                          free=("E", "contact_point", "baseline"), segment="approach", jobs=2)
    rows["E"], rows["E_error"], rows["chi2"], rows["flag"], rows["reason"]   # one per curve
    assert len(rows) == 4
    assert np.all(rows["flag"] == 0) and np.all(rows["reason"] == "fitted")
    assert np.all(rows["E_error"] > 0) and np.all(rows["E"] > 0)


def test_same_as_cli(cli):
    header, table, _ = run_cli("afm", "fit", MAP, "--radius", "10um", "--halfspace", "1kPa,0.5", "--jobs", "1")
    columns = [h for h in header if h.startswith("# columns: ")][0][len("# columns: "):].split("\t")
    rows = cc.afm.fit_map(MAP, radius=10e-6, halfspace=(1e3, 0.5), jobs=1)
    assert list(rows.dtype.names) == columns
    for name in ("E", "E_error", "contact_point", "baseline", "chi2", "pulloff"):
        assert [float(r[columns.index(name)]) for r in table] == list(rows[name]), name


def test_curves_as_paths():
    by_path = cc.afm.fit_map(MAP, radius=10e-6, halfspace=(1e3, 0.5))
    by_curve = cc.afm.fit_map(cc.afm.read(MAP), radius=10e-6, halfspace=(1e3, 0.5))
    same_rows(by_path, by_curve)


@pytest.fixture(scope="module")
def synthetic(tmp_path_factory):
    if not os.access(MAKE_MAP, os.X_OK):
        pytest.fail(f"make_afm_map not found at {MAKE_MAP} (set COATCONTACT_BUILD_DIR)")
    folder = tmp_path_factory.mktemp("map")
    path, truth = str(folder / "syn.jpk-force-map"), str(folder / "truth.tsv")
    subprocess.run([MAKE_MAP, path, "6", "6", "--points", "200", "--seed", "11", "--truth", truth], check=True)
    return path, np.loadtxt(truth, comments="#", delimiter="\t")


def test_synthetic_flags_and_jobs(synthetic):
    path, truth = synthetic
    serial = cc.afm.fit_map(path, radius=10e-6, halfspace=(5e3, 0.5), jobs=1)
    assert list(serial["flag"]) == [int(v) for v in truth[:, 7]]
    fitted = serial["flag"] == 0
    # 3 standard errors of E on every fitted curve (27 curves; a Gaussian |z| > 3 has p = 0.0027 each).
    assert np.all(np.abs(serial["E"][fitted] - truth[fitted, 3]) < 3 * serial["E_error"][fitted])
    same_rows(serial, cc.afm.fit_map(path, radius=10e-6, halfspace=(5e3, 0.5), jobs=2))


def test_dask_local_cluster(synthetic, tmp_path):
    distributed = pytest.importorskip("distributed", reason="python3-distributed (scripts/install-deps.sh)")
    path, _ = synthetic
    # Several files, one of them unreadable: the workers' shares cross the files.
    bad = tmp_path / "notes.jpk-force"
    bad.write_text("not a force curve\n")
    files = [MAP, str(bad), path]
    serial = cc.afm.fit_map(path, radius=10e-6, halfspace=(5e3, 0.5), jobs=1)
    with pytest.warns(UserWarning, match="notes.jpk-force"):
        serial_files = cc.afm.fit_map(files, radius=10e-6, halfspace=(5e3, 0.5), jobs=1)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster, \
            distributed.Client(cluster) as client:
        spread = cc.afm.fit_map(path, radius=10e-6, halfspace=(5e3, 0.5), client=client)
        with pytest.warns(UserWarning, match="notes.jpk-force"):
            spread_files = cc.afm.fit_map(files, radius=10e-6, halfspace=(5e3, 0.5), client=client)
    same_rows(serial, spread)
    same_rows(serial_files, spread_files)
    assert len(spread_files) == 4 + 1 + 36 and list(spread_files["flag"][4:5]) == [8]


def test_unreadable_file_is_a_flagged_row(tmp_path):
    """A non-AFM file with an AFM extension in a folder or a list: one row flagged unreadable
    (8), a warning naming the file and why, and the other files' curves fitted; a single such
    file named is a ValueError (issue 25 item 1)."""
    folder = tmp_path / "mixed"
    folder.mkdir()
    (folder / "map.jpk-force-map").write_bytes(open(MAP, "rb").read())
    bad = folder / "notes.jpk-force"
    bad.write_text("not a force curve\n")
    for given in (str(folder), [str(folder / "map.jpk-force-map"), str(bad)]):
        with pytest.warns(UserWarning, match="notes.jpk-force: not a zip archive"):
            rows = cc.afm.fit_map(given, radius=10e-6, halfspace=(1e3, 0.5), jobs=1)
        assert len(rows) == 5
        flagged = rows["flag"] != 0
        assert list(rows["file"][flagged]) == [str(bad)] and list(rows["reason"][flagged]) == ["unreadable"]
        assert list(rows["flag"][flagged]) == [8] and rows["curve"][flagged][0] == 0
        assert np.all(np.isnan(rows["E"][flagged])) and np.all(rows["E"][~flagged] > 0)
    with pytest.raises(ValueError, match="notes.jpk-force: not a zip archive"):
        cc.afm.fit_map(str(bad), radius=10e-6, halfspace=(1e3, 0.5))


@pytest.mark.parametrize("kwargs, words", [
    ({"jobs": 0}, ["jobs", "0"]),
    ({"model": "foo"}, ["model", "'foo'"]),
    ({"segment": "side"}, ["segment", "'side'"]),
])
def test_refusals(kwargs, words):
    with pytest.raises(ValueError) as error:
        cc.afm.fit_map(MAP, **{"radius": 10e-6, "halfspace": (1e3, 0.5), **kwargs})
    for w in words:
        assert w in str(error.value)


def cli_rows(*args):
    """The CLI's table as the columns fit_map returns (strings for file and reason, floats else)."""
    header, table, _ = run_cli("afm", "fit", *args, "--jobs", "1")
    columns = [h for h in header if h.startswith("# columns: ")][0][len("# columns: "):].split("\t")
    return columns, {name: [r[i] for r in table] for i, name in enumerate(columns)}


def same_as_cli(rows, columns, table):
    """Every column of the rows equals the CLI's printed value (NaN where both have none)."""
    assert list(rows.dtype.names) == columns
    for name in columns:
        if name in ("file", "reason", "warnings"):
            # The CLI's "-" is the rows' "" (no warnings).
            assert [str(v) or "-" for v in rows[name]] == table[name], name
        else:
            # "-" where the CLI has no value: NaN, or -1 (grid index) and 0 (points) in the rows.
            missing = {"grid_x": -1.0, "grid_y": -1.0, "points": 0.0}.get(name, np.nan)
            np.testing.assert_array_equal(np.asarray(rows[name], dtype=float),
                                          np.array([missing if v == "-" else float(v) for v in table[name]]),
                                          err_msg=name)


def test_jkr_real_map_same_as_cli(cli):
    """model="jkr" over the real 2x2 JPK map: one row per curve with w and tilt columns, the
    CLI's `afm fit MAP --model jkr` table value for value."""
    columns, table = cli_rows(MAP, "--model", "jkr", "--radius", "10um", "--halfspace", "1kPa,0.5")
    rows = cc.afm.fit_map(MAP, model="jkr", radius=10e-6, halfspace=(1e3, 0.5), jobs=1)
    for name in ("w", "w_error", "tilt", "tilt_error"):
        assert name in rows.dtype.names
    assert len(rows) == 4
    same_as_cli(rows, columns, table)
    # Rows with estimates: fitted (0), or undetermined (10) / no_detachment (11) with the estimates
    # kept (issue 36: on this map w's standard error exceeds w, which used to pass as fitted).
    kept = np.isin(rows["flag"], (0, 10, 11))
    assert np.any(kept) and np.all(rows["w_error"][kept] > 0) and np.all(np.isnan(rows["w"][~kept]))
    undetermined = rows["flag"] == 10
    assert np.all(rows["w_error"][undetermined] > np.abs(rows["w"][undetermined]))
    assert np.all(np.isfinite(rows["maugis_lambda"][kept])) and np.all(rows["rating"][~kept] == 0)


def test_jkr_synthetic_map_same_as_cli(cli, synthetic):
    """model="jkr" over the synthetic map (its bad curves flagged as the CLI flags them), jobs=2
    identical to jobs=1, and the CLI's table value for value."""
    path, truth = synthetic
    columns, table = cli_rows(path, "--model", "jkr", "--radius", "10um", "--halfspace", "5kPa,0.5")
    serial = cc.afm.fit_map(path, model="jkr", radius=10e-6, halfspace=(5e3, 0.5), jobs=1)
    same_as_cli(serial, columns, table)
    # Its bad curves keep their flags (no_contact, empty_segment, calibration), but for jump_in:
    # the jump-in is the approach's, and the adhesive fit takes the retract.
    bad = (truth[:, 7] != 0) & (truth[:, 7] != 2)
    assert list(serial["flag"][bad]) == [int(v) for v in truth[bad, 7]]
    same_rows(serial, cc.afm.fit_map(path, model="jkr", radius=10e-6, halfspace=(5e3, 0.5), jobs=2))


def test_md_real_map_same_as_cli(cli):
    """model="md" (Maugis-Dugdale through the cantilever) over the real map: the CLI's table."""
    columns, table = cli_rows(MAP, "--model", "md", "--radius", "10um", "--halfspace", "1kPa,0.5")
    rows = cc.afm.fit_map(MAP, model="md", radius=10e-6, halfspace=(1e3, 0.5), jobs=1)
    same_as_cli(rows, columns, table)


def test_adhesive_map_refusals():
    with pytest.raises(ValueError, match="work, tilt: parameters of model='jkr' or 'md' only"):
        cc.afm.fit_map(MAP, radius=10e-6, halfspace=(1e3, 0.5), work=1e-3)
    with pytest.raises(ValueError, match="surface_force_range"):
        cc.afm.fit_map(MAP, model="md", radius=10e-6, halfspace=(1e3, 0.5), surface_force_range=0.0)
    with pytest.raises(ValueError, match="work: a fixed w needs work="):
        cc.afm.fit_map(MAP, model="jkr", radius=10e-6, halfspace=(1e3, 0.5), free=("E", "contact_point", "baseline", "tilt"))
