"""Issue 39's teaching list: Python takes the CLI's pyramid (`contact --shape pyramid:THETA`,
`fit --shape pyramid:THETA`) as shape=("pyramid", theta) and the spring of `sphere --spring k`
as cc.contact(spring=k), with the CLI's units, semantics and refusals. The numbers are compared
with the CLI's printed ones (17 significant digits) to 1e-12 relative: the same library call
behind both, so only the printing rounds."""
import math
import warnings

import numpy as np
import pytest

import coatcontact as cc

TOL = 1e-12  # printing to 17 digits and back; any other difference is a different computation
COATING = dict(film=(1e8, 0.35), substrate=(1e10, 0.25), thickness=20e-9, work=0.1)
CLI_COATING = ["--film", "100MPa,0.35", "--substrate", "10GPa,0.25", "--thickness", "20nm", "--work", "100mJ/m2"]
SPHERE = dict(radius=5e-3, thickness=50e-6, film=(1e6, 0.49), substrate=(70e9, 0.22), work=0.04)
CLI_SPHERE = ["--radius", "5mm", "--thickness", "50um", "--film", "1MPa,0.49", "--substrate", "70GPa,0.22",
              "--work", "40mJ/m2"]


def values_of(header):
    return dict(l[2:].split(": ", 1) for l in header if ": " in l)


def close(printed, value):
    return abs(float(printed) - value) <= TOL * abs(float(printed))


def pulloff_line(text):
    """'F (contact radius a m, penetration d m)' -> (F, a, d)."""
    f, rest = text.split(" (contact radius ")
    a, rest = rest.split(" m, penetration ")
    return float(f), float(a), float(rest.split(" m)")[0])


def test_pyramid_shape_contact_equals_cli(cli):
    header, rows, _ = cli("contact", "--shape", "pyramid:70deg", *CLI_COATING, "--spring", "1",
                          "--contact-radius", "5nm,10nm,30nm")
    values = values_of(header)
    assert values["shape"].startswith("four-sided pyramid, face half angle 70 deg")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cc.ValidityWarning)
        r = cc.shape_contact(shape=("pyramid", math.radians(70)), **COATING, a=[5e-9, 1e-8, 3e-8], spring=1.0)
    for row, delta, force in zip(rows, r["delta"], r["F"]):
        assert close(row[1], delta) and close(row[2], force), row
    for control, key in (("load", "load"), ("displacement", "disp"), ("spring", "spring")):
        F, a, d = pulloff_line(values["pull-off force, %s control [N]" % control])
        p = r["pulloff"]
        assert abs(p["F_" + key] - F) <= TOL * abs(F) and abs(p["a_" + key] - a) <= TOL * a, control
        assert abs(p["delta_" + key] - d) <= TOL * abs(d), control


def test_pyramid_is_the_cone_of_equal_area():
    # Independent of the CLI: a four-sided pyramid of face half angle theta has at depth h the
    # cross-section 4 h^2 tan^2(theta), the cone's is pi h^2 tan^2(beta): equal for
    # tan(beta) = 2 tan(theta)/sqrt(pi) (THEORY.md section 11), computed here.
    theta = math.radians(65.3)
    beta = math.atan(2 * math.tan(theta) / math.sqrt(math.pi))
    a = [5e-9, 2e-8]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cc.ValidityWarning)
        p = cc.shape_contact(shape=("pyramid", theta), **COATING, a=a)
        c = cc.shape_contact(shape=("cone", beta), **COATING, a=a)
    assert np.allclose(p["F"], c["F"], rtol=1e-12, atol=0)
    assert np.allclose(p["delta"], c["delta"], rtol=1e-12, atol=0)


def test_pyramid_refusals():
    for bad in (("pyramid",), ("pyramid", 1.2, 3.0)):
        with pytest.raises(ValueError, match="needs 1 parameter"):
            cc.shape_contact(shape=bad, **COATING)
    for theta in (0.0, math.pi / 2, 1.7, -0.3):
        with pytest.raises(ValueError, match="pyramid face half angle"):
            cc.shape_contact(shape=("pyramid", theta), **COATING)


def test_sphere_spring_equals_cli(cli):
    header, _, _ = cli("sphere", *CLI_SPHERE, "--spring", "0.5mN/um")
    values = values_of(header)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cc.ValidityWarning)
        r = cc.contact(**SPHERE, spring="0.5mN/um")
    p = r["pulloff"]
    assert p["k"] == 500.0 and float(values["spring stiffness k [N/m]"]) == 500.0
    assert close(values["k_bar = k (pi^2 w^2 R/E1*^2)^(1/3)/(pi w R)"], p["k_bar"])
    F, a, d = pulloff_line(values["pull-off force, spring control [N]"])
    assert abs(p["F_spring"] - F) <= TOL * abs(F) and abs(p["a_spring"] - a) <= TOL * a
    assert abs(p["delta_spring"] - d) <= TOL * abs(d)
    # Section 10's bounds: the spring's pull-off lies between displacement and load control.
    assert p["F_load"] < p["F_spring"] < p["F_disp"]


def test_sphere_spring_refused_as_the_cli_refuses(cli):
    for text, pattern in (("-1", "must be > 0"), ("0", "must be > 0"), ("abc", "is not a number"),
                          ("inf", "is not a number"), ("500um", "unknown stiffness unit 'um'")):
        _, _, err = cli("sphere", *CLI_SPHERE, "--spring", text, expect=2)
        assert "--spring: stiffness" in err or "--spring: unknown stiffness" in err, err
        assert pattern in err, err
        with pytest.raises(ValueError, match=pattern):
            cc.contact(**SPHERE, spring=text)
    for number in (-1.0, 0.0):
        with pytest.raises(ValueError, match="spring: stiffness .* must be > 0"):
            cc.contact(**SPHERE, spring=number)
    with pytest.raises(ValueError, match="outside the allowed range"):
        cc.contact(**SPHERE, spring=math.inf)


def test_fit_with_a_pyramid_equals_cli(cli, source_dir):
    # The cone data of data/ (beta = 80 deg) fitted through the pyramid of equal area.
    theta = "78.7464deg"
    header, _, _ = cli("fit", "data/example_cone_a_F.tsv", "--columns", "a,F", "--shape", "pyramid:" + theta,
                       "--film", "1MPa,0.49", "--substrate", "70GPa,0.22", "--thickness", "5um")
    estimate, error = values_of(header)["w [J/m2]"].split(" +- ")
    a, F = np.loadtxt(source_dir + "/data/example_cone_a_F.tsv", unpack=True)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", cc.ValidityWarning)
        r = cc.fit(a, F, shape=("pyramid", math.radians(78.7464)), film=(1e6, 0.49), substrate=(70e9, 0.22),
                   thickness=5e-6)
    assert close(estimate, r["estimates"]["w"]) and close(error, r["errors"]["w"])
    assert abs(r["estimates"]["w"] - 0.05) < 3 * r["errors"]["w"]  # the data's truth
