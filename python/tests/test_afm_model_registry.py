"""The AFM force models as the library's registry lists them (issue 35; THEORY.md section 15):
Python's model names, aliases and default free parameters come from it and agree with the CLI's
--model message; the batch's model_jump_off_force/_indentation columns hold each curve's own
jump-off of the adhesive model (the single fit's "jump_off", and the CLI table's columns), and
are absent (NaN in Python, "-" in the table) for Hertz."""
import os

import numpy as np
import pytest

import coatcontact as cc
from coatcontact import afm as afm_module

from conftest import SOURCE_DIR, run_cli

MAP = os.path.join(SOURCE_DIR, "data", "afm", "fmt-jpk-fd_map2x2_extracted.jpk-force-map")


def test_models_listed_once_with_the_cli_names():
    names = list(afm_module._MODELS)
    assert len(names) == len(set(names)) and {"hertz", "jkr", "md", "dmt"} <= set(names)
    # The CLI's message lists the same names in the same order.
    _, _, err = run_cli("afm", "fit", MAP, "--model", "lj", "--radius", "10um", "--halfspace", "1kPa,0.5", expect=2)
    assert "allowed: " + ", ".join(names) in err
    with pytest.raises(ValueError, match="allowed: " + ", ".join(repr(n) for n in names)):
        cc.afm.fit(cc.afm.read(MAP)[0], model="lj", radius=10e-6, halfspace=(1e3, 0.5))
    assert afm_module._model_name("maugis-dugdale") == "md"
    for m in afm_module._MODELS.values():
        # The adhesive models (w a parameter) are those that need the spring and fit the retract.
        has_w = any(p["name"] == "w" for p in m["parameters"])
        assert m["spring"] == has_w and m["segment"] == ("retract" if has_w else "approach"), m["name"]
        assert m["default_free"].split(",")[0] == "E" and m["coating_default_free"].split(",")[0] == "E1"


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the map's weak JKR fits warn (lambda, w undetermined)
def test_batch_model_jump_off_columns():
    curves = cc.afm.read(MAP)
    rows = cc.afm.fit_map(MAP, model="jkr", radius=10e-6, halfspace=(10e3, 0.5), jobs=1)
    header, table, _ = run_cli("afm", "fit", MAP, "--model", "jkr", "--radius", "10um", "--halfspace", "10kPa,0.5",
                               "--jobs", "1")
    columns = [h for h in header if h.startswith("# columns: ")][0][len("# columns: "):].split("\t")
    units = [h for h in header if h.startswith("# units: ")][0][len("# units: "):].split("\t")
    f_col, d_col = columns.index("model_jump_off_force"), columns.index("model_jump_off_indentation")
    assert (units[f_col], units[d_col]) == ("N", "m")
    for i, curve in enumerate(curves):
        r = cc.afm.fit(curve, model="jkr", radius=10e-6, halfspace=(10e3, 0.5))
        for name, key, col in (("model_jump_off_force", "F", f_col), ("model_jump_off_indentation", "indentation", d_col)):
            assert rows[name][i] == r["jump_off"][key], (name, i)
            assert float(table[i][col]) == r["jump_off"][key], (name, i)
        # The JKR jump-off through a spring is tensile and at a negative indentation (THEORY.md section 15).
        assert r["jump_off"]["F"] < 0 and r["jump_off"]["indentation"] < 0
    hertz = cc.afm.fit_map(MAP, radius=10e-6, halfspace=(1e3, 0.5), jobs=1)
    assert np.all(np.isnan(hertz["model_jump_off_force"])) and np.all(np.isnan(hertz["model_jump_off_indentation"]))
    header, table, _ = run_cli("afm", "fit", MAP, "--radius", "10um", "--halfspace", "1kPa,0.5", "--jobs", "1")
    columns = [h for h in header if h.startswith("# columns: ")][0][len("# columns: "):].split("\t")
    assert all(row[columns.index("model_jump_off_force")] == "-" for row in table)
