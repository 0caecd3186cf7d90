"""Regression (issue 35): coatcontact.afm had an extension module of its own, so one Python
process held two copies of the static library and of its process-wide state (the FFTW planning
lock among them). Every compiled part is now in the one module _core; the AFM part is its
submodule."""
import glob
import importlib.machinery
import os

import coatcontact as cc
import coatcontact.afm


def test_one_extension_module_per_process():
    folder = os.path.dirname(cc.__file__)
    modules = [p for p in glob.glob(os.path.join(folder, "*"))
               if p.endswith(tuple(importlib.machinery.EXTENSION_SUFFIXES))]
    assert [os.path.basename(p).split(".")[0] for p in modules] == ["_core"], modules
    assert coatcontact.afm._afm is cc._core._afm
