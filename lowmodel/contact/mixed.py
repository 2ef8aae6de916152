"""Mixed lubrication of a rough raceway and its friction (sun2021 Sec 2.3 eq 15 ``ROU``, Sec 3.2 eqs 21-23).

sun2021 writes the friction coefficient as ``mu = (mu_a Q_a + Q_f) / Q`` (eq 21)
with the film friction ``Q_f = int_{A_h} tau_f dA`` (eq 22, Eyring shear eq 23)
and ``Q = Q_f + Q_a`` "including the film bearing force and the asperity
bearing force"; the same symbol ``Q_f`` names the film's *load* share and its
*friction force*.  Here the two are kept apart: the load ``Q`` is shared as
``Q = W_f + Q_a`` (film load ``W_f``, asperity load ``Q_a``, ``R_s = Q_a / Q``)
and the friction force is ``mu_a Q_a + F_f`` with ``F_f`` the integral of eq 22.

sun2021 solves one Reynolds equation with the rough film (eq 15 with ``ROU``,
its ref [24] Hu & Zhu 2000: a unified equation whose contact cells carry the
asperity pressure).  It leaves unstated how the contact cells are found and how
the load is shared.  This module (docs/mixed_lubrication.md):

0. coupled rough film (full film): the Reynolds equation with the roughness in
   the film, eq 15 with ``ROU = -z`` (:func:`ballbench.lowmodel.contact.ehl.solve_reynolds`
   on the gap ``gap - z``).  If it converges the film is positive everywhere
   (the solver keeps ``h > 0``): full film, ``R_s = 0``; the film pressure also
   flattens the roughness elastically.  If it does not converge the film is taken
   to close (at the sun2021 scenes' grid the smooth solve converges at every
   speed where the rough one fails) and the decoupled, deterministic load
   sharing below estimates the asperity share:

1. film: the smooth EHL solve of :func:`ballbench.lowmodel.contact.ehl.solve_reynolds`
   at the film load ``W_f`` gives the film ``h_s(x, y)`` (deformation included);
2. asperities: the raceway heights ``z`` (:mod:`.roughness`, ``ROU = -z``) that
   reach through the film touch the ball; their pressure is the dry half-space
   contact of the gap ``h_s - z`` at zero approach
   (:func:`ballbench.lowmodel.contact.halfspace.solve`, elastic interaction of
   the asperities included), ``Q_a`` its sum;
3. load sharing: ``W_f`` is the root of ``W_f + Q_a(W_f) = Q`` (bracketed
   regula falsi, Illinois).  ``Q_a = 0`` at ``W_f = Q`` is full film: the rough
   film ``h_s - z`` stays positive everywhere (``clearance > 0``).

In steps 1-3 the film is computed without the roughness in the Reynolds equation
(the roughness enters the film thickness of eqs 22-23 and the asperity contact), so
the flattening of the roughness by the film pressure is lost there: the decoupled
model touches at higher speeds than the coupled one (docs/mixed_lubrication.md).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import ehl, halfspace
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["MixedContact", "asperity_contact", "solve", "MixedFriction", "mixed_friction"]


@dataclass(frozen=True)
class MixedContact:
    """Rough-raceway EHL contact with load sharing (module docstring); SI units, fields (nx, ny).

    Attributes
    ----------
    film : :class:`~ballbench.lowmodel.contact.ehl.EHLSolution`: the coupled rough film (full film), or the
        smooth film at the film load (decoupled)
    smooth : the smooth EHL solution at the full load (the no-roughness reference)
    coupled : True when the coupled rough solve converged (full film)
    heights : raceway heights z [m] (``ROU = -z`` in sun2021 eq 15)
    rough_film : [m] the coupled film, or ``h_s - z + V(p_a)`` (decoupled; the asperities' deflection
        included, 0 where they touch)
    asperity_pressure : [Pa]
    load : Q [N];  film_load : W_f [N];  asperity_load : Q_a [N]
    asperity_share : R_s = Q_a / Q
    clearance : [m] the coupled film's minimum (coupled), or ``min(h_s - z)`` at the full load (decoupled,
        negative where the rigid roughness reaches through the smooth film)
    central_asperity_pressure : asperity pressure at the grid point nearest the centre [Pa]
    iterations : EHL solves (smooth, coupled, load sharing)
    """

    film: ehl.EHLSolution
    smooth: ehl.EHLSolution
    coupled: bool
    heights: np.ndarray
    rough_film: np.ndarray
    asperity_pressure: np.ndarray
    load: float
    film_load: float
    asperity_load: float
    asperity_share: float
    clearance: float
    central_asperity_pressure: float
    iterations: int


def asperity_contact(film: np.ndarray, heights: np.ndarray, grid: halfspace.SurfaceGrid,
                     contact_modulus: float) -> tuple[np.ndarray, float, np.ndarray]:
    """Asperity pressure [Pa], load [N] and rough film [m] where the raceway heights reach through the film.

    ``film`` h_s [m] and ``heights`` z [m] (nx, ny): the dry half-space contact
    (sun2021 eqs 3-12) of the gap ``h_s - z`` at zero approach; the rough film is
    its separation ``h_s - z + V(p_a)`` (0 on the asperity contacts).  No contact
    (zero pressure, rough film ``h_s - z``) where ``h_s - z > 0`` everywhere.
    """
    gap = np.asarray(film, dtype=float) - np.asarray(heights, dtype=float)
    if gap.shape != (grid.nx, grid.ny) or not np.all(np.isfinite(gap)):
        raise ValueError(f"film and heights must be finite arrays of shape {(grid.nx, grid.ny)}")
    if float(gap.min()) >= 0.0:
        return np.zeros_like(gap), 0.0, gap
    if float(np.max(np.abs(gap))) > halfspace.LARGEST_LENGTH:
        raise ValueError(f"film - heights must lie within +-{halfspace.LARGEST_LENGTH:g} m (halfspace.solve), got "
                         f"{float(np.max(np.abs(gap)))!r} m")
    contact = halfspace.solve(gap, grid, contact_modulus, approach=0.0, tolerance=1e-6)
    return contact.pressure, contact.force, contact.separation


def solve(gap: np.ndarray, heights: np.ndarray, grid: halfspace.SurfaceGrid, contact_modulus: float,
                load: float, entrainment_speed: float, viscosity_0: float, density_0: float = 1.0, *,
                initial_film: float = 1e-7, share_tolerance: float = 1e-2, max_iterations: int = 12,
                smallest_film_share: float = 0.02, coarsest: int = 16, ehl_iterations: int = 400,
                centre: tuple[float, float] = (0.0, 0.0), coupled: bool = True) -> MixedContact:
    """Load-shared mixed EHL contact of a smooth ball on a rough raceway (module docstring).

    ``gap`` [m] (nx, ny) the smooth undeformed separation (as for
    :func:`~ballbench.lowmodel.contact.ehl.solve_reynolds`), ``heights`` z [m]
    the raceway roughness, ``contact_modulus`` E* [Pa], ``load`` Q [N],
    ``entrainment_speed`` [m/s], ``viscosity_0`` [Pa s], ``density_0`` [kg/m^3].
    ``coupled=False`` skips step 0 (the decoupled model alone).
    The share ``W_f`` is found to ``|W_f + Q_a - Q| < share_tolerance Q``.
    ConvergenceError when the film would carry less than ``smallest_film_share``
    of the load (boundary lubrication: outside this model) or the sharing does
    not converge in ``max_iterations`` EHL solves; the EHL solver's own errors pass through
    (``ehl_iterations`` its Newton iterations: a small value fails fast where it stalls).
    """
    heights = np.asarray(heights, dtype=float)
    if heights.shape != (grid.nx, grid.ny) or not np.all(np.isfinite(heights)):
        raise ValueError(f"heights must be a finite array of shape {(grid.nx, grid.ny)}")
    e_star = checks.positive("contact_modulus", contact_modulus, "Pa")
    load = checks.positive("load", load, "N")
    share_tolerance = checks.bounded("share_tolerance", share_tolerance, 0.0, 1.0)
    smallest = checks.bounded("smallest_film_share", smallest_film_share, 0.0, 1.0)
    max_iterations = checks.count("max_iterations", max_iterations, 1)
    ehl_iterations = checks.count("ehl_iterations", ehl_iterations, 1)
    solves = {}

    def evaluate(film_load):
        solution = ehl.solve_reynolds(gap, grid, e_star, film_load, entrainment_speed, viscosity_0, density_0,
                                      initial_film=initial_film, coarsest=coarsest, centre=centre,
                                      max_iterations=ehl_iterations)
        pressure, asperity, separation = asperity_contact(solution.film, heights, grid, e_star)
        solves[film_load] = (solution, pressure, asperity, separation)
        return film_load + asperity - load  # sun2021 eq 21: Q = W_f + Q_a

    X, Y = grid.coordinates()
    i, j = np.unravel_index(np.argmin((X - centre[0]) ** 2 + (Y - centre[1]) ** 2), X.shape)
    hi = load
    f_hi = evaluate(hi)
    smooth = solves[hi][0]
    if coupled:
        try:  # step 0: sun2021 eq 15 with ROU = -z inside the Reynolds equation
            rough = ehl.solve_reynolds(gap - heights, grid, e_star, load, entrainment_speed, viscosity_0, density_0,
                                       initial_film=initial_film, coarsest=coarsest, centre=centre,
                                       max_iterations=ehl_iterations)
        except ConvergenceError:
            rough = None
        if rough is not None:
            return MixedContact(film=rough, smooth=smooth, coupled=True, heights=heights, rough_film=rough.film,
                                asperity_pressure=np.zeros_like(heights), load=load, film_load=load,
                                asperity_load=0.0, asperity_share=0.0, clearance=rough.minimum_film,
                                central_asperity_pressure=0.0, iterations=len(solves) + 1)
    clearance = float(np.min(smooth.film - heights))
    best = hi
    if f_hi > share_tolerance * load:
        # W_f = Q - Q_a(Q) undershoots the root (Q_a grows with the film load): a lower bracket
        lo = max(load - f_hi, smallest * load)
        f_lo = evaluate(lo)
        if f_lo > 0.0 and lo > smallest * load:
            lo = smallest * load
            f_lo = evaluate(lo)
        if f_lo > 0.0:
            raise ConvergenceError("mixed lubrication: the asperities carry the load even when the film carries "
                                   f"{100 * smallest:g} % of it (boundary lubrication)", residual=f_lo / load,
                                   iterations=len(solves), tolerance=share_tolerance,
                                   reason="boundary lubrication")
        side = 0
        for _ in range(max_iterations):
            best = lo if abs(f_lo) < abs(f_hi) else hi
            if abs(min(f_lo, f_hi, key=abs)) <= share_tolerance * load:
                break
            trial = (lo * f_hi - hi * f_lo) / (f_hi - f_lo)
            f_trial = evaluate(trial)
            if f_trial > 0.0:
                hi, f_hi = trial, f_trial
                if side == 1:
                    f_lo *= 0.5  # Illinois
                side = 1
            else:
                lo, f_lo = trial, f_trial
                if side == -1:
                    f_hi *= 0.5
                side = -1
        else:
            raise ConvergenceError("mixed lubrication load sharing did not converge", residual=min(
                abs(f_lo), abs(f_hi)) / load, iterations=len(solves), tolerance=share_tolerance,
                reason="iteration limit")
        best = min(solves, key=lambda w: abs(w + solves[w][2] - load))
    film, pressure, asperity, rough = solves[best]
    return MixedContact(film=film, smooth=smooth, coupled=False, heights=heights, rough_film=rough,
                        asperity_pressure=pressure,
                        load=load, film_load=float(best), asperity_load=float(asperity),
                        asperity_share=float(asperity) / load, clearance=clearance,
                        central_asperity_pressure=float(pressure[i, j]), iterations=len(solves) + int(coupled))


@dataclass(frozen=True)
class MixedFriction:
    """Friction of a mixed contact (sun2021 eqs 21-23).

    friction_coefficient : mu = (mu_a Q_a + F_f) / Q (eq 21)
    film_friction : F_f = int tau_f dA over the wet film area [N] (eqs 22-23)
    asperity_friction : mu_a Q_a [N]
    """

    friction_coefficient: float
    film_friction: float
    asperity_friction: float


def mixed_friction(contact: MixedContact, sliding_speed: float, viscosity_0: float, eyring_stress: float,
                   dry_friction: float = 0.1) -> MixedFriction:
    """Friction coefficient of a :class:`MixedContact` (sun2021 eqs 21-23).

    Film shear ``tau_f = tau0 asinh(eta(p) |du| / (tau0 h))`` (eq 23) with the
    Roelands viscosity of the film pressure and the rough film ``h = h_s - z`` on
    the cells that carry film pressure and no asperity (``A_h``, eq 22);
    asperities ``mu_a Q_a`` (``dry_friction`` mu_a = 0.1 in sun2021 Sec 3.2).
    ``sliding_speed`` du [m/s], ``viscosity_0`` [Pa s], ``eyring_stress`` tau0 [Pa]
    (sun2021 leaves it unstated).
    """
    du = abs(float(checks.finite("sliding_speed", sliding_speed, "m/s")))
    wet = (contact.film.pressure > 0.0) & (contact.rough_film > 0.0)
    film_friction = 0.0
    if du > 0.0 and np.any(wet):
        eta = ehl.roelands_viscosity(contact.film.pressure[wet], viscosity_0)  # eq 16
        tau = ehl.eyring_shear_stress(eta, du, contact.rough_film[wet], eyring_stress)  # eq 23
        film_friction = float(np.sum(tau)) * contact.film.grid.cell_area  # eq 22
    mu = ehl.friction_coefficient(contact.asperity_load, film_friction, contact.load, dry_friction)  # eq 21
    mu_a = checks.non_negative("dry_friction", dry_friction)
    if not math.isfinite(mu):
        raise ValueError("friction coefficient is not finite")
    return MixedFriction(friction_coefficient=mu, film_friction=film_friction,
                         asperity_friction=mu_a * contact.asperity_load)
