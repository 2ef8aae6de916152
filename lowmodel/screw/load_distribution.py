"""Static axial load distribution over the balls of a ball-screw nut (low-order; stands in for lin2019 ref [19]).

lin2019 Sec 3.4 takes the load of each ball from its ref [19] (a low-order model with
lateral deformation and geometric errors, not available here).  This module is a
documented substitute with two ingredients:

1. **Hertz contacts of one ball** (:mod:`lowmodel.screw.ball`): the relative
   axial shift ``u`` of nut and screw that makes a nominal ball (theta = 0, the
   module's preload) carry the axial load ``q``, ``u = U(q)``, tabulated by solving the
   single-ball model (friction included) on a grid of loads and interpolated
   (monotone cubic, scipy ``PchipInterpolator``).
2. **Axial compliance of screw and nut** as bars: the screw is loaded at the end before the nut (``z < 0``) and
   carries ``N_s(z) = F_a - S(z)`` over the nut, ``S(z)`` the load already handed over by the balls with
   ``z_i < z``.  The nut is held at its flange (:data:`FLANGES`): at the loaded end (``"loaded end"``, the
   bolt-and-nut "tension-compression" arrangement: the nut carries ``N_n(z) = F_a - S(z)`` towards its flange) or
   at the far end (``"far end"``, "tension-tension": ``N_n(z) = S(z)`` away from the loaded end).  A ball is
   relieved by as much as its screw groove moves less than at the loaded end (the screw's stretch up to it) and
   its nut groove moves towards the flange; the shift seen by ball ``j`` is
   ``u_j = u_0 - o_j``, the offset

       o_j = int_0^{z_j} (N_s / (E A_s) + s_n N_n / (E A_n)) dz,     s_n = +1 loaded end, -1 far end

   (the far flange's nut offset ``-int_0^z S / (E A_n)`` equals its nut groove's move towards the ball's load,
   ``(Z - max(z_j, z_k)) / (E A_n)`` per unit load at ``z_k``, up to a constant; the loaded end's is its move
   ``min(z_j, z_k) / (E A_n)``: :func:`nut_bar_compliance`).  An elastic nut of any shape enters through its
   compliance matrix (``nut_compliance``, the FE rung's: fem.nut_fe) in place of the bar.

The loads solve ``q_j = U^-1(u_j)``, ``sum q_j = F_a`` (fixed-point iteration on the
elastic offsets, relaxed where it stops contracting, ``brentq`` for ``u_0``; with numba the steps are compiled in
:mod:`lowmodel.screw.distribution_kernels`, the same numbers to the last bit).
Left out (docs/ball_screw.md): radial and lateral deformation of screw and nut, thread bending, shear lag of the
nut wall, geometric errors in the distribution (every ball is the nominal one here; the
deviations enter the friction model only), friction's effect on the shares,
centrifugal and gyroscopic loads.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from ballbench.lowmodel import checks, kernels
from ballbench.lowmodel.cubic_pieces import cubic_pieces
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.solvers import check_solver_options

__all__ = ["BarSections", "bar_sections", "AxialStiffness", "axial_stiffness", "distribute", "FLANGES",
           "nut_bar_compliance", "NUT_OUTER_RADIUS_FACTOR"]

FLANGES = ("loaded end", "far end")  # where the nut is held (module docstring)
NUT_OUTER_RADIUS_FACTOR = 1.7  # the nut's default outer radius over R_P (an assumption: lin2019 gives no nut size)


@dataclass(frozen=True)
class BarSections:
    """Axial cross-section areas [m^2] of the screw shaft and the nut wall."""

    screw_area: float
    nut_area: float


def bar_sections(module: screw_contacts.ScrewModule, *, screw_radius: float | None = None,
                 nut_outer_radius: float | None = None) -> BarSections:
    """Screw as a solid bar of radius ``R_P - R_B`` (default), nut as a tube from ``R_P + R_B`` to
    ``nut_outer_radius`` (default ``1.7 R_P``, an assumption: lin2019 Table 4 gives no nut size) [m]."""
    inner = module.pitch_radius + module.ball_radius
    screw_radius = module.pitch_radius - module.ball_radius if screw_radius is None else screw_radius
    outer = NUT_OUTER_RADIUS_FACTOR * module.pitch_radius if nut_outer_radius is None else nut_outer_radius
    screw_radius = checks.positive("screw_radius", screw_radius, "m")
    outer = checks.bounded("nut_outer_radius", outer, inner, math.inf, "m", note="beyond R_P + R_B")
    with np.errstate(over="ignore"):
        screw_area = checks.finite_result("screw_radius", math.pi * np.float64(screw_radius) ** 2, "m^2")
        nut_area = checks.finite_result("nut_outer_radius", math.pi * (np.float64(outer) ** 2 - inner**2), "m^2")
    return BarSections(screw_area, nut_area)


@dataclass(frozen=True)
class AxialStiffness:
    """Tabulated shift ``u = U(q)`` [m] of one nominal ball against its axial load ``q`` [N].

    ``loads`` and ``shifts`` are read-only (the cached interpolant is built from them; edit with
    :func:`dataclasses.replace`, lowmodel.checks.freeze_arrays).
    """

    loads: np.ndarray
    shifts: np.ndarray

    def __post_init__(self):
        checks.freeze_arrays(self, "loads", "shifts")

    def __reduce__(self):
        return checks.rebuilt_through_init(self)

    @cached_property
    def _interpolant(self):
        order = np.argsort(self.shifts)
        return PchipInterpolator(self.shifts[order], self.loads[order])

    @cached_property
    def _pieces(self):
        return cubic_pieces(self._interpolant)

    def load(self, shift) -> np.ndarray:
        """``q = U^-1(u)``: monotone cubic (pchip) through the tabulated points, extrapolated beyond them.

        scipy's ``PchipInterpolator`` evaluated by :class:`lowmodel.cubic_pieces.CubicPieces` (the same numbers to the
        last bit without scipy's call overhead: :func:`distribute`'s root search evaluates it thousands of times)."""
        return self._pieces(shift)

    def shift(self, load) -> np.ndarray:
        """``u = U(q)``, the exact inverse of :meth:`load` (brentq per value)."""
        values = np.atleast_1d(np.asarray(load, dtype=float))
        low, high = self.shifts.min(), self.shifts.max()
        out = np.array([brentq(lambda u, q=q: float(self._interpolant(u)) - q, low, high, xtol=1e-18)
                        for q in values.ravel()])
        return out.reshape(np.shape(load)) if np.ndim(load) else float(out[0])


def axial_stiffness(module: screw_contacts.ScrewModule, max_load: float, points: int = 13, *,
                    contact_law: screw_contacts.GrooveContactLaws | None = None) -> AxialStiffness:
    """Solve the single-ball model (theta = 0) for ``points`` loads in ``[0, max_load]`` [N].

    ``contact_law``: calibrated contact laws of the screw and nut grooves (:class:`ball.GrooveContactLaws`,
    ``delta = C F^(2/3) + C_b F``) in place of Hertz's ``delta = C F^(2/3)`` (lin2019 eq 53).
    """
    max_load = checks.positive("max_load", max_load, "N")
    points = checks.count("points", points, 4)
    loads = np.linspace(0.0, max_load, points)
    contacts = screw_contacts.ball_contacts(module, 0.0, contact_law=contact_law)
    try:   # the largest load of the table must still be a Hertz contact (ball.reference_force)
        sb.reference_force(contacts, max_load)
    except ValueError as error:
        raise ValueError(f"max_load: {error}") from None
    shifts = np.array([sb.solve(contacts, float(q)).nut_shift for q in loads])
    steps = np.diff(shifts)
    if not (np.all(steps > 0.0) or np.all(steps < 0.0)):
        raise ValueError("the ball's axial shift is not monotone in its load on [0, max_load]; "
                         "reduce max_load or increase the preload")
    return AxialStiffness(loads, shifts)


KERNELS = "screw.distribution_kernels"  # the compiled root search of u_0 (lowmodel.kernels.load)
_ROOT_XTOL = 1e-16             # m, Brent's absolute tolerance on u_0
_ROOT_RTOL = 4 * np.finfo(float).eps   # Brent's relative tolerance (scipy.optimize.brentq's default, its least)
_ROOT_ITERATIONS = 2000


def _swamped(offset, low, high):
    raise ValueError(f"positions, lead, lead_error, youngs_modulus: the offsets of the balls (up to "
                     f"{float(np.max(np.abs(offset)))!r} m) swamp the range of the ball's shift table "
                     f"({float(high - low)!r} m) in double precision; positions must be azimuths in the nut")


def _step(loads, order, segment, geometric, total, compliance_s, compliance_n, flange, sign, stiffness, low, high,
          nut_compliance=None):
    """One step of :func:`distribute`'s fixed-point iteration: the loads that carry ``total`` on the offsets of
    ``loads`` (``low``, ``high``: the range of the table's shifts; ``nut_compliance`` (n, n) in place of the nut
    bar, whose ``compliance_n`` is then 0)."""
    n = loads.size
    handed = np.cumsum(loads[order]) - loads[order]           # S(z) just before each ball
    before = np.concatenate([[0.0], handed[1:]])               # S over each segment
    strain = (total - before) * compliance_s + (flange * total - before) * compliance_n
    offset = np.empty(n)
    offset[order] = np.cumsum(strain * segment)                # int_0^z (eps_s + s_n eps_n)
    offset = offset + geometric
    if nut_compliance is not None:
        offset = offset + nut_compliance @ loads
    shifted = sign * offset

    def mismatch(u0):   # np.clip's value, through the ufuncs (np.clip's Python wrapper costs more than its work)
        return float(stiffness.load(np.minimum(np.maximum(u0 - shifted, low), high)).sum() - total)

    # bracket: every ball at the bottom of the table, then every ball at its top (sum 0, then >= total)
    start = min(low - offset.max(), low + shifted.min())
    end = max(high + offset.max(), high + shifted.max())
    if mismatch(start) * mismatch(end) > 0.0:   # offsets so large that the table's range is lost: no sign change
        _swamped(offset, low, high)
    try:   # bisection may need ~1100 halvings where the offsets dwarf the table (absurd stiffness)
        u0 = brentq(mismatch, start, end, xtol=_ROOT_XTOL, rtol=_ROOT_RTOL, maxiter=_ROOT_ITERATIONS)
    except RuntimeError as error:
        raise ConvergenceError(f"distribute: the nut shift u_0 was not found ({error})", residual=math.inf,
                               iterations=_ROOT_ITERATIONS, tolerance=_ROOT_XTOL, reason="no root bracketed") from None
    new = stiffness.load(np.clip(u0 - sign * offset, low, high))
    if abs(float(new.sum()) - total) > 1e-6 * total:   # the loads must carry the axial load (lost precision)
        _swamped(offset, low, high)
    return new


def nut_bar_compliance(z, nut_area: float, youngs_modulus: float, flange: str = "loaded end",
                       length: float | None = None) -> np.ndarray:
    """(n, n) m/N, the nut bar's compliance at the balls ``z`` (n,) [m from the loaded end]: the move of ball ``j``'s
    nut groove towards its flange under a unit axial load at ball ``k``, ``min(z_j, z_k) / (E A_n)`` held at the
    loaded end, ``(length - max(z_j, z_k)) / (E A_n)`` at the far end ``z = length`` (default the last ball's z;
    module docstring)."""
    checks.choice("flange", flange, FLANGES)
    z = np.asarray(z, dtype=float).reshape(-1)
    stiffness = checks.positive("nut_area", nut_area, "m^2") * checks.positive("youngs_modulus", youngs_modulus,
                                                                                "Pa")
    if flange == "loaded end":
        return np.minimum.outer(z, z) / stiffness
    length = float(z.max()) if length is None else checks.bounded("length", length, float(z.max()), math.inf, "m")
    return (length - np.maximum.outer(z, z)) / stiffness


def distribute(positions, total_load: float, stiffness: AxialStiffness, sections: BarSections, lead: float,
               youngs_modulus: float, *, lead_error: float = 0.0, flange: str = "loaded end",
               nut_compliance=None, tolerance: float = 1e-10, max_iterations: int = 50) -> np.ndarray:
    """Axial load [N] of each ball, shape (n,).

    ``positions``: azimuth of each ball in the nut [rad] from the loaded end (``z = lead psi / 2 pi``);
    ``total_load`` [N] >= 0 on the screw; ``lead`` [m]; ``youngs_modulus`` [Pa] of screw and nut;
    ``lead_error`` [m per turn]: the nut groove's lead minus the screw's (a geometric error, lin2019
    Sec 3.1 / ref [19]); it adds ``lead_error psi / 2 pi`` to the nut's axial position at each ball
    (with the sign of the elastic shortening: a positive error unloads the far balls);
    ``flange`` one of :data:`FLANGES` (module docstring); ``nut_compliance`` (n, n) [m/N] an elastic nut's
    compliance at the balls (symmetric; the nut bar's :func:`nut_bar_compliance` gives the bar's loads) in place of
    the bar (``sections.nut_area`` then unused).
    """
    check_solver_options(tolerance, max_iterations)
    checks.choice("flange", flange, FLANGES)
    psi = np.asarray(checks.non_negative("positions", positions, "rad"), dtype=float).reshape(-1)
    total = checks.non_negative("total_load", total_load, "N")
    lead = checks.non_negative("lead", lead, "m")
    youngs_modulus = checks.positive("youngs_modulus", youngs_modulus, "Pa")
    n = psi.size
    if total == 0.0:
        return np.zeros(n)
    if total > n * stiffness.loads[-1]:
        raise ValueError(f"total_load must be at most n * max_load of the stiffness table = "
                         f"{n * stiffness.loads[-1]!r} N, got {total!r}")
    with np.errstate(over="ignore", invalid="ignore"):
        z = checks.finite_result("lead, positions", lead * psi / (2.0 * math.pi), "m")
        geometric = checks.finite_result("lead_error, positions", checks.finite(
            "lead_error", lead_error, "m per turn") * psi / (2.0 * math.pi), "m")
    with np.errstate(over="ignore", invalid="ignore", divide="ignore"):
        compliance_s = checks.finite_result("youngs_modulus", 1.0 / np.float64(youngs_modulus * sections.screw_area),
                                            "1/N")
        compliance_n = checks.finite_result("youngs_modulus", 1.0 / np.float64(youngs_modulus * sections.nut_area),
                                            "1/N")
    if nut_compliance is not None:
        nut_compliance = np.asarray(nut_compliance, dtype=float)
        if nut_compliance.shape != (n, n) or not np.all(np.isfinite(nut_compliance)):
            raise ValueError(f"nut_compliance must be a finite ({n}, {n}) matrix [m/N] (one row per ball), got "
                             f"shape {nut_compliance.shape}")
        compliance_n = 0.0
    flange_total = 1.0 if flange == "loaded end" else 0.0
    order = np.argsort(z)
    segment = np.diff(np.concatenate([[0.0], z[order]]))      # z from the previous ball (or 0)
    sign = 1.0 if stiffness.shifts[-1] > stiffness.shifts[0] else -1.0
    low, high = stiffness.shifts.min(), stiffness.shifts.max()
    compiled = kernels.load(KERNELS)
    if compiled is not None and n <= compiled.MAX_BALLS and nut_compliance is None:   # the same operations compiled
        data = compiled.pack(n, low, high, total, stiffness._pieces)

        def step(loads):
            start, end, at_start, at_end = compiled.offsets(loads, order, segment, geometric, total, compliance_s,
                                                            compliance_n, flange_total, sign, data)
            if at_start * at_end > 0.0:
                _swamped(compiled.shifted(data), low, high)
            u0, status, _ = compiled.nut_shift(data, start, end, _ROOT_XTOL, _ROOT_RTOL, _ROOT_ITERATIONS)
            if status != compiled.CONVERGED or not math.isfinite(u0):
                raise ConvergenceError(f"distribute: the nut shift u_0 was not found (scipy's Brent routine, status "
                                       f"{status}, u_0 = {u0!r})", residual=math.inf, iterations=_ROOT_ITERATIONS,
                                       tolerance=_ROOT_XTOL, reason="no root bracketed")
            new = np.empty(n)
            if abs(compiled.loads_at(u0, data, new) - total) > 1e-6 * total:
                _swamped(compiled.shifted(data), low, high)
            return new
    else:
        def step(loads):
            return _step(loads, order, segment, geometric, total, compliance_s, compliance_n, flange_total, sign,
                         stiffness, low, high, nut_compliance)
    loads = np.full(n, total / n)
    relaxation, previous = 1.0, math.inf   # the plain fixed point; halved where a step does not shrink the change
    for _ in range(max_iterations):
        new = step(loads)
        change = float(np.max(np.abs(new - loads)))
        if change <= tolerance * total:
            return new
        if change > 0.9 * previous:   # bars soft against the balls: the plain step overshoots (it may cycle)
            relaxation *= 0.5
        previous = change
        loads = new if relaxation == 1.0 else loads + relaxation * (new - loads)
    raise ConvergenceError("distribute: the fixed-point iteration of the ball loads did not converge",
                           residual=change / total, iterations=max_iterations, tolerance=tolerance,
                           reason="iteration limit")
