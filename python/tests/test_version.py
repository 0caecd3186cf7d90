"""One version number and one license everywhere (issue 28): project() in CMakeLists.txt is the
source; the installed program's --version, the CMake package version file, coatcontact.pc, the
Python package (__version__ and its distribution metadata) and CITATION.cff must all say it."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import CLI, SOURCE_DIR

BUILD = os.environ.get("COATCONTACT_BUILD_DIR")
CMAKE = os.environ.get("COATCONTACT_CMAKE", "cmake")
SITE = os.environ.get("COATCONTACT_PYTHON_INSTALL_DIR", "lib/python3/dist-packages")


def project_version():
    text = open(os.path.join(SOURCE_DIR, "CMakeLists.txt"), encoding="utf-8").read()
    m = re.search(r"project\(\s*coatcontact\s+VERSION\s+([0-9]+\.[0-9]+\.[0-9]+)", text)
    assert m, "no project(coatcontact VERSION x.y.z) in CMakeLists.txt"
    return m.group(1)


def program_version(program):
    p = subprocess.run([program, "--version"], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    words = p.stdout.split()
    assert words[0] == "coatcontact", p.stdout
    return words[1]


def test_build_tree_agrees():
    import coatcontact
    import importlib.metadata as md
    version = project_version()
    assert coatcontact.__version__ == version
    assert coatcontact.__license__ == "BSD-3-Clause"
    assert program_version(CLI) == version
    # The build tree's python/ folder holds the distribution metadata too (PYTHONPATH).
    assert md.version("coatcontact") == version
    assert md.metadata("coatcontact")["License"] == "BSD-3-Clause"


def test_citation_and_license_files():
    version = project_version()
    cff = open(os.path.join(SOURCE_DIR, "CITATION.cff"), encoding="utf-8").read()
    assert re.search(r'^version:\s*"?%s"?\s*$' % re.escape(version), cff, re.M), \
        "CITATION.cff does not give version %s" % version
    assert re.search(r"^license:\s*BSD-3-Clause\s*$", cff, re.M)
    for doi in ("10.1088/0022-3727/40/4/021", "10.1557/jmr.2004.19.2.600"):
        assert doi in cff
    license_text = open(os.path.join(SOURCE_DIR, "LICENSE"), encoding="utf-8").read()
    assert license_text.startswith("BSD 3-Clause License")
    readme = open(os.path.join(SOURCE_DIR, "README.md"), encoding="utf-8").read()
    assert "BSD-3-Clause" in readme and "CITATION.cff" in readme


@pytest.mark.skipif(not BUILD, reason="COATCONTACT_BUILD_DIR not set (CTest sets it)")
def test_installed_tree_agrees(tmp_path):
    version = project_version()
    prefix = tmp_path / "prefix"
    p = subprocess.run([CMAKE, "--install", BUILD, "--prefix", str(prefix)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr

    assert program_version(str(prefix / "bin" / "coatcontact")) == version

    config_version = list(prefix.glob("lib*/cmake/coatcontact/coatcontactConfigVersion.cmake"))
    assert len(config_version) == 1
    m = re.search(r'set\(PACKAGE_VERSION "([^"]+)"\)', config_version[0].read_text())
    assert m and m.group(1) == version
    config = config_version[0].with_name("coatcontactConfig.cmake").read_text()
    assert 'set(coatcontact_LICENSE "BSD-3-Clause")' in config

    pc = list(prefix.glob("lib*/pkgconfig/coatcontact.pc"))
    assert len(pc) == 1
    pkg_config = shutil.which("pkg-config")
    if pkg_config:
        env = dict(os.environ, PKG_CONFIG_PATH=str(pc[0].parent))
        p = subprocess.run([pkg_config, "--modversion", "coatcontact"], capture_output=True, text=True, env=env)
        assert p.returncode == 0, p.stderr
        assert p.stdout.strip() == version
    else:
        assert re.search(r"^Version: %s$" % re.escape(version), pc[0].read_text(), re.M)

    assert (prefix / "share" / "doc" / "coatcontact" / "LICENSE").is_file()
    assert (prefix / "share" / "doc" / "coatcontact" / "CITATION.cff").is_file()

    site = prefix / SITE
    code = ("import coatcontact, importlib.metadata as md; "
            "assert coatcontact.__file__.startswith(%r); "
            "print(coatcontact.__version__, md.version('coatcontact'), md.metadata('coatcontact')['License'])"
            % str(site))
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    env["PYTHONPATH"] = str(site)
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, cwd=tmp_path)
    assert p.returncode == 0, p.stderr
    assert p.stdout.split() == [version, version, "BSD-3-Clause"]
