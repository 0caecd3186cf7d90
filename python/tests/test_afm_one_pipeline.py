"""One AFM pipeline (issue 35; THEORY.md section 15): a real curve of data/afm/ gives the same
estimates (to 1e-12 relative) fitted alone by `afm fit --index N`, as its row of the batch
(--jobs 1 and 2, with and without --map-plot), from Python as a Curve, as a plain mapping with
a "segment" column (only the requested segment is fitted), as a row of fit_map, and with
baseline_model="offset" as plain arrays of the segment; for Hertz on the approach, JKR and DMT
on the retract. A curve without contact raises in Python with the CLI's message."""
import os
import subprocess

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

DATA = os.path.join(SOURCE_DIR, "data", "afm")
# Files read without a user calibration, with curves of contact on both segments.
HERTZ_FILES = ["fmt-jpk-fd_spot3-0192.jpk-force", "fmt-jpk-fd_map2x2_extracted.jpk-force-map",
               "fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force",
               "fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force", "fmt-igor-fd_U3_3_p10004.ibw"]
JKR_FILES = ["fmt-igor-fd_U3_3_p10004.ibw", "fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force",
             "fmt-jpk-fd_spot3-0192.jpk-force"]
MODELS = {"hertz": (["--radius", "10um", "--halfspace", "1kPa,0.5"], dict(radius=10e-6, halfspace=(1e3, 0.5)),
                    ["E", "contact_point", "baseline"]),
          "jkr": (["--model", "jkr", "--radius", "10um", "--halfspace", "10kPa,0.5"],
                  dict(model="jkr", radius=10e-6, halfspace=(10e3, 0.5)), ["E", "w", "contact_point", "baseline", "tilt"]),
          "dmt": (["--model", "dmt", "--radius", "10um", "--halfspace", "10kPa,0.5"],
                  dict(model="dmt", radius=10e-6, halfspace=(10e3, 0.5)), ["E", "w", "contact_point", "baseline", "tilt"])}
HEADER_KEYS = {"E": "E [Pa]", "w": "w [J/m2]", "contact_point": "contact point [m]", "baseline": "baseline [N]",
               "tilt": "tilt [N/m]"}


def close(a, b, what):
    assert abs(a - b) <= 1e-12 * max(abs(a), abs(b)) + 1e-300, (what, a, b, (a - b) / max(abs(a), abs(b)))


def header_value(header, key):
    line = [h for h in header if h.startswith(f"# {key}: ")][0]
    return float(line[len(f"# {key}: "):].split()[0])


def table_rows(path):
    lines = open(path, encoding="utf-8").read().splitlines()
    names = [l for l in lines if l.startswith("# columns: ")][0][len("# columns: "):].split("\t")
    return [dict(zip(names, l.split("\t"))) for l in lines if l and not l.startswith("#")]


def segment_mapping(curve):
    """A plain mapping as the Python AFM tools give: arrays, a 0/1 "segment" column, metadata."""
    index = np.zeros(len(curve), dtype=int)
    for s in curve.segments:
        if s["kind"] == "retract":
            index[s["begin"]:s["end"]] = 1
    mapping = {"force": curve["force"], "segment": index, "metadata": {"spring constant": curve.metadata["spring constant"]}}
    for name in ("height (measured)", "height (piezo)"):
        if name in curve:
            mapping[name] = curve[name]
    return mapping


@pytest.mark.parametrize("model,name", [("hertz", f) for f in HERTZ_FILES] + [("jkr", f) for f in JKR_FILES] +
                         [("dmt", f) for f in JKR_FILES])
def test_same_estimates_alone_in_a_map_and_from_python(cli, tmp_path, model, name):
    options, keywords, names = MODELS[model]
    path = os.path.join(DATA, name)
    curves = cc.afm.read(path)
    tables = {}
    runs = [("jobs1", ["--jobs", "1"]), ("jobs2", ["--jobs", "2"])]
    plot = ["--jobs", "1", "--map-plot", str(tmp_path / "map.png")]
    if any(c.metadata.get("grid index x") is not None for c in curves):
        runs.append(("plot", plot))
    else:  # no grid, no map image: refused, and no table written
        _, _, err = cli("afm", "fit", path, *options, *plot, "--output", str(tmp_path / "plot.tsv"), expect=2)
        assert "no curve of the run has a grid position" in err and not (tmp_path / "plot.tsv").exists()
    for label, extra in runs:
        out = tmp_path / f"{label}.tsv"
        cli("afm", "fit", path, *options, *extra, "--output", str(out))
        tables[label] = table_rows(out)
    rows = cc.afm.fit_map(curves, jobs=1, **keywords)
    for i, curve in enumerate(curves):
        header, _, _ = cli("afm", "fit", path, "--index", str(i), *options)
        alone = {p: header_value(header, HEADER_KEYS[p]) for p in names}
        python = cc.afm.fit(curve, **keywords)
        # A 0/1 segment column has no pause: a curve with one is compared as a Curve only.
        paused = any(s["kind"] == "pause" for s in curve.segments)
        mapping = None if paused else cc.afm.fit(segment_mapping(curve), **keywords)
        for p in names:
            close(python["estimates"][p], alone[p], (name, i, p, "Curve"))
            if mapping is not None:
                close(mapping["estimates"][p], alone[p], (name, i, p, "mapping with a segment column"))
            close(float(rows[p][i]), alone[p], (name, i, p, "fit_map"))
            for label, table in tables.items():
                close(float(table[i][p]), alone[p], (name, i, p, label))
        kind = "approach" if model == "hertz" else "retract"
        part = curve.segment(kind)
        assert python["index"].min() >= part.start and python["index"].max() < part.stop  # one segment only
        assert python["baseline_model"] == ("tilt" if model == "hertz" else "offset")  # adhesive: the tilt is free
        if model == "hertz":
            offset = cc.afm.fit(curve, baseline_model="offset", **keywords)
            plain = cc.afm.fit((curve["tip position"][part], curve["force"][part]), **keywords)
            for p in names:
                close(plain["estimates"][p], offset["estimates"][p], (name, i, p, "plain arrays, offset"))


def synthetic_map(path, *arguments):
    """A map written by the test tool make_afm_map (its arguments after the path); its path."""
    make_map = os.path.join(os.environ.get("COATCONTACT_BUILD_DIR", os.path.join(SOURCE_DIR, "build")), "tests", "afm",
                            "make_afm_map")
    if not os.access(make_map, os.X_OK):
        pytest.fail(f"make_afm_map not found at {make_map} (set COATCONTACT_BUILD_DIR)")
    subprocess.run([make_map, str(path), *arguments], check=True)
    return str(path)


def test_curve_without_contact_raises_the_cli_message(cli, tmp_path):
    """Curve 3 of a synthetic map (make_afm_map) never reaches the sample: `afm fit --index 3`
    exits 2, Python raises ValueError with the same words (it used to return a fit of the
    baseline, E ~ 0 with R^2 ~ 0)."""
    path = synthetic_map(tmp_path / "syn.jpk-force-map", "2", "2", "--points", "200", "--seed", "3")
    _, _, message = cli("afm", "fit", path, "--index", "3", "--radius", "10um", "--halfspace", "5kPa,0.5", expect=2)
    curve = cc.afm.read(path)[3]
    with pytest.raises(ValueError) as error:
        cc.afm.fit(curve, radius=10e-6, halfspace=(5e3, 0.5))
    assert str(error.value) in message and "no contact" in str(error.value)
    with pytest.raises(ValueError, match="no contact"):
        cc.afm.fit(segment_mapping(curve), radius=10e-6, halfspace=(5e3, 0.5))


def test_baseline_model_refusals():
    curve = cc.afm.read(os.path.join(DATA, "fmt-jpk-fd_spot3-0192.jpk-force"))[0]
    with pytest.raises(ValueError, match="baseline_model"):
        cc.afm.fit(curve, radius=10e-6, halfspace=(1e3, 0.5), baseline_model="linear")
    with pytest.raises(ValueError, match="count the slope twice"):
        cc.afm.fit(curve, radius=10e-6, halfspace=(1e3, 0.5), free=("E", "contact_point", "baseline", "tilt"),
                   baseline_model="tilt")
    with pytest.raises(ValueError, match="fitted as given"):
        cc.afm.fit((curve["tip position"], curve["force"]), radius=10e-6, halfspace=(1e3, 0.5), baseline_model="tilt")


def test_measured_pulloff_is_the_same_for_every_model():
    """The pull-off is measured (issue 35): the retract's most tensile force against a line fitted
    by least squares (numpy here, GSL in the library) on its last half, identical for Hertz and
    JKR; the JKR fit reports its own jump-off beside it."""
    curve = cc.afm.read(os.path.join(DATA, "fmt-igor-fd_U3_3_p10004.ibw"))[0]
    hertz = cc.afm.fit(curve, radius=10e-6, halfspace=(10e3, 0.5))
    jkr = cc.afm.fit(curve, model="jkr", radius=10e-6, halfspace=(10e3, 0.5))
    assert hertz["pulloff"] == jkr["pulloff"]
    part = curve.segment("retract")
    z, F = curve["tip position"][part], curve["force"][part]
    half = len(z) // 2
    slope, offset = np.polyfit(z[-half:], F[-half:], 1)
    corrected = F - (offset + slope * z)
    i = int(np.argmin(corrected))
    # 1e-9 relative: numpy's and GSL's least squares differ by rounding in the line's offset.
    assert abs(hertz["pulloff"]["F"] - corrected[i]) < 1e-9 * abs(corrected[i])
    assert hertz["pulloff"]["z"] == z[i]
    assert jkr["jump_off"]["F"] < 0 and jkr["jump_off"]["F"] != jkr["pulloff"]["F"]


def test_missing_calibration_is_one_flag_for_every_reader(cli, tmp_path):
    """Regression (issue 35): an NT-MDT export (no calibration in the file) was flagged unreadable
    while a JPK or AFM Workshop curve without its calibration is flagged calibration; now every
    reader's missing calibration is flag 6, calibration, in the CLI's table and in fit_map."""
    files = [os.path.join(DATA, n) for n in ("fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt",
                                             "fmt-afm-workshop-fd_single_2021-10-22_14.16.csv",
                                             "fmt-jpk-fd_spot3-0192.jpk-force")]
    with pytest.warns(UserWarning):
        rows = cc.afm.fit_map(files, radius=10e-6, halfspace=(1e3, 0.5), jobs=1)
    assert list(rows["flag"]) == [6, 6, 0]
    out = tmp_path / "rows.tsv"
    cli("afm", "fit", *files, "--radius", "10um", "--halfspace", "1kPa,0.5", "--output", str(out))
    assert [r["flag"] for r in table_rows(out)] == ["6", "6", "0"]


def test_md_map_on_an_elastic_base_gives_the_single_curve_fits(cli, tmp_path):
    """The Maugis-Dugdale fit over a map (issue 37; THEORY.md section 15, "A map of
    Maugis-Dugdale retracts"): a synthetic 2 x 2 map of a film on an elastic base (make_afm_map
    --md, the library's own MD model), E1 and w free; the CLI's rows (--jobs 2), fit_map's
    (jobs=2) and fit() of each curve in this process are the same doubles, bit for bit: the
    cohesive-zone tables the curves share are pure functions of the stack and the grid index."""
    path = synthetic_map(tmp_path / "md.jpk-force-map", "2", "2", "--seed", "7", "--md", "--clean")
    out = tmp_path / "md.tsv"
    cli("afm", "fit", path, "--model", "md", "--radius", "10um", "--film", "250kPa,0.5", "--substrate", "1MPa,0.3",
        "--thickness", "4um", "--range", "0.5um", "--jobs", "2", "--output", str(out))
    table = table_rows(out)
    keywords = dict(model="md", radius=10e-6, film=(250e3, 0.5), substrate=(1e6, 0.3), thickness=4e-6,
                    surface_force_range=0.5e-6, free=("E1", "w", "contact_point", "baseline", "tilt"))
    curves = cc.afm.read(path)
    rows = cc.afm.fit_map(curves, jobs=2, **keywords)
    names = ["E1", "w", "contact_point", "baseline", "tilt"]
    for i in reversed(range(len(curves))):  # fit() in another order than the map's
        python = cc.afm.fit(curves[i], **keywords)
        assert table[i]["flag"] == "0" and int(rows["flag"][i]) == 0
        for p in names:
            assert float(table[i][p]) == python["estimates"][p], (i, p, "CLI row")
            assert float(table[i][p + "_error"]) == python["errors"][p], (i, p, "CLI row's error")
            assert float(rows[p][i]) == python["estimates"][p], (i, p, "fit_map")
