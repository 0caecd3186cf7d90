"""Nanoindentation files of the vendors (docs/indentation.md).

    tests = coatcontact.indent.read("FS_Calibration.xls")
    t = tests[0]
    t.depth, t.load, t.stiffness         # NumPy arrays in SI (m, N, N/m); None where absent
    t.metadata["area coefficients"]      # C0, C1, ... of A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + ...

Formats (chosen by content and extension): Agilent/KLA NanoSuite .xls, Hysitron .txt and
.hld, Micromaterials .zip, FischerScope .txt. Bad files raise ValueError naming the file, the
sheet or archive entry and the line.
"""
from . import _core
from .indent_analysis import MODELS, analyse, film

__all__ = ["read", "Test", "analyse", "film", "MODELS"]

_STANDARD = ("depth", "load", "time", "stiffness", "hardness", "modulus", "segment")


class Test:
    """One indentation test in SI units.

    Attributes: ``name`` (the vendor's test name), ``depth`` [m], ``load`` [N], ``time`` [s],
    ``stiffness`` [N/m] (CSM harmonic contact stiffness), ``hardness`` and ``modulus`` [Pa]
    (the vendor's own columns), ``segment`` (int) -- each a NumPy array, or None where the
    file has no such channel; NaN marks a value the vendor wrote as missing. ``channels``:
    every channel by name (the file's others with their SI unit, e.g. "Depth [V]").
    ``metadata``: "test", "area coefficients" (array or None), "poisson", "frame stiffness"
    [N/m], "tip", "beta", "epsilon", "range" ((min, max) [m] of the vendor's averages) and
    "calibration source" as the file states them (None where it is silent), "format",
    "file", then everything else the file states (text). ``vendor_results``: the vendor's own
    results in SI ("E_mean", "H_mean" [Pa] of a NanoSuite Results sheet, ...).
    """

    def __init__(self, raw, index):
        self.name = raw["name"]
        self.index = index
        self.channels = dict(raw["channels"])
        for key in _STANDARD:
            setattr(self, key, self.channels.get(key))
        self.metadata = dict(raw["file metadata"])
        self.metadata.update(raw["calibration"])
        self.metadata["test"] = self.name
        self.vendor_results = dict(raw["vendor results"])

    def __getitem__(self, channel):
        return self.channels[channel]

    def __len__(self):
        return len(self.depth)

    def __repr__(self):
        return "<coatcontact.indent.Test %r: %d points, channels %s>" % (self.name, len(self), ", ".join(self.channels))


def read(path):
    """Every test of the indentation file at ``path`` (a list of Test, in file order)."""
    path = str(path)
    return [Test(raw, i) for i, raw in enumerate(_core.indent_read(path))]
