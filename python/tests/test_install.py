"""`cmake --install` puts the package into the prefix's site-packages, where it imports and
computes without the build tree."""
import os
import subprocess
import sys

import pytest

BUILD = os.environ.get("COATCONTACT_BUILD_DIR")
CMAKE = os.environ.get("COATCONTACT_CMAKE", "cmake")
SITE = os.environ.get("COATCONTACT_PYTHON_INSTALL_DIR", "lib/python3/dist-packages")


@pytest.mark.skipif(not BUILD, reason="COATCONTACT_BUILD_DIR not set (CTest sets it)")
def test_installed_package_imports(tmp_path):
    prefix = tmp_path / "prefix"
    p = subprocess.run([CMAKE, "--install", BUILD, "--prefix", str(prefix)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    site = prefix / SITE
    assert (site / "coatcontact" / "__init__.py").is_file()
    code = ("import coatcontact as cc; assert cc.__file__.startswith(%r); "
            "r = cc.reduced(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=[1.0]); "
            "print(repr(float(r['E_eq'][0])))" % str(site))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    # The package and the installed program run the same library: the same E_eq to the last bit.
    cli = subprocess.run([str(prefix / "bin" / "coatcontact"), "reduced", "--film", "0.1,0.25",
                          "--substrate", "1,0.25", "--a-over-t", "1"], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    rows = [line.split("\t") for line in cli.stdout.splitlines() if not line.startswith("#")]
    header = next(line for line in cli.stdout.splitlines() if line.startswith("# columns:"))
    column = header[len("# columns:"):].strip().split("\t").index("E_eq")
    assert float(p.stdout) == float(rows[0][column])
