"""Units of a sweep spec: the one place where a spec's ``unit = "..."`` becomes an SI factor.

Inputs are converted at the edge (docs/developing.md); a unified units parser
for case files and the sweep and calibrate specs replaces :func:`si_factor`
without touching the spec parser.
"""
from __future__ import annotations

import math

# units accepted in a spec and their SI factor
UNITS = {"": 1.0, "1": 1.0, "rad": 1.0, "deg": math.pi / 180.0, "m": 1.0, "mm": 1e-3, "um": 1e-6, "N": 1.0,
         "kN": 1e3, "Pa": 1.0, "GPa": 1e9, "m/s": 1.0, "mm/s": 1e-3, "s": 1.0}
DIMENSIONLESS = ("", "1")


def si_factor(where: str, unit: str) -> float:
    """The factor that turns a number in ``unit`` into SI; ValueError naming ``where`` for an unknown unit."""
    if unit not in UNITS:
        raise ValueError(f"{where}: unit must be one of {sorted(UNITS)}, got {unit!r}")
    return UNITS[unit]
