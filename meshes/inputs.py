"""TEMPORARY: input checks of meshes/ until ``ballbench.lowmodel.checks`` (branch issue8-geo) lands.

Same names and signatures as ``lowmodel.checks``; deleted when meshes switches over.
"""
from __future__ import annotations

import math


def finite(name: str, value, unit: str = "") -> float:
    try:
        value = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a finite real number {unit}, got {value!r}") from None
    if not math.isfinite(value):
        raise ValueError(f"{name} must be a finite real number {unit}, got {value!r}")
    return value


def positive(name: str, value, unit: str = "") -> float:
    value = finite(name, value, unit)
    if value <= 0.0:
        raise ValueError(f"{name} must lie in (0, inf) {unit}, got {value!r}")
    return value


def non_negative(name: str, value, unit: str = "") -> float:
    value = finite(name, value, unit)
    if value < 0.0:
        raise ValueError(f"{name} must lie in [0, inf) {unit}, got {value!r}")
    return value


def conformity(name: str, value) -> float:
    value = finite(name, value)
    if not 0.5 < value < 1.0:
        raise ValueError(f"{name} (groove radius / ball diameter) must lie in (0.5, 1), got {value!r}")
    return value


def contact_angle(name: str, value) -> float:
    value = finite(name, value, "rad")
    if not 0.0 < value < math.pi / 2:
        raise ValueError(f"{name} must lie in (0, pi/2) rad (0-90 deg exclusive), got {value!r}")
    return value


def choice(name: str, value, allowed: tuple):
    if value not in allowed:
        raise ValueError(f"{name} must be one of {allowed}, got {value!r}")
    return value
