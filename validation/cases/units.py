"""Units at the edge: the one parser of quantities in case files, sweep specs and calibrate specs (SI inside).

A quantity is written ``"3.175 mm"``, ``"2 deg"``, ``"500 N"`` or ``{ value = 3.175, unit = "mm" }`` (the value
may be a list there); :func:`quantity` turns it into an SI float (or a list of them) after checking that the unit
belongs to the dimension the key expects, and names the key, the unit it got and the units it takes (with a "did
you mean" for a misspelt one).  A bare number is SI only where the caller allows it (sweep specs, for
compatibility); case files demand a unit on every dimensioned key, so a radius in mm cannot pass as metres.

Table-driven rather than pint (docs/cases.md, "Units: why not pint"): the papers' numbers must not move, and a
decimal unit such as ``mm`` or ``um`` is applied here in decimal arithmetic (``"40 um"`` is exactly the literal
``4e-05``, ``"1.6848340370165068 um"`` exactly ``1.6848340370165068e-06``), where pint multiplies by a binary
factor (``3.9999999999999996e-05``, ``1.6848340370165066e-06``); the unit set a bearing needs is small, and this
module imports nothing beyond the standard library.  Non-decimal factors (``deg``, ``rpm``, ``rev/s``) multiply
by the float factor, as ``math.radians`` does.
"""
from __future__ import annotations

import difflib
import math
import re
import sys
from decimal import Decimal, DecimalException, InvalidOperation

__all__ = ["UNITS", "DIMENSIONS", "DIMENSIONLESS", "SI_UNIT", "UnitError", "quantity", "factor", "si_factor",
           "units_of", "dimension_of", "split", "format_quantity"]


class UnitError(ValueError):
    """A quantity that cannot be read: a missing or unknown unit, a unit of another dimension, not a number."""


# unit -> (dimension, SI factor).  A factor given as a string is decimal and applied exactly; a float factor is
# irrational in SI (angles) and multiplies the value.
_PI = math.pi
UNITS: dict[str, tuple[str, str | float]] = {
    # dimensionless
    "": ("dimensionless", "1"), "1": ("dimensionless", "1"), "%": ("dimensionless", "0.01"),
    # length
    "m": ("length", "1"), "cm": ("length", "1e-2"), "mm": ("length", "1e-3"), "um": ("length", "1e-6"),
    "nm": ("length", "1e-9"), "in": ("length", "0.0254"),
    # angle
    "rad": ("angle", "1"), "mrad": ("angle", "1e-3"), "deg": ("angle", _PI / 180.0),
    "arcmin": ("angle", _PI / 10800.0),
    # force
    "N": ("force", "1"), "mN": ("force", "1e-3"), "kN": ("force", "1e3"),
    # pressure, stress, elastic modulus
    "Pa": ("pressure", "1"), "kPa": ("pressure", "1e3"), "MPa": ("pressure", "1e6"), "GPa": ("pressure", "1e9"),
    "N/mm^2": ("pressure", "1e6"),
    # speed
    "m/s": ("speed", "1"), "mm/s": ("speed", "1e-3"), "m/min": ("speed", 1.0 / 60.0),
    # angular speed
    "rad/s": ("angular speed", "1"), "rev/s": ("angular speed", 2.0 * _PI), "rpm": ("angular speed", 2.0 * _PI / 60),
    "deg/s": ("angular speed", _PI / 180.0),
    # time
    "s": ("time", "1"), "ms": ("time", "1e-3"), "min": ("time", "60"),
    # mass and density
    "kg": ("mass", "1"), "g": ("mass", "1e-3"),
    "kg/m^3": ("density", "1"), "g/cm^3": ("density", "1e3"),
    # dynamic viscosity
    "Pa s": ("viscosity", "1"), "mPa s": ("viscosity", "1e-3"), "cP": ("viscosity", "1e-3"),
    # torque
    "N m": ("torque", "1"), "N mm": ("torque", "1e-3"),
}
# spellings read as the unit on the right
_ALIASES = {"µm": "um", "μm": "um", "micron": "um", "degree": "deg", "degrees": "deg", "°": "deg",
            "inch": "in", "N*m": "N m", "N·m": "N m", "Nm": "N m", "N*mm": "N mm", "Nmm": "N mm", "Pa*s": "Pa s",
            "Pa·s": "Pa s", "mPa*s": "mPa s", "mPa·s": "mPa s", "kg/m3": "kg/m^3", "g/cm3": "g/cm^3",
            "N/mm2": "N/mm^2", "r/min": "rpm"}
# a rate that does not say what turns: refused, with the units an angular speed takes (radians or revolutions?)
_PER_TIME = {"1/s": "rad/s or rev/s", "/s": "rad/s or rev/s", "s^-1": "rad/s or rev/s", "1/min": "rpm",
             "/min": "rpm", "min^-1": "rpm"}
DIMENSIONS = tuple(dict.fromkeys(d for d, _ in UNITS.values()))
DIMENSIONLESS = ("", "1")
# the SI unit of each dimension (what a bare number means where a bare number is allowed)
SI_UNIT = {"dimensionless": "1", "length": "m", "angle": "rad", "force": "N", "pressure": "Pa", "speed": "m/s",
           "angular speed": "rad/s", "time": "s", "mass": "kg", "density": "kg/m^3", "viscosity": "Pa s",
           "torque": "N m"}
_NUMBER = re.compile(r"^\s*([-+]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][-+]?\d+)?)\s*(.*?)\s*$")


def units_of(dimension: str) -> list[str]:
    """The units of ``dimension``, as written in a file."""
    if dimension not in DIMENSIONS:
        raise ValueError(f"dimension must be one of {DIMENSIONS}, got {dimension!r}")
    return [u for u, (d, _) in UNITS.items() if d == dimension and u]


def _normalise(unit: str) -> str:
    unit = " ".join(str(unit).split())
    return _ALIASES.get(unit, unit)


def _lookup(where: str, unit: str, dimension: str | None) -> tuple[str, str | float]:
    name = _normalise(unit)
    if name in _PER_TIME and dimension in (None, "angular speed"):
        raise UnitError(f"{where}: {unit!r} does not say what turns (radians or revolutions); write "
                        f"{_PER_TIME[name]}; an angular speed takes {', '.join(units_of('angular speed'))}")
    if name not in UNITS:
        pool = units_of(dimension) if dimension else [u for u in UNITS if u]
        close = difflib.get_close_matches(name, pool, n=2, cutoff=0.5)
        hint = f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""
        raise UnitError(f"{where}: unknown unit {unit!r}{hint}; " + (
            f"a {dimension} takes {', '.join(units_of(dimension))}" if dimension and dimension != "dimensionless"
            else f"units: {', '.join(u for u in UNITS if u)}"))
    found, value = UNITS[name]
    if dimension is not None and found != dimension:
        takes = ("no unit (a plain number)" if dimension == "dimensionless"
                 else ", ".join(units_of(dimension)))
        raise UnitError(f"{where}: {unit!r} is a unit of {found}, but {where.split('.')[-1]} is a {dimension}; "
                        f"it takes {takes}")
    return name, value


def dimension_of(unit: str, where: str = "unit") -> str:
    """The dimension of ``unit`` (``"mm"`` -> ``"length"``); UnitError naming ``where`` for an unknown unit."""
    return UNITS[_lookup(where, unit, None)[0]][0]


def split(text: str) -> tuple[str, str] | None:
    """``(number, unit)`` of a quantity text such as ``"3.175 mm"``; None for text that does not start with a
    number."""
    match = _NUMBER.match(text)
    return (match.group(1), match.group(2)) if match else None


def factor(unit: str, where: str = "unit", dimension: str | None = None) -> float:
    """The SI factor of ``unit`` (a float); UnitError naming ``where`` for an unknown unit or one of another
    ``dimension``."""
    _, value = _lookup(where, unit, dimension)
    return float(Decimal(value)) if isinstance(value, str) else value


def si_factor(where: str, unit: str) -> float:
    """The SI factor of ``unit`` in a sweep spec (any dimension); UnitError naming ``where``."""
    return factor(unit, where)


def _number_text(where: str, value) -> str:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise UnitError(f"{where}: the value must be a number, got {value!r}")
    if isinstance(value, int) and not -_FLOAT_MAX <= value <= _FLOAT_MAX:  # no float holds it
        raise UnitError(f"{where}: an integer of {_digits(value)} digits is beyond the float range "
                        f"(|value| up to {sys.float_info.max:.4g})")
    if not math.isfinite(value):
        raise UnitError(f"{where} must be finite, got {value!r}")
    return repr(value)  # the shortest text that reads back as the same float: "3.175", not its binary expansion


def _digits(value: int) -> str:
    """The number of decimal digits of the integer ``value``, from its bit length (``str`` of an integer of
    more than 4300 digits raises ValueError)."""
    bits = abs(value).bit_length()
    return str(len(str(abs(value)))) if bits < 10000 else f"about {int(bits * math.log10(2)) + 1}"


_FLOAT_MAX = int(sys.float_info.max)


def _scaled(where: str, text: str, unit_factor: str | float) -> float:
    beyond = (f"{where}: {text} is beyond the float range (|value| up to {sys.float_info.max:.4g} in SI "
              "units)")
    if isinstance(unit_factor, str):
        try:
            result = float(Decimal(text) * Decimal(unit_factor))
        except InvalidOperation:
            raise UnitError(f"{where}: {text!r} is not a number") from None
        except DecimalException:  # decimal.Overflow of an exponent beyond the decimal context's
            raise UnitError(beyond) from None
    else:
        result = float(text) * unit_factor
    if math.isinf(result):
        raise UnitError(beyond)
    if not math.isfinite(result):
        raise UnitError(f"{where} must be finite, got {text}")
    return result


def _example(dimension: str, value) -> str:
    unit = {"length": "mm", "angle": "deg", "pressure": "GPa", "speed": "mm/s", "angular speed": "rpm"}.get(
        dimension, SI_UNIT.get(dimension, ""))
    return f'"{value} {unit}"'


def quantity(value, dimension: str, where: str, *, bare_si: bool = False):
    """``value`` in SI: a float, or a list of floats for ``{ value = [...], unit = "..." }``.

    ``value``: ``"3.175 mm"``, ``{ value = 3.175, unit = "mm" }``, or a bare number (dimensionless keys; other
    keys only with ``bare_si=True``, where it is SI).  UnitError names ``where``: a missing unit (with an
    example), an unknown one (did you mean), one of another dimension, a value that is not a finite number.
    """
    if dimension not in DIMENSIONS:
        raise ValueError(f"dimension must be one of {DIMENSIONS}, got {dimension!r}")
    if isinstance(value, str):
        match = _NUMBER.match(value)
        if not match:
            raise UnitError(f"{where}: {value!r} is not a quantity; write a number and a unit, e.g. "
                            f"{_example(dimension, 3)}")
        text, unit = match.group(1), match.group(2)
        if not unit and dimension != "dimensionless":
            raise UnitError(f"{where}: {value!r} has no unit; write e.g. {_example(dimension, text)} "
                            f"({dimension}: {', '.join(units_of(dimension))})")
        _, unit_factor = _lookup(where, unit, dimension)
        return _scaled(where, text, unit_factor)
    if isinstance(value, dict):
        unknown = set(value) - {"value", "unit"}
        if unknown or "value" not in value:
            raise UnitError(f"{where}: a quantity table needs 'value' and 'unit', got keys {sorted(value)}")
        unit = value.get("unit", "")
        if not isinstance(unit, str):
            raise UnitError(f"{where}.unit must be text such as \"mm\", got {unit!r}")
        if not unit and dimension != "dimensionless" and not bare_si:
            raise UnitError(f"{where}: give 'unit' ({dimension}: {', '.join(units_of(dimension))})")
        _, unit_factor = _lookup(f"{where}.unit", unit, dimension)
        inner = value["value"]
        if isinstance(inner, list):
            return [_scaled(f"{where}.value[{k}]", _number_text(f"{where}.value[{k}]", v), unit_factor)
                    for k, v in enumerate(inner)]
        return _scaled(f"{where}.value", _number_text(f"{where}.value", inner), unit_factor)
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise UnitError(f"{where}: expected a quantity such as {_example(dimension, 3)}, got {value!r}")
    if not math.isfinite(value):
        raise UnitError(f"{where} must be a finite number, got {value!r}")
    if dimension == "dimensionless" or bare_si:
        return _scaled(where, _number_text(where, value), "1")
    raise UnitError(f"{where} = {value!r} has no unit; write e.g. {_example(dimension, value)} "
                    f"({dimension}: {', '.join(units_of(dimension))})")


def format_quantity(value: float, unit: str) -> str:
    """``value`` [SI] written in ``unit``, e.g. ``format_quantity(3.175e-3, "mm") == "3.175 mm"``; the inverse of
    :func:`quantity` to the 12 significant digits it prints."""
    return f"{value / factor(unit):.12g} {unit}".rstrip()
