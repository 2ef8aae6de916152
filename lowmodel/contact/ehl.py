"""Elastohydrodynamic point contact of sun2021 (Sec 2.3, eqs 14-23): the closed-form pieces.

Implemented here (each a plain function, SI units):

* Roelands pressure-viscosity law (sun2021 eq 16) and its pressure-viscosity
  coefficient at ambient pressure;
* Dowson-Higginson pressure-density law (sun2021 eq 17);
* Eyring shear stress of the film (sun2021 eq 23);
* Hamrock-Dowson central and minimum film thickness of a fully flooded,
  isothermal, smooth elliptical contact (Hamrock & Dowson, J. Lubr. Technol. 99
  (1977) 264, eqs for H_c and H_min), the reference a numerical EHL solution is
  checked against;
* a seeded Weierstrass-Mandelbrot fractal height map (sun2021 Sec 2.3, ref [28];
  the 3D form of Ausloos & Berman 1985 as written by Yan & Komvopoulos, J. Appl.
  Phys. 84 (1998) 3617, eq 4) for the raceway roughness ``ROU(x, y)`` of eq 15.

and the isothermal Reynolds solver (eqs 14, 15, 18, 19; :func:`solve_reynolds`)
with the DC-FFT deformation of :mod:`.halfspace`.

The film traction (eqs 22-23, :func:`film_traction`) and the mixed friction
coefficient (eq 21, :func:`friction_coefficient`) are here; the rough (mixed)
solve is :mod:`.mixed`, the friction torque of eq 20 :mod:`lowmodel.screw.friction_torque`.

One concept in one file (about 650 lines): the smooth isothermal EHL point contact, the lubricant laws its
Reynolds solve evaluates at every Newton step, that solve and the check of its answer (:func:`verify`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import LinearOperator, gmres, splu
from threadpoolctl import threadpool_limits

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import halfspace
from ballbench.lowmodel.errors import ConvergenceError

__all__ = [
    "wm_parameters",
    "wm_top_level",
    "ROELANDS_PRESSURE",
    "ROELANDS_Z",
    "roelands_viscosity",
    "roelands_pressure_viscosity_coefficient",
    "dowson_higginson_density",
    "eyring_shear_stress",
    "hamrock_dowson_film",
    "weierstrass_mandelbrot_surface",
    "EHLSolution",
    "solve_reynolds",
    "verify",
    "film_traction",
    "friction_coefficient",
]

ROELANDS_PRESSURE = 1.0 / 5.1e-9  # Pa, p_r = 1.96e8 Pa (sun2021 eq 16: 5.1e-9 p)
ROELANDS_Z = 0.68  # pressure-viscosity index (sun2021 eq 16)
ROELANDS_LN_ETA_INF = -9.67  # ln(eta_inf / (1 Pa s)), eta_inf = 6.31e-5 Pa s (sun2021 eq 16: ln eta0 + 9.67)


def roelands_viscosity(pressure, viscosity_0: float):
    """Roelands viscosity ``eta(p)`` [Pa s] (sun2021 eq 16).

    ``eta = eta0 exp{(ln eta0 + 9.67) [(1 + 5.1e-9 p)^0.68 - 1]}`` with ``p`` [Pa]
    (array or scalar; negative pressures are cavitated and taken as 0) and the
    ambient viscosity ``viscosity_0`` eta0 [Pa s].
    """
    eta0 = checks.positive("viscosity_0", viscosity_0, "Pa s")
    p = np.maximum(np.asarray(pressure, dtype=float), 0.0)
    with np.errstate(over="ignore"):
        eta = eta0 * np.exp((math.log(eta0) - ROELANDS_LN_ETA_INF) * ((1.0 + p / ROELANDS_PRESSURE) ** ROELANDS_Z
                                                                       - 1.0))
    if np.any(np.isinf(eta)):  # only at pressures far beyond any contact's (~1e11 Pa for eta0 = 0.05 Pa s)
        raise ValueError(f"pressure up to {float(np.max(p))!r} Pa gives a Roelands viscosity beyond the "
                         f"floating-point range (viscosity_0 {eta0!r} Pa s)")
    return eta


def roelands_pressure_viscosity_coefficient(viscosity_0: float) -> float:
    """``alpha = d ln(eta) / dp`` at ``p = 0`` [1/Pa] of the Roelands law (sun2021 eq 16).

    ``alpha = (ln eta0 + 9.67) z / p_r``: the coefficient the Barus law and the
    Hamrock-Dowson parameter ``G = alpha E'`` use.
    """
    eta0 = checks.positive("viscosity_0", viscosity_0, "Pa s")
    return (math.log(eta0) - ROELANDS_LN_ETA_INF) * ROELANDS_Z / ROELANDS_PRESSURE


def dowson_higginson_density(pressure, density_0: float):
    """Dowson-Higginson density ``rho(p)`` [kg/m^3] (sun2021 eq 17).

    ``rho = rho0 (1 + 0.6e-9 p / (1 + 1.7e-9 p))``, ``p`` [Pa] (negative taken as
    0); tends to ``rho0 (1 + 0.6/1.7)`` (+35 %) at high pressure.
    """
    rho0 = checks.positive("density_0", density_0, "kg/m^3")
    p = np.maximum(np.asarray(pressure, dtype=float), 0.0)
    return rho0 * (1.0 + 0.6e-9 * p / (1.0 + 1.7e-9 * p))


def eyring_shear_stress(viscosity, sliding_speed, film_thickness, eyring_stress: float):
    """Eyring film shear stress ``tau = tau0 asinh(eta du / (tau0 h))`` [Pa] (sun2021 eq 23).

    ``viscosity`` eta [Pa s], ``sliding_speed`` du = u1 - u2 [m/s] (signed),
    ``film_thickness`` h [m] > 0, ``eyring_stress`` tau0 [Pa] > 0 (sun2021 does
    not state it).  Reduces to Newton's ``eta du / h`` for small shear rates.
    """
    tau0 = checks.positive("eyring_stress", eyring_stress, "Pa")
    eta = checks.positive("viscosity", viscosity, "Pa s")
    h = checks.positive("film_thickness", film_thickness, "m")
    du = checks.finite("sliding_speed", sliding_speed, "m/s")
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        tau = tau0 * np.arcsinh(eta * du / (tau0 * h))
        beyond = ~np.isfinite(tau)
        if np.any(beyond):  # the shear rate overflows (tau0 h ~ 0): asinh(x) = sign(x) ln(2 |x|) for |x| > 1e154
            log_rate = math.log(2.0) + np.log(eta) + np.log(np.abs(du)) - math.log(tau0) - np.log(h)
            tau = np.where(beyond, np.where(du == 0.0, 0.0, np.sign(du) * tau0 * log_rate), tau)
    if not np.all(np.isfinite(tau)):
        raise ValueError(f"eyring_stress {tau0!r} Pa, viscosity, sliding_speed and film_thickness give a shear "
                         "stress beyond the floating-point range")
    return tau


def hamrock_dowson_film(entrainment_speed: float, load: float, radius_x: float, radius_y: float,
                        reduced_modulus: float, viscosity_0: float, pressure_viscosity: float) -> dict:
    """Hamrock-Dowson (1977) central and minimum film thickness [m] of a smooth elliptical EHL contact.

    Inputs: ``entrainment_speed`` u = (u1 + u2)/2 [m/s] along x, ``load`` [N],
    reduced radii ``radius_x`` (rolling direction), ``radius_y`` [m], the
    reduced modulus ``reduced_modulus`` E' = 2 E* [Pa], ``viscosity_0`` [Pa s],
    ``pressure_viscosity`` alpha [1/Pa].  Dimensionless groups ``U = eta0 u /
    (E' R_x)``, ``G = alpha E'``, ``W = F / (E' R_x^2)``, ellipticity ``k =
    1.0339 (R_y/R_x)^0.636``::

        H_c   = 2.69 U^0.67 G^0.53 W^-0.067 (1 - 0.61 exp(-0.73 k))
        H_min = 3.63 U^0.68 G^0.49 W^-0.073 (1 - exp(-0.68 k))

    Returns a dict with ``h_c``, ``h_min`` [m] and ``U``, ``G``, ``W``, ``k``.
    The fit scatters by about 10 % around full numerical solutions.
    """
    u = checks.positive("entrainment_speed", entrainment_speed, "m/s")
    load = checks.positive("load", load, "N")
    rx = checks.positive("radius_x", radius_x, "m")
    ry = checks.positive("radius_y", radius_y, "m")
    e_prime = checks.positive("reduced_modulus", reduced_modulus, "Pa")
    eta0 = checks.positive("viscosity_0", viscosity_0, "Pa s")
    alpha = checks.positive("pressure_viscosity", pressure_viscosity, "1/Pa")
    try:
        U = eta0 * u / (e_prime * rx)
        G = alpha * e_prime
        W = load / (e_prime * rx * rx)
        k = 1.0339 * (ry / rx) ** 0.636
        h_c = rx * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * math.exp(-0.73 * k))
        h_min = rx * 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - math.exp(-0.68 * k))
        groups = {"h_c": h_c, "h_min": h_min, "U": U, "G": G, "W": W, "k": k}
    except (ZeroDivisionError, OverflowError):  # a group under- or overflows
        groups = {}
    if not groups or not all(math.isfinite(v) and v > 0.0 for v in groups.values()):
        raise ValueError(f"entrainment_speed, load, radius_x, radius_y, reduced_modulus, viscosity_0 and "
                         f"pressure_viscosity ({u!r}, {load!r}, {rx!r}, {ry!r}, {e_prime!r}, {eta0!r}, {alpha!r}) "
                         f"give Hamrock-Dowson groups outside the floating-point range: {groups}")
    return groups


def wm_parameters(fractal_dimension, roughness_scale, sample_length, cutoff_length, gamma, ridges):
    """Checked ``(D, G [m], L [m], L_s [m], gamma, M)`` of the WM surface: D in (2, 3), G, L, L_s > 0,
    L_s < L, gamma > 1, M >= 1 (ValueError naming the parameter otherwise)."""
    D = checks.bounded("fractal_dimension", fractal_dimension, 2.0, 3.0)
    G = checks.positive("roughness_scale", roughness_scale, "m")
    L, Ls, gamma = _wm_lengths(sample_length, cutoff_length, gamma)
    M = checks.count("ridges", ridges, 1)
    return D, G, L, Ls, gamma, M


def _wm_lengths(sample_length, cutoff_length, gamma) -> tuple[float, float, float]:
    """Checked ``(L, L_s, gamma)``: L, L_s > 0 m, L_s < L, gamma > 1."""
    L = checks.positive("sample_length", sample_length, "m")
    Ls = checks.positive("cutoff_length", cutoff_length, "m")
    if not Ls < L:
        raise ValueError(f"cutoff_length must be < sample_length {L!r} m, got {Ls!r}")
    if not math.isfinite(L / Ls):
        raise ValueError(f"cutoff_length {Ls!r} m is too small against sample_length {L!r} m (L / L_s overflows)")
    gamma = checks.positive("gamma", gamma)
    if not gamma > 1.0:
        raise ValueError(f"gamma must be > 1, got {gamma!r}")
    return L, Ls, gamma


def wm_top_level(sample_length: float, cutoff_length: float, gamma: float) -> int:
    """``n_max = floor(ln(L / L_s) / ln gamma)`` of Yan & Komvopoulos eq 4 (the smallest wavelength L_s).

    ``sample_length`` L [m] > ``cutoff_length`` L_s [m] > 0, ``gamma`` > 1 (ValueError naming the parameter).
    """
    L, Ls, gamma = _wm_lengths(sample_length, cutoff_length, gamma)
    return int(math.floor(math.log(L / Ls) / math.log(gamma)))


def weierstrass_mandelbrot_surface(x, y, fractal_dimension: float, roughness_scale: float, sample_length: float,
                                   *, cutoff_length: float, gamma: float = 1.5, ridges: int = 10,
                                   seed: int = 0) -> np.ndarray:
    """Seeded Weierstrass-Mandelbrot height map ``z(x, y)`` [m] (sun2021 Sec 2.3, ref [28]).

    Yan & Komvopoulos (1998) eq 4::

        z = L (G/L)^(D-2) (ln gamma / M)^(1/2) sum_m=1..M sum_n=0..n_max gamma^((D-3) n)
            [cos phi_mn - cos(2 pi gamma^n r / L cos(theta - pi m / M) + phi_mn)]

    ``x``, ``y`` [m] arrays of one shape; ``fractal_dimension`` D in (2, 3)
    (sun2021: 2.47); ``roughness_scale`` G [m] (sun2021: "0.41", unit unstated);
    ``sample_length`` L [m]; ``cutoff_length`` L_s [m] (smallest wavelength,
    ``n_max = floor(ln(L/L_s) / ln gamma)``); ``gamma`` > 1; ``ridges`` M; phases
    ``phi_mn`` uniform in [0, 2 pi) from ``numpy.random.default_rng(seed)``.
    ``z = 0`` at the origin by construction.
    """
    D, G, L, Ls, gamma, M = wm_parameters(fractal_dimension, roughness_scale, sample_length, cutoff_length, gamma,
                                          ridges)
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    n_max = wm_top_level(L, Ls, gamma)
    phases = np.random.default_rng(seed).uniform(0.0, 2.0 * math.pi, size=(M, n_max + 1))
    r = np.hypot(x, y)
    theta = np.arctan2(y, x)
    z = np.zeros(x.shape)
    for m in range(1, M + 1):
        projection = r * np.cos(theta - math.pi * m / M)
        for n in range(n_max + 1):
            phi = phases[m - 1, n]
            z += gamma ** ((D - 3.0) * n) * (math.cos(phi) - np.cos(2.0 * math.pi * gamma**n * projection / L + phi))
    return L * (G / L) ** (D - 2.0) * math.sqrt(math.log(gamma) / M) * z


# --------------------------------------------------------------------------
# Reynolds solver (sun2021 eqs 14-19)
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class EHLSolution:
    """Isothermal EHL point contact on a :class:`~ballbench.lowmodel.contact.halfspace.SurfaceGrid`.

    Attributes
    ----------
    grid : the grid (x along the entrainment direction)
    pressure : (nx, ny) film pressure [Pa], ``>= 0`` (cavitated cells 0)
    film : (nx, ny) film thickness h [m] (sun2021 eq 15)
    h0 : the rigid offset of eq 15 [m] (found from the load balance, eq 19)
    central_film, minimum_film : h at the grid point nearest ``centre`` and the minimum of h [m]
    central_pressure, max_pressure : [Pa]
    force : ``sum p dA`` [N]
    load_error : ``|force - load| / load``
    iterations : Newton iterations
    residual : final relative pressure change
    """

    grid: halfspace.SurfaceGrid
    pressure: np.ndarray
    film: np.ndarray
    h0: float
    central_film: float
    minimum_film: float
    central_pressure: float
    max_pressure: float
    force: float
    load_error: float
    iterations: int
    residual: float


LINE_SEARCH_HALVINGS = 14  # damping of the Newton step down to 2^-13


def _stalled(grid, iteration, merit, tolerance, closed, film, start_film, wet) -> ConvergenceError:
    # the line search found no step: why, from what it saw
    where = f"EHL Reynolds solve on the {grid.nx} x {grid.ny} grid, Newton iteration {iteration}"
    if closed == LINE_SEARCH_HALVINGS:
        reason = "the film closes"
        detail = (f"every damped Newton step (1 to 2^-{LINE_SEARCH_HALVINGS - 1}) makes the film non-positive; "
                  f"minimum film {film:.3e} m, down from {start_film:.3e} m at the start, {wet} cells carry "
                  "pressure: the grid does not resolve a film at this load and speed (refine the grid, or raise "
                  "the entrainment speed or lower the load)")
    else:
        reason = "no descent step"
        detail = (f"no damped Newton step (1 to 2^-{LINE_SEARCH_HALVINGS - 1}) lowers the Reynolds residual "
                  f"({closed} of the {LINE_SEARCH_HALVINGS} trials close the film); minimum film {film:.3e} m")
    return ConvergenceError(f"{where}: {reason}: {detail}", residual=merit, iterations=iteration, tolerance=tolerance,
                            reason=reason)


def _upwind(field: np.ndarray, dx: float) -> np.ndarray:
    # second-order upwind d/dx along +x (first order in row 1, none in row 0: the inlet ghost copies row 0)
    up1 = np.vstack([field[:1], field[:-1]])
    up2 = np.vstack([field[:1], field[:1], field[:-2]])
    derivative = (1.5 * field - 2.0 * up1 + 0.5 * up2) / dx
    derivative[1] = (field[1] - field[0]) / dx
    derivative[0] = 0.0
    return derivative


def _reynolds_terms(p, film, eta, rho, dx, dy, u_s):
    # sun2021 eq 14 with eps = rho h^3 / (12 eta) and u_s = (u1 + u2)/2; p = 0 outside the grid (eq 18):
    # the Poiseuille flow, the Couette term u_s d(rho h)/dx and the face values of eps (residual = flow - couette)
    eps = rho * film**3 / (12.0 * eta)
    padded = np.pad(eps, 1, mode="edge")
    centre_ = padded[1:-1, 1:-1]
    xp, xm = 0.5 * (centre_ + padded[2:, 1:-1]), 0.5 * (centre_ + padded[:-2, 1:-1])
    yp, ym = 0.5 * (centre_ + padded[1:-1, 2:]), 0.5 * (centre_ + padded[1:-1, :-2])
    pp = np.pad(p, 1)
    flow = ((xp * (pp[2:, 1:-1] - p) - xm * (p - pp[:-2, 1:-1])) / dx**2
            + (yp * (pp[1:-1, 2:] - p) - ym * (p - pp[1:-1, :-2])) / dy**2)
    return flow, u_s * _upwind(rho * film, dx), (xp, xm, yp, ym)


def solve_reynolds(gap: np.ndarray, grid: halfspace.SurfaceGrid, contact_modulus: float, load: float,
                   entrainment_speed: float, viscosity_0: float, density_0: float = 1.0, *,
                   initial_film: float = 1e-7, initial_pressure: np.ndarray | None = None,
                   initial_h0: float | None = None,
                   tolerance: float = 1e-7, load_tolerance: float = 1e-5, max_iterations: int = 400,
                   centre: tuple[float, float] = (0.0, 0.0), coarsest: int = 48) -> EHLSolution:
    """Steady isothermal EHL point contact (sun2021 eqs 14-19) by a damped Newton-Krylov method.

    Reynolds (eq 14) with ``u_s = (u1 + u2)/2`` along +x::

        d/dx(rho h^3/(12 eta) dp/dx) + d/dy(rho h^3/(12 eta) dp/dy) = u_s d(rho h)/dx

    on the cell centres of ``grid`` (five-point Poiseuille stencil with face
    values of ``rho h^3 / eta`` averaged, second-order upwind Couette term,
    first order next to the inlet), ``p = 0`` outside the grid (eq 18), cavitation
    by ``p >= 0`` (cells clipped at 0 carry no Reynolds equation); film (eq 15)
    ``h = h0 + gap + V(p)`` with ``V`` the DC-FFT deflection of
    :func:`~ballbench.lowmodel.contact.halfspace.deformation`; Roelands
    viscosity (eq 16), Dowson-Higginson density (eq 17); load balance (eq 19)
    ``sum p dA = load`` with ``h0`` as the extra unknown.

    Solver: damped Newton on ``(p, h0)``.  Each linear step is solved by
    GMRES with the exact Jacobian-vector product (a directional difference of
    the residual: dense deflection, ``eps(p, h)``, density), preconditioned by the
    sparse "semi-system" matrix (Hu & Zhu, J. Tribol. 122 (2000) 1, sun2021's
    ref [24]: the Poiseuille stencil, the density derivative and the deflection
    coefficients of the nearest cells in the Couette term) bordered by the load
    row through its Schur complement; the step is halved until the scaled
    residual falls.  Cavitation: a cell at ``p = 0`` whose residual would drive it
    negative keeps ``p = 0`` (identity row); pressures are clipped at 0.  Nested
    iteration: on a grid with even cell counts >= ``2 coarsest`` the solution on
    the grid of twice the cell size (gap averaged over 2 x 2 cells),
    interpolated, is the start; the coarsest grid starts from the dry
    (non-Hertzian) pressure of :func:`~ballbench.lowmodel.contact.halfspace.solve`
    (sun2021 Sec 2.3) lifted to the film ``initial_film`` [m] (Hamrock-Dowson's
    ``h_c`` is a good value).  Converged when a full (undamped) Newton step
    changes the pressure by less than ``tolerance`` (relative) and the load error
    is below ``load_tolerance``; the result is then checked from its pressure
    alone (:func:`verify`: Reynolds with cavitation, positive film, load
    balance).  ``ConvergenceError`` (with ``.reason``) when no damped step lowers
    the residual (``"the film closes"``: every trial step makes the film
    non-positive, the grid does not resolve the film at this load and speed;
    ``"no descent step"`` otherwise: both stop at once instead of running to
    ``max_iterations``), at ``max_iterations`` (``"iteration limit"``), on a
    floating-point failure, or when the check fails.  ``initial_pressure`` [Pa]
    and ``initial_h0`` [m] give another start.

    ``gap`` [m] (nx, ny) is the undeformed separation
    (geometry and roughness, ``x^2/(2R_x) + y^2/(2R_y) + ROU``); ``contact_modulus`` E* [Pa];
    ``load`` [N]; ``entrainment_speed`` u_s [m/s] > 0; ``viscosity_0`` [Pa s];
    ``density_0`` [kg/m^3] (cancels in eq 14).
    """
    # one BLAS thread: GMRES's many short vector operations stall (several times slower in wall time)
    # when a threaded BLAS competes for cores the machine shares
    tolerance = checks.positive("tolerance", tolerance)
    load_tolerance = checks.positive("load_tolerance", load_tolerance)
    max_iterations = checks.count("max_iterations", max_iterations, 1)
    coarsest = checks.count("coarsest", coarsest, 4)  # coarse grids stay >= 4 cells across (halfspace)
    # a floating-point overflow or invalid operation (an operating point the grid cannot resolve: a contact far
    # below one cell, a film many decades thinner than initial_film) is a failed solve, not a NaN or a warning
    with threadpool_limits(limits=1, user_api="blas"), np.errstate(over="raise", invalid="raise", divide="raise"):
        try:
            return _reynolds_newton(gap, grid, contact_modulus, load, entrainment_speed, viscosity_0, density_0,
                                    initial_film=initial_film, initial_pressure=initial_pressure,
                                    initial_h0=initial_h0, tolerance=tolerance, load_tolerance=load_tolerance,
                                    max_iterations=max_iterations, centre=centre, coarsest=coarsest)
        except FloatingPointError as error:
            raise ConvergenceError(f"EHL Reynolds solve: floating-point failure ({error}); load, entrainment_speed "
                                   "or initial_film outside what the grid resolves", residual=math.inf,
                                   iterations=0, tolerance=tolerance, reason="floating-point failure") from None


def _reynolds_newton(gap, grid, contact_modulus, load, entrainment_speed, viscosity_0, density_0, *,  # noqa: C901 - one algorithm: nested-grid Newton-Krylov with its cavitation set and line search
                     initial_film, initial_pressure, initial_h0, tolerance, load_tolerance, max_iterations,
                     centre, coarsest) -> EHLSolution:
    # the body of solve_reynolds (its docstring), with the nested coarse-grid solve
    gap = np.asarray(gap, dtype=float)
    if gap.shape != (grid.nx, grid.ny) or not np.all(np.isfinite(gap)):
        raise ValueError(f"gap must be a finite array of shape {(grid.nx, grid.ny)}")
    e_star = checks.positive("contact_modulus", contact_modulus, "Pa")
    load = checks.positive("load", load, "N")
    u_s = checks.positive("entrainment_speed", entrainment_speed, "m/s")
    eta0 = checks.positive("viscosity_0", viscosity_0, "Pa s")
    rho0 = checks.positive("density_0", density_0, "kg/m^3")
    nx, ny, dx, dy = grid.nx, grid.ny, grid.dx, grid.dy
    area = grid.cell_area
    kernel = halfspace.influence_coefficients(5, 5, dx, dy) / e_star  # offsets -4..4 around (4, 4)
    if initial_pressure is None and nx % 2 == 0 and ny % 2 == 0 and min(nx, ny) >= 2 * coarsest:
        # nested iteration: the solution on the grid of twice the cell size, interpolated, is the start
        coarse_grid = halfspace.SurfaceGrid(nx // 2, ny // 2, 2 * dx, 2 * dy, grid.x_centre, grid.y_centre)
        coarse = _reynolds_newton(gap.reshape(nx // 2, 2, ny // 2, 2).mean(axis=(1, 3)), coarse_grid, e_star, load,
                                  u_s, eta0, rho0, initial_film=initial_film, initial_pressure=None,
                                  initial_h0=None, tolerance=tolerance, load_tolerance=load_tolerance,
                                  max_iterations=max_iterations, centre=centre, coarsest=coarsest)
        from scipy.interpolate import RegularGridInterpolator

        interpolate = RegularGridInterpolator((coarse_grid.x, coarse_grid.y), coarse.pressure, bounds_error=False,
                                              fill_value=None)
        X, Y = grid.coordinates()
        initial_pressure = np.maximum(interpolate(np.stack([X, Y], -1)), 0.0)
        initial_pressure *= load / (float(initial_pressure.sum()) * grid.cell_area)
        # the film of the coarse solution at the same pressure: h0 so that the central films agree
        initial_h0 = coarse.h0
    if initial_pressure is None:
        dry = halfspace.solve(gap, grid, e_star, force=load)
        p = dry.pressure.copy()
        # dry contact: gap + V = approach inside; h0 = initial_film - approach lifts it to initial_film
        h0 = checks.positive("initial_film", initial_film, "m") - dry.approach
    else:
        p = np.array(initial_pressure, dtype=float)
        if p.shape != gap.shape or not np.all(np.isfinite(p)) or np.any(p < 0.0) or not p.sum() > 0.0:
            raise ValueError("initial_pressure must be a finite, non-negative, non-zero array of the grid's shape")
        h0 = float(initial_h0) if initial_h0 is not None else 0.0
    n = nx * ny
    index = np.arange(n).reshape(nx, ny)
    offsets = ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (-1, 1), (-1, -1), (-2, 0))

    def influence(di: int, dj: int) -> float:
        # K at offset (di, dj) cells [m/Pa]
        return float(kernel[di + 4, dj + 4])

    def upwind(field):
        return _upwind(field, dx)

    def state(p, h0):
        film = h0 + gap + halfspace.deformation(p, grid, e_star)  # sun2021 eq 15
        eta = roelands_viscosity(p, eta0)  # eq 16
        rho = dowson_higginson_density(p, rho0) / rho0  # eq 17 (rho0 cancels in eq 14)
        return film, eta, rho

    def residual(p, film, eta, rho):
        flow, couette, faces_ = _reynolds_terms(p, film, eta, rho, dx, dy, u_s)
        return flow - couette, faces_

    film, eta, rho = state(p, h0)
    start_film = float(film.min())
    change = math.inf
    load_error = math.inf
    for iteration in range(1, max_iterations + 1):  # noqa: B007 - the count is reported after the loop
        res, (xp, xm, yp, ym) = residual(p, film, eta, rho)
        rows, cols, values = [], [], []
        all_i, all_j = np.nonzero(np.ones((nx, ny), dtype=bool))

        def add(di, dj, coefficient):
            k, m = all_i + di, all_j + dj
            inside = (k >= 0) & (k < nx) & (m >= 0) & (m < ny)
            rows.append(index[all_i[inside], all_j[inside]])
            cols.append(index[k[inside], m[inside]])
            values.append(np.broadcast_to(coefficient, (nx, ny))[all_i[inside], all_j[inside]])

        # Poiseuille stencil, eps frozen
        add(0, 0, -(xp + xm) / dx**2 - (yp + ym) / dy**2)
        add(1, 0, xp / dx**2)
        add(-1, 0, xm / dx**2)
        add(0, 1, yp / dy**2)
        add(0, -1, ym / dy**2)
        # Couette: -u_s d/dx(rho h), h through the stencil's deflection coefficients (semi-system)
        rho_1 = np.vstack([rho[:1], rho[:-1]])
        rho_2 = np.vstack([rho[:1], rho[:1], rho[:-2]])
        for di, dj in offsets:
            coefficient = -u_s / dx * (1.5 * rho * influence(-di, -dj) - 2.0 * rho_1 * influence(-1 - di, -dj)
                                       + 0.5 * rho_2 * influence(-2 - di, -dj))
            add(di, dj, coefficient)
        # Couette: the density's own pressure dependence
        drho_h = 0.6e-9 / (1.0 + 1.7e-9 * p) ** 2 * film
        add(0, 0, -u_s / dx * 1.5 * drho_h)
        add(-1, 0, u_s / dx * 2.0 * np.vstack([drho_h[:1], drho_h[:-1]]))
        add(-2, 0, -u_s / dx * 0.5 * np.vstack([drho_h[:1], drho_h[:1], drho_h[:-2]]))
        jac = sp.csr_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))
        diagonal = np.abs(jac.diagonal()).reshape(nx, ny)
        # cavitation (eq 18, p >= 0): a cell at p = 0 whose residual pushes it negative stays at 0 (identity
        # row); one whose residual pushes it positive (the diagonal is negative) joins the solve
        frozen_grid = (p <= 0.0) & (res <= 0.0)
        frozen = frozen_grid.ravel()
        jac = sp.diags((~frozen).astype(float)) @ jac + sp.diags(frozen.astype(float))
        dh0 = np.where(frozen, 0.0, -u_s * upwind(rho).ravel())
        load_row = np.where(frozen, 0.0, area)
        rhs = np.append(np.where(frozen, 0.0, -res.ravel()), load - float(p.sum()) * area)  # eq 19
        # Jacobian-free Newton-Krylov: the exact Jacobian (dense deflection, eps(p, h)) by a directional
        # difference of the residual, preconditioned by the sparse semi-system matrix above
        # the bordered semi-system matrix [[J, b], [c, 0]] by its Schur complement (no dense fill in the LU)
        factor = splu(jac.tocsc(), permc_spec="MMD_AT_PLUS_A")  # less fill than COLAMD on the grid stencil
        z = factor.solve(dh0)
        schur = float(load_row @ z)

        def precondition(v):
            x = factor.solve(v[:n])
            y = (float(load_row @ x) - v[n]) / schur
            return np.append(x - z * y, y)

        base = res.ravel()
        free = ~frozen
        p_norm = max(float(np.abs(p).max()), 1.0)

        def product(v):
            v = np.asarray(v, dtype=float).ravel()
            vp = np.where(frozen, 0.0, v[:n]).reshape(nx, ny)
            size = float(np.abs(vp).max()) / p_norm + abs(v[n]) / max(abs(h0), 1e-12)
            tau = 1e-7 / max(size, 1e-30)
            perturbed = residual(p + tau * vp, *state(p + tau * vp, h0 + tau * v[n]))[0].ravel()
            out = np.where(free, (perturbed - base) / tau, v[:n])
            return np.append(out, area * float(vp.sum()))

        # inexact Newton: a loose linear solve far from the solution, a tight one near it (Eisenstat-Walker-like)
        forcing = min(1e-2, max(1e-6, change))
        operator = LinearOperator((n + 1, n + 1), matvec=product)
        step, info = gmres(operator, rhs, M=LinearOperator((n + 1, n + 1), matvec=precondition),
                           rtol=forcing, restart=40, maxiter=2)
        dp, dh = step[:n].reshape(nx, ny), float(step[n])

        def merit(res_, p_):
            # residual in pressure units (row / |diagonal| [Pa]) on the cells that carry the equation
            carry = ~((p_ <= 0.0) & (res_ <= 0.0))
            return float(np.linalg.norm((res_ / diagonal)[carry]))

        current = merit(res, p)
        omega = 1.0
        closed = 0  # trial steps whose film is not positive
        for _ in range(LINE_SEARCH_HALVINGS):
            trial_p = np.maximum(p + omega * dp, 0.0)
            trial_h0 = h0 + omega * dh
            trial_state = state(trial_p, trial_h0)
            if np.min(trial_state[0]) > 0.0:
                trial_res, _ = residual(trial_p, *trial_state)
                if merit(trial_res, trial_p) <= current:
                    break
            else:
                closed += 1
            omega *= 0.5
        else:
            # no damped step lowers the residual: the iteration cannot go on (it used to take the last step anyway
            # and crawl for max_iterations with a negative film); the evidence decides the reason
            raise _stalled(grid, iteration, current, tolerance, closed, float(film.min()), start_film,
                           int(np.count_nonzero(p > 0.0)))
        change = float(np.abs(trial_p - p).sum() / max(float(trial_p.sum()), 1e-300))
        p, h0 = trial_p, trial_h0
        film, eta, rho = trial_state
        load_error = abs(float(p.sum()) * area - load) / load
        # converged on a full Newton step only: a damped step is small because it is damped (a film closing
        # by halves used to pass as converged with a Reynolds residual 1e9 times that of the solution)
        if omega == 1.0 and change < tolerance and load_error < load_tolerance:
            break
    else:
        raise ConvergenceError(f"EHL Reynolds solve on the {nx} x {ny} grid did not converge in max_iterations",
                               residual=change, iterations=max_iterations, tolerance=tolerance,
                               reason="iteration limit: the pressure still changes")
    X, Y = grid.coordinates()
    i, j = np.unravel_index(np.argmin((X - centre[0]) ** 2 + (Y - centre[1]) ** 2), X.shape)
    solution = EHLSolution(grid=grid, pressure=p, film=film, h0=h0, central_film=float(film[i, j]),
                           minimum_film=float(film.min()), central_pressure=float(p[i, j]),
                           max_pressure=float(p.max()), force=float(p.sum()) * area, load_error=load_error,
                           iterations=iteration, residual=change)
    verify(solution, gap, e_star, load, u_s, eta0, rho0, tolerance=tolerance, load_tolerance=load_tolerance)
    return solution


REYNOLDS_CHECK = 1e-6  # floor of the residual check (of the Couette term's norm): converged solves measure <= 1.2e-11


def verify(solution: EHLSolution, gap: np.ndarray, contact_modulus: float, load: float, entrainment_speed: float,
           viscosity_0: float, density_0: float = 1.0, *, tolerance: float = 1e-7,
           load_tolerance: float = 1e-5) -> None:
    """Check an EHL solution against the conditions that define it, from its pressure and ``h0`` alone.

    The film ``h = h0 + gap + V(p)`` (eq 15, a fresh deflection), Roelands viscosity and Dowson-Higginson density
    of ``p``, then:

    * ``p >= 0`` and ``h > 0`` everywhere (cavitation keeps the pressure non-negative; a closed film is no EHL);
    * Reynolds (eq 14) with cavitation: the residual ``R = flow - u_s d(rho h)/dx`` is zero where ``p > 0`` and
      ``R <= 0`` where ``p = 0`` (the cell would go negative); ``|| where(p > 0, R, max(R, 0)) ||_2`` at most
      ``max(10 tolerance, 1e-6)`` times ``|| u_s d(rho h)/dx ||_2`` (``tolerance``: the solve's, on the relative
      pressure change);
    * load balance (eq 19): ``|dA sum p - load| / load <= load_tolerance``.

    Arguments as for :func:`solve_reynolds`.  Raises ConvergenceError naming the check, its value and tolerance.
    """
    grid, p = solution.grid, solution.pressure
    e_star = checks.positive("contact_modulus", contact_modulus, "Pa")
    limit = max(10.0 * checks.positive("tolerance", tolerance), REYNOLDS_CHECK)
    film = solution.h0 + np.asarray(gap, dtype=float) + halfspace.deformation(p, grid, e_star)
    failed = None
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(film))):
        failed = ("finite pressure and film", math.inf, 0.0)
    elif float(p.min()) < 0.0:
        failed = ("p >= 0", -float(p.min()), 0.0)
    elif not float(film.min()) > 0.0:
        failed = ("positive film h > 0 [m]", -float(film.min()), 0.0)
    else:
        eta = roelands_viscosity(p, viscosity_0)
        rho = dowson_higginson_density(p, density_0) / checks.positive("density_0", density_0, "kg/m^3")
        flow, couette, _ = _reynolds_terms(p, film, eta, rho, grid.dx, grid.dy,
                                           checks.positive("entrainment_speed", entrainment_speed, "m/s"))
        balance = flow - couette
        complementarity = np.where(p > 0.0, balance, np.maximum(balance, 0.0))
        scale = float(np.linalg.norm(couette))
        relative = float(np.linalg.norm(complementarity)) / scale if scale > 0.0 else math.inf
        load_error = abs(float(p.sum()) * grid.cell_area - load) / load
        if not relative <= limit:
            failed = ("Reynolds with cavitation ||R|| / ||u_s d(rho h)/dx||", relative, limit)
        elif not load_error <= load_tolerance:
            failed = ("load balance |dA sum p - load| / load", load_error, load_tolerance)
    if failed is not None:
        check, value, limit = failed
        raise ConvergenceError(f"EHL Reynolds solve on the {grid.nx} x {grid.ny} grid: the solution fails its check "
                               f"of {check}: {value:.3e} > {limit:.3e}", residual=value,
                               iterations=solution.iterations, tolerance=limit, reason=f"fails the check of {check}")


def film_traction(solution: EHLSolution, sliding_speed: float, viscosity_0: float, eyring_stress: float) -> float:
    """Film friction force ``Q_f = int_{A_h} tau_f dA`` [N] of an EHL solution (sun2021 eqs 22-23).

    ``tau_f = tau0 asinh(eta(p) du / (tau0 h))`` (Eyring, eq 23) with the Roelands
    viscosity of the solution's pressure, summed over the cells that carry film
    pressure (``A_h``: ``p > 0``); ``sliding_speed`` du = u1 - u2 [m/s] (signed, along
    the entrainment), ``viscosity_0`` eta0 [Pa s], ``eyring_stress`` tau0 [Pa].
    """
    du = float(checks.finite("sliding_speed", sliding_speed, "m/s"))
    wet = solution.pressure > 0.0
    eta = roelands_viscosity(solution.pressure[wet], viscosity_0)
    tau = eyring_shear_stress(eta, du, solution.film[wet], eyring_stress)
    return float(np.sum(tau)) * solution.grid.cell_area


def friction_coefficient(asperity_load: float, film_friction: float, load: float, dry_friction: float = 0.1) -> float:
    """Mixed friction coefficient ``mu = (mu_a Q_a + Q_f) / Q`` (sun2021 eq 21; mu_a = 0.1 in sun2021 Sec 3.2).

    ``asperity_load`` Q_a [N] >= 0, ``film_friction`` Q_f [N] (eq 22), ``load`` Q [N] > 0.
    """
    q_a = checks.non_negative("asperity_load", asperity_load, "N")
    q_f = checks.finite("film_friction", film_friction, "N")
    q = checks.positive("load", load, "N")
    if q_a > q:
        raise ValueError(f"asperity_load must not exceed load {q!r} N, got {q_a!r}")
    mu_a = checks.non_negative("dry_friction", dry_friction)
    mu = (mu_a * q_a + q_f) / q
    if not math.isfinite(mu):  # a subnormal load
        raise ValueError(f"load {q!r} N is too small for film_friction {q_f!r} N (mu overflows)")
    return mu
