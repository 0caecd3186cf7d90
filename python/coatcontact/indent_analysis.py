"""Oliver-Pharr and the film's modulus from an indentation test (THEORY.md section 16).

    t = coatcontact.indent.read("FS_Calibration.xls")[0]
    r = coatcontact.indent.analyse(t)                    # the file's area function and range
    r["E_mean"], r["E_sd"], r["H_mean"], r["H_sd"]       # Pa, over the depth range
    f = coatcontact.indent.film(t, thickness=500e-9, film_poisson=0.17, substrate=(162e9, 0.22))
    f["depth"], f["a_over_t"], f["E_apparent"], f["E_film"], f["E_film_error"]
    f["E_film_mean"], f["E_film_mean_error"]             # fitted over the range, with its SE

Both go through the C API (coatcontact_indent_analysis.h). A test is a coatcontact.indent.Test
or any object with ``depth``, ``load`` (and ``stiffness``, ``hardness`` or None) arrays in SI
and a ``metadata`` dict ("area coefficients", "poisson", "range"). Bad input raises
ValueError naming the option; a film modulus that no stiffness can reproduce leaves that depth
undelivered (``delivered`` False, value 0), a range without any raises NumericalError.
"""
import math

import numpy as np

from . import _core

__all__ = ["analyse", "film", "MODELS"]

MODELS = ("exact", "doerner-nix", "king", "saha-nix", "mencik-linear", "mencik-exponential",
          "mencik-reciprocal", "gao", "hay-crawford", "bec", "perriot-barthel")
_STIFFNESS = {"auto": 0, "csm": 1, "unloading": 2}
_NAN = float("nan")


def _number(value, name):
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError("%s = %r is not a number" % (name, value)) from None


def _data(test):
    meta = getattr(test, "metadata", {}) or {}
    area = meta.get("area coefficients")
    rng = meta.get("range")
    poisson = meta.get("poisson")
    arrays = []
    for name in ("stiffness", "hardness"):
        v = getattr(test, name, None)
        arrays.append(None if v is None else np.asarray(v, dtype=float))
    return _core.IndentData(np.asarray(test.depth, dtype=float), np.asarray(test.load, dtype=float),
                            arrays[0], arrays[1], [] if area is None else [float(c) for c in area],
                            _NAN if poisson is None else float(poisson),
                            _NAN if rng is None else float(rng[0]), _NAN if rng is None else float(rng[1]))


def _options(area, poisson, indenter, beta, epsilon, depth_range, stiffness, frame_stiffness):
    if isinstance(indenter, str):
        if indenter != "rigid":
            raise ValueError("indenter = %r: give (E, nu) or 'rigid'" % (indenter,))
        rigid, ei, nui = True, 1.0, 0.0
    else:
        rigid, (ei, nui) = False, indenter
    if stiffness not in _STIFFNESS:
        raise ValueError("stiffness = %r: use one of %s" % (stiffness, ", ".join(_STIFFNESS)))
    if depth_range is None:
        dmin = dmax = _NAN
    else:
        dmin, dmax = (_number(v, "depth_range") for v in depth_range)
    if isinstance(area, str):
        if area != "hardness":
            raise ValueError("area = %r: give coefficients, 'hardness' or None" % (area,))
        coefficients, from_hardness = [], True
    else:
        coefficients, from_hardness = ([] if area is None else [float(c) for c in area]), False
    options = {"area_from_hardness": from_hardness, "rigid_indenter": rigid,
               "indenter_modulus": _number(ei, "indenter"), "indenter_poisson": _number(nui, "indenter"),
               "poisson": _NAN if poisson is None else _number(poisson, "poisson"),
               "beta": _number(beta, "beta"), "epsilon": _number(epsilon, "epsilon"),
               "frame_stiffness": _NAN if frame_stiffness is None else _number(frame_stiffness, "frame_stiffness"),
               "depth_min": dmin, "depth_max": dmax, "stiffness": _STIFFNESS[stiffness]}
    return coefficients, options


def analyse(test, area=None, poisson=None, indenter=(1141e9, 0.07), beta=1.0, depth_range=None,
            epsilon=0.75, stiffness="auto", frame_stiffness=None):
    """Oliver-Pharr on one test.

    ``area``: None (the file's coefficients), "hardness" (A = P/H from the vendor's column) or
    the coefficients C0, C1, ... of A [nm^2] = C0 h^2 + C1 h + C2 h^(1/2) + ... (h_c in nm).
    ``poisson``: the sample's (None: the file's). ``indenter``: (E, nu) or "rigid".
    ``depth_range``: (min, max) [m] of the averages (None: the file's, else all points).
    ``stiffness``: "auto" (CSM when the test has it), "csm" or "unloading" (power-law fit).

    Returns a dict of per-point arrays "depth", "load", "stiffness", "contact_depth" [m],
    "area" [m^2], "contact_radius" [m], "E_r", "E", "H" [Pa], "in_range" (bool), and
    "E_mean", "E_sd", "H_mean", "H_sd" [Pa], "points" (in the range), "range" (min, max) [m],
    "poisson", "dropped" (first-contact points without a modulus); quasi-static also
    "unloading" (alpha, h_f, m, S).
    """
    coefficients, options = _options(area, poisson, indenter, beta, epsilon, depth_range, stiffness, frame_stiffness)
    raw = _core.indent_analyse(_data(test), coefficients, options)
    c, s = raw["columns"], raw["scalars"]
    out = {"depth": c["depth"], "load": c["load"], "stiffness": c["stiffness"], "contact_depth": c["contact_depth"],
           "area": c["area"], "contact_radius": c["contact_radius"], "E_r": c["reduced_modulus"], "E": c["modulus"],
           "H": c["hardness"], "in_range": c["in_range"].astype(bool),
           "E_mean": s["E_mean"], "E_sd": s["E_sd"], "H_mean": s["H_mean"], "H_sd": s["H_sd"],
           "points": int(s["range_points"]), "range": (s["range_min"], s["range_max"]), "poisson": s["poisson"],
           "dropped": int(s["dropped"])}
    if not s["csm"]:
        out["unloading"] = {"alpha": s["unload_alpha"], "h_f": s["unload_final_depth"],
                            "m": s["unload_exponent"], "S": s["unload_stiffness"]}
    return out


def film(test, thickness=None, film_poisson=None, substrate=None, layers=None, indenter=(1141e9, 0.07),
         beta=1.0, area=None, model="exact", depth_range=None, epsilon=0.75, contact_depth="half-space",
         alpha=None, film_modulus=None, max_points=200):
    """The film's modulus from the exact coated stiffness (or an empirical ``model``).

    ``thickness`` [m] and ``film_poisson`` of the film (the top layer); ``substrate``: (E0, nu0)
    or "rigid"; ``layers``: known layers below the film, top first, as (thickness, E, nu).
    ``model``: "exact" or one of MODELS. ``contact_depth``: "half-space" (eps P/S) or "coated"
    (eps scaled by the exact cone's kappa(a/t), exact model only). ``alpha``: the empirical
    models' constant (None: fitted over the range). With ``film_modulus`` given (and
    ``thickness`` None or a start value) the unknown is the thickness: the keys then read
    "t_film", "t_film_error", "t_film_mean", "t_film_mean_error" [m].

    Returns per-depth arrays "depth", "contact_depth", "contact_radius" [m], "a_over_t",
    "E_apparent" (the composite's Oliver-Pharr E) [Pa], "E_film", "E_film_error" [Pa],
    "in_range", "delivered" (bool), and "E_film_mean", "E_film_mean_error" [Pa] fitted over the
    range, "points", "rms_relative" (the fit's relative stiffness scatter), "alpha", "model".
    """
    if film_poisson is None or substrate is None:
        raise ValueError("film needs film_poisson and substrate")
    solve_thickness = film_modulus is not None
    if thickness is None and not solve_thickness:
        raise ValueError("film needs the thickness (or film_modulus to find the thickness)")
    if model not in MODELS:
        raise ValueError("model = %r: use one of %s" % (model, ", ".join(MODELS)))
    if contact_depth not in ("half-space", "coated"):
        raise ValueError("contact_depth = %r: use 'half-space' or 'coated'" % (contact_depth,))
    top = [_number(thickness if thickness is not None else 100e-9, "thickness"),
           _number(film_modulus, "film_modulus") if solve_thickness else 1.0, _number(film_poisson, "film_poisson")]
    flat = top + [_number(v, "layers") for layer in (layers or []) for v in layer]
    if isinstance(substrate, str):
        if substrate != "rigid":
            raise ValueError("substrate = %r: give (E0, nu0) or 'rigid'" % (substrate,))
        sub = {"substrate_rigid": True, "substrate_modulus": 1.0, "substrate_poisson": 0.0}
    else:
        sub = {"substrate_rigid": False, "substrate_modulus": _number(substrate[0], "substrate"),
               "substrate_poisson": _number(substrate[1], "substrate")}
    coefficients, options = _options(area, film_poisson, indenter, beta, epsilon, depth_range, "auto", None)
    f = dict(sub, solve_thickness=solve_thickness, model=model, alpha=_NAN if alpha is None else _number(alpha, "alpha"),
             coated_contact_depth=contact_depth == "coated", max_points=int(max_points))
    raw = _core.indent_film(_data(test), coefficients, options, flat, f)
    c, s = raw["columns"], raw["scalars"]
    key = "t_film" if solve_thickness else "E_film"
    return {"depth": c["depth"], "load": c["load"], "stiffness": c["stiffness"], "contact_depth": c["contact_depth"],
            "contact_radius": c["contact_radius"], "a_over_t": c["a_over_t"], "E_apparent": c["E_apparent"],
            key: c["value"], key + "_error": c["value_error"], "in_range": c["in_range"].astype(bool),
            "delivered": c["delivered"].astype(bool), key + "_mean": s["mean"], key + "_mean_error": s["mean_error"],
            "points": int(s["points"]), "rms_relative": s["rms_relative"],
            "alpha": None if math.isnan(s["alpha"]) else s["alpha"], "model": model}
