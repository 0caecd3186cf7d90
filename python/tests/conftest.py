"""Shared fixtures: the CLI to compare with and the source tree (set by CTest; the defaults
fit a Release tree in build/ run from the source folder)."""
import os
import subprocess

import pytest

SOURCE_DIR = os.environ.get("COATCONTACT_SOURCE_DIR",
                            os.path.abspath(os.path.join(os.path.dirname(__file__), "..", "..")))
CLI = os.environ.get("COATCONTACT_CLI", os.path.join(SOURCE_DIR, "build", "bin", "coatcontact"))


@pytest.fixture(scope="session")
def source_dir():
    return SOURCE_DIR


def run_cli(*args, expect=0):
    """Runs the CLI; returns (header lines, rows as lists of the printed strings, stderr)."""
    p = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=SOURCE_DIR)
    assert p.returncode == expect, (args, p.returncode, p.stderr)
    header = [l for l in p.stdout.splitlines() if l.startswith("#")]
    rows = [l.split("\t") for l in p.stdout.splitlines() if l and not l.startswith("#")]
    return header, rows, p.stderr.strip()


@pytest.fixture(scope="session")
def cli():
    if not os.access(CLI, os.X_OK):
        pytest.fail("coatcontact CLI not found at %s (set COATCONTACT_CLI)" % CLI)
    return run_cli
