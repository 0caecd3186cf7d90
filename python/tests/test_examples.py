"""examples/python: each script runs headless (Agg) and writes a non-blank PNG of its size
(checked by tests/figures/check_png.py)."""
import importlib.util
import os
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def check_png():
    spec = importlib.util.spec_from_file_location("check_png", os.path.join(SOURCE_DIR, "tests", "figures", "check_png.py"))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module.check


@pytest.mark.parametrize("script,png,size", [
    ("fig5.py", "fig5_python.png", (1000, 720)),
    ("fit_data.py", "fit_python.png", (800, 700)),
    ("thin_film.py", "thin_film_python.png", (1000, 720)),
])
def test_example_writes_a_png(tmp_path, script, png, size):
    env = dict(os.environ, MPLBACKEND="Agg", MPLCONFIGDIR=str(tmp_path / "mpl"))
    p = subprocess.run([sys.executable, os.path.join(SOURCE_DIR, "examples", "python", script),
                        "--output", str(tmp_path)], capture_output=True, text=True, env=env)
    assert p.returncode == 0, p.stderr
    check_png()(str(tmp_path / png), size)  # raises ValueError when blank or malformed
