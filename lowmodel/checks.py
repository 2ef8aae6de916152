"""Shared input checks: one ``ValueError`` per bad input, naming the parameter, its unit and allowed range.

Every check takes the parameter's ``name`` first and returns the value as
floats: a Python ``float`` for a scalar input (so it can go into a cache key
or a frozen dataclass), a float ``numpy.ndarray`` for an array input.  NaN and
inf are refused everywhere.  Messages show the offending value (the first
offending element of an array, with the array's shape)::

    ball_radius must be finite and > 0 m, i.e. in (0, inf) m; got -0.001

Ranges used across the project, each defined once here:

* ``contact_angle``: (0, pi/2) rad, i.e. (0, 90) deg (lin2017 Sec 2.1).
* ``lead_angle``: [0, pi/2) rad (0 is a ball bearing).
* ``conformity``: groove radius / ball diameter ``f = r_g / (2 R_B)`` in the
  open range **(0.5, 1)**.  ``f > 0.5``: the groove is wider than the ball
  (at 0.5 the surfaces conform and Hertz theory does not apply).  ``f < 1``:
  the groove radius stays below the ball diameter; real grooves have 0.505 to
  0.6 (lin2019 Tables 1 and 4: 0.56), and neither the papers nor the meshes
  (the gothic-arch flank must rise above the contact point) go beyond.
* integers (``count``): Python or numpy integers; ``True``/``False`` are refused.
* plausible ranges (:data:`PLAUSIBLE`, :func:`plausible`): where a unit mistake (mm for m, deg for rad, GPa for
  Pa) puts an input orders of magnitude off, the entry points of the models and the case files refuse values
  outside the sizes of real bearings, naming the parameter and the SI unit it expects.

Frozen dataclasses that cache data derived from their arrays hold those arrays read-only
(:func:`freeze_arrays` in ``__post_init__``): ``frozen=True`` stops rebinding a field but not
``obj.array[0] = x``, after which the caches would silently disagree with the arrays.  An in-place
edit raises numpy's "assignment destination is read-only"; :func:`dataclasses.replace` builds the
edited object with fresh caches.  Their ``__reduce__`` is :func:`rebuilt_through_init`, so pickle and
:func:`copy.deepcopy` pass ``__init__`` too (they would otherwise hand back writable arrays).
"""
from __future__ import annotations

import dataclasses
import contextlib
import contextvars
import math
import numbers

import numpy as np

__all__ = ["real", "finite", "scalar", "positive", "non_negative", "bounded", "contact_angle", "lead_angle",
           "conformity", "choice", "count", "trailing_axis", "read_only", "freeze_arrays",
           "rebuilt_through_init", "finite_result", "power_of_two_scale", "PLAUSIBLE", "plausible",
           "beyond_plausible"]

CONFORMITY_RANGE = (0.5, 1.0)  # open range of f = r_g / (2 R_B), module docstring


def _unit(unit: str) -> str:
    return f" {unit}" if unit else ""


def _shown(array: np.ndarray, bad: np.ndarray) -> str:
    """The offending value for a message: the value itself, or an array's first bad element."""
    if array.ndim == 0:
        return repr(float(array))
    first = float(np.broadcast_to(array, bad.shape)[bad].ravel()[0])
    return f"{first!r} (first offending element of an array of shape {array.shape})"


def _bound(x: float) -> str:
    if x == 0.5 * math.pi:
        return "pi/2"
    return "inf" if x == math.inf else "-inf" if x == -math.inf else f"{x:.12g}"


def _digits(value) -> str:
    """A short description of a too-large integer input (its repr may run to hundreds of digits)."""
    text = repr(value)
    return text if len(text) <= 40 else f"{text[:20]}... ({len(text)} characters)"


def _out(array: np.ndarray):
    return float(array) if array.ndim == 0 else array


def real(name: str, value) -> np.ndarray:
    """``value`` as a float array (any shape); ValueError if it is not real (strings, None, complex)."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a real number, not a boolean; got {value!r}")
    try:
        return np.asarray(value, dtype=float)
    except OverflowError:  # a Python int beyond float range (e.g. 10**400)
        raise ValueError(f"{name} must be finite; got an integer beyond float range ({_digits(value)})") from None
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number or array of them, got {value!r}") from None


def _note(note: str) -> str:
    return f" ({note})" if note else ""


def finite(name: str, value, unit: str = "", *, note: str = ""):
    """``value`` as floats; ValueError unless every element is finite (no NaN, no inf).

    ``note`` (here and in the other checks) is added to the message in brackets.
    """
    array = real(name, value)
    bad = ~np.isfinite(array)
    if np.any(bad):
        raise ValueError(f"{name} must be finite{_unit(unit)}, i.e. in (-inf, inf){_note(note)}; "
                         f"got {_shown(array, bad)}")
    return _out(array)


def bounded(name: str, value, lower: float, upper: float, unit: str = "", *, lower_closed: bool = False,
            upper_closed: bool = False, note: str = ""):
    """``value`` as floats; ValueError unless finite and inside the interval from ``lower`` to ``upper``.

    The ends are open unless ``lower_closed`` / ``upper_closed``; ``note`` is
    appended to the message (e.g. the equivalent range in degrees).
    """
    array = real(name, value)
    above = array >= lower if lower_closed else array > lower
    below = array <= upper if upper_closed else array < upper
    bad = ~(np.isfinite(array) & above & below)
    if np.any(bad):
        interval = f"{'[' if lower_closed else '('}{_bound(lower)}, {_bound(upper)}{']' if upper_closed else ')'}"
        raise ValueError(f"{name} must lie in {interval}{_unit(unit)}{_note(note)}; got {_shown(array, bad)}")
    return _out(array)


def scalar(name: str, value, unit: str = "", *, note: str = "") -> float:
    """``value`` as a Python float; ValueError unless it is one finite number (a 0-d value, not an array)."""
    array = real(name, value)
    if array.ndim != 0:
        raise ValueError(f"{name} must be a single number{f' [{unit}]' if unit else ''}{_note(note)}, not an array; "
                         f"got shape {array.shape}")
    return finite(name, array, unit, note=note)


def positive(name: str, value, unit: str = "", *, note: str = ""):
    """``value`` as floats; ValueError unless finite and > 0."""
    array = real(name, value)
    bad = ~(np.isfinite(array) & (array > 0.0))
    if np.any(bad):
        raise ValueError(f"{name} must be finite and > 0{_unit(unit)}, i.e. in (0, inf){_unit(unit)}{_note(note)}; "
                         f"got {_shown(array, bad)}")
    return _out(array)


def non_negative(name: str, value, unit: str = "", *, note: str = ""):
    """``value`` as floats; ValueError unless finite and >= 0."""
    array = real(name, value)
    bad = ~(np.isfinite(array) & (array >= 0.0))
    if np.any(bad):
        raise ValueError(f"{name} must be finite and >= 0{_unit(unit)}, i.e. in [0, inf){_unit(unit)}{_note(note)}; "
                         f"got {_shown(array, bad)}")
    return _out(array)


def contact_angle(name: str, value):
    """Contact angle [rad] in the open range (0, pi/2), i.e. (0, 90) deg."""
    return bounded(name, value, 0.0, 0.5 * math.pi, "rad", note="i.e. (0, 90) deg")


def lead_angle(name: str, value):
    """Lead (helix) angle [rad] in [0, pi/2); 0 is a ball bearing."""
    return bounded(name, value, 0.0, 0.5 * math.pi, "rad", lower_closed=True, note="i.e. [0, 90) deg")


def conformity(name: str, value):
    """Conformity ``f = r_g / (2 R_B)`` (groove radius / ball diameter) in (0.5, 1) (module docstring)."""
    return bounded(name, value, *CONFORMITY_RANGE, note="groove radius / ball diameter")


def choice(name: str, value, allowed: tuple):
    """``value`` itself; ValueError unless it is one of ``allowed``."""
    try:
        ok = value in allowed
    except TypeError:  # unhashable or incomparable
        ok = False
    if not ok:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value


def count(name: str, value, minimum: int = 0, maximum: int | None = None) -> int:
    """``value`` as ``int``; ValueError unless an integer (not a bool) in ``[minimum, maximum]``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        raise ValueError(f"{name} must be an integer (not a bool or float), got {value!r}")
    if value < minimum or (maximum is not None and value > maximum):
        upper = "inf)" if maximum is None else f"{maximum}]"
        raise ValueError(f"{name} must be an integer in [{minimum}, {upper}, got {value!r}")
    return int(value)


def four_angles(name: str, value, labels: str) -> list[float]:
    """``value`` as a list of four angles [rad], one per contact ``labels`` (e.g. "(BL, BR, TR, TL)"); ValueError
    naming ``name`` otherwise (not a sequence of four numbers)."""
    try:
        angles = [float(v) for v in value]
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"{name} must be four angles {labels} [rad], got {value!r}") from None
    if len(angles) != 4:
        raise ValueError(f"{name} must be four angles {labels} [rad], got {value!r}")
    return angles


def trailing_axis(name: str, value, length: int, labels: str = "", unit: str = "") -> np.ndarray:
    """``value`` as a float array with a trailing axis of ``length`` (e.g. the four contacts); ValueError otherwise.

    ``labels`` names the entries of that axis in the message, e.g. ``"(BL, BR, TR, TL)"``.
    """
    array = real(name, value)
    if array.ndim == 0 or array.shape[-1] != length:
        what = f" {labels}" if labels else ""
        raise ValueError(f"{name} must have a trailing axis of {length}{what}{_unit(unit and f'[{unit}]')}, "
                         f"got shape {array.shape}")
    return array


def read_only(value) -> np.ndarray:
    """``value`` as an array nobody can write into: ``value`` itself when neither it nor any array it is a
    view of is writable (e.g. a slice of another read-only array), else a read-only copy.

    A caller holding a writable array (or a writable base of a view) keeps it writable and theirs.
    """
    array = np.asarray(value)
    base = array
    while isinstance(base, np.ndarray):
        if base.flags.writeable:
            break
        base = base.base
    if base is not None:  # a writable array in the chain, or memory numpy does not own (a buffer)
        array = array.copy()
        array.setflags(write=False)
    return array


def freeze_arrays(instance, *names: str) -> None:
    """Replace the fields ``names`` of the frozen dataclass ``instance`` by :func:`read_only` arrays (in
    ``__post_init__``; ``None`` stays ``None``)."""
    for name in names:
        value = getattr(instance, name)
        if value is not None:
            object.__setattr__(instance, name, read_only(value))


def rebuilt_through_init(instance) -> tuple:
    """``__reduce__`` of a frozen dataclass with :func:`freeze_arrays`: ``(type, field values)``, so that pickle
    and :mod:`copy` rebuild it through ``__init__`` (read-only arrays, no cached data carried over)."""
    return type(instance), tuple(getattr(instance, field.name) for field in dataclasses.fields(instance))


def finite_result(names: str, value, unit: str = ""):
    """A computed ``value`` as floats; ValueError naming the inputs ``names`` unless every element is finite.

    For results that overflow double precision (or become NaN) at extreme but finite inputs: the message
    names the inputs responsible, e.g. ``finite_result("pitch_radius, lead", curvature, "1/m")``.
    """
    array = np.asarray(value, dtype=float)
    bad = ~np.isfinite(array)
    if np.any(bad):
        raise ValueError(f"{names}: the result overflows double precision{_unit(unit)} (got "
                         f"{_shown(array, bad)}); use inputs of a physical size")
    return _out(array)


def power_of_two_scale(value) -> float:
    """A power of two ``2**k`` near ``max |value|`` (1.0 for zeros): dividing lengths by it is exact in binary
    floating point, so a computation on the scaled values gives bit-identical results wherever the unscaled one
    neither overflows nor underflows (e.g. squares of 1e300 m or 1e-300 m)."""
    peak = float(np.max(np.abs(np.asarray(value, dtype=float))))
    if peak == 0.0 or not math.isfinite(peak):
        return 1.0
    return math.ldexp(1.0, math.frexp(peak)[1])


# Plausible ranges of inputs that a unit mistake puts orders of magnitude off (mm for m, um for m, GPa for Pa, deg
# for rad): (low, high, SI unit, what the range is, an example in SI).  Closed ranges.  Ball radii 0.1 mm to 100 mm
# cover miniature guides to slewing rings; pitch radii 1 mm to 1 m; leads up to 0.5 m; an oversize (preload by
# interference) up to 100 um; elastic moduli of polymers (1 GPa) to carbides (1 TPa); contact angle deviations up
# to 20 deg (machining and assembly errors are a few degrees); axial loads of a ball screw up to 10 MN (the largest
# catalogue screws are rated a few MN statically; beyond, lin2019's Hertz contacts of real balls approach by more
# than the ball radius, which the model refuses only once its contacts are built: lowmodel.screw.ball).
PLAUSIBLE = {
    "ball_radius": (1e-4, 0.1, "m", "a ball radius", "a 3.175 mm ball radius is 3.175e-3 m"),
    "pitch_radius": (1e-3, 1.0, "m", "a ball-screw pitch radius", "a 20 mm pitch radius is 0.02 m"),
    "lead": (0.0, 0.5, "m", "a ball-screw lead", "a 10 mm lead is 0.01 m"),
    "oversize": (0.0, 1e-4, "m", "a ball oversize", "a 2 um oversize is 2e-6 m"),
    "youngs_modulus": (1e9, 1e12, "Pa", "an elastic modulus", "210 GPa is 2.1e11 Pa"),
    "deviation": (-0.35, 0.35, "rad", "a contact angle deviation (20 deg)", "2 deg is 0.0349 rad"),
    "axial_load": (0.0, 1e7, "N", "a ball screw's axial load", "a 5 kN load is 5000 N"),
}


# set by beyond_plausible(): a limit study (R_P -> infinity) that leaves the plausible ranges on purpose
_LIMIT_STUDY = contextvars.ContextVar("ballbench_limit_study", default=False)


@contextlib.contextmanager
def beyond_plausible():
    """Within this block :func:`plausible` checks only that values are finite: for limit studies that leave the
    sizes of real bearings on purpose (a ball screw of pitch radius 1000 R_B tending to the linear bearing).  The
    models' own range checks (positive radii, conformity, angles) stay."""
    token = _LIMIT_STUDY.set(True)
    try:
        yield
    finally:
        _LIMIT_STUDY.reset(token)


def plausible(name: str, value, kind: str | None = None):
    """``value`` as floats; ValueError naming ``name`` unless inside the plausible range of ``kind`` (default
    ``name``; a key of :data:`PLAUSIBLE`), which says the SI unit expected and gives an example.  Inside
    :func:`beyond_plausible` only finiteness is checked."""
    low, high, unit, what, example = PLAUSIBLE[kind or name]
    if _LIMIT_STUDY.get():
        return finite(name, value, unit)
    return bounded(name, value, low, high, unit, lower_closed=True, upper_closed=True,
                   note=f"the plausible range of {what}; outside it the value is most likely in another unit: "
                        f"SI units, {example}")
