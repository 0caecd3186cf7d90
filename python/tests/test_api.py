"""The package API: the README call, shapes, objects, threads (the GIL is released), help."""
import pydoc
import threading

import numpy as np
import pytest

import coatcontact as cc


def test_readme_call():
    import numpy as np, coatcontact as cc  # noqa: E401 (the README's line)
    r = cc.reduced(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=np.geomspace(0.01, 100, 200))
    for key in ("E_eq", "Gamma1", "error_estimate"):
        assert isinstance(r[key], np.ndarray) and r[key].shape == (200,)
    # The columns, and the status and reason of each radius (issue 25 item 6): all delivered.
    assert set(r) == set(cc.REDUCED_KEYS) | {"status", "reason"}
    assert (r["status"] == 0).all() and (r["reason"] == "").all()
    assert (r["error_estimate"] <= 1e-8).all()
    # Limits of section 6: homogeneous at small a/t, towards E0*/E1* = 10 at large a/t.
    assert r["E_eq"][0] == pytest.approx(1, abs=0.01)
    assert 8 < r["E_eq"][-1] < 10


def test_objects_and_reuse():
    stack = cc.Stack(film=(0.1, 0.25), substrate=(1, 0.25))
    assert stack.reference_modulus == pytest.approx(0.1 / (1 - 0.25**2))
    assert cc.Stack(film=(0.1, 0.25), substrate=(1, 0.25), indenter=(0.1, 0.25)).reference_modulus \
        == pytest.approx(0.5 * 0.1 / (1 - 0.25**2))
    solver = cc.ReducedSolver(stack)
    assert solver.solve(1.2)["E_eq"] == cc.reduced(stack, a_over_t=1.2)["E_eq"]
    model = cc.AdhesiveModel(stack)
    lo, hi = model.default_range
    assert 0 < lo < 0.01 and hi == pytest.approx(10)
    curve = model.curve(1.0)
    assert curve["a_bar"][0] == pytest.approx(lo) and curve["a_bar"][-1] == pytest.approx(hi)
    c = model.contact(radius=1e-3, thickness=50e-6, work=0.05)
    assert c.scales["eta"] > 0 and c.pulloff()["F_load"] < 0
    grid = c.at(np.full((2, 3), 2e-5))
    assert grid["F"].shape == (2, 3)


def test_homogeneous_jkr_limits():
    p = cc.pulloff(film=(1, 0.25), substrate=(1, 0.25), eta=[0.1, 1, 10])
    assert p["P_load"] == pytest.approx(-1.5, rel=1e-6)
    assert p["P_disp"] == pytest.approx(-5 / 6, rel=1e-6)
    a = np.array([0.5, 1, 2])
    c = cc.adhesive_curve(film=(1, 0.25), substrate=(1, 0.25), eta=1, a_bar=a)
    assert c["P"] == pytest.approx(4 / 3 * a**3 - 2 * np.sqrt(2) * a**1.5, rel=1e-7)


def test_threads_give_the_serial_results():
    # Solves run without the GIL; a model serializes its own calls.
    radii = np.geomspace(0.01, 100, 40)
    stack = cc.Stack(film=(0.3, 0.3), substrate=(1, 0.25))
    serial = cc.reduced(stack, a_over_t=radii)["Gamma1"]
    model = cc.AdhesiveModel(stack)
    expected_pull = model.pulloff([0.5, 2])["P_load"]
    results, errors = [], []

    def work():
        try:
            results.append(cc.reduced(stack, a_over_t=radii)["Gamma1"])
            results.append(model.pulloff([0.5, 2])["P_load"])
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for r in results:
        assert r.shape in (serial.shape, expected_pull.shape)
        assert (r == serial).all() if r.shape == serial.shape else (r == expected_pull).all()


def test_help_reads_well():
    text = pydoc.render_doc(cc, renderer=pydoc.plaintext)
    for word in ("reduced", "adhesive_curve", "pulloff", "contact", "fit", "Stack", "NumericalError",
                 "THEORY.md", "[m]", "[N]", "Pa"):
        assert word in text
    for f in (cc.reduced, cc.adhesive_curve, cc.pulloff, cc.contact, cc.fit, cc.fit_stack, cc.Stack):
        assert f.__doc__ and len(f.__doc__) > 200, f.__name__


def test_readme_example_runs(source_dir):
    # The Python block under the set-up commands of README.md, as printed there.
    with open(source_dir + "/README.md", encoding="utf-8") as f:
        text = f.read()
    block = text.split("```python\n", 1)[1].split("```", 1)[0]
    assert len(block.strip().splitlines()) == 5
    scope = {}
    exec(compile(block, "README.md", "exec"), scope)
    assert scope["r"]["E_eq"].shape == (200,) and scope["c"]["F"].shape == (200,)
