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

fit(curve, ...) fits one segment with the adhesionless Hertz/Sneddon model on a half-space:
E, the contact point (tip-position axis) and a force baseline (THEORY.md section 15).

fit_map(paths_or_curves, ...) fits every curve of maps, files or folders (or of given curves)
the same way and returns one row per curve, flagged curves included (THEORY.md section 15,
"Many curves"); jobs= threads, or client= a dask.distributed Client to spread the work.

preprocess(curve) runs the named steps of the command line's `afm export --preprocess`: tip
position, baseline offset and tilt on the leading part of the approach, contact point
("piecewise-fit", robust to noise, or "deviation").

Errors: ValueError naming the file and the reason (unreadable or truncated file, missing
channel, empty segment, and missing calibration: then pass spring_constant= and/or
sensitivity=, which override the file's values and are recorded as source "user").
"""
import math
import os
import warnings

import numpy as np

from ._core import _afm
from ._core import NumericalError

__all__ = ["read", "preprocess", "fit", "fit_map", "Curve"]


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


def _has_column(curve, name):
    """Whether a mapping (or an AFM tool's curve object) has the column `name`."""
    try:
        return name in curve
    except TypeError:
        return False


def _segment_slice(curve, segment, n):
    """Point range of `segment` in a Curve (its segments), a mapping with an afmformats-style
    "segment" array (0 approach, 1 retract), or plain arrays (all points)."""
    if segment not in ("approach", "retract"):
        raise ValueError(f"segment: {segment!r} is not allowed; expected 'approach' or 'retract'")
    segments = getattr(curve, "segments", None)
    if segments is not None:
        for s in segments:
            if s["kind"] == segment:
                return slice(s["begin"], s["end"])
        raise ValueError(f"segment: the curve has no {segment} segment")
    if curve is not None and _has_column(curve, "segment"):
        index = np.asarray(curve["segment"])
        points = np.flatnonzero(index == (0 if segment == "approach" else 1))
        if points.size == 0:
            raise ValueError(f"segment: the curve has no {segment} segment")
        return slice(int(points[0]), int(points[-1]) + 1)
    return slice(0, n)


def fit(curve, model="hertz", *, radius=None, shape=None, halfspace=None, film=None, substrate=None,
        thickness=None, layers=None, free=("E", "contact_point", "baseline"), contact_point=None, baseline=None,
        segment=None, spring_constant=None, tip_range=None, indentation_range=None,
        max_indentation=None, max_force=None, noise=None, work=None, surface_force_range=0.3e-9, tilt=None,
        baseline_model=None, weight_cp=None, depth_profile=False):
    """Adhesionless fit of one segment of an AFM force curve (THEORY.md section 15):
    F(z) = baseline + E/(1 - nu^2) g(contact_point - z) on the tip-position axis z (decreasing
    toward the sample), g the Hertz/Sneddon force of the tip per reduced modulus, 0 out of
    contact. The contact point is found by profiling the least-squares sum over the whole
    fitted range (the global optimum); E and the baseline in closed form at each contact point.
    "tilt" in free adds a baseline slope, F = baseline + tilt (z - contact_point) + E* g (in closed
    form with E and the baseline; the result's "tilt" [N/m] with its error).

    curve      a Curve of read(); any mapping with "force" and "tip position" (or heights and
               spring_constant=), and optionally "segment" (0 approach, 1 retract, as afmformats);
               or plain arrays (tip_position, force).
    model      "hertz" (adhesionless) or "jkr": the adhesive retract, F = baseline + tilt (z - contact_point)
               + F_JKR(contact_point - z), JKR of the sphere on the half-space or the coating on the
               branch stable under the cantilever's spring k (the curve's "spring constant" or
               spring_constant=), zero past its jump-off (THEORY.md section 15). Its free names add
               "w" and "tilt" (default: the modulus, w, contact_point, baseline, tilt); work= is w
               [J/m2] (the value if fixed, else the centre of its search; default from the most
               tensile force), tilt= [N/m] a fixed tilt, surface_force_range= z0 [m] of the
               reported Tabor mu and Maugis lambda (default 0.3 nm). The result adds "w", "tilt"
               (estimates, errors), "tabor_mu", "maugis_lambda", "jump_off" ({"F" [N] above the
               baseline, "indentation" [m]}) and "warnings" (lambda outside JKR's range, ...).
               Every model's result from a curve (not plain arrays) adds "flag" ("fitted", or
               "undetermined" / "no_detachment" with the estimates kept and a RuntimeWarning),
               "rating" (0-10, docs/afm.md "Curve rating") and "warnings".
               Or "md": the same with F_MD, the Maugis-Dugdale force of the cohesive-zone table with
               sigma0 = w/h0, h0 = 0.97 surface_force_range (so lambda follows w and E); warns when
               lambda leaves [1e-3, 1e4] or the spring holds the tip down to the curve's end.
               Or "dmt": F_DMT, the adhesionless force less 2 pi w R while in contact; any spring
               lets go at the contact point (pull-off -2 pi w R); warns above lambda 0.1.
    radius     tip radius R [m] (a paraboloid); or shape=("sphere", R), ("cone", beta),
               ("pyramid", theta: face half angle; the cone of equal area), ("pyramid3", theta:
               three-sided, face angle, nanite's hertz_pyr3s), ("sneddon-sphere", R: the exact
               sphere), ("punch", A),
               ("power", n, R), ("blunted-cone", R, beta), ("profile", r, z); angles in rad.
    halfspace  (E [Pa], nu): the sample; E is the value if fixed (any > 0 if free), nu fixed.
    film, substrate, thickness
               a coating instead: film (E1 [Pa], nu1), substrate (E0, nu0) or "rigid", thickness
               t [m]; E1 and t are the values if fixed, else the centres of their log searches
               (a factor 10 each way). Tips: sphere, cone, pyramid.
    layers     a stack instead, as the CLI's --layer and coatcontact.fit's layers=: [(h [m], E [Pa],
               nu[, slip]), ...] top first, with substrate=; "E<K>" in free frees layer K's modulus
               (default E1; the estimate, its error and unit are named "E<K>", as fit_map's columns), the
               others and every h fixed; model hertz.
    free       names among "E" (half-space) or "E1", "t" (coating), "contact_point", "baseline"
               (default: the modulus, contact_point and baseline); a fixed contact_point [m] or
               baseline [N] is given by the keyword of that name.
    segment    "approach" (default for hertz) or "retract" (default for jkr and md).
    tip_range (min, max) [m]; indentation_range (min, max) [m] and max_indentation [m] relative
               to the preprocessing's contact point; max_force [N] above its baseline. Without
               a range the whole segment is fitted. Ranges combine.
    noise      force noise [N] for chi2 (default: the preprocessing's baseline sigma when the
               curve has heights and a spring constant; else chi2 is None).
    weight_cp  D [m]: nanite's contact-point weighting, each residual times min(|z - z_c|/D, 1)
               (hertz on a half-space, no free tilt; default None: unweighted).
    baseline_model
               "tilt" (default): the preprocessing's baseline slope is subtracted from the forces
               (the baseline is then the one at its contact point); "offset": the forces as
               measured. With "tilt" in free the model fits the slope (offset).
    depth_profile
               True (hertz, a curve with heights, the modulus free, t fixed): the result adds
               "depth_profile", the modulus against depth (`afm fit --depth-profile`, docs/afm.md):
               a dict of arrays "depth" (asked, from the whole-range fit's contact point) and
               "max_indentation" [m], the modulus ("E", "E1", a stack's "E<K>") and its "_error" [Pa], "flag",
               "points_in_contact"; on a coating also "E_apparent" and "E_apparent_error" [Pa]
               (the half-space fit of the same points) and "over_thickness_fraction" (bool: deeper
               than "thickness_fraction" t, 0.1); "modulus_name", "warnings". NaN where a depth
               has no estimate. The rest of the result is the whole-range fit.

    A file path (a file of one curve), a Curve, or a mapping with a height, a spring constant
    and optionally a "segment" column, goes through the library's one-curve pipeline, as `coatcontact afm fit` and each row of
    fit_map: the requested segment only, the preprocessing steps (recorded in "steps"), the
    baseline model, the range, the fit and the pull-off; a curve without contact raises the
    command line's ValueError. (tip_position, force) arrays, or a mapping with a "tip position"
    only, are fitted as given (baseline model offset, no steps).

    Returns a dict in the layout of coatcontact.fit: names, estimates, errors, units (dicts by
    name: "E" [Pa] (or "E1" [Pa], "t" [m]), "contact_point" [m], "baseline" [N]; error 0 when
    fixed), free,
    residual_norm and residual_sigma [N], r_squared, chi2, chi2_per_dof, points,
    points_in_contact, contact_point [m], pulloff (measured, the same for every model: {"F" [N], "z"
    [m]} of the retract's most tensile force against its free-cantilever baseline, a line
    "baseline_offset" [N] + "baseline_slope" [N/m] z on its last half; or None), and per fitted point index (into the curve), tip_position, F,
    indentation, F_model, residual (F_model - F); seconds (the fit's time)."""
    curve = _one_curve(curve, spring_constant)
    model = _model_name(model)
    jkr = _MODELS[model]["spring"]  # the adhesive models share their keywords
    if segment is None:
        segment = _MODELS[model]["segment"]
    if segment not in ("approach", "retract"):
        raise ValueError(f"segment: {segment!r} is not allowed; expected 'approach' or 'retract'")
    if not jkr and (work is not None or tilt is not None):
        raise ValueError("work, tilt: parameters of model='jkr' or 'md' only")
    tip, E, nu, free, coating = _problem("afm.fit", model, radius, shape, halfspace, film, substrate, thickness, free,
                                         contact_point, layers)

    if baseline_model not in (None, "tilt", "offset"):
        raise ValueError(f"baseline_model: {baseline_model!r} is not allowed; expected 'tilt' or 'offset'")
    if jkr:
        if "w" not in free and work is None:
            raise ValueError("work: a fixed w needs work= (J/m2)")
        if "tilt" in free and tilt is not None:
            raise ValueError("tilt: the tilt is free; drop it from free to fix it")
    lo_i, hi_i = (None, None) if indentation_range is None else (float(indentation_range[0]), float(indentation_range[1]))
    if max_indentation is not None:
        hi_i = float(max_indentation) if hi_i is None else min(hi_i, float(max_indentation))
    lo_t, hi_t = (None, None) if tip_range is None else (float(tip_range[0]), float(tip_range[1]))
    ranges = (lo_t, hi_t, lo_i, hi_i, None if max_force is None else float(max_force))
    mapping = None if isinstance(curve, (tuple, list)) and len(curve) == 2 else curve
    if mapping is not None and _has_heights(mapping) and _spring_constant(mapping, spring_constant) is not None:
        # The library's one-curve pipeline, as `afm fit` and each row of fit_map.
        arrays = _curve_arrays(mapping, 0, spring_constant)[:6]
        adhesion = _adhesion(model, work, float(spring_constant or 0.0), surface_force_range, tilt) if jkr else None
        try:
            r = _afm.fit_curve(*arrays, tip, E, nu, free, float(contact_point or 0.0), float(baseline or 0.0), coating,
                               segment, *ranges, adhesion, baseline_model or "", float(noise or 0.0),
                               weight_cp=float(weight_cp or 0.0), depth_profile=bool(depth_profile))
        except RuntimeError as e:
            raise NumericalError(str(e)) from None
    else:
        if depth_profile:
            raise ValueError("depth_profile: needs a curve with heights and a spring constant (the one-curve "
                             "pipeline's preprocessing); (tip_position, force) arrays have none")
        r = _fit_given_arrays(curve, mapping, model, segment, spring_constant, tip, E, nu, free, contact_point,
                              baseline, coating, ranges, noise, work, surface_force_range, tilt, baseline_model,
                              float(weight_cp or 0.0))
    for message in r.get("warnings", []):
        warnings.warn(message, RuntimeWarning, stacklevel=2)
    r["contact_point"] = r["estimates"]["contact_point"]
    return r


def _one_curve(curve, spring_constant):
    """fit()'s curve: a file path is read (it must hold one curve, as `afm fit FILE` without
    --index needs); anything but a Curve, a mapping or two arrays is refused by name."""
    if _is_path(curve):
        curves = read(os.fsdecode(curve), spring_constant=spring_constant)
        if len(curves) != 1:
            raise ValueError(f"curve: {os.fsdecode(curve)!r} holds {len(curves)} curves; fit() takes one: pass "
                             f"coatcontact.afm.read(path)[i], or fit them all with fit_map(path)")
        return curves[0]
    if isinstance(curve, (tuple, list)) and len(curve) == 2:
        return curve
    if isinstance(curve, Curve) or hasattr(curve, "keys") or hasattr(curve, "__getitem__") and not isinstance(curve, (tuple, list)):
        return curve
    raise TypeError(f"curve: a {type(curve).__name__} is not allowed; expected a file path, a Curve "
                    "(coatcontact.afm.read), a mapping of columns, or (tip_position, force) arrays")


def _has_heights(mapping):
    return _has_column(mapping, "height (measured)") or _has_column(mapping, "height (piezo)")


def _spring_constant(mapping, spring_constant):
    if spring_constant is not None:
        return spring_constant
    meta = getattr(mapping, "metadata", None) or (mapping.get("metadata", {}) if hasattr(mapping, "get") else {})
    return meta.get("spring constant")


def _fit_given_arrays(curve, mapping, model, segment, spring_constant, tip, E, nu, free, contact_point, baseline,
                      coating, ranges, noise, work, surface_force_range, tilt, baseline_model, weight_cp=0.0):
    """fit() of (tip_position, force) arrays, or of a mapping with a "tip position" but no heights
    and spring constant: the requested segment as given, without the preprocessing (no baseline
    tilt to subtract: the offset model; the relative ranges refer to a first fit of the segment)."""
    if baseline_model == "tilt":
        raise ValueError("baseline_model: 'tilt' needs the preprocessing's baseline, so a curve with heights and a "
                         "spring constant; (tip_position, force) arrays are fitted as given (offset)")
    if mapping is None:
        z_all, f_all = (np.asarray(a, dtype=float) for a in curve)
    else:
        f_all = np.asarray(mapping["force"], dtype=float)
        if "tip position" not in mapping:
            raise ValueError("curve: needs \"tip position\", or a height and spring_constant=")
        z_all = np.asarray(mapping["tip position"], dtype=float)
    if z_all.shape != f_all.shape or z_all.ndim != 1:
        raise ValueError("curve: tip position and force must be one-dimensional arrays of one length")
    part = _segment_slice(mapping, segment, len(f_all))
    z, f = z_all[part], f_all[part]
    adhesion = None
    if _MODELS[model]["spring"]:
        k = _spring_constant(mapping, spring_constant) if mapping is not None else spring_constant
        if k is None:
            raise ValueError(f"spring_constant: the {model} model needs the cantilever's spring constant (N/m); "
                             "the curve has none, pass spring_constant=")
        adhesion = _adhesion(model, work, k, surface_force_range, tilt)
    reference_contact = reference_baseline = 0.0
    if any(v is not None for v in ranges[2:]):
        first = _afm.fit(z, f, tip, E, nu, ["E1" if coating else "E", "contact_point", "baseline"], 0.0, 0.0, 0.0,
                         None, None, None, None, None, 0.0, 0.0, coating)
        reference_contact = first["estimates"]["contact_point"]
        reference_baseline = first["estimates"]["baseline"]
    try:
        r = _afm.fit(z, f, tip, E, nu, free, float(contact_point or 0.0), float(baseline or 0.0), float(noise or 0.0),
                     *ranges, float(reference_contact), float(reference_baseline), coating, adhesion,
                     weight_cp=weight_cp)
    except RuntimeError as e:
        raise NumericalError(str(e)) from None
    r["index"] = r["index"] + (part.start or 0)
    r["baseline_model"] = "offset"
    r["steps"] = []
    r["pulloff"] = None
    retract = None
    if mapping is not None and (getattr(mapping, "segments", None) is not None or _has_column(mapping, "segment")):
        try:
            retract = _segment_slice(mapping, "retract", len(f_all))
        except ValueError:
            retract = None
    if retract is not None:
        r["pulloff"] = _afm.measured_pulloff(z_all[retract], f_all[retract])
    return r


def _adhesion(model, work, k, surface_force_range, tilt):
    """The adhesive model's settings as _afm takes them: (w, k, z0, tilt, model); k 0: each curve's."""
    z0 = float(surface_force_range)
    if not z0 > 0.0:
        raise ValueError(f"surface_force_range: {surface_force_range!r} is not allowed; expected a length > 0 (m), "
                         "e.g. 0.3e-9")
    return (float(work or 0.0), float(k), z0, float(tilt or 0.0), model)


# The library's force models (its registry): name -> name, aliases, "spring" (the adhesive models
# through the cantilever), default "segment", parameters and default free parameters.
_MODELS = {m["name"]: m for m in _afm.models()}
_ALIASES = {alias: m["name"] for m in _MODELS.values() for alias in m["aliases"]}


def _model_name(model):
    """The registry's name of `model` (an alias resolved); ValueError naming the allowed ones."""
    if isinstance(model, str) and model in _ALIASES:
        return _ALIASES[model]
    if not isinstance(model, str) or model not in _MODELS:
        raise ValueError(f"model: {model!r} is not a model; allowed: " + ", ".join(repr(n) for n in _MODELS))
    return model


def _stack_free(free, count):
    """The free layer of layers= (the K of "E<K>" in free, default 1) and free with it named E1."""
    layer, found, out = 0, 0, []
    for item in free:
        if len(item) >= 2 and item[0] == "E" and item[1:].isdigit():
            k = int(item[1:])
            if not 1 <= k <= count:
                raise ValueError(f"free: {item!r} is not a layer's modulus; allowed with {count} layers: E1..E{count}")
            found += 1
            if found > 1:
                raise ValueError(f"free: one layer's modulus is free at a time (got {','.join(free)!r})")
            layer, item = k - 1, "E1"
        out.append(item)
    return layer, out


def _stack_coating(layers, substrate, free, film, thickness, halfspace):
    """The coating tuple of layers= (as the CLI's --layer h,E,nu[,slip], repeated)."""
    if film is not None or thickness is not None or halfspace is not None:
        raise ValueError("layers: give the sample as layers= with substrate=, not with film=, thickness= or halfspace=")
    if substrate is None:
        raise ValueError("layers: a stack needs substrate=(E0, nu0) or \"rigid\"")
    rows = []
    for i, layer in enumerate(layers):
        if len(layer) not in (3, 4):
            raise ValueError(f"layers: layer {i + 1} is {layer!r}; expected (h, E, nu) or (h, E, nu, slip)")
        rows.append((float(layer[0]), float(layer[1]), float(layer[2]), bool(layer[3]) if len(layer) > 3 else False))
    if not rows:
        raise ValueError("layers: give at least one layer (h, E, nu)")
    if isinstance(free, str):
        free = [f.strip() for f in free.split(",")]
    k, free = _stack_free([str(f) for f in free], len(rows))
    sub = None if (isinstance(substrate, str) and substrate == "rigid") else tuple(float(v) for v in substrate)
    return (rows[k][1], rows[k][2], sub, rows[k][0], tuple(rows), k), free


def _problem(caller, model, radius, shape, halfspace, film, substrate, thickness, free, contact_point, layers=None):
    """The tip, sample and free parameters of fit and fit_map as _afm takes them."""
    model = _model_name(model)
    default_free = free == ("E", "contact_point", "baseline")  # the keyword's default: the model's
    if default_free:
        free = tuple(_MODELS[model]["default_free"].split(","))
    coating = None
    if layers is not None:
        if default_free:
            free = tuple(_MODELS[model]["coating_default_free"].split(","))
        coating, free = _stack_coating(layers, substrate, free, film, thickness, halfspace)
        E, nu = coating[0], coating[1]
    elif film is not None or substrate is not None or thickness is not None:
        if halfspace is not None:
            raise ValueError("halfspace: give one sample, halfspace=(E, nu) or film=, substrate=, thickness=")
        if film is None or substrate is None or thickness is None:
            raise ValueError("a coating needs film=(E1, nu1), substrate=(E0, nu0) or \"rigid\", and thickness=t")
        sub = None if (isinstance(substrate, str) and substrate == "rigid") else tuple(float(v) for v in substrate)
        coating = (float(film[0]), float(film[1]), sub, float(thickness))
        E, nu = coating[0], coating[1]
        if default_free:
            free = tuple(_MODELS[model]["coating_default_free"].split(","))
    elif halfspace is None:
        raise ValueError("halfspace: give the sample as halfspace=(E, nu), or a coating film=, substrate=, thickness=")
    else:
        E, nu = (float(v) for v in halfspace)
    if (radius is None) == (shape is None):
        raise ValueError("give the tip as radius= or shape=, one of them")
    tip = ("sphere", float(radius)) if radius is not None else tuple(shape)
    if isinstance(free, str):
        free = [f.strip() for f in free.split(",")]
    free = [str(f) for f in free]
    if "contact_point" not in free and contact_point is None:
        raise ValueError("contact_point: a fixed contact point needs contact_point= (m)")
    return tip, E, nu, free, coating


def _is_path(item):
    return isinstance(item, (str, bytes, os.PathLike))


def _curve_arrays(curve, number, spring_constant):
    """A curve of read() or a mapping with the AFM tools' keys as the tuple _afm.fit_map_curves takes."""
    meta = getattr(curve, "metadata", None) or (curve.get("metadata", {}) if hasattr(curve, "get") else {})
    k = spring_constant if spring_constant is not None else meta.get("spring constant")
    if k is None:
        raise ValueError("curve: needs a spring constant (metadata \"spring constant\" or spring_constant=)")
    force = np.asarray(curve["force"], dtype=float)
    piezo = np.asarray(curve["height (piezo)"], dtype=float) if "height (piezo)" in curve else None
    measured = np.asarray(curve["height (measured)"], dtype=float) if "height (measured)" in curve else None
    for key, values in (("height (piezo)", piezo), ("height (measured)", measured)):
        if values is not None and values.shape != force.shape:
            raise ValueError(f"curve: {key!r} has {values.size} values for {force.size} forces; expected one per force")
    if "segment" in curve and np.shape(curve["segment"]) != force.shape:
        raise ValueError(f"curve: 'segment' has {np.size(curve['segment'])} values for {force.size} forces; "
                         "expected one segment number per force (0 approach, 1 retract)")
    segments = getattr(curve, "segments", None)
    if segments is not None:
        parts = [(s["kind"], int(s["begin"]), int(s["end"])) for s in segments]
    else:
        index = np.asarray(curve["segment"]) if "segment" in curve else np.zeros(len(force), dtype=int)
        parts, begin = [], 0
        for i in range(1, len(index) + 1):
            if i == len(index) or index[i] != index[begin]:
                parts.append(("approach" if index[begin] == 0 else "retract", begin, i))
                begin = i
    name = str(meta.get("path", f"curve {number}"))
    return (force, piezo, measured, parts, float(k), name, int(meta.get("curve index", number)),
            meta.get("grid index x"), meta.get("grid index y"), meta.get("position x"), meta.get("position y"))


def _fit_part(files, survey, tolerate, first, count, args, adhesion=None, baseline_model="", weight_cp=0.0):
    """One share of a fit_map run (a task of a Dask worker): curves first..first+count-1 of the
    files, read by the worker itself (the survey spares it counting the curves: it opens only
    the files of its share, once)."""
    return _afm.fit_map_files(files, *args, jobs=1, first=first, count=count, survey=survey, tolerate=tolerate,
                               adhesion=adhesion, baseline_model=baseline_model, weight_cp=weight_cp)


def _concatenated(parts):
    """The columns of the shares, in the order of the shares."""
    columns = {"names": parts[0]["names"]}
    for name in columns["names"]:
        values = [p[name] for p in parts]
        columns[name] = sum(values, []) if isinstance(values[0], list) else np.concatenate(values)
    return columns


def _shares(survey, workers):
    """(first, count) of each task: one run of consecutive curves per worker, so that each
    worker opens each file of its share once (opening a map's archive reads its whole central
    directory: ~20 ms for a 64 x 64 map, ~0.6 s for a 256 x 256 one)."""
    total = sum(entry[0] for entry in survey)
    share = max(1, -(-total // workers))
    return [(first, min(share, total - first)) for first in range(0, total, share)]


def _structured(columns):
    names = list(columns["names"])
    fields = []
    for name in names:
        column = columns[name]
        if name in ("file", "reason", "warnings"):
            width = max([len(v) for v in column] + [1])
            fields.append((name, f"U{width}"))
        else:
            fields.append((name, np.asarray(column).dtype))
    out = np.empty(len(columns["flag"]), dtype=fields)
    for name in names:
        out[name] = columns[name]
    return out


def fit_map(paths_or_curves, model="hertz", *, radius=None, shape=None, halfspace=None, film=None, substrate=None,
            thickness=None, layers=None, free=("E", "contact_point", "baseline"), contact_point=None, baseline=None,
            segment=None, spring_constant=None, sensitivity=None, tip_range=None, indentation_range=None,
            max_indentation=None, max_force=None, jobs=None, client=None, as_frame=False, work=None,
            surface_force_range=0.3e-9, tilt=None, baseline_model=None, sort_by=None, weight_cp=None,
            curve_plots=None):
    """Fits every curve of maps, QI data, files or folders (or of the curves given) and returns
    one row per curve, as `coatcontact afm fit FILES...` does (THEORY.md section 15, "Many
    curves"): each curve through fit()'s pipeline with the same keywords (preprocessed: baseline
    offset and tilt, contact point; baseline_model "tilt" by default), so a row holds the
    estimates fit() gives that curve; a curve that cannot be fitted is flagged and the others go on.

    paths_or_curves  a path, a folder (its AFM files by extension) or a list of them; or a list
                     of curves (read()'s, or mappings with "force", a height and "segment").
    jobs             threads (default: the machine's cores); the rows are the same for any jobs.
    client           a dask.distributed.Client: the curves of the files are split into one run of
                     consecutive curves per worker, each read and fitted by that worker (with one
                     thread) from the files themselves, and gathered in order; the rows are the
                     serial ones. Dask is imported only then.
    as_frame         a pandas DataFrame instead of the NumPy structured array (needs pandas).
    model            "hertz" (segment "approach" by default), or "jkr" / "md" with fit()'s keywords
                     work=, tilt=, surface_force_range= (segment "retract" by default; each curve's
                     spring constant, or spring_constant= for every curve).

    A file of several, or of a folder, that cannot be read (not a force-curve file, corrupt) is
    one row flagged unreadable (8) with a warning naming it and why; a single file given that
    cannot be read is a ValueError.

    Columns: file, curve, grid_x, grid_y (-1 when unknown), x, y [m], flag (0 fitted; 1
    no_contact, 2 jump_in, 3 no_convergence, 4 empty_segment, 5 missing_segment, 6 calibration,
    7 too_few_points, 8 unreadable, 9 bad_data; 10 undetermined: a free E, E1, t or w whose standard
    error exceeds its value, 11 no_detachment: the retract ends off the free-cantilever level; 10
    and 11 keep their estimates), reason, each free estimate ("E" [Pa], "E1" [Pa] (a stack's E<K>),
    "t" [m], "w" [J/m2] and "tilt" [N/m] of jkr and md, "contact_point" [m], "baseline" [N]) and its
    "_error", contact_point [m] when
    fixed, chi2, chi2_per_dof, residual_sigma [N], pulloff [N], pulloff_position [m],
    model_jump_off_force [N] and model_jump_off_indentation [m] (the fitted model's own jump-off
    through the spring), points, rating (0..10, docs/afm.md "Curve rating"; 0 without estimates),
    tabor_mu and maugis_lambda (these four: adhesive models; NaN for hertz), warnings ("; "-separated, "" for none);
    NaN where a flagged curve has no value.
    sort_by          "rating": the rows by their rating, highest first (stable).
    weight_cp        D [m]: nanite's contact-point weighting, as fit()'s (hertz on a half-space).
    curve_plots      FILE.pdf: one control-plot page per curve, as `afm fit --curve-plots` draws
                     them (the contact region's data, fitted points dark, the model, the contact
                     point; the residuals; file, curve, grid place, flag, rating and estimates in
                     the title), drawn with matplotlib as the rows come (not with client=);
                     written atomically when the run ends."""
    if sort_by not in (None, "rating"):
        raise ValueError(f"sort_by: {sort_by!r} is not allowed; expected 'rating' (or None: curve order)")
    model = _model_name(model)
    tip, E, nu, free, coating = _problem("afm.fit_map", model, radius, shape, halfspace, film, substrate, thickness,
                                         free, contact_point, layers)
    adhesive = _MODELS[model]["spring"]
    if not adhesive and (work is not None or tilt is not None):
        raise ValueError("work, tilt: parameters of model='jkr' or 'md' only")
    if adhesive and "w" not in free and work is None:
        raise ValueError("work: a fixed w needs work= (J/m2)")
    if adhesive and "tilt" in free and tilt is not None:
        raise ValueError("tilt: the tilt is free; drop it from free to fix it")
    # k 0: each curve's spring constant (spring_constant= sets every curve's through the calibration).
    adhesion = _adhesion(model, work, 0.0, surface_force_range, tilt) if adhesive else None
    if segment is None:
        segment = _MODELS[model]["segment"]
    lo_i, hi_i = (None, None) if indentation_range is None else (float(indentation_range[0]),
                                                                  float(indentation_range[1]))
    if max_indentation is not None:
        hi_i = float(max_indentation) if hi_i is None else min(hi_i, float(max_indentation))
    lo_t, hi_t = (None, None) if tip_range is None else (float(tip_range[0]), float(tip_range[1]))
    args = (tip, E, nu, free, float(contact_point or 0.0), float(baseline or 0.0), coating, segment, lo_t, hi_t,
            lo_i, hi_i, None if max_force is None else float(max_force))
    if baseline_model not in (None, "tilt", "offset"):
        raise ValueError(f"baseline_model: {baseline_model!r} is not allowed; expected 'tilt' or 'offset'")
    baseline_model = baseline_model or ""
    weight_cp = 0.0 if weight_cp is None else float(weight_cp)
    if not (math.isfinite(weight_cp) and weight_cp >= 0.0):
        raise ValueError(f"weight_cp: {weight_cp!r} is not allowed; expected a length > 0 (m) or None")
    if jobs is not None and (int(jobs) != jobs or jobs < 1):
        raise ValueError(f"jobs: {jobs!r} is not allowed; expected a whole number of threads >= 1 (or None: the cores)")
    k = None if spring_constant is None else _calibration(spring_constant, "spring_constant")
    s = None if sensitivity is None else _calibration(sensitivity, "sensitivity")
    items = [paths_or_curves] if _is_path(paths_or_curves) else list(paths_or_curves)
    pages = None
    if curve_plots is not None:
        if client is not None:
            raise ValueError("curve_plots: draws the pages as the rows come; not with client= (fit the paths without it)")
        pages = _CurvePlotPages(os.fspath(curve_plots), [os.fspath(i) for i in items if _is_path(i)])
    try:
        rows = _fit_map_rows(items, args, k, s, jobs, client, model_args=(adhesion, baseline_model, weight_cp),
                             spring_constant=spring_constant, pages=pages)
        if pages is not None:
            pages.commit()
    finally:
        if pages is not None:
            pages.close()
    if sort_by == "rating":
        rows = rows[np.argsort(-rows["rating"], kind="stable")]
    if as_frame:
        try:
            import pandas
        except ImportError:
            raise ImportError("as_frame=True needs pandas (Debian: python3-pandas)") from None
        return pandas.DataFrame(rows)
    return rows


def _fit_map_rows(items, args, k, s, jobs, client, model_args, spring_constant, pages):
    """The rows of fit_map (a structured array) for paths or curves; `pages` draws each row's page."""
    adhesion, baseline_model, weight_cp = model_args
    sink = pages.add if pages is not None else None
    if items and all(_is_path(i) for i in items):
        paths = [os.fspath(i) for i in items]
        files = _afm.expand_paths(paths)
        # A file that cannot be read is a flagged row of a run over several files or a folder; a
        # single file named is the run's input (ValueError).
        tolerate = len(paths) > 1 or any(os.path.isdir(p) for p in paths)
        survey = _afm.survey_files(files, k, s, tolerate)
        for curves, why, flag in survey:
            if why:
                what = "file without calibration" if flag == 6 else "unreadable file"
                warnings.warn(f"afm.fit_map: {what}, one flagged row: {why}", stacklevel=3)
        if client is None:
            columns = _afm.fit_map_files(files, *args, k, s, jobs=int(jobs or 0), first=0, count=None, survey=survey,
                                         tolerate=tolerate, adhesion=adhesion, baseline_model=baseline_model,
                                         weight_cp=weight_cp, trace_sink=sink)
        else:
            workers = max(1, len(client.scheduler_info().get("workers", {})))
            shares = _shares(survey, workers)
            # A worker reads the files in its own working folder: it gets absolute paths, and the
            # rows keep the names the caller gave, as the serial run's do.
            absolute = [os.path.abspath(f) for f in files]
            futures = [client.submit(_fit_part, absolute, survey, tolerate, first, count, args + (k, s), adhesion,
                                     baseline_model, weight_cp, pure=False)
                       for first, count in shares]
            parts = client.gather(futures)
            if parts:
                columns = _concatenated(parts)
                given = dict(zip(absolute, files))
                columns["file"] = [given.get(f, f) for f in columns["file"]]
            else:
                columns = _afm.fit_map_files(files, *args, k, s, jobs=1, first=0, count=0, survey=survey,
                                             tolerate=tolerate, adhesion=adhesion, baseline_model=baseline_model,
                                             weight_cp=weight_cp)
    elif items and not any(_is_path(i) for i in items):
        if client is not None:
            raise ValueError("client: spreads the curves of files; give paths, or fit given curves without client=")
        curves = [_curve_arrays(c, n, spring_constant) for n, c in enumerate(items)]
        columns = _afm.fit_map_curves(curves, *args, adhesion=adhesion, baseline_model=baseline_model,
                                      weight_cp=weight_cp, trace_sink=sink)
    else:
        raise ValueError("paths_or_curves: expected a path, a folder, a list of them, or a list of curves (not mixed)")
    return _structured(columns)


_PREFIXES = {-15: "f", -12: "p", -9: "n", -6: "µ", -3: "m", 0: "", 3: "k", 6: "M"}


def _prefix(magnitude, unit):
    e = 3 * math.floor(math.log10(magnitude) / 3 + 1e-9) if magnitude > 0 else 0
    e = min(max(e, -15), 6)
    return 10.0 ** -e, _PREFIXES[e] + unit


class _CurvePlotPages:
    """fit_map(curve_plots=): one page per row (the command line's --curve-plots layout), drawn
    into a temporary file beside FILE.pdf that commit() renames over it."""

    def __init__(self, path, inputs):
        if not path.endswith(".pdf"):
            raise ValueError(f"curve_plots: {path!r} is not allowed; it must end in .pdf (one page per curve)")
        if any(os.path.exists(i) and os.path.exists(path) and os.path.samefile(i, path) for i in inputs):
            raise ValueError(f"curve_plots: {path!r} is an input of the run")
        import matplotlib
        matplotlib.use("Agg", force=False)
        from matplotlib.backends.backend_pdf import PdfPages
        from matplotlib.figure import Figure
        self._figure = Figure
        import tempfile
        folder = os.path.dirname(os.path.abspath(path))
        fd, self._temporary = tempfile.mkstemp(prefix=os.path.basename(path) + ".tmp.", dir=folder)
        os.close(fd)
        self._path = path
        self._pdf = PdfPages(self._temporary)
        self.pages = 0

    def add(self, page):
        fig = self._figure(figsize=(7.5, 5.5))
        top, bottom = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2.3, 1]})
        grid = f" (grid {page['grid'][0]}, {page['grid'][1]})" if page["grid"] is not None else ""
        fig.suptitle(f"{os.path.basename(page['file'])} #{page['curve']}{grid}: {page['flag']}, "
                     f"rating {page['rating']:.1f}/10", fontsize=11)
        if page["estimates"]:
            parts = []
            for name, value, error, unit in page["estimates"]:
                scale, u = _prefix(abs(value), unit)
                digits = 7 if name in ("contact_point", "baseline") else 4
                parts.append(f"{name} = {value * scale:.{digits}g} ± {error * scale:.2g} {u}")
            key = ", ".join(parts) + f", χ²/dof = {page['chi2_per_dof']:.3g}"
        else:
            key = page["message"][:125]
        top.set_title(key, fontsize=8)
        if "z" in page:
            z, F, model, seg, fitted = (page[k] for k in ("z", "force", "model", "segment", "fitted"))
            zs, zu = _prefix(np.max(np.abs(z)), "m")
            fs, fu = _prefix(np.max(np.abs(F)), "N")
            colours = np.where(seg == 0, np.where(fitted == 1, "#0072b2", "#a6c8e0"),
                               np.where(fitted == 1, "#d55e00", "#f2bfa0"))
            top.scatter(z * zs, F * fs, s=3, c=colours)
            zc = page["contact_point"]
            lo, hi = z.min(), z.max()
            if np.isfinite(zc) and zc > lo:
                hi = min(hi, zc + 2 * (zc - lo))
                top.plot(z * zs, model * fs, color="black", lw=1.5, label="model")
                for ax in (top, bottom):
                    ax.axvline(zc * zs, color="#009e73", ls="--", lw=1.2, label="contact point" if ax is top else None)
                keep = fitted == 1
                bottom.scatter(z[keep] * zs, (model[keep] - F[keep]) * fs, s=3, c=colours[keep])
                bottom.axhline(0, color="#555555", lw=0.8, ls=":")
                inside = (z >= lo) & (z <= hi)
                top.set_ylim(*_margins(F[inside] * fs))
                top.legend(loc="upper right", fontsize=8)
            top.set_xlim(lo * zs, hi * zs)
            top.set_ylabel(f"force F ({fu})")
            bottom.set_ylabel(f"model - data ({fu})")
            bottom.set_xlabel(f"tip position z ({zu})   [the tip indents the sample for z < z_c]")
        else:
            top.text(0.5, 0.5, "no data to draw (see the flag above)", ha="center", transform=top.transAxes)
        for ax in (top, bottom):
            ax.grid(color="#dddddd")
        self._pdf.savefig(fig)
        self.pages += 1

    def commit(self):
        self._pdf.close()
        self._closed = True
        os.replace(self._temporary, self._path)

    def close(self):
        try:
            if not getattr(self, "_closed", False):
                self._pdf.close()
        finally:
            if os.path.exists(self._temporary):
                os.remove(self._temporary)


def _margins(values):
    lo, hi = float(np.min(values)), float(np.max(values))
    pad = 0.05 * (hi - lo) if hi > lo else 1.0
    return lo - pad, hi + pad
