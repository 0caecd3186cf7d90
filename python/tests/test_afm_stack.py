"""The AFM sample as a stack (issue 35; THEORY.md section 15, "A stack of layers"):
coatcontact.afm.fit(..., layers=[(h, E, nu), ...], substrate=...) equals `afm fit --layer ...`
on the real spot3 curve to 1e-12 relative (one pipeline behind both doors), names the free layer
as --free does (E<K>), and refuses what the CLI refuses (Maugis-Dugdale on a stack); JKR on a
stack equals the CLI's."""
import os

import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

SPOT = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_spot3-0192.jpk-force")
LAYERS = [(1e-6, 5e3, 0.5), (4e-6, 2e4, 0.5)]


def header_value(header, key):
    for line in header:
        if line.startswith(f"# {key}: "):
            return [float(v) for v in line[len(f"# {key}: "):].split() if v not in ("+-", "(fixed)")]
    raise AssertionError(f"no {key} in the header")


def test_stack_fit_equals_the_cli(cli):
    out, _, _ = cli("afm", "fit", SPOT, "--radius", "10um", "--layer", "1um,5kPa,0.5", "--layer", "4um,20kPa,0.5",
                    "--substrate", "rigid", "--free", "contact_point,baseline")
    curve = cc.afm.read(SPOT)[0]
    r = cc.afm.fit(curve, radius=10e-6, layers=LAYERS, substrate="rigid", free=("contact_point", "baseline"))
    for name, key in (("contact_point", "contact point [m]"), ("baseline", "baseline [N]")):
        value, error = header_value(out, key)
        for a, b in ((r["estimates"][name], value), (r["errors"][name], error)):
            assert abs(a - b) <= 1e-12 * abs(b), (name, a, b)
    assert header_value(out, "E1 [Pa]") == [5000.0]


def test_stack_refusals():
    curve = cc.afm.read(SPOT)[0]
    with pytest.raises(ValueError, match=r"'E3' is not a layer's modulus; allowed with 2 layers: E1\.\.E2"):
        cc.afm.fit(curve, radius=10e-6, layers=LAYERS, substrate="rigid", free=("E3", "contact_point", "baseline"))
    with pytest.raises(ValueError, match=r"layer 1 is .*expected \(h, E, nu\)"):
        cc.afm.fit(curve, radius=10e-6, layers=[(5e3, 0.5)], substrate="rigid")
    with pytest.raises(ValueError, match="not with film="):
        cc.afm.fit(curve, radius=10e-6, layers=LAYERS, film=(5e3, 0.5), substrate="rigid")
    with pytest.raises(ValueError, match="takes one bonded film"):
        cc.afm.fit(curve, "md", radius=10e-6, layers=LAYERS, substrate="rigid", work=1e-3)


def test_stack_free_modulus_named_after_its_layer(cli):
    """--free E2 on two layers: the map's columns, Python's keys (fit and fit_map) and the C API's
    parameter say E2, not E1; the values equal the CLI's map row (1e-12). One film keeps E1."""
    layers = [(1e-6, 15e3, 0.5), (4e-6, 15e3, 0.5)]
    header, rows_printed, _ = cli("afm", "fit", SPOT, "--radius", "10um", "--layer", "1um,15kPa,0.5", "--layer",
                                  "4um,15kPa,0.5", "--substrate", "rigid", "--free", "E2,contact_point,baseline",
                                  "--jobs", "1")
    columns = next(line for line in header if line.startswith("# columns: "))[len("# columns: "):].split("\t")
    assert "E2" in columns and "E2_error" in columns and "E1" not in columns, columns
    row = dict(zip(columns, rows_printed[0]))
    curve = cc.afm.read(SPOT)[0]
    keywords = dict(radius=10e-6, layers=layers, substrate="rigid", free=("E2", "contact_point", "baseline"))
    r = cc.afm.fit(curve, **keywords)
    assert r["names"][0] == "E2" and "E1" not in r["estimates"] and r["free"][0] == "E2" and r["units"]["E2"] == "Pa"
    rows = cc.afm.fit_map(SPOT, jobs=1, **keywords)
    assert "E2" in rows.dtype.names and "E1" not in rows.dtype.names
    for value in (r["estimates"]["E2"], rows["E2"][0]):
        assert abs(value - float(row["E2"])) <= 1e-12 * float(row["E2"]), (value, row["E2"])
    assert abs(r["errors"]["E2"] - float(row["E2_error"])) <= 1e-12 * float(row["E2_error"])
    one_film = cc.afm.fit(curve, radius=10e-6, layers=layers[:1], substrate="rigid", free=("contact_point", "baseline"))
    assert one_film["names"][0] == "E1"


def test_jkr_stack_equals_the_cli(cli):
    # JKR on a stack (THEORY.md section 15, "JKR and DMT on a stack"), the deeper layer's E free.
    free = ("E2", "w", "contact_point", "baseline", "tilt")
    out, _, _ = cli("afm", "fit", SPOT, "--radius", "10um", "--layer", "1um,5kPa,0.5", "--layer", "4um,20kPa,0.5",
                    "--substrate", "1MPa,0.3", "--model", "jkr", "--free", ",".join(free))
    curve = cc.afm.read(SPOT)[0]
    r = cc.afm.fit(curve, "jkr", radius=10e-6, layers=LAYERS, substrate=(1e6, 0.3), free=free)
    for name, key in (("w", "w [J/m2]"), ("contact_point", "contact point [m]"), ("baseline", "baseline [N]")):
        value, error = header_value(out, key)
        for a, b in ((r["estimates"][name], value), (r["errors"][name], error)):
            assert abs(a - b) <= 1e-12 * abs(b), (name, a, b)
    value, error = header_value(out, "E2 [Pa]")
    modulus = [v for k, v in r["estimates"].items() if k in ("E1", "E2")]
    assert len(modulus) == 1 and abs(modulus[0] - value) <= 1e-12 * value, (r["estimates"], value)
