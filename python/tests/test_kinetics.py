"""coatcontact.kinetics (THEORY.md section 14): the README call, agreement with the CLI, the
sweep, and bad input."""
import math

import numpy as np
import pytest

import coatcontact as cc

README = dict(film=(1e6, 0.49), substrate=(70e9, 0.22), radius=2e-3, thickness=50e-6, work=0.04,
              v_star=1e-6, n=0.6, spring=500.0)
PROTOCOL = [("approach", 1e-6, 1e-3), ("dwell", 1.0), ("retract", 1e-5)]


@pytest.fixture(scope="module")
def readme_run():
    return cc.kinetics(**README, protocol=PROTOCOL)


def test_readme_call(readme_run):
    r = readme_run
    assert r["pulloff"]["F"] < 0.0
    for key in ("t", "z", "delta", "a", "F", "G"):
        assert r[key].shape == r["t"].shape and np.all(np.isfinite(r[key]))
    assert np.all(np.diff(r["t"]) >= 0.0)
    assert r["F"].max() == pytest.approx(1e-3, rel=1e-9)       # the approach's target force
    assert r["pulloff"]["F"] == r["F"].min()
    assert r["pulloff"]["t"] < r["loss"]["t"] == r["t"][-1]
    # The spring: F = k (z - delta) at every sample.
    np.testing.assert_allclose(r["F"], 500.0 * (r["z"] - r["delta"]), rtol=0, atol=1e-12 * 1e-3 * 1e3)


def test_cli_agreement(readme_run, cli):
    header, rows, _ = cli("kinetics", "--film", "1e6,0.49", "--substrate", "70e9,0.22", "--radius", "2e-3",
                          "--thickness", "50e-6", "--work", "0.04", "--v-star", "1e-6", "--n", "0.6",
                          "--spring", "500", "--protocol", "approach:1um/s:1mN,dwell:1s,retract:10um/s")
    pulloff = float([h for h in header if h.startswith("# pull-off (most")][0].split(": ")[1])
    assert pulloff == pytest.approx(readme_run["pulloff"]["F"], rel=1e-15)
    assert len(rows) == len(readme_run["t"])


def test_sweep_grows_with_speed():
    r = cc.kinetics(**README, protocol=PROTOCOL, retract_speeds=[1e-7, 1e-6, 1e-5])
    f = r["sweep"]["F"]
    assert np.all(np.diff(f) < 0.0)  # more tensile at higher speed
    assert r["sweep"]["V"] == pytest.approx([1e-7, 1e-6, 1e-5], rel=1e-15)


@pytest.mark.parametrize("change, fragment", [
    (dict(n=0.0), "n = 0"),
    (dict(v_star=-1e-6), "v_star"),
    (dict(spring=-1.0), "spring"),
    (dict(protocol=[("retract", 1e-6)]), "segment 1"),
    (dict(protocol=PROTOCOL + [("dwell", 1.0)]), "segment 4"),
    (dict(protocol=[("approach", -1e-6, 1e-3), ("retract", 1e-6)]), "speed"),
    (dict(protocol=[("hold", 1.0)]), "not understood"),
])
def test_bad_input(change, fragment):
    args = dict(README, protocol=PROTOCOL)
    args.update(change)
    with pytest.raises(ValueError, match=fragment):
        cc.kinetics(**args)


def test_displacement_control_accepts_inf():
    r = cc.kinetics(**dict(README, spring=math.inf), protocol=PROTOCOL)
    assert r["pulloff"]["F"] < 0.0


def test_cone_keyword_as_the_cli(cli):
    """shape=("cone", beta) (rad, as shape_contact) runs the cone of `kinetics --shape cone:BETA`
    (section 14, "The cone"); radius= and shape= together are refused."""
    cone = {k: v for k, v in README.items() if k != "radius"}
    r = cc.kinetics(**cone, shape=("cone", math.radians(70.0)), protocol=PROTOCOL)
    header, rows, _ = cli("kinetics", "--film", "1e6,0.49", "--substrate", "70e9,0.22", "--shape", "cone:70deg",
                          "--thickness", "50e-6", "--work", "0.04", "--v-star", "1e-6", "--n", "0.6",
                          "--spring", "500", "--protocol", "approach:1um/s:1mN,dwell:1s,retract:10um/s")
    pulloff = float([h for h in header if h.startswith("# pull-off (most")][0].split(": ")[1])
    assert pulloff == pytest.approx(r["pulloff"]["F"], rel=1e-15)
    assert len(rows) == len(r["t"])
    assert r["F"].max() == pytest.approx(1e-3, rel=1e-9)
    # The cone's own force scale F_s = E1* L_a L_D (section 14).
    e1 = 1e6 / (1 - 0.49 ** 2)
    tb = math.tan(math.radians(70.0))
    l_a, l_d = 4 * 0.04 * tb ** 2 / (math.pi * e1), 2 * 0.04 * tb / e1
    assert r["scales"]["F_scale"] == pytest.approx(e1 * l_a * l_d, rel=1e-14)
    sphere = cc.kinetics(**cone, shape=("sphere", 2e-3), protocol=PROTOCOL)
    assert sphere["pulloff"]["F"] == cc.kinetics(**README, protocol=PROTOCOL)["pulloff"]["F"]
    with pytest.raises(ValueError, match="radius"):
        cc.kinetics(**README, shape=("cone", 1.2), protocol=PROTOCOL)
    with pytest.raises(ValueError, match="shape"):
        cc.kinetics(**cone, shape=("punch", 1e-3), protocol=PROTOCOL)
    with pytest.raises(ValueError, match="half angle"):
        cc.kinetics(**cone, shape=("cone", 2.0), protocol=PROTOCOL)
