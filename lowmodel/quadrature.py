"""Quadrature rules on (0, 1), cached and read-only (shared by every caller).

* :func:`tanh_sinh`: the tanh-sinh (double-exponential) rule of Takahasi and Mori (1974),
  exponentially convergent for integrands analytic inside (0, 1), also with algebraic
  endpoint singularities: the angular integrals of the ellipse friction (lin2019 eqs A4-A6,
  :mod:`lowmodel.contact.ellipse_friction`) and of its offset form (eqs 44-47, A9-A11,
  :mod:`lowmodel.contact.ellipse_friction_offset`), whose near-singularities sit at panel ends.
* :func:`gauss_legendre`: Gauss-Legendre on (0, 1) (numpy's nodes and weights, mapped).

The arrays are ``lru_cache``'d and read-only (:func:`lowmodel.checks.read_only`): an in-place
edit would change every later integral.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["tanh_sinh", "gauss_legendre", "TANH_SINH_LEVELS"]

TANH_SINH_LEVELS = (0, 12)  # step 2^-level: 1 to 2^12 nodes per unit of t (level 12 is ~3e4 nodes)


def tanh_sinh(level: int) -> tuple[np.ndarray, np.ndarray]:
    """Tanh-sinh nodes and weights on (0, 1): step ``h = 2^-level`` in ``t`` over [-4, 4].

    ``x = (1 + tanh(pi/2 sinh t))/2``, ``w = h (pi/4) cosh t / cosh^2(pi/2 sinh t)``; nodes that round
    to 0 or 1 are left out.  ``level``: an integer in :data:`TANH_SINH_LEVELS` (ValueError otherwise).
    """
    level = checks.count("level", level, *TANH_SINH_LEVELS)
    return _tanh_sinh(level)


@lru_cache(maxsize=8)
def _tanh_sinh(level: int) -> tuple[np.ndarray, np.ndarray]:
    """:func:`tanh_sinh` without the input check (the friction integrals' inner loop)."""
    step = 2.0**-level
    t = np.arange(-4.0, 4.0 + 0.5 * step, step)
    arg = 0.5 * math.pi * np.sinh(t)
    x = 0.5 * (1.0 + np.tanh(arg))
    w = step * 0.25 * math.pi * np.cosh(t) / np.cosh(arg) ** 2
    keep = (x > 0.0) & (x < 1.0) & (w > 0.0)
    return checks.read_only(x[keep]), checks.read_only(w[keep])  # cached: shared by every caller


@lru_cache(maxsize=8)
def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """``n``-point Gauss-Legendre nodes and weights on (0, 1) (exact for polynomials of degree 2 n - 1)."""
    x, w = np.polynomial.legendre.leggauss(n)
    return checks.read_only(0.5 * (x + 1.0)), checks.read_only(0.5 * w)  # on [0, 1]; cached: shared
