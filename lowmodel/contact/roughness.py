"""Fractal raceway roughness of sun2021 (Sec 2.3, eq 15 ``ROU``): Weierstrass-Mandelbrot closed forms.

sun2021 puts the raceway roughness ``ROU(x, y)`` into the film of eq 15 and
takes it from the fractal theory of its ref [28] (Ausloos & Berman 1985) with
``D = 2.47`` and ``G = 0.41``; the ball is smooth.  The height map itself is
:func:`ballbench.lowmodel.contact.ehl.weierstrass_mandelbrot_surface` (the 3D
form of Yan & Komvopoulos, J. Appl. Phys. 84 (1998) 3617, eq 4); this module adds
what a check needs to judge it and what the mixed-lubrication model needs to
use it:

* :func:`wm_rms`: the ensemble rms height about the mean (random phases), in closed form;
* :func:`wm_line_spectrum`: the discrete WM spectrum, frequencies ``gamma^n / L``
  and line amplitudes ``C gamma^((D-3) n)`` of every ridge;
* :func:`raceway_roughness`: the seeded raceway heights on an EHL grid, mean
  zero, sampled to the grid's Nyquist length.

sun2021 leaves unstated: the unit of ``G``, the sample length ``L``, the cutoff
``L_s``, ``gamma`` and the number of ridges ``M``.  The choices (docs/mixed_lubrication.md):
``L`` and ``L_s`` given by the caller (defaults: the longer side of the
grid, twice the larger cell size), ``gamma = 1.5`` and ``M = 10`` (Yan & Komvopoulos' values), ``G`` in
metres as the caller gives it (the sun2021 scenes read the printed 0.41 in pm
and in nm and report both).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import ehl, halfspace

__all__ = ["wm_amplitude", "wm_rms", "wm_line_spectrum", "RacewayRoughness", "raceway_roughness"]


def wm_amplitude(fractal_dimension: float, roughness_scale: float, sample_length: float, *, gamma: float = 1.5,
                 ridges: int = 10) -> float:
    """Prefactor ``C = L (G/L)^(D-2) (ln gamma / M)^(1/2)`` [m] of the WM surface (Yan & Komvopoulos eq 4).

    The ridge ``m``, level ``n`` term has amplitude ``C gamma^((D-3) n)``.
    """
    half = checks.positive("sample_length / 2", 0.5 * checks.positive("sample_length", sample_length, "m"), "m")
    D, G, L, _, gamma, M = ehl.wm_parameters(fractal_dimension, roughness_scale, sample_length, half, gamma, ridges)
    return L * (G / L) ** (D - 2.0) * math.sqrt(math.log(gamma) / M)


def wm_rms(fractal_dimension: float, roughness_scale: float, sample_length: float, cutoff_length: float, *,
           gamma: float = 1.5) -> float:
    """Ensemble rms height about the mean [m] of the WM surface (random phases; closed form).

    Each term ``cos(k . r + phi)`` has variance 1/2 over the random phase, the
    terms are uncorrelated, so ``sigma^2 = C^2 M / 2 sum_n gamma^(2 (D-3) n)`` and
    the ridge count cancels::

        sigma = L (G/L)^(D-2) [ln(gamma) / 2 sum_{n=0..n_max} gamma^(2 (D-3) n)]^(1/2)

    ``fractal_dimension`` D in (2, 3), ``roughness_scale`` G [m],
    ``sample_length`` L [m], ``cutoff_length`` L_s [m] < L, ``gamma`` > 1.
    """
    D, G, L, Ls, gamma, _ = ehl.wm_parameters(fractal_dimension, roughness_scale, sample_length, cutoff_length,
                                              gamma, 1)
    n = np.arange(ehl.wm_top_level(L, Ls, gamma) + 1)
    return L * (G / L) ** (D - 2.0) * math.sqrt(0.5 * math.log(gamma) * float(np.sum(gamma ** (2.0 * (D - 3.0) * n))))


def wm_line_spectrum(fractal_dimension: float, roughness_scale: float, sample_length: float, cutoff_length: float,
                     *, gamma: float = 1.5, ridges: int = 10) -> tuple[np.ndarray, np.ndarray]:
    """Discrete WM spectrum: ``(frequency [1/m], amplitude [m])`` of the levels ``n = 0..n_max``.

    Level ``n`` of ridge ``m`` is the plane wave ``C gamma^((D-3) n) cos(2 pi
    gamma^n / L (r . e_m) + phi)`` along ``e_m = (cos(pi m/M), sin(pi m/M))``, so
    along a ridge direction the profile has lines at ``gamma^n / L`` of amplitude
    ``C gamma^((D-3) n)``: ``log(amplitude)`` falls with slope ``(D - 3)`` against
    ``log(frequency)`` (power spectrum ``~ f^(2D - 6)``).
    """
    D, G, L, Ls, gamma, M = ehl.wm_parameters(fractal_dimension, roughness_scale, sample_length, cutoff_length,
                                              gamma, ridges)
    n = np.arange(ehl.wm_top_level(L, Ls, gamma) + 1)
    amplitude = wm_amplitude(D, G, L, gamma=gamma, ridges=M) * gamma ** ((D - 3.0) * n)
    return gamma**n / L, amplitude


@dataclass(frozen=True)
class RacewayRoughness:
    """Raceway heights on a grid (sun2021 eq 15: ``ROU = -heights``, asperity tops narrow the film).

    heights : (nx, ny) [m], mean zero over the grid, positive toward the ball
    rms : the ensemble rms of :func:`wm_rms` [m] (the sample's own rms is ``heights.std()``)
    sample_length, cutoff_length : L, L_s [m]
    fractal_dimension, roughness_scale, gamma, ridges, seed : the WM inputs
    """

    heights: np.ndarray
    rms: float
    sample_length: float
    cutoff_length: float
    fractal_dimension: float
    roughness_scale: float
    gamma: float
    ridges: int
    seed: int


def raceway_roughness(grid: halfspace.SurfaceGrid, fractal_dimension: float, roughness_scale: float, *,
                      sample_length: float | None = None, cutoff_length: float | None = None,
                      gamma: float = 1.5, ridges: int = 10, seed: int = 0) -> RacewayRoughness:
    """Seeded WM raceway heights on ``grid`` (sun2021 Sec 2.3: D = 2.47, G = 0.41, raceway rough, ball smooth).

    ``sample_length`` L [m] (default the longer side of the grid), ``cutoff_length``
    L_s [m] (default twice the larger cell size, the shortest wavelength the grid
    resolves in both directions; a given L_s must be at least that); heights
    shifted to mean zero over the grid (the nominal surface is the mean plane).
    ``roughness_scale`` G [m].  A roughness that should not change with the grid
    passes both lengths.
    """
    L = max(grid.nx * grid.dx, grid.ny * grid.dy) if sample_length is None else float(sample_length)
    nyquist = 2.0 * max(grid.dx, grid.dy)
    Ls = nyquist if cutoff_length is None else float(cutoff_length)
    if not Ls >= nyquist * (1.0 - 1e-12):
        raise ValueError(f"cutoff_length must be >= twice the larger cell size {nyquist!r} m (the grid must resolve "
                         f"the shortest wavelength), got {cutoff_length!r}")
    X, Y = grid.coordinates()
    z = ehl.weierstrass_mandelbrot_surface(X, Y, fractal_dimension, roughness_scale, L, cutoff_length=Ls,
                                           gamma=gamma, ridges=ridges, seed=seed)
    z = z - float(z.mean())
    return RacewayRoughness(heights=z, rms=wm_rms(fractal_dimension, roughness_scale, L, Ls, gamma=gamma),
                            sample_length=L, cutoff_length=Ls, fractal_dimension=float(fractal_dimension),
                            roughness_scale=float(roughness_scale), gamma=float(gamma), ridges=int(ridges),
                            seed=int(seed))
