"""coatcontact.afm.read on the real files of data/afm/: the channel names of the Python AFM
tools, values bit for bit against a decoding written here (zipfile + struct on the JPK
archive, scaled by its headers) and against `coatcontact afm export`, metadata, and the
calibration keywords."""
import os
import struct
import zipfile

import numpy as np
import pytest

import coatcontact as cc

from conftest import SOURCE_DIR

DATA = os.path.join(SOURCE_DIR, "data", "afm")
SPOT = os.path.join(DATA, "fmt-jpk-fd_spot3-0192.jpk-force")


def properties(text):
    out = {}
    for line in text.splitlines():
        if line and not line.startswith("#") and "=" in line:
            key, value = line.split("=", 1)
            out[key] = value
    return out


def jpk_channel(path, segment, channel, slots):
    """Raw big-endian shorts scaled by the encoder, then each slot's offset + multiplier."""
    with zipfile.ZipFile(path) as z:
        p = properties(z.read(f"segments/{segment}/segment-header.properties").decode())
        raw = z.read(f"segments/{segment}/channels/{channel}.dat")
    c = f"channel.{channel}."
    assert p[c + "data.encoder.type"] == "signedshort"
    values = struct.unpack(f">{len(raw) // 2}h", raw)
    off = float(p[c + "data.encoder.scaling.offset"])
    mul = float(p[c + "data.encoder.scaling.multiplier"])
    out = []
    for v in values:
        x = off + mul * v
        for slot in slots:
            s = f"{c}conversion-set.conversion.{slot}.scaling."
            x = float(p[s + "offset"]) + float(p[s + "multiplier"]) * x
        out.append(x)
    return np.array(out)


def test_readme_call_and_names():
    curve = cc.afm.read(SPOT)[0]
    for name in ("force", "height (piezo)", "height (measured)", "tip position", "segment", "time"):
        assert name in curve and len(curve[name]) == 4000, name
    m = curve.metadata
    assert m["spring constant"] == pytest.approx(0.0435, rel=0.01)
    assert m["vendor"] == "JPK" and m["point count"] == 4000 and m["curve index"] == 0
    assert [s["kind"] for s in curve.segments] == ["approach", "retract"]
    assert curve.segment("retract") == slice(2000, 4000)


def test_jpk_channels_bit_for_bit():
    curve = cc.afm.read(SPOT)[0]
    for segment in (0, 1):
        part = slice(2000 * segment, 2000 * (segment + 1))
        assert np.array_equal(curve["force"][part], jpk_channel(SPOT, segment, "vDeflection", ["distance", "force"]))
        assert np.array_equal(curve["height (piezo)"][part], jpk_channel(SPOT, segment, "height", ["nominal", "calibrated"]))
        assert np.array_equal(curve["height (measured)"][part],
                              jpk_channel(SPOT, segment, "strainGaugeHeight", ["absolute", "nominal"]))
    k = curve.metadata["spring constant"]
    assert np.array_equal(curve["tip position"], curve["height (measured)"] + curve["force"] / k)


def test_agrees_with_cli_export(cli):
    header, rows, _ = cli("afm", "export", "data/afm/fmt-jpk-fd_map2x2_extracted.jpk-force-map", "--index", "2")
    curve = cc.afm.read(os.path.join(DATA, "fmt-jpk-fd_map2x2_extracted.jpk-force-map"))[2]
    columns = [h for h in header if h.startswith("# columns:")][0][len("# columns: "):].split("\t")
    table = np.array(rows, dtype=float)
    names = {"time_s": "time", "segment": "segment", "height_piezo_m": "height (piezo)",
             "height_measured_m": "height (measured)", "force_N": "force", "tip_position_m": "tip position"}
    for j, column in enumerate(columns):
        assert np.array_equal(table[:, j], curve[names[column]]), column
    # position-index 90 of a back-and-forth 10 x 10 map: row 9 runs backwards, so column 9
    assert curve.metadata["grid index x"] == 9 and curve.metadata["grid index y"] == 9


def test_calibration_keywords():
    modified = os.path.join(DATA, "fmt-jpk-fd_single-modified_2023.jpk-force")
    with pytest.raises(ValueError, match="no spring constant.*spring_constant="):
        cc.afm.read(modified)
    curve = cc.afm.read(modified, spring_constant=0.05)[0]
    assert curve.metadata["spring constant"] == 0.05
    assert curve.metadata["spring constant source"] == "user"
    assert curve.metadata["sensitivity source"] == "file"
    spot = cc.afm.read(SPOT, spring_constant=0.1)[0]
    base = cc.afm.read(SPOT)[0]
    distance = base["force"] / base.metadata["spring constant"]
    assert np.allclose(spot["force"], 0.1 * distance, rtol=1e-15, atol=0)
    with pytest.raises(ValueError, match="spring_constant"):
        cc.afm.read(SPOT, spring_constant=-1)
    with pytest.raises(ValueError, match="no such file"):
        cc.afm.read(os.path.join(DATA, "missing.jpk-force"))


def test_every_file_reads():
    supplied = dict(spring_constant=0.1, sensitivity=5e-8)
    counts = {}
    for name in sorted(os.listdir(DATA)):
        if name.startswith("fmt-"):
            curves = cc.afm.read(os.path.join(DATA, name), **supplied)
            counts[name.split("_")[0]] = len(curves)
            for c in curves:
                assert np.all(np.isfinite(c["force"])) and len(c["force"]) == c.metadata["point count"]
    assert counts["fmt-afm-workshop-fd"] in (1, 16)
    qi = cc.afm.read(os.path.join(DATA, "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data"))
    assert len(qi) == 4 and [c.metadata["grid index x"] for c in qi] == [0, 1, 2, 3]


def test_preprocess_agrees_with_cli(cli):
    header, rows, _ = cli("afm", "export", "data/afm/fmt-jpk-fd_spot3-0192.jpk-force", "--preprocess")
    curve = cc.afm.read(SPOT)[0]
    p = cc.afm.preprocess(curve)
    table = np.array(rows, dtype=float)
    assert np.array_equal(table[:, -1], p["force (corrected)"])
    assert np.array_equal(p["tip position"], curve["tip position"])
    line = [h for h in header if h.startswith("# contact point [m]:")][0]
    assert float(line.split(":")[1].split()[0]) == p["contact point"]
    assert p["contact point method"] == "piecewise-fit"
    approach = curve.segment("approach")
    assert approach.start + p["baseline points"] <= p["contact index"] < approach.stop


def test_preprocess_plain_arrays():
    z = np.linspace(5e-6, 0.5e-6, 1000)
    force = 1e-10 + 1e-4 * z + np.where(z < 1e-6, 14.0 * np.clip(1e-6 - z, 0, None) ** 1.5, 0.0)
    force += np.random.default_rng(1).normal(0, 1e-12, z.size)
    p = cc.afm.preprocess({"force": force, "height (piezo)": z - force / 0.1}, spring_constant=0.1)
    assert abs(p["contact point"] - 1e-6) < 5 * (z[0] - z[1])
    assert abs(p["baseline slope"] - 1e-4) < 4 * p["baseline slope error"]
    with pytest.raises(ValueError, match="spring constant"):
        cc.afm.preprocess({"force": force, "height (piezo)": z})
