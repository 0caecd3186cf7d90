"""Runs Jupyter notebooks headless with the python3 that runs the tests (the one that imports
coatcontact and NumPy), whatever kernels the machine has installed."""
import contextlib
import json
import os
import sys
import tempfile

KERNEL_NAME = "coatcontact-test-python3"


@contextlib.contextmanager
def kernel_for_this_python():
    """A kernel spec named KERNEL_NAME that starts sys.executable, on JUPYTER_PATH while the
    block runs (the kernel inherits the environment: PYTHONPATH, MPLBACKEND)."""
    with tempfile.TemporaryDirectory(prefix="coatcontact-kernel.") as root:
        spec_dir = os.path.join(root, "kernels", KERNEL_NAME)
        os.makedirs(spec_dir)
        with open(os.path.join(spec_dir, "kernel.json"), "w") as f:
            json.dump({"argv": [sys.executable, "-Xfrozen_modules=off", "-m", "ipykernel_launcher", "-f", "{connection_file}"],
                       "display_name": "coatcontact tests", "language": "python",
                       # figures inline (as in Jupyter), whatever MPLBACKEND the tests run with
                       "env": {"MPLBACKEND": "module://matplotlib_inline.backend_inline"}}, f)
        saved = os.environ.get("JUPYTER_PATH")
        os.environ["JUPYTER_PATH"] = root + (os.pathsep + saved if saved else "")
        try:
            yield KERNEL_NAME
        finally:
            if saved is None:
                del os.environ["JUPYTER_PATH"]
            else:
                os.environ["JUPYTER_PATH"] = saved
