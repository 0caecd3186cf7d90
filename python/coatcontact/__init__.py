"""coatcontact: adhesive contact of an indenter with a coated elastic substrate.

A thin layer over the library's C interface (coatcontact/coatcontact.h): the surface-stress-
transform solution of E. Barthel and A. Perriot, J. Phys. D 40 (2007) 1059. NumPy arrays in,
dicts of NumPy arrays out; every solve runs in the compiled library with the GIL released.
Section numbers (section N) refer to docs/THEORY.md.

    import numpy as np, coatcontact as cc
    r = cc.reduced(film=(0.1, 0.25), substrate=(1, 0.25), a_over_t=np.geomspace(0.01, 100, 200))
    r["E_eq"], r["Gamma1"], r["error_estimate"]   # one value per radius

Functions
    reduced         reduced variables Pi_s, Delta_s, Pi_c, Delta_c, E_eq, Gamma1 (sections 4-5)
    adhesive_curve  normalized JKR curve P(a_bar), D(a_bar) at one eta (section 5)
    pulloff         normalized pull-off under load and displacement control (section 5)
    contact         sphere on a coating in SI units: a [m], delta [m], F [N], pull-off (section 5)
    fit             least-squares w (t, E1) of one film from measured (a, F) or (delta, F) data
    fit_stack       least-squares fit of any of w, h1..hN, E1..EN of a layered coating
    stack_parameter_names
                    the parameter names of a stack fit, in the order of its arrays
    pulloff_spring  pull-off through a spring of normalized stiffness k_bar (section 10)
    maugis_dugdale_curve, maugis_dugdale_pulloff
                    finite interaction zone, lambda = 2 sigma0 (R/(pi w K^2))^(1/3) (section 13)
    shape_contact   any axisymmetric indenter in SI units: sphere, cone, punch, power law,
                    blunted cone, measured profile (section 11)
    kinetics        rate-dependent adhesion: crack kinetics at the contact edge, driven
                    through a spring, from first contact to the loss of contact (section 14)
    kinetics_fit    w, v*, n from force-time curves at several retract speeds (section 14)

Classes
    Stack           film (layers), substrate or "rigid", indenter (sections 1, 9, 12)
    ReducedSolver   the solver of one stack (kernel table built once)
    AdhesiveModel   interpolated reduced variables of one stack: curves, pull-off, contacts
    Contact         one sphere radius R, thickness t, work of adhesion w on a model

Units and normalization (sections 1 and 5): moduli in Pa (or any consistent unit for the
normalized functions), lengths in m, forces in N, compressive positive. E* is the top
layer's E/(1 - nu^2) (E_r with an elastic indenter); with sphere radius R, work of adhesion w
and coating thickness t, l = (pi w R^2/E*)^(1/3), a = a_bar l, t = eta l, delta = D l^2/R,
F = P pi w R.

Errors: ValueError for input outside its allowed range (the library's message: the text the
command line prints after the option names), NumericalError (a RuntimeError) when a result cannot be reached to
its tolerance. No function returns NaN.
"""
import functools
import math
import re
import sys
import time
import warnings

import numpy as np

from . import _core
from ._core import NumericalError
from ._version import __version__, __license__
from . import afm  # real AFM force curves: coatcontact.afm.read (afm.py)
from . import indent  # nanoindentation files: coatcontact.indent.read (indent.py)

__all__ = ["Stack", "ReducedSolver", "AdhesiveModel", "Contact", "NumericalError", "ValidityWarning",
           "PointsNotDeliveredWarning", "CorrelationWarning",
           "reduced", "adhesive_curve", "pulloff", "contact", "fit", "fit_stack",
           "stack_parameter_names", "pulloff_spring", "read_curve",
           "maugis_dugdale_curve", "maugis_dugdale_pulloff", "shape_contact", "kinetics", "kinetics_fit",
           "REDUCED_KEYS"]

from .kinetics import kinetics, kinetics_fit  # noqa: E402  (section 14)

NumericalError.__doc__ = ("A result could not be delivered to its tolerance (the command "
                          "line's exit status 3); a RuntimeError.")
NumericalError.__module__ = __name__

#: Keys of reduced()'s result, the columns of `coatcontact reduced`.
REDUCED_KEYS = ("a_over_t", "Pi_s", "Delta_s", "Pi_c", "Delta_c", "E_eq", "Gamma1", "error_estimate")
_PULLOFF_KEYS = ("P_load", "a_bar_load", "D_load", "P_disp", "a_bar_disp", "D_disp")
_DEFAULT_TOL = 1e-8


# The CLI's unit spellings (coatcontact/units.hpp) for values given as text, e.g. "1MPa".
_UNITS = {
    "pressure": {"Pa": 1.0, "kPa": 1e3, "MPa": 1e6, "GPa": 1e9},
    "length": {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6, "\u00b5m": 1e-6, "\u03bcm": 1e-6, "nm": 1e-9},
    "energy per area": {"J/m2": 1.0, "mJ/m2": 1e-3, "J/m^2": 1.0, "mJ/m^2": 1e-3, "N/m": 1.0, "mN/m": 1e-3},
}
_NUMBER = re.compile(r"\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s?(\S*)\s*$")


def _si(value, kind, what):
    """A number (SI) or a text with a unit of `kind` ("1MPa", "50 um") -> float [SI]."""
    if isinstance(value, str):
        match = _NUMBER.match(value)
        units = _UNITS[kind]
        if not match or (match.group(2) and match.group(2) not in units):
            raise ValueError("%s: %r is not a %s; give a number in SI units or a text with a unit (%s)"
                             % (what, value, kind, " ".join(units))) from None
        number, unit = float(match.group(1)), match.group(2)
        factor = units[unit] if unit else 1.0
        # As the library's to_si: sub-units divide by the exact power of ten.
        return number / round(1.0 / factor) if factor < 1.0 else number * factor
    try:
        return float(value)
    except (TypeError, ValueError):
        raise ValueError("%s: expected a number (SI) or a text with a unit, got %s"
                         % (what, type(value).__name__)) from None


_FORCE_UNITS = {"N": 1.0, "mN": 1e-3, "uN": 1e-6, "\u00b5N": 1e-6, "\u03bcN": 1e-6, "nN": 1e-9}
_STIFFNESS_EXPECTED = ("expected a number with an optional unit (N/m, or a force unit over a length unit: "
                       "N/mm mN/um nN/nm ...)")


def _to_si(value, factor):
    # The library's to_si: sub-units divide by the exact power of ten.
    return value / round(1.0 / factor) if factor < 1.0 else value * factor


def _stiffness(value, what="spring"):
    """A spring stiffness k [N/m]: a number (SI) or a text with a unit ("500N/m", "0.5mN/um"),
    > 0 and finite, read and refused as the CLI's --spring reads it."""
    if isinstance(value, str):
        match = _NUMBER.match(value)
        if not match:
            raise ValueError("%s: stiffness %r is not a number; %s" % (what, value.strip(), _STIFFNESS_EXPECTED))
        number, unit = float(match.group(1)), match.group(2)
        si = number
        if unit:
            top, _, bottom = unit.partition("/")
            below = _UNITS["length"].get(bottom, 0.0)
            if top not in _FORCE_UNITS or below == 0.0:
                raise ValueError("%s: unknown stiffness unit %r in %r; %s" % (what, unit, value, _STIFFNESS_EXPECTED))
            si = _to_si(number, _FORCE_UNITS[top])
            si = si * round(1.0 / below) if below < 1.0 else si / below
        shown = repr(value)
    else:
        try:
            number = si = float(value)
        except (TypeError, ValueError):
            raise ValueError("%s: expected a stiffness [N/m] (a number or a text with a unit), got %s"
                             % (what, type(value).__name__)) from None
        shown = repr(number)
    if not number > 0.0:
        raise ValueError("%s: stiffness %s must be > 0" % (what, shown))
    if not (math.isfinite(si) and 1e-100 <= si <= 1e100):
        raise ValueError("%s: stiffness %s is outside the allowed range [1e-100, 1e100] (SI units)" % (what, shown))
    return si


def _material(value, what):
    try:
        e, nu = value
    except (TypeError, ValueError):
        raise ValueError("%s: expected (E, nu), e.g. (1e6, 0.49) or (\"1MPa\", 0.49), got %r" % (what, value)) from None
    try:
        nu = float(nu)
    except (TypeError, ValueError):
        raise ValueError("%s: Poisson ratio %r is not a number" % (what, nu)) from None
    return _si(e, "pressure", what + " E"), nu


class Stack:
    """The elastic system: layers on a substrate, touched by an indenter (sections 1, 9, 12).

    Stack(film=(E1, nu1), substrate=(E0, nu0) or "rigid", indenter=None)
    Stack(layers=[(t, E1, nu1), ...], substrate=..., indenter=...)

    film        (Young's modulus [Pa], Poisson ratio) of a single coating; its thickness
                enters only through a/t, eta or the t of contact() and fit().
    layers      (thickness, Young's modulus [Pa], Poisson ratio[, slip]) per layer, top
                first, 1 to 1000 layers (section 12); slip=True makes the interface below
                that layer frictionless. Normalized results use the total thickness T.
    substrate   (E0 [Pa], nu0) or "rigid".
    indenter    None or "rigid" (default), or (E2 [Pa], nu2): an elastic indenter makes
                E_r, 1/E_r = 1/E1* + 1/E2*, the reference modulus (section 9).

    Every value is checked at once with the library's rules (ValueError). A Stack is
    immutable after construction and may be shared between threads.
    """

    def __init__(self, film=None, *, layers=None, substrate=None, indenter=None):
        if (film is None) == (layers is None):
            raise ValueError("stack: give either film=(E, nu) or layers=[(t, E, nu), ...]")
        if substrate is None:
            raise ValueError("stack: give substrate=(E0, nu0) or substrate='rigid'")
        if layers is None:
            layers = [(1.0,) + _material(film, "film")]
        self._core = _core.Stack()
        def _layer(layer):
            if len(layer) not in (3, 4):
                raise ValueError("stack: a layer is (t, E, nu) or (t, E, nu, slip), got %r" % (layer,))
            t = _si(layer[0], "length", "layer thickness")
            e, nu = _material(layer[1:3], "layer")
            return (t, e, nu, bool(layer[3]) if len(layer) == 4 else False)
        self.layers = tuple(_layer(layer) for layer in layers)
        for t, e, nu, slip in self.layers:
            self._core.add_layer(t, e, nu, slip)
        if isinstance(substrate, str):
            if substrate != "rigid":
                raise ValueError("stack: substrate %r is neither (E0, nu0) nor 'rigid'" % substrate)
            self._core.set_rigid_substrate()
            self.substrate = "rigid"
        else:
            self.substrate = _material(substrate, "substrate")
            self._core.set_substrate(*self.substrate)
        if indenter is None or (isinstance(indenter, str) and indenter == "rigid"):
            self.indenter = "rigid"
        elif isinstance(indenter, str):
            raise ValueError("stack: indenter %r is neither (E2, nu2) nor 'rigid'" % indenter)
        else:
            self.indenter = _material(indenter, "indenter")
            self._core.set_indenter(*self.indenter)

    @property
    def reference_modulus(self):
        """E* of the normalizations [Pa]: the top layer's E/(1 - nu^2), or E_r (section 9)."""
        return self._core.reference_modulus()

    def _key(self):
        return (self.layers, self.substrate, self.indenter)

    def __repr__(self):
        return "Stack(layers=%r, substrate=%r, indenter=%r)" % self._key()

    def __eq__(self, other):
        return isinstance(other, Stack) and self._key() == other._key()

    def __hash__(self):
        return hash(self._key())


def _stack(stack, film, substrate, indenter):
    if stack is not None:
        if film is not None or substrate is not None or indenter is not None:
            raise ValueError("give either a Stack or film=/substrate=/indenter=, not both")
        if not isinstance(stack, Stack):
            raise ValueError("stack: expected a coatcontact.Stack, got %r" % type(stack).__name__)
        return stack
    if film is None:
        raise ValueError("give a Stack or film=(E, nu) and substrate=(E0, nu0) or 'rigid'")
    return Stack(film, substrate=substrate, indenter=indenter)


class _ProgressLine:
    """progress=True: "done/total" on stderr, redrawn at most every 0.2 s and at the end."""

    def __init__(self):
        self._last = 0.0

    def __call__(self, done, total):
        now = time.monotonic()
        if done < total and now - self._last < 0.2:
            return
        self._last = now
        sys.stderr.write("\rcoatcontact: %d/%d%s" % (done, total, "\n" if done >= total else ""))
        sys.stderr.flush()


def _progress(progress):
    # None: no reports; True: a line on stderr; else a callable(done, total) (its exception,
    # like Ctrl-C, stops the call and is raised).
    if progress is None or progress is False:
        return None
    if progress is True:
        return _ProgressLine()
    if not callable(progress):
        raise ValueError("progress must be None, True or a callable(done, total)")
    return progress


def _tolerance(tol):
    # The C interface reads 0 as "the default"; a Python caller's tol is checked against the
    # documented range instead, so tol=0 (or nan) is refused, not silently replaced.
    value = float(tol)
    if not (_MIN_TOL <= value <= _MAX_TOL):
        raise ValueError("tolerance tol = %r not allowed (need %g <= tol <= %g)" % (tol, _MIN_TOL, _MAX_TOL))
    return value


_MIN_TOL = 1e-13
_MAX_TOL = 1e-1


class ValidityWarning(UserWarning):
    """A curve leaves the model's validity limits (a > 0.1 R, a past the sphere's radius,
    penetration above the coating thickness, mean pressure above 0.1 E*); the messages come
    from the library (coatcontact/limits.hpp), the same as the command-line warnings."""


def _warn_validity(core_contact, out):
    rows = np.column_stack([np.ravel(out["a"]), np.ravel(out["delta"]), np.ravel(out["F"])])
    for message in core_contact.validity(np.ascontiguousarray(rows, dtype=float)).splitlines():
        warnings.warn(message, ValidityWarning, stacklevel=3)


class CorrelationWarning(UserWarning):
    """Two free parameters of a fit correlated beyond |r| = 0.99: the data hardly separate
    them (their standard errors are large and their values depend on each other); fix one
    or add data that tells them apart. The CLI's `fit` warns the same."""


_MAX_CORRELATION = 0.99


def _warn_correlation(by_name):
    for (a, b), r in by_name.items():
        if a < b and abs(r) > _MAX_CORRELATION:
            warnings.warn("correlation %s, %s = %.4g (|r| > %g): the data hardly separate %s and %s; fix one of "
                          "them or add data that tells them apart" % (a, b, r, _MAX_CORRELATION, a, b),
                          CorrelationWarning, stacklevel=4)


class PointsNotDeliveredWarning(UserWarning):
    """Some points of an array could not be delivered to the tolerance; their values are masked
    and the result's "status" and "reason" say which and why (strict=True raises instead)."""


def _points(out, value_keys, status, reasons, shape, what):
    # The tolerant result: status (0 delivered, 3 not: the command line's numerical-failure
    # code) and reason per point; where a point failed, the value arrays are numpy masked
    # arrays with that point masked (its stored value is 0, never NaN).
    status = np.asarray(status).reshape(shape)
    failed = status != 0
    out["status"] = status
    out["reason"] = np.array(reasons, dtype=object).reshape(shape)
    if failed.any():
        for key in value_keys:
            out[key] = np.ma.masked_array(out[key], mask=failed)
        first = int(np.flatnonzero(failed.ravel())[0])
        warnings.warn("%d of %d %s not delivered (the first, index %d: %s); their values are masked"
                      % (int(failed.sum()), failed.size, what, first, out["reason"].ravel()[first]),
                      PointsNotDeliveredWarning, stacklevel=3)
    return out


class ReducedSolver:
    """The reduced-variable solver of one stack (sections 4-5); builds the kernel table once.

    ReducedSolver(stack).solve(a_over_t, tol=1e-8) -> dict, as reduced(). Thread-safe.
    """

    def __init__(self, stack):
        self.stack = stack
        self._core = _core.Solver(stack._core)

    def solve(self, a_over_t, tol=_DEFAULT_TOL, progress=None, strict=False):
        """Reduced variables at each contact radius over coating thickness a/t in (0, 1e8].

        Returns a dict of arrays of the shape of a_over_t with the keys REDUCED_KEYS: a_over_t;
        Pi_s, Delta_s (adhesionless sphere); Pi_c, Delta_c (cone); E_eq (flat-punch
        stiffness over E*); Gamma1 (edge stress intensity); error_estimate (bound on the
        largest relative error of the six, <= tol).
        tol: relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).
        progress: see reduced(). Ctrl-C stops the call between radii (KeyboardInterrupt).
        strict: see reduced() (status, reason and masked values unless strict).
        """
        x = np.asarray(a_over_t, dtype=float)
        flat = np.ascontiguousarray(x.ravel())
        if strict:
            table = self._core.sweep(flat, _tolerance(tol), _progress(progress))
            return {k: table[:, i].reshape(x.shape) for i, k in enumerate(REDUCED_KEYS)}
        table, status, reasons = self._core.sweep_each(flat, _tolerance(tol), _progress(progress))
        out = {k: table[:, i].reshape(x.shape) for i, k in enumerate(REDUCED_KEYS)}
        return _points(out, REDUCED_KEYS[1:], status, reasons, x.shape, "radii")


class AdhesiveModel:
    """JKR adhesive sphere on one stack, normalized (section 5, [EqSolNormF, EqSolNormD]).

    The reduced variables are solved at `tol` on Chebyshev nodes and interpolated; a model
    is built once and reused by every curve, pull-off and contact made from it. Calls on one
    model are serialized (its cache is filled lazily).
    tol: relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).
    """

    def __init__(self, stack, tol=_DEFAULT_TOL):
        self.stack = stack
        self.tol = float(tol)
        self._core = _core.Model(_solver(stack)._core, _tolerance(tol))

    @property
    def default_range(self):
        """Default a_bar range of a curve: [0.01 min(1, r), 10 max(1, r)], r = (E*/E_base*)^(1/3)."""
        return self._core.default_range()

    def curve(self, eta, a_bar=None, points=400, strict=False):
        """Load P and penetration D versus contact radius a_bar at one eta.

        eta     coating thickness over l = (pi w R^2/E*)^(1/3), in [1e-6, 1e6].
        a_bar   contact radii a/l, each in [1e-6, 1e6]; default `points` log-spaced over
                default_range (as `coatcontact adhesive`).
        Returns a dict of arrays: a_bar, a_over_t (= a_bar/eta), P = F/(pi w R),
        D = delta/(l^2/R); status and reason per point unless strict (see reduced()).
        """
        if a_bar is None:
            lo, hi = self.default_range
            a_bar = np.geomspace(lo, hi, int(points))
        x = np.asarray(a_bar, dtype=float)
        keys = ("a_bar", "a_over_t", "P", "D")
        if strict:
            table = self._core.curve(float(eta), np.ascontiguousarray(x.ravel()))
            return {k: table[:, i].reshape(x.shape) for i, k in enumerate(keys)}
        table, status, reasons = self._core.curve_each(float(eta), np.ascontiguousarray(x.ravel()))
        out = {k: table[:, i].reshape(x.shape) for i, k in enumerate(keys)}
        return _points(out, ("P", "D"), status, reasons, x.shape, "points")

    def pulloff(self, eta, progress=None):
        """Pull-off at each eta: the minimum of P(a_bar) (load control) and of D (displacement).

        progress: None, True (a progress line on stderr) or a callable(done, total), called
        after each eta. Ctrl-C stops the call (KeyboardInterrupt), also inside the first
        call's build of the model's interpolant.

        Returns a dict of arrays of the shape of eta: eta, P_load, a_bar_load, D_load,
        P_disp, a_bar_disp, D_disp, and flags (bitmask: 1 several load minima, 2 no interior
        load minimum, 4/8 the same under displacement control, 16 scan truncated at large
        a/t). Homogeneous limit: P_load = -3/2, P_disp = -5/6.
        """
        x = np.asarray(eta, dtype=float)
        table, flags = self._core.pulloff(np.ascontiguousarray(x.ravel()), _progress(progress))
        out = {"eta": x.copy()}
        out.update({k: table[:, i].reshape(x.shape) for i, k in enumerate(_PULLOFF_KEYS)})
        out["flags"] = flags.reshape(x.shape)
        return out

    def contact(self, radius, thickness, work):
        """A Contact of a sphere of radius R [m] on a coating of thickness t [m] with work of
        adhesion w [J/m^2] on this model."""
        return Contact(self, radius, thickness, work)


# Radii of the scan that ends a default curve at the validity limits (~16 per decade over the
# default range, as the CLI's scan).
_SCAN_POINTS = 64


def _last_inside(rows, validity):
    """The largest first-column value of `rows` before the first row outside the validity
    limits (validity(row) returns the warnings' text); None when the first row is outside,
    the last value when none is."""
    last = None
    for row in rows:
        if validity(row).strip():
            break
        last = float(row[0])
    return last


class Contact:
    """A sphere of radius R [m] on a coating of total thickness t [m], work of adhesion
    w [J/m^2], in SI units (section 5). eta = t/l must lie in [1e-6, 1e6]."""

    def __init__(self, model, radius, thickness, work):
        self.model = model
        self._core = _core.Contact(model._core, float(radius), float(thickness), float(work))
        l, dscale, fscale, eta = self._core.scales()
        #: l [m], l^2/R [m], pi w R [N] and eta = t/l.
        self.scales = {"l": l, "delta_scale": dscale, "F_scale": fscale, "eta": eta}

    def at(self, a, strict=False):
        """Penetration delta [m] and force F [N] (compressive positive) at contact radii a [m].
        Returns a dict of arrays a, delta, F of the shape of a; status and reason per point
        unless strict (see reduced())."""
        x = np.asarray(a, dtype=float)
        if strict:
            table = self._core.at(np.ascontiguousarray(x.ravel()))
            return {k: table[:, i].reshape(x.shape) for i, k in enumerate(("a", "delta", "F"))}
        table, status, reasons = self._core.at_each(np.ascontiguousarray(x.ravel()))
        out = {k: table[:, i].reshape(x.shape) for i, k in enumerate(("a", "delta", "F"))}
        return _points(out, ("delta", "F"), status, reasons, x.shape, "contact radii")

    def curve(self, points=200):
        """The curve at `points` radii log-spaced over the model's default a_bar range, ended,
        as `coatcontact sphere` ends it, at the largest radius still inside the validity
        limits (but past the pull-off under load control): dict of arrays a [m], delta [m],
        F [N]."""
        keys = ("a", "delta", "F")
        if int(points) < 2:  # the library's own refusal (ValueError) of a point count
            self._core.curve(int(points))
        scan = self._core.curve(_SCAN_POINTS)
        hi = _last_inside(scan, lambda row: self._core.validity(np.ascontiguousarray(row[None, :3])))
        if hi is None:  # even the first radius is outside: the full range, the warnings say so
            table = self._core.curve(int(points))
            return {k: table[:, i] for i, k in enumerate(keys)}
        pull = self.pulloff()
        hi = max(hi, min(1.2 * pull["a_load"], scan[-1, 0]))
        radii = np.geomspace(scan[0, 0], hi, int(points))
        radii[-1] = hi
        out = self.at(radii, strict=True)
        return {k: np.asarray(out[k]) for k in keys}

    def pulloff(self):
        """Pull-off in SI units: dict F_load [N], a_load [m], delta_load [m], F_disp, a_disp,
        delta_disp, flags (as AdhesiveModel.pulloff)."""
        values, flags = self._core.pulloff()
        keys = ("F_load", "a_load", "delta_load", "F_disp", "a_disp", "delta_disp")
        out = {k: float(values[i]) for i, k in enumerate(keys)}
        out["flags"] = int(flags)
        return out

    def pulloff_spring(self, k):
        """Pull-off through a spring of stiffness k [N/m] (section 10, `coatcontact sphere
        --spring k`): the jump where dF/d(delta) = -k, at k_bar = k (l^2/R)/(pi w R). Returns a
        dict k [N/m], k_bar, F_spring [N], a_spring [m], delta_spring [m]."""
        k = _stiffness(k)
        k_bar = k * self.scales["delta_scale"] / self.scales["F_scale"]
        row = _core.pulloff_spring(self.model._core, self.scales["eta"], np.array([k_bar]))[0]
        scales = self.scales
        return {"k": k, "k_bar": float(k_bar), "F_spring": float(row[0]) * scales["F_scale"],
                "a_spring": float(row[1]) * scales["l"], "delta_spring": float(row[2]) * scales["delta_scale"]}


# Solvers are read-only and models serialize their own calls: both are cached per stack so
# that repeated calls do not rebuild the kernel table or the interpolant.
@functools.lru_cache(maxsize=16)
def _solver(stack):
    return ReducedSolver(stack)


@functools.lru_cache(maxsize=16)
def _model(stack, tol):
    return AdhesiveModel(stack, tol)


def reduced(stack=None, *, film=None, substrate=None, indenter=None, a_over_t, tol=_DEFAULT_TOL,
            progress=None, strict=False):
    """Reduced variables of the coated-substrate contact (sections 4-5), one per radius.

    reduced(stack, a_over_t=...) or reduced(film=(E1, nu1), substrate=(E0, nu0) | "rigid",
    indenter=None | (E2, nu2), a_over_t=...).

    a_over_t  contact radius over coating thickness, each in (0, 1e8] (array or scalar).
    tol       relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).

    Returns a dict of arrays of the shape of a_over_t with the keys REDUCED_KEYS, the columns
    of `coatcontact reduced`: a_over_t, Pi_s, Delta_s (adhesionless sphere), Pi_c, Delta_c
    (cone), E_eq (flat-punch stiffness over E*), Gamma1 (edge stress intensity, section 6),
    error_estimate (bound on the largest relative error of the six; <= tol).
    progress  None, True (a progress line on stderr) or a callable(done, total) called
              between radii (an exception it raises stops the call and is raised).
    Every radius that can be solved is returned: "status" (0 delivered, 3 the tolerance could
    not be met there) and "reason" ("" or why) per radius; when a radius failed, the value
    arrays are numpy masked arrays with it masked, and a PointsNotDeliveredWarning says how
    many. strict=True raises NumericalError at the first such radius instead (no status keys).
    Raises ValueError for input out of range, NumericalError when no radius can be delivered
    (or, with strict, any one), KeyboardInterrupt on Ctrl-C (checked between radii).
    """
    return _solver(_stack(stack, film, substrate, indenter)).solve(a_over_t, tol, progress, strict)


def adhesive_curve(stack=None, *, film=None, substrate=None, indenter=None, eta, a_bar=None,
                   points=400, tol=_DEFAULT_TOL, strict=False):
    """Normalized JKR curve of a rigid sphere on the coated substrate at one eta (section 5).

    eta    coating thickness over l = (pi w R^2/E*)^(1/3), in [1e-6, 1e6].
    a_bar  contact radii a/l (default `points` log-spaced over the model's default range,
           [0.01 min(1, r), 10 max(1, r)], r = (E*/E_base*)^(1/3), as `coatcontact adhesive`).
    Returns a dict of arrays: a_bar, a_over_t = a_bar/eta, P = F/(pi w R), D = delta R/l^2.
    Homogeneous limit (a film like its substrate): the JKR curve
    P = (4/3) a_bar^3 - 2 sqrt(2) a_bar^(3/2), D = a_bar^2 - sqrt(2 a_bar).
    tol    relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).
    status, reason per point and masked P, D where the table's decade cannot be built at tol,
    unless strict=True (NumericalError): as reduced().
    """
    return _model(_stack(stack, film, substrate, indenter), float(tol)).curve(eta, a_bar, points, strict)


def pulloff(stack=None, *, film=None, substrate=None, indenter=None, eta, tol=_DEFAULT_TOL,
            progress=None):
    """Normalized pull-off at each eta (section 5): dict of arrays eta, P_load, a_bar_load,
    D_load (minimum of P, load control), P_disp, a_bar_disp, D_disp (minimum of D,
    displacement control), flags (see AdhesiveModel.pulloff). JKR: -3/2 and -5/6.
    progress as in AdhesiveModel.pulloff (per eta); Ctrl-C raises KeyboardInterrupt.
    tol: relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8)."""
    return _model(_stack(stack, film, substrate, indenter), float(tol)).pulloff(eta, progress)


def contact(stack=None, *, film=None, substrate=None, indenter=None, radius, thickness, work,
            a=None, points=200, spring=None, tol=_DEFAULT_TOL, strict=False):
    """Sphere on a coated substrate in SI units (section 5).

    radius     sphere radius R [m];  thickness  coating thickness t [m];
    work       work of adhesion w [J/m^2];  film/substrate/indenter moduli in Pa.
    a          contact radii [m]; default `points` radii over the model's default a_bar range,
               ended at the validity limits (past the pull-off), as `coatcontact sphere`.
    Lengths, moduli and w may also be texts with a unit: radius="5mm", film=("1MPa", 0.49).
    A curve beyond the model's validity limits (a > 0.1 R, delta > t, F/(pi a^2) > 0.1 E*)
    raises a ValidityWarning per limit (warnings.warn), as `coatcontact sphere` warns.
    Returns a dict: a [m], delta [m], F [N] (arrays, F compressive positive); scales
    (l [m], delta_scale = l^2/R [m], F_scale = pi w R [N], eta = t/l); pulloff (F_load [N],
    a_load [m], delta_load [m], F_disp, a_disp, delta_disp, flags; with spring, also k [N/m],
    k_bar, F_spring [N], a_spring [m], delta_spring [m]).
    spring     stiffness k [N/m] of the cantilever or frame (a number, or a text: "500N/m",
               "0.5mN/um"; > 0): adds the pull-off through that spring (section 10), as
               `coatcontact sphere --spring k`.
    tol        relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).
    With a: status, reason per radius and masked delta, F where a radius cannot be delivered,
    unless strict=True (NumericalError): as reduced(); the validity limits see the delivered
    radii.
    """
    radius, thickness = _si(radius, "length", "radius"), _si(thickness, "length", "thickness")
    work = _si(work, "energy per area", "work")
    k = None if spring is None else _stiffness(spring)
    c = Contact(_model(_stack(stack, film, substrate, indenter), _tolerance(tol)), radius, thickness, work)
    out = c.at(a, strict) if a is not None else c.curve(points)
    if "status" in out and np.any(out["status"] != 0):
        kept = np.ravel(out["status"]) == 0
        _warn_validity(c._core, {k: np.ravel(np.ma.getdata(out[k]))[kept] for k in ("a", "delta", "F")})
    else:
        _warn_validity(c._core, out)
    out["scales"] = c.scales
    out["pulloff"] = c.pulloff()
    if k is not None:
        out["pulloff"].update(c.pulloff_spring(k))
    return out


_FIT_KINDS = {"a": "FIT_RADIUS_FORCE", "delta": "FIT_PENETRATION_FORCE", "z": "FIT_BASE_FORCE"}


def _fit_unit(name):
    if name.startswith("w"):
        return "J/m^2"
    if name == "k":
        return "N/m"
    if name == "lambda":
        return ""
    return "Pa" if name.startswith("E") else "m"


def _fit_sigma(value, values, name):
    """One uncertainty entry of sigma=: a number [SI], an array per point, or "p%" of |values|."""
    if isinstance(value, str):
        text = value.strip()
        if not text.endswith("%"):
            raise ValueError("sigma %s: %r is neither a number nor a percentage such as '0.3%%'" % (name, value))
        try:
            percent = float(text[:-1])
        except ValueError:
            raise ValueError("sigma %s: %r is not a percentage such as '0.3%%'" % (name, value)) from None
        if not (0.0 < percent < 100.0):
            raise ValueError("sigma %s: %r is not a percentage in (0, 100)" % (name, value))
        return 0.01 * percent * np.abs(values)
    out = np.asarray(value, dtype=float)
    if out.ndim == 0:
        out = np.full(values.shape, float(out))
    return np.ascontiguousarray(out.ravel())


def _fit_shape(shape):
    if shape is None:
        return None
    if shape[0] == "profile":
        return _core.make_profile(np.asarray(shape[1], dtype=float), np.asarray(shape[2], dtype=float))
    if shape[0] == "pyramid":
        _check_pyramid(shape)
    params = [float(v) for v in shape[1:]] + [0.0]
    return _core.make_shape(shape[0], params[0], params[1])


def fit(x, F, *, kind="a", radius=None, shape=None, film=None, substrate, thickness=None, layers=None,
        work=None, free=("w",), indenter=None, sigma=None, branch=None, branch_select="both", unload_work=None,
        spring=None, model="jkr", lambda_=None, bootstrap=0, seed=1, curve_points=200):
    """Least-squares fit of measured (a, F), (delta, F) or (z, F) data (residuals in force): the
    library call behind `coatcontact fit`, with the same models and the same numbers.

    x, F       arrays: contact radius a [m] (> 0; kind="a"), penetration delta [m]
               (kind="delta") or base displacement z = delta + F/k [m] of a sphere on the
               spring k (kind="z", spring= required), and force F [N], compressive positive.
    radius     sphere radius R [m]; or shape= any indenter as in shape_contact: ("sphere", R),
               ("cone", beta), ("pyramid", theta), ("punch", A), ("power", n, R), ("blunted-cone", R, beta),
               ("profile", r, z) (its own parameters fixed; the model is solved at every point).
    film       (E1 [Pa], nu1): E1 is the start value if fitted.  substrate (E0, nu0) or "rigid".
    thickness  t [m] of the film: fixed value or start value.
    layers     in place of film= and thickness=, a stack as the CLI's --layer repeated:
               [(h [m], E [Pa], nu[, slip]), ...], top first; the thicknesses and moduli are
               the fixed values or the start values of the free ones (free names h1..hN,
               E1..EN; one layer: t = h1).
    work       w [J/m^2]: fixed value or start value; default (when w is free) the library's
               start value (from the most tensile force through the JKR pull-off, as the CLI).
    free       names among "w", "t", "E1"; "w_load", "w_unload" in place of "w" give the loading
               and unloading rows their own w (branch= says which row is which, 1 loading,
               0 unloading; default: the rows after the largest x unload); "k" with kind="z";
               "lambda" with model="md"; with layers= "h1".."hN", "E1".."EN". A sequence or a
               comma-separated string; default w.
    branch_select  "both" (default), "load" or "unload": fit only the loading rows (up to and
               including the first largest x) or the unloading rows (from it on), as the CLI's
               --branch; the per-point results (F_model, a_model, residual) are those rows'.
    sigma      uncertainties: {"a": .., "F": ..} (the abscissa's name, or "F"), each a number
               [m or N], an array per point, or a percentage string "0.3%": residuals weighted by
               the effective variance sigma_F^2 + (dF/dx)^2 sigma_x^2, chi2_per_dof reported.
    spring     k [N/m]: the spring of z,F data (fixed, or the start of k when free); for other
               data, report the pull-off through it.
    model      "jkr" (default) or "md": a Maugis-Dugdale zone with lambda_ (fixed, or the start of
               lambda when free; default 1), a,F data of a rigid sphere.
    bootstrap  residual-bootstrap refits (0: none; seed: of the resampling): interval68/95.

    Returns a dict: names (all parameters in order), estimates, errors, start and units (dicts
    by name; error 0 for fixed ones), free (the names of the free parameters), correlation and
    covariance (arrays of the free parameters only, in the order of free), correlation_by_name
    (dict (name_a, name_b) -> r of the free pairs; a CorrelationWarning when |r| > 0.99, as the
    CLI warns), residual_norm [N], residual_sigma [N], r_squared, weighted,
    chi2_per_dof, iterations, converged, points, load_pulloff and displacement_pulloff (dicts
    a [m], delta [m], F [N] of the fitted model; under load control None when the curve has
    no interior minimum), spring_pulloff (with spring=, else None), F_model, a_model and
    residual (F_model - F) at the data points, interval68/interval95 (dicts of (low, high),
    with bootstrap) and, for the sphere and JKR, curve (the fitted model on curve_points radii).
    Raises ValueError for bad input (as the CLI's exit 2, with the same message), NumericalError
    when the fit does not converge, the parameters are not identifiable or the model does not
    describe the data (R^2 < 0.5).
    """
    if kind not in _FIT_KINDS:
        raise ValueError("fit: kind %r is none of 'a', 'delta', 'z'" % (kind,))
    if model not in ("jkr", "md"):
        raise ValueError("model: %r is neither 'jkr' nor 'md' (Maugis-Dugdale)" % (model,))
    if (radius is None) == (shape is None):
        raise ValueError("radius: give the sphere radius radius=R or an indenter shape=(...), not both")
    if layers is None and (film is None or thickness is None):
        raise ValueError("film: give film=(E1, nu1) and thickness=t, or a stack as layers=[(h, E, nu), ...]")
    if layers is not None and (film is not None or thickness is not None):
        raise ValueError("layers: the layers carry their thicknesses and moduli; give layers= or "
                         "film= with thickness=, not both")
    if isinstance(free, str):
        free = tuple(s.strip() for s in free.split(","))
    free = tuple(free)
    if layers is not None and len(layers) == 1:
        free = tuple("t" if name == "h1" else name for name in free)
    x = np.ascontiguousarray(np.asarray(x, dtype=float).ravel())
    F = np.ascontiguousarray(np.asarray(F, dtype=float).ravel())
    if branch_select not in ("both", "load", "unload"):
        raise ValueError("branch_select: %r is not allowed (load, unload or both)" % (branch_select,))
    if branch_select != "both":
        if "w_load" in free or "w_unload" in free:
            raise ValueError("branch_select: %r keeps one branch, but w_load,w_unload need both (leave "
                             "branch_select out)" % (branch_select,))
        if branch is not None:
            raise ValueError("branch: the branch column is read only when the branches have their own "
                             "adhesion energies (free w_load,w_unload)")
        # The rows of one branch by their order, as the library's fit::select_branch: the turning
        # point (the first largest x) belongs to both.
        top = int(np.argmax(x)) if x.size else 0
        rows = slice(0, top + 1) if branch_select == "load" else slice(top, x.size)
        x, F = np.ascontiguousarray(x[rows]), np.ascontiguousarray(F[rows])
        sigma = {name: (value[rows] if np.ndim(value) == 1 and not isinstance(value, str) else value)
                 for name, value in (sigma or {}).items()}
    empty = np.zeros(0)
    sigma_x = sigma_F = empty
    for name, value in (sigma or {}).items():
        if name == "F":
            sigma_F = _fit_sigma(value, F, name)
        elif name == kind:
            sigma_x = _fit_sigma(value, x, name)
        else:
            raise ValueError("sigma: %r is not a column of these data (allowed: %s, F)" % (name, kind))
    unloading = empty if branch is None else np.ascontiguousarray(1.0 - np.asarray(branch, dtype=float).ravel())
    if work is None and "w" not in free and "w_load" not in free:
        raise ValueError("w is fixed: give it with work=... (or add 'w' to free)")
    # The C interface takes the layers' thicknesses as lengths (the fixed values or the hints).
    if layers is None:
        layers = [(float(thickness), film[0], film[1])]
    stack = Stack(layers=layers, substrate=substrate, indenter=indenter)
    r = _core.fit_run(stack._core, getattr(_core, _FIT_KINDS[kind]), x, F, sigma_x, sigma_F, unloading,
                      0.0 if radius is None else float(radius), _fit_shape(shape), ",".join(free),
                      0.0 if work is None else float(work), 0.0 if unload_work is None else float(unload_work),
                      0.0 if spring is None else float(spring),
                      _core.FIT_MAUGIS_DUGDALE if model == "md" else _core.FIT_JKR,
                      0.0 if lambda_ is None else float(lambda_), int(bootstrap), int(seed))
    names = tuple(r["names"].split(","))
    value, error, corr = r["value"], r["standard_error"], r["correlation"]
    free_names = tuple(n for n in names if n in free or (n == "t" and "h1" in free))
    # The correlation of the free parameters only, in the order of free_names ([0, 1] is the
    # pair one named first), and by name.
    index = [names.index(n) for n in free_names]
    corr_free = np.asarray(corr)[np.ix_(index, index)]
    error_free = np.asarray(error)[index]
    out = {
        "names": names,
        "estimates": {n: float(value[i]) for i, n in enumerate(names)},
        "errors": {n: float(error[i]) for i, n in enumerate(names)},
        "start": {n: float(r["start"][i]) for i, n in enumerate(names)},
        "units": {n: _fit_unit(n) for n in names},
        "correlation": corr_free,
        "correlation_by_name": {(a, b): float(corr_free[i, j]) for i, a in enumerate(free_names)
                                for j, b in enumerate(free_names) if i != j},
        "covariance": corr_free * np.outer(error_free, error_free),
        "free": free_names,
        "converged": True,
    }
    _warn_correlation(out["correlation_by_name"])
    for k in ("points", "residual_norm", "residual_sigma", "r_squared", "iterations", "weighted", "chi2_per_dof"):
        out[k] = r[k]
    as_point = lambda p: None if p is None else dict(zip(("F", "a", "delta"), map(float, p)))
    out["load_pulloff"] = as_point(r["load_pulloff"])
    out["displacement_pulloff"] = as_point(r["displacement_pulloff"]) or {"F": 0.0, "a": 0.0, "delta": 0.0}
    out["spring_pulloff"] = as_point(r["spring_pulloff"])
    out["F_model"] = r["F_model"]
    out["a_model"] = r["a_model"]
    out["residual"] = r["F_model"] - F
    if bootstrap:
        out["bootstrap_samples"] = r["bootstrap_samples"]
        for key in ("interval68", "interval95"):
            out[key] = {n: (float(r[key][i, 0]), float(r[key][i, 1])) for i, n in enumerate(names) if n in free_names}
    if shape is None and model == "jkr":
        # The fitted curve: the same model at the estimates (w_unload with two energies), through
        # the SI contact.
        est = out["estimates"]
        if film is not None:
            fitted = Stack((est["E1"], film[1]), substrate=substrate, indenter=indenter)
        elif "t" in est:
            fitted = Stack(layers=[(est["t"], est["E1"]) + tuple(stack.layers[0][2:])], substrate=substrate,
                           indenter=indenter)
        else:
            fitted = Stack(layers=[(est["h%d" % (i + 1)], est["E%d" % (i + 1)]) + tuple(layer[2:])
                                   for i, layer in enumerate(stack.layers)], substrate=substrate, indenter=indenter)
        w = est.get("w_unload", est.get("w", est.get("w_load")))
        thickness_total = est["t"] if "t" in est else sum(layer[0] for layer in fitted.layers)
        c = Contact(_model(fitted, _DEFAULT_TOL), radius, thickness_total, w)
        out["curve"] = c.curve(curve_points)
    return out


def stack_parameter_names(layers):
    """Names of a stack fit's parameters, in the order of fit_stack()'s arrays: w, then the
    thicknesses h1..hN, then the moduli E1..EN (N layers, top first). One layer: w, t, E1
    (h1 is accepted for t), as fit()."""
    n = int(layers)
    if n < 1:
        raise ValueError("layers: a stack has at least one layer, got %d" % n)
    if n == 1:
        return ("w", "t", "E1")
    return ("w",) + tuple("h%d" % (i + 1) for i in range(n)) + tuple("E%d" % (i + 1) for i in range(n))


def fit_stack(x, F, stack=None, *, layers=None, substrate=None, indenter=None, kind="a", radius,
              work=None, free=("w",), curve_points=200):
    """Least-squares fit of any parameters of a layered coating (residuals in force).

    The stack is given as everywhere else in the package, either a Stack or layers=
    [(h [m], E [Pa], nu[, slip]), ...] (top first) with substrate= and indenter=; here the
    layer thicknesses are lengths in m (not just ratios): with the moduli they are the
    fixed values, or the start values of the free ones. (A Stack made with film= has one
    layer 1 m thick: give layers= instead.)

    x, F    arrays: contact radius a [m] (> 0; kind="a") or penetration delta [m]
            (kind="delta"), and force F [N], compressive positive.
    radius  sphere radius R [m].
    work    w [J/m^2]: fixed value or start value; default (when w is free) from the most
            tensile force through the JKR pull-off F_min = -(3/2) pi w R, as fit().
    free    names among stack_parameter_names(N): "w", "h1".."hN", "E1".."EN" (one layer:
            "w", "t" or "h1", "E1"), as a sequence or a comma-separated string; default w.

    Returns a dict: names (all parameters, in order), value and standard_error (arrays in
    that order; error 0 for fixed parameters), estimates, errors and units (dicts by name),
    free (the names, in the order of `names`), start (dict by name), residual_sigma
    = sqrt(RSS/(n - p)) [N], points, curve (the fitted model: a, delta, F on curve_points
    radii) and, for kind="a", F_model and residual (F_model - F) at the data points.
    The C interface does not return the correlation of a stack fit: there is no
    correlation or covariance key (fit() has them for one film). One adhesion energy for
    all points: loading and unloading branches with their own w (w_load, w_unload) are not
    available through the C interface.

    Raises ValueError naming the bad argument, NumericalError when the fit does not
    converge, the parameters are not identifiable or the model does not describe the data.
    """
    if kind not in ("a", "delta"):
        raise ValueError("kind: %r is neither 'a' nor 'delta'" % (kind,))
    if stack is not None:
        if layers is not None or substrate is not None or indenter is not None:
            raise ValueError("stack: give either a Stack or layers=/substrate=/indenter=, not both")
        if not isinstance(stack, Stack):
            raise ValueError("stack: expected a coatcontact.Stack, got %r" % type(stack).__name__)
    else:
        if layers is None:
            raise ValueError("layers: give a Stack or layers=[(h, E, nu), ...] and substrate=")
        if isinstance(layers, (str, bytes)) or not hasattr(layers, "__len__") or len(layers) == 0:
            raise ValueError("layers: expected a non-empty list of (h [m], E [Pa], nu[, slip]), got %r" % (layers,))
        stack = Stack(layers=layers, substrate=substrate, indenter=indenter)
    names = stack_parameter_names(len(stack.layers))
    if isinstance(free, str):
        free = [s.strip() for s in free.split(",")]
    free = ["t" if (name == "h1" and len(stack.layers) == 1) else name for name in free]
    if not free:
        raise ValueError("free: no parameter named (allowed: %s)" % ", ".join(names))
    for name in free:
        if name not in names:
            raise ValueError("free: %r is not a parameter of this %d-layer stack (allowed: %s)"
                             % (name, len(stack.layers), ", ".join(names)))
    if len(set(free)) != len(free):
        raise ValueError("free: a parameter is named twice in %r" % (free,))
    try:
        radius = float(radius)
    except (TypeError, ValueError):
        raise ValueError("radius: expected a number [m], got %r" % (radius,)) from None
    if not (math.isfinite(radius) and radius > 0):
        raise ValueError("radius: the sphere radius must be finite and > 0 m, got %r" % radius)
    x = np.ascontiguousarray(np.asarray(x, dtype=float).ravel())
    F = np.ascontiguousarray(np.asarray(F, dtype=float).ravel())
    if x.shape != F.shape:
        raise ValueError("F: %d forces for %d x values" % (F.size, x.size))
    if work is None:
        if "w" not in free:
            raise ValueError("work: w is fixed, give it with work=... (or add 'w' to free)")
        f_min = float(F.min()) if F.size else 0.0
        work = f_min / (-1.5 * math.pi * radius) if f_min < 0.0 else 0.05
    work = float(work)
    if not (math.isfinite(work) and work > 0):
        raise ValueError("work: the work of adhesion must be finite and > 0 J/m^2, got %r" % work)

    kind_code = _core.FIT_RADIUS_FORCE if kind == "a" else _core.FIT_PENETRATION_FORCE
    r = _core.fit_stack(stack._core, kind_code, x, F, radius, work, ",".join(free), len(names))
    value, error = r["value"], r["standard_error"]
    n_layers = len(stack.layers)
    start = [work] + [layer[0] for layer in stack.layers] + [layer[1] for layer in stack.layers]
    out = {
        "names": names,
        "value": value,
        "standard_error": error,
        "estimates": {n: float(value[i]) for i, n in enumerate(names)},
        "errors": {n: float(error[i]) for i, n in enumerate(names)},
        "units": {n: ("J/m^2" if n == "w" else "Pa" if n.startswith("E") else "m") for n in names},
        "free": tuple(n for n in names if n in free),
        "start": {n: float(start[i]) for i, n in enumerate(names)},
        "residual_sigma": r["residual_sigma"],
        "points": int(x.size),
    }

    # The fitted curve: the stack at the estimates, through the SI contact.
    thickness = value[1:1 + n_layers]
    moduli = value[1 + n_layers:]
    fitted = Stack(layers=[(thickness[i], moduli[i], layer[2], layer[3]) for i, layer in enumerate(stack.layers)],
                   substrate=stack.substrate, indenter=stack.indenter)
    c = Contact(_model(fitted, _DEFAULT_TOL), radius, float(thickness.sum()), float(value[0]))
    out["curve"] = c.curve(curve_points)
    if kind == "a":
        out["F_model"] = c.at(x)["F"]
        out["residual"] = out["F_model"] - F
    return out


def pulloff_spring(stack=None, *, film=None, substrate=None, indenter=None, eta, k_bar,
                   tol=_DEFAULT_TOL):
    """Pull-off through a spring (section 10): the contact jumps off where Z = D + P/k_bar is
    minimal along the curve (dP/dD = -k_bar).

    eta    one coating thickness over l = (pi w R^2/E*)^(1/3);
    k_bar  normalized stiffness k (pi^2 w^2 R/E*^2)^(1/3)/(pi w R), array; 0 gives load
           control, inf displacement control.
    tol    relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).
    Returns a dict of arrays k_bar, P, a_bar, D at the jump. JKR at k_bar = 1: P = -1.41024.
    """
    k = np.atleast_1d(np.asarray(k_bar, dtype=float))
    model = _model(_stack(stack, film, substrate, indenter), float(tol))
    rows = _core.pulloff_spring(model._core, float(eta), k)
    return {"k_bar": k, "P": rows[:, 0], "a_bar": rows[:, 1], "D": rows[:, 2]}


# One model per stack and solve: the table's tiles, built on first use, serve later calls.
@functools.lru_cache(maxsize=8)
def _maugis_dugdale(stack, direct_solve=False):
    return _core.MaugisDugdale(stack._core, bool(direct_solve))


def maugis_dugdale_curve(stack=None, *, film=None, substrate=None, indenter=None, eta, lambda_,
                         a_bar, direct_solve=False):
    """Sphere with a Dugdale interaction zone (section 13) at one eta and lambda.

    lambda_       2 sigma0 (R/(pi w K^2))^(1/3), K = 4E*/3 (inf is JKR: use adhesive_curve);
    a_bar         contact radii a/l, >= 0 (0: the end of the curve, a -> 0).
    direct_solve  False (default): from the reduced table of the cohesive zone, each value
                  within its error estimate of the direct solve; True: the direct per-radius
                  solve (the reference, the command line's --md-direct; slower).
    Returns a dict of arrays a_bar, a_over_t, m = c/a (inf at a = 0), P, D.
    """
    rows = _maugis_dugdale(_stack(stack, film, substrate, indenter), bool(direct_solve)).curve(
        float(eta), float(lambda_), np.atleast_1d(np.asarray(a_bar, dtype=float)))
    return {key: rows[:, i] for i, key in enumerate(("a_bar", "a_over_t", "m", "P", "D"))}


def maugis_dugdale_pulloff(stack=None, *, film=None, substrate=None, indenter=None, eta, lambda_,
                           direct_solve=False):
    """Maugis-Dugdale pull-off (section 13): dict P_load, a_bar_load, D_load, m_load (minimum
    of P), P_disp, a_bar_disp, D_disp, m_disp (minimum of D; at the end of the curve, a -> 0,
    when end_of_curve is True), and for each its error estimate KEY_err (P_load_err, ...,
    m_disp_err; the minimum's location included; m_disp_err 0 at the curve's end). direct_solve as maugis_dugdale_curve: False reads the reduced table of the
    cohesive zone (error estimates ~1e-5 relative), True the direct per-radius solve (~1e-11).
    Homogeneous: -1.81556, -1.60073, -1.51676 at lambda 0.3, 1, 3."""
    row, errors, flags = _maugis_dugdale(_stack(stack, film, substrate, indenter), bool(direct_solve)).pulloff(
        float(eta), float(lambda_))
    keys = ("P_load", "a_bar_load", "D_load", "m_load", "P_disp", "a_bar_disp", "D_disp", "m_disp")
    out = {key: float(row[i]) for i, key in enumerate(keys)}
    out.update({key + "_err": float(errors[i]) for i, key in enumerate(keys)})
    out["end_of_curve"] = bool(flags & 1)
    return out


def _check_pyramid(shape):
    # As the CLI's pyramid:THETA: one parameter, the face half angle (here in radians).
    if len(shape) != 2:
        raise ValueError("shape: %r needs 1 parameter: (\"pyramid\", theta), theta the face half angle in "
                         "radians (e.g. math.radians(70))" % (tuple(shape),))
    theta = float(shape[1])
    if not 0.0 < theta < math.pi / 2:
        raise ValueError("shape: pyramid face half angle %r rad not allowed (need 0 < theta < pi/2, e.g. "
                         "math.radians(70))" % theta)


def shape_contact(stack=None, *, film=None, substrate=None, indenter=None, shape, thickness, work,
                  a=None, points=200, spring=0.0, tol=_DEFAULT_TOL, strict=False):
    """Adhesive (JKR) contact of any axisymmetric indenter in SI units (section 11).

    shape      ("sphere", R), ("cone", beta), ("pyramid", theta), ("punch", A), ("power", n, R),
               ("blunted-cone", R, beta) or ("profile", r, z) with arrays r, z [m]; lengths
               in m, beta the half included angle and theta a four-sided pyramid's face half
               angle in radians (the pyramid as the cone of equal area, as the CLI's
               pyramid:THETA).
    thickness  coating thickness t [m]; work  w [J/m^2].
    spring     stiffness k [N/m] (a number or a text, "500N/m"; 0: none): adds its pull-off.
    tol        relative tolerance of the solver's values, allowed 1e-13..1e-1 (default 1e-8).
    a          contact radii [m] (default `points` log-spaced over the default range).
    Returns a dict: a, delta, F, delta_H, F_H (arrays, adhesive then adhesionless at the same
    a) and pulloff: F, a, delta under load, displacement (and spring) control; status and
    reason per radius, masked values where the solver cannot serve a radius at tol, unless
    strict=True (NumericalError): as reduced().
    A curve beyond the validity limits (delta > t, F/(pi a^2) > 0.1 E*, and for a sphere
    a > 0.1 R) raises a ValidityWarning per limit, as `coatcontact contact` warns.
    """
    k = 0.0 if isinstance(spring, (int, float)) and spring == 0 else _stiffness(spring)
    kind = shape[0]
    if kind == "profile":
        core_shape = _core.make_profile(np.asarray(shape[1], dtype=float), np.asarray(shape[2], dtype=float))
    else:
        if kind == "pyramid":
            _check_pyramid(shape)
        params = [float(v) for v in shape[1:]] + [0.0]
        core_shape = _core.make_shape(kind, params[0], params[1])
    c = _core.ShapeContact(_stack(stack, film, substrate, indenter)._core, core_shape, float(thickness),
                           float(work), _tolerance(tol))
    if a is None:
        # As `coatcontact contact`: the default curve ends inside the validity limits.
        lo, hi = c.default_range()
        if lo < hi:
            scan = c.curve(np.ascontiguousarray(np.geomspace(lo, hi, _SCAN_POINTS)))
            last = _last_inside(scan, lambda row: c.validity(np.ascontiguousarray(row[None, :])))
            if last is not None and last > lo:
                hi = last
        a = np.geomspace(lo, hi, points)
    keys = ("a", "delta", "F", "delta_H", "F_H")
    radii = np.ascontiguousarray(np.atleast_1d(np.asarray(a, dtype=float)))
    if strict:
        rows = c.curve(radii)
        status, reasons = np.zeros(len(radii), dtype=int), None
    else:
        rows, status, reasons = c.curve_each(radii)
    kept = np.asarray(status) == 0
    for message in c.validity(np.ascontiguousarray(rows[kept], dtype=float)).splitlines():
        warnings.warn(message, ValidityWarning, stacklevel=2)
    out = {key: rows[:, i] for i, key in enumerate(keys)}
    if not strict:
        _points(out, keys[1:], status, reasons, radii.shape, "contact radii")
    try:
        p = c.pulloff(k)
    except NumericalError as error:
        if strict:
            raise
        # As `coatcontact contact` without --strict: the curve stands, the pull-off is None.
        warnings.warn("pull-off not computed (the curve is): %s" % error, PointsNotDeliveredWarning, stacklevel=2)
        out["pulloff"] = None
        return out
    out["pulloff"] = {"F_load": p[0], "a_load": p[1], "delta_load": p[2],
                      "F_disp": p[3], "a_disp": p[4], "delta_disp": p[5],
                      "F_spring": p[6], "a_spring": p[7], "delta_spring": p[8]}
    return out


def read_curve(path, columns="a,F"):
    """A measured force curve in SI units, read as `coatcontact fit` reads DATA (the library's
    reader and unit table): tab-, comma- or semicolon-separated, '#' comments, a '# units: um mN'
    line or units in the column names ("a [um]").

    columns  as the CLI's --columns: "a,F", "delta,F", "z,F" (or F first), or named/numbered
             columns such as "a=2,F=5,sigma_F=6,branch=7".
    Returns a dict: the abscissa under its name ("a", "delta" or "z") [m], "F" [N], the
    columns the file has of "sigma_a"/"sigma_delta"/"sigma_z", "sigma_F", "branch", "line"
    (the file's line number of each row), and "units" (how the units were read).
    ValueError for a bad file or column choice."""
    kind, units, values = _core.read_curve(str(path), str(columns))
    x = {_core.FIT_RADIUS_FORCE: "a", _core.FIT_PENETRATION_FORCE: "delta"}.get(kind, "z")
    out = {x: values.pop("x")}
    if "sigma_x" in values:
        out["sigma_" + x] = values.pop("sigma_x")
    out.update(values)
    out["units"] = units
    return out


# Messages for a Python caller: without the C interface's function names ("cc_fit_run: ") and
# with the shortest text of each number ("0.6", not the C side's "0.59999999999999998").
_C_NAME = re.compile(r"\bcc_[a-z0-9_]+(?:\(\))?: ?")
_LONG_NUMBER = re.compile(r"(?<![\w.])[-+]?\d+\.\d{12,}(?:[eE][-+]?\d+)?")


def _plain_message(text):
    text = _C_NAME.sub("", text)
    return _LONG_NUMBER.sub(lambda m: repr(float(m.group(0))), text)


def _plain_errors(function):
    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except (ValueError, NumericalError) as error:
            text = str(error)
            plain = _plain_message(text)
            if plain == text:
                raise
            raise type(error)(plain) from None
    return wrapper


for _name in ("reduced", "adhesive_curve", "pulloff", "contact", "fit", "fit_stack", "pulloff_spring", "read_curve",
              "maugis_dugdale_curve", "maugis_dugdale_pulloff", "shape_contact", "kinetics", "kinetics_fit"):
    globals()[_name] = _plain_errors(globals()[_name])
Stack.__init__ = _plain_errors(Stack.__init__)
del _name
