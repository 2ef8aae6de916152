"""Richardson extrapolation of a mesh-convergence study and its uncertainty (the grid convergence index).

The reference of a case without a published number: an FE quantity ``f(h)`` solved on three or more meshes of
element sizes ``h_1 > h_2 > h_3`` (the finest three are used) is extrapolated to ``h -> 0`` (Richardson 1911;
the procedure of Celik et al. 2008, J. Fluids Eng. 130, 078001, eqs 1-4, for refinement ratios that differ; Celik
numbers the meshes fine to coarse, here 1 is the coarsest, so his ``r_21, e_32 / e_21`` are ``r_32, e_21 / e_32``):

    r_21 = h_1 / h_2, r_32 = h_2 / h_3,  e_21 = f_2 - f_1,  e_32 = f_3 - f_2,  s = sign(e_32 / e_21)
    p = |ln|e_21 / e_32| + q(p)| / ln r_32,   q(p) = ln((r_32^p - s) / (r_21^p - s))     (fixed point)
    f_ext = f_3 + e_32 / (r_32^p - 1),        U = F_s |e_32| / (r_32^p - 1)  (GCI_fine, Roache 1994)

with the safety factor ``F_s = 1.25`` when the observed order ``p`` is trusted (monotone convergence, p within
[0.5, 2 p_formal]) and ``F_s = 3`` with the formal order otherwise (oscillating or stalled convergence: the
extrapolation then only estimates, and the uncertainty says so).  With two meshes the formal order is used with
``F_s = 3``.  Pure arithmetic on the FE values: it never calls a model.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

__all__ = ["Extrapolation", "extrapolate", "study_levels"]

SAFETY_OBSERVED = 1.25  # Roache's factor of safety with three meshes and the observed order
SAFETY_FORMAL = 3.0     # with two meshes, or when the observed order is not trusted


@dataclass(frozen=True)
class Extrapolation:
    """``value``: f at h -> 0; ``uncertainty``: the band ``U`` about it (same unit); ``order``: the order used;
    ``observed``: True when that order is the observed one; ``finest``: f on the finest mesh; ``note``: how."""

    value: float
    uncertainty: float
    order: float
    observed: bool
    finest: float
    note: str

    @property
    def relative_uncertainty(self) -> float:
        """``U / |f_ext|`` (inf for a zero reference)."""
        return self.uncertainty / abs(self.value) if self.value != 0.0 else math.inf


def _observed_order(r21: float, r32: float, e21: float, e32: float) -> float | None:
    if e21 == 0.0 or e32 == 0.0:
        return None
    s = 1.0 if e32 / e21 > 0 else -1.0
    p = abs(math.log(abs(e21 / e32))) / math.log(r32)
    for _ in range(100):
        try:
            q = math.log((r32 ** p - s) / (r21 ** p - s))
        except (ValueError, ZeroDivisionError, OverflowError):
            return None
        new = abs(math.log(abs(e21 / e32)) + q) / math.log(r32)
        if abs(new - p) < 1e-12 * max(1.0, p):
            p = new
            break
        p = new
    return p if math.isfinite(p) else None


def study_levels(sizes, values, minimum: int, name: str, hint: str = "") -> tuple[list[float], list[float]]:
    """``sizes`` and ``values`` of a mesh study as floats, checked: at least ``minimum`` meshes with one value
    each, sizes decreasing from coarse to fine and > 0, finite values; ValueError naming ``name`` (the function
    that asks) otherwise, with ``hint`` after a count that is too small."""
    sizes, values = [float(h) for h in sizes], [float(v) for v in values]
    if len(sizes) != len(values) or len(sizes) < minimum:
        raise ValueError(f"{name} needs >= {minimum} meshes with one value each, got {len(sizes)} sizes and "
                         f"{len(values)} values{hint}")
    if any(not (a > b > 0) for a, b in zip(sizes, sizes[1:])):
        raise ValueError(f"sizes must decrease from coarse to fine and stay > 0, got {sizes}")
    if not all(math.isfinite(v) for v in values):
        raise ValueError(f"values must be finite, got {values}")
    return sizes, values


def extrapolate(sizes, values, formal_order: float = 2.0) -> Extrapolation:
    """Extrapolate ``values`` on meshes of element ``sizes`` (coarse to fine, >= 2) to h -> 0 (module
    docstring).  ValueError for fewer than two meshes or sizes that do not decrease."""
    sizes, values = study_levels(sizes, values, 2, "extrapolate")
    if len(sizes) == 2:
        (h2, h3), (f2, f3) = sizes, values
        r = h2 / h3
        e = f3 - f2
        return Extrapolation(f3 + e / (r ** formal_order - 1), SAFETY_FORMAL * abs(e) / (r ** formal_order - 1),
                             formal_order, False, f3, f"two meshes: formal order {formal_order:g}, F_s 3")
    (h1, h2, h3), (f1, f2, f3) = sizes[-3:], values[-3:]
    r21, r32 = h1 / h2, h2 / h3
    e21, e32 = f2 - f1, f3 - f2
    if e32 == 0.0:
        return Extrapolation(f3, 0.0, formal_order, False, f3, "the two finest meshes agree to the last bit")
    p = _observed_order(r21, r32, e21, e32)
    monotone = e21 != 0.0 and e32 / e21 > 0
    if p is not None and monotone and 0.5 <= p <= 2.0 * formal_order:
        return Extrapolation(f3 + e32 / (r32 ** p - 1), SAFETY_OBSERVED * abs(e32) / (r32 ** p - 1), p, True, f3,
                             f"three meshes, observed order {p:.2f}, F_s 1.25")
    why = ("oscillating" if not monotone else f"observed order {p:.2f} outside [0.5, {2 * formal_order:g}]"
           if p is not None else "no observed order")
    return Extrapolation(f3 + e32 / (r32 ** formal_order - 1), SAFETY_FORMAL * abs(e32) / (r32 ** formal_order - 1),
                         formal_order, False, f3, f"three meshes, {why}: formal order {formal_order:g}, F_s 3")
