"""Ctrl-C in coatcontact.afm (issue 40, item 4): a SIGINT during cc.afm.read of a large map or
cc.afm.fit_map stops the call between curves with KeyboardInterrupt instead of running to the
end (the binding runs Python's signal handlers from the batch's progress callback and between
the curves it reads). Each case runs in its own interpreter, so a hang fails by timeout."""
import os
import subprocess
import sys
import textwrap

import pytest

from conftest import SOURCE_DIR

BUILD_DIR = os.environ.get("COATCONTACT_BUILD_DIR", os.path.join(SOURCE_DIR, "build"))
MAKE_MAP = os.path.join(BUILD_DIR, "tests", "afm", "make_afm_map")


def run_python(code, timeout):
    p = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True, timeout=timeout,
                       env=dict(os.environ))
    assert p.returncode == 0, p.stderr
    return p.stdout.split()


@pytest.fixture(scope="module")
def big_map(tmp_path_factory):
    if not os.access(MAKE_MAP, os.X_OK):
        pytest.fail(f"make_afm_map not found at {MAKE_MAP} (set COATCONTACT_BUILD_DIR)")
    path = str(tmp_path_factory.mktemp("interrupt") / "big.jpk-force-map")
    # 4096 curves: reading them takes ~2 s, fitting them ~10 s or more on one thread.
    subprocess.run([MAKE_MAP, path, "64", "64", "--points", "300", "--seed", "2", "--clean"], check=True,
                   capture_output=True)
    return path


@pytest.mark.parametrize("call,delay", [("cc.afm.fit_map(PATH, radius=10e-6, halfspace=(5e3, 0.5), jobs=1)", 1.0),
                                        ("cc.afm.read(PATH)", 0.2)])
def test_regression_ctrl_c_ignored_in_afm_calls(big_map, call, delay):
    word, seconds = run_python(f"""
        import os, signal, threading, time
        import coatcontact as cc
        PATH = {big_map!r}
        threading.Timer({delay}, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        start = time.monotonic()
        try:
            {call}
            print("finished", time.monotonic() - start)
        except KeyboardInterrupt:
            print("interrupted", time.monotonic() - start)
    """, timeout=300)
    assert word == "interrupted", (word, seconds)
