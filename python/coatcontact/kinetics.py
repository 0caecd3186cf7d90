"""Rate-dependent adhesion: crack kinetics at the JKR contact edge, driven through a spring
(docs/THEORY.md section 14)."""
import warnings

import numpy as np

from . import _core
from ._core import NumericalError  # noqa: F401  (raised by _core.kinetics)


def _segment(item):
    if not isinstance(item, (tuple, list)) or not item:
        raise ValueError("protocol: each segment is a tuple, e.g. ('approach', 1e-6, 1e-3), got %r" % (item,))
    kind = item[0]
    values = [float(v) for v in item[1:]]
    if kind == "approach" and len(values) == 2:
        return ("approach", values[0], 0.0, values[1], True)
    if kind == "dwell" and len(values) == 1:
        return ("dwell", 0.0, values[0], 0.0, False)
    if kind == "retract" and len(values) in (1, 2):
        return ("retract", values[0], 0.0, values[1] if len(values) == 2 else 0.0, len(values) == 2)
    raise ValueError("protocol: segment %r not understood; expected ('approach', speed, force), "
                     "('dwell', time) or ('retract', speed[, force])" % (item,))


def _materials(film, substrate):
    from . import _material  # the package's (E, nu) reader: numbers or texts with a unit
    e1, nu1 = _material(film, "film")
    if isinstance(substrate, str):
        if substrate != "rigid":
            raise ValueError("substrate: expected (E0, nu0) or 'rigid', got %r" % substrate)
        return e1, nu1, True, 1.0, 0.0
    e0, nu0 = _material(substrate, "substrate")
    return e1, nu1, False, e0, nu0


def _tip(radius, shape):
    """(R, beta) of the indenter: a sphere (beta = 0) or a cone (section 14, "The cone")."""
    if shape is None:
        if radius is None:
            raise ValueError("radius or shape: give the sphere's radius=R or shape=('sphere', R) / ('cone', beta)")
        return float(radius), 0.0
    if radius is not None:
        raise ValueError("radius: not with shape (give shape=('sphere', R))")
    if isinstance(shape, (tuple, list)) and len(shape) == 2 and shape[0] in ("sphere", "cone"):
        value = float(shape[1])
        if shape[0] == "sphere":
            return value, 0.0
        if not 0.0 < value < np.pi / 2:
            raise ValueError("shape: cone half angle %r rad not allowed (need 0 < beta < pi/2)" % (shape[1],))
        return 0.0, value
    raise ValueError("shape: expected ('sphere', R) or ('cone', beta [rad]), the shapes the JKR table serves; "
                     "got %r" % (shape,))


def kinetics(*, film, substrate, thickness, work, v_star, n, spring, protocol, radius=None, shape=None,
             v_star_adv=None, n_adv=None, retract_speeds=None, tol=1e-8):
    """Rate-dependent JKR adhesion of a sphere or a cone on a coating (section 14).

    film        (E1 [Pa], nu1);  substrate  (E0 [Pa], nu0) or "rigid".
    radius      sphere radius R [m]; or shape=("sphere", R) or ("cone", beta), beta the half
                included angle in rad (as shape_contact); thickness  coating thickness t [m];
                work  w [J/m^2].
    v_star, n   receding edge: G - w = w (|v|/v_star)^n  (v_star [m/s], n > 0).
    v_star_adv, n_adv
                advancing edge: w - G = w (v/v_star_adv)^n_adv (default: the receding values).
    spring      k [N/m] between the base and the sphere, F = k (z - delta); 0 is load control
                (speeds are then force rates in N/s), math.inf displacement control.
    protocol    list of ("approach", speed, force), ("dwell", time), ("retract", speed[, force]),
                from first contact; the last is a retract until contact is lost.
    retract_speeds
                optional array: run once per speed of the last retract (the part before it is
                simulated once) and return only the pull-offs, under "sweep".
    tol         relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).

    Returns a dict: t [s], z [m], delta [m], a [m], F [N], G [J/m^2] (arrays, F compressive
    positive); pulloff (F, t, a: the most tensile force of the last retract); loss (F, t, a
    where contact is lost); work, dissipation (reduced, pi w l^2); scales (l, delta_scale,
    F_scale, t_scale = l/v_star, eta, k_bar, drive_rate; the cone's l, delta_scale, F_scale are
    its own, section 14). With retract_speeds: scales and
    sweep (arrays V, F, t, a, F_loss, t_loss and the reduced pull-off P).
    """
    e1, nu1, rigid, e0, nu0 = _materials(film, substrate)
    tip_radius, half_angle = _tip(radius, shape)
    segments = [_segment(item) for item in protocol]
    speeds = [] if retract_speeds is None else [float(v) for v in np.atleast_1d(retract_speeds)]
    return _core.kinetics(e1, nu1, rigid, e0, nu0, tip_radius, half_angle, float(thickness), float(work),
                          float(v_star), float(n), 0.0 if v_star_adv is None else float(v_star_adv),
                          0.0 if n_adv is None else float(n_adv), float(spring), segments, speeds,
                          float(tol))


_FIT_NAMES = ("w", "v_star", "n", "t", "E1")


def kinetics_fit(*, film, substrate, radius, thickness, work, v_star, n, curves,
                 free=("w", "v_star", "n"), v_star_adv=None, n_adv=None, tol=1e-8):
    """Fit the crack-kinetics law to force-time curves at several retract speeds (section 14,
    "Fitting the law to curves at several speeds"); the CLI's `coatcontact kinetics --fit`.

    film, substrate, radius, thickness, v_star_adv, n_adv, tol: as kinetics().
    work, v_star, n
                start values of the free parameters, values of the fixed ones (E1 starts at
                film[0]).
    curves      list of dicts, one per measured curve: "protocol" (as kinetics(), from first
                contact, ending with the retract), "spring" k [N/m], "t" [s since first
                contact], "F" [N], optional "sigma_F" [N] (all curves or none).
    free        names among "w", "v_star", "n", "t", "E1". v_star and n together need curves
                at two retract speeds at least (ValueError otherwise); each value of E1 the fit
                tries builds its own table (slower: seconds per iteration).

    Returns a dict: names, values, errors, free (per parameter, in the order w, v_star, n, t, E1),
    correlation, F_model and residual (all points of all curves in order), r_squared,
    chi2_per_dof (None without sigma_F), residual_sigma, iterations, simulations, seconds.
    """
    e1, nu1, rigid, e0, nu0 = _materials(film, substrate)
    unknown = [name for name in free if name not in _FIT_NAMES]
    if unknown:
        raise ValueError("free: unknown parameter %r (allowed: w, v_star, n, t, E1)" % unknown[0])
    packed = []
    for index, curve in enumerate(curves):
        missing = [key for key in ("protocol", "spring", "t", "F") if key not in curve]
        if missing:
            raise ValueError("curves[%d]: missing %r (need protocol, spring, t, F)" % (index, missing[0]))
        sigma = curve.get("sigma_F")
        packed.append(([_segment(item) for item in curve["protocol"]], float(curve["spring"]),
                       [float(v) for v in np.atleast_1d(curve["t"])],
                       [float(v) for v in np.atleast_1d(curve["F"])],
                       [] if sigma is None else [float(v) for v in np.atleast_1d(sigma)]))
    result = _core.kinetics_fit(e1, nu1, rigid, e0, nu0, float(radius), float(thickness), float(work),
                                float(v_star), float(n), 0.0 if v_star_adv is None else float(v_star_adv),
                                0.0 if n_adv is None else float(n_adv), packed,
                                [name in free for name in _FIT_NAMES], float(tol))
    result["values"] = np.asarray(result["values"])
    _warn_kinetics_correlation(result, free)
    return result


def _warn_kinetics_correlation(result, free):
    """A CorrelationWarning per pair of free parameters with |r| > 0.99, as `fit`."""
    from . import CorrelationWarning, _MAX_CORRELATION
    corr = np.asarray(result.get("correlation", []), dtype=float)
    names = [name for name in _FIT_NAMES if name in free]
    index = [_FIT_NAMES.index(name) for name in names]
    if corr.ndim != 2 or corr.shape[0] < len(_FIT_NAMES):
        return
    for i, a in enumerate(names):
        for b in names[i + 1:]:
            r = corr[index[i], _FIT_NAMES.index(b)]
            if abs(r) > _MAX_CORRELATION:
                warnings.warn("correlation %s-%s = %.4g (|r| > %g): the curves hardly separate them; fix one or "
                              "add curves that do" % (a, b, r, _MAX_CORRELATION), CorrelationWarning, stacklevel=4)


__all__ = ["kinetics", "kinetics_fit"]
