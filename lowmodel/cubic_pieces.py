"""Piecewise cubics of scipy (``CubicSpline``, ``PchipInterpolator``) evaluated without scipy's call overhead.

A scipy ``PPoly`` of order 4 with one value per point holds breakpoints ``x_0 < .. < x_m`` and per piece the
coefficients ``c_0 .. c_3`` of ``s^3, s^2, s, 1`` in ``s = u - x_i``.  Its evaluation costs ~15 us per call in scipy's
Python wrapper whatever the size, which dominates the loops that evaluate a small table thousands of times (the
root search of :func:`lowmodel.screw.load_distribution.distribute`, the Hertz tables of
:func:`lowmodel.screw.contacts.ball_contacts` at every step of the whole screw).  :class:`CubicPieces` evaluates the
same piecewise cubic with the arithmetic of scipy's evaluation, so the numbers are the same to the last bit (tests
compare the two at 0 difference):

* the piece ``i`` with ``x_i <= u < x_(i+1)``; the last piece closed at ``x_m``; the end pieces extended beyond the
  table (scipy's ``extrapolate=True``, the default of both interpolants);
* ``c_3 + c_2 s + c_1 s^2 + c_0 s^3`` summed in this order, with ``s^2 = s s`` and ``s^3 = (s s) s``.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["CubicPieces", "cubic_pieces"]


@dataclass(frozen=True)
class CubicPieces:
    """Breakpoints ``x_0 .. x_m`` (m + 1,), the inner ones ``x_1 .. x_(m-1)`` and the coefficients ``c_0 .. c_3`` of
    ``s^3, s^2, s, 1`` per piece, (m,) each; read-only (build with :func:`cubic_pieces`)."""

    breaks: np.ndarray
    inner: np.ndarray
    c0: np.ndarray
    c1: np.ndarray
    c2: np.ndarray
    c3: np.ndarray

    def __post_init__(self):
        checks.freeze_arrays(self, "breaks", "inner", "c0", "c1", "c2", "c3")

    def __reduce__(self):
        return checks.rebuilt_through_init(self)

    def __call__(self, u) -> np.ndarray:
        """The cubic at ``u`` (any shape; a 0-d array for a number), as scipy's ``PPoly.__call__``."""
        u = np.asarray(u, dtype=float)
        index = self.inner.searchsorted(u, side="right")   # the piece: 0 below x_1, m - 1 from x_(m-1) on
        s = u - self.breaks[index]
        square = s * s
        value = self.c3[index] + self.c2[index] * s + self.c1[index] * square + self.c0[index] * (square * s)
        return value if u.ndim else np.asarray(value)   # a 0-d array like scipy's, not a numpy scalar


def cubic_pieces(interpolant) -> CubicPieces:
    """The :class:`CubicPieces` of a scipy cubic ``PPoly`` (``CubicSpline``, ``PchipInterpolator``) of one value per
    point that extrapolates (``extrapolate=True``)."""
    c = np.asarray(interpolant.c)
    if c.ndim != 2 or c.shape[0] != 4 or interpolant.extrapolate is not True:
        raise ValueError(f"interpolant must be a cubic PPoly of one value per point that extrapolates, got "
                         f"coefficients of shape {c.shape}, extrapolate={interpolant.extrapolate!r}")
    breaks = np.array(interpolant.x, dtype=float)
    return CubicPieces(breaks, breaks[1:-1].copy(), *(np.ascontiguousarray(row, dtype=float) for row in c))
