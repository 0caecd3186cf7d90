"""Real AFM force curves: the instruments' files read into NumPy arrays in SI units.

    import coatcontact as cc
    curve = cc.afm.read("data/afm/fmt-jpk-fd_spot3-0192.jpk-force")[0]
    curve["force"], curve["tip position"], curve.metadata["spring constant"]

Formats (chosen by content and extension): JPK .jpk-force, .jpk-force-map, .jpk-qi-data,
.jpk-qi-series; Asylum Research .ibw; AFM Workshop .csv and zipped maps; NT-MDT Nova text
exports. The arrays carry the names of the Python AFM tools: "force" [N], "height (piezo)" [m]
and "height (measured)" [m] when recorded, "tip position" [m] (height (measured), else piezo,
plus force / spring constant), "segment" (index into curve.segments), "time" [s] when the file
has a time base. `metadata` holds "spring constant" [N/m], "sensitivity" [m/V], "vendor",
"instrument", "date", "time", "path", "curve index", "grid index x", "grid index y",
"position x", "position y" [m], "point count", ... (the keys a file provides).

preprocess(curve) runs the named steps of the command line's `afm export --preprocess`: tip
position, baseline offset and tilt on the leading part of the approach, contact point
("piecewise-fit", robust to noise, or "deviation").

Errors: ValueError naming the file and the reason (unreadable or truncated file, missing
channel, empty segment, and missing calibration: then pass spring_constant= and/or
sensitivity=, which override the file's values and are recorded as source "user").
"""
import math

from . import _afm

__all__ = ["read", "preprocess", "Curve"]


class Curve:
    """One force curve: curve[name] gives an array (see the module's names), curve.metadata a
    dict, curve.segments a list of {"kind", "begin", "end", "name", "duration"} (approach,
    pause, retract; point indices begin..end-1)."""

    def __init__(self, data):
        self.metadata = data.pop("metadata")
        self.segments = data.pop("segments")
        self._columns = data

    def __getitem__(self, name):
        return self._columns[name]

    def __contains__(self, name):
        return name in self._columns

    def keys(self):
        return self._columns.keys()

    def __len__(self):
        return len(self._columns["segment"])

    def segment(self, kind):
        """The first segment of `kind` ("approach", "pause", "retract") as a slice, or None."""
        for s in self.segments:
            if s["kind"] == kind:
                return slice(s["begin"], s["end"])
        return None

    def __repr__(self):
        m = self.metadata
        return (f"<coatcontact.afm.Curve {m.get('vendor', '')} {m.get('path', '')} #{m.get('curve index', 0)}: "
                f"{len(self)} points, segments {[s['kind'] for s in self.segments]}>")


def _calibration(value, name):
    if value is None:
        return None
    value = float(value)
    if not (math.isfinite(value) and value > 0):
        raise ValueError(f"{name}: {value!r} is not allowed; it must be a finite number > 0")
    return value


def read(path, spring_constant=None, sensitivity=None):
    """Every curve in the file at `path` (one for a single curve, all curves of a map), as a
    list of Curve. spring_constant [N/m] and sensitivity [m/V] override the file's values."""
    curves = _afm.read(str(path), _calibration(spring_constant, "spring_constant"),
                       _calibration(sensitivity, "sensitivity"))
    return [Curve(c) for c in curves]


def preprocess(curve, contact_point="piecewise-fit", baseline_fraction=0.5, deviation_sigmas=5.0,
               spring_constant=None):
    """Preprocessing steps of one curve (a Curve, or any mapping with "force" and "height
    (measured)" and/or "height (piezo)", plus `segments` or an all-approach curve):

    1. "tip position" = height (measured, else piezo) + force / spring constant [m];
    2. baseline force = offset + slope * tip position, least squares on the first
       `baseline_fraction` of the approach points; "force (corrected)" = force - baseline [N];
    3. "contact point" [m] on the tip-position axis: "piecewise-fit" (F = 0, then A (z_c - z)^1.5,
       least squares over all the contact-side points; robust to noise) or "deviation" (the first
       point after which the corrected force stays above `deviation_sigmas` baseline sigmas).

    Returns a dict with those arrays and the steps' parameters ("baseline offset" [N],
    "baseline slope" [N/m] with their standard errors, "baseline sigma" [N], "contact index")."""
    metadata = getattr(curve, "metadata", None) or {}
    k = spring_constant if spring_constant is not None else metadata.get("spring constant")
    if k is None:
        raise ValueError("preprocess needs a spring constant: pass spring_constant= (N/m)")
    force = curve["force"]
    segments = getattr(curve, "segments", None)
    if segments is None:
        segments = [{"kind": "approach", "begin": 0, "end": len(force)}]
    piezo = curve["height (piezo)"] if "height (piezo)" in curve else None
    measured = curve["height (measured)"] if "height (measured)" in curve else None
    return _afm.preprocess(force, piezo, measured, [(s["kind"], s["begin"], s["end"]) for s in segments],
                           float(k), contact_point, float(baseline_fraction), float(deviation_sigmas),
                           str(metadata.get("path", "curve")))
