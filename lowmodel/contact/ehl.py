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

Not yet implemented (issue 14 items 5-6): the Reynolds solver (eqs 14, 15,
18, 19) with the DC-FFT deformation of :mod:`.halfspace`, the asperity/film load
split (eqs 21-22) and the friction torque (eq 20).
"""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel import checks

__all__ = [
    "ROELANDS_PRESSURE",
    "ROELANDS_Z",
    "roelands_viscosity",
    "roelands_pressure_viscosity_coefficient",
    "dowson_higginson_density",
    "eyring_shear_stress",
    "hamrock_dowson_film",
    "weierstrass_mandelbrot_surface",
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
    return eta0 * np.exp((math.log(eta0) - ROELANDS_LN_ETA_INF) * ((1.0 + p / ROELANDS_PRESSURE) ** ROELANDS_Z - 1.0))


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
    return tau0 * np.arcsinh(eta * du / (tau0 * h))


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
    U = eta0 * u / (e_prime * rx)
    G = alpha * e_prime
    W = load / (e_prime * rx * rx)
    k = 1.0339 * (ry / rx) ** 0.636
    h_c = rx * 2.69 * U**0.67 * G**0.53 * W**-0.067 * (1.0 - 0.61 * math.exp(-0.73 * k))
    h_min = rx * 3.63 * U**0.68 * G**0.49 * W**-0.073 * (1.0 - math.exp(-0.68 * k))
    return {"h_c": h_c, "h_min": h_min, "U": U, "G": G, "W": W, "k": k}


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
    D = checks.bounded("fractal_dimension", fractal_dimension, 2.0, 3.0)
    G = checks.positive("roughness_scale", roughness_scale, "m")
    L = checks.positive("sample_length", sample_length, "m")
    Ls = checks.positive("cutoff_length", cutoff_length, "m")
    if not Ls < L:
        raise ValueError(f"cutoff_length must be < sample_length {L!r} m, got {Ls!r}")
    gamma = checks.positive("gamma", gamma)
    if not gamma > 1.0:
        raise ValueError(f"gamma must be > 1, got {gamma!r}")
    M = checks.count("ridges", ridges, 1)
    x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
    n_max = int(math.floor(math.log(L / Ls) / math.log(gamma)))
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
