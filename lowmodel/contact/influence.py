"""Tangential influence coefficients of two elastic half-spaces (Boussinesq-Cerruti) on a grid of rectangles.

The displacement difference ``u = u1 - u2`` of the surfaces of two half-spaces at the centre of cell ``I``
due to a uniform traction ``p`` on cell ``J`` (on body 1; ``-p`` on body 2), per unit traction [m/Pa].
Cerruti's point-force solution (Johnson 1985 eqs 2.19, surface ``z = 0``) summed over the two bodies
with Kalker's combined constants (Kalker 1990, Sec 1.4)::

    1/G = (1/G1 + 1/G2)/2,   nu/G = (nu1/G1 + nu2/G2)/2,   K = (G/4) ((1 - 2 nu1)/G1 - (1 - 2 nu2)/G2)

    u_x = 1/(pi G) [(1 - nu)/r + nu X^2/r^3] Q_x + nu/(pi G) X Y/r^3 Q_y           (X, Y = field - source)
    u_y = nu/(pi G) X Y/r^3 Q_x + 1/(pi G) [(1 - nu)/r + nu Y^2/r^3] Q_y

integrated in closed form over the source rectangle (``d^2 H / dX dY`` = integrand)::

    1/r     : X asinh(Y/|X|) + Y asinh(X/|Y|)      (Love's primitive)
    X^2/r^3 : Y asinh(X/|Y|)
    Y^2/r^3 : X asinh(Y/|X|)
    X Y/r^3 : -r

so ``A_xx = [[(1 - nu) X asinh(Y/|X|) + Y asinh(X/|Y|)]] / (pi G)``,
``A_yy = [[X asinh(Y/|X|) + (1 - nu) Y asinh(X/|Y|)]] / (pi G)``, ``A_xy = -nu [[r]] / (pi G)``, with
``[[H]] = H(X+, Y+) - H(X+, Y-) - H(X-, Y+) + H(X-, Y-)`` over the cell edges ``X+- = X +- dx/2``.
These are the piecewise-constant coefficients of Kalker (1990, Sec 5.2) and of CONTACT (Vollebregt, user
guide Sec 'Discretisation of the problem').

Normal-tangential coupling of dissimilar materials (``K != 0``): the tangential displacement difference due
to a normal pressure ``p_n`` (compressive > 0 on both bodies), Boussinesq (Johnson eq 3.19b summed over the
bodies)::

    u_x = -(K / (pi G)) X / r^2 p_n,   u_y = -(K / (pi G)) Y / r^2 p_n

(body 1 is the upper body ``z > 0`` as in Kalker; ``K > 0`` when body 1 is the more compressible one:
its surface is drawn towards the load more than body 2's).  Over a rectangle
``[[X atan(Y/X) + Y/2 ln(X^2 + Y^2)]]`` and its mirror.

Plane strain (2D line contact, Carter's problem; Johnson eq 2.26 for the two bodies): ``u_x = -(2 (1 - nu) /
(pi G)) ln|X| Q_x`` per unit length, over a cell ``-(2 (1 - nu) / (pi G)) [[t ln|t| - t]]``, defined up to a
constant that cancels in the steady-state (rolling) operator.

Steady state rolling (Kalker 1990 Sec 5.2; CONTACT's discretisation with the rolling step equal to the
cell size): the bodies roll in ``+x`` (material flows through the contact in ``-x``, entering at the
leading edge ``x = +a``); the slip per unit rolling distance at cell ``I`` is
``s_I = w_I + (u(x_I) - u(x_I + dx)) / dx``, the difference of the displacement of the particle pair now
and one cell upstream.  As a convolution ``s = w + C * p`` with
``C(k, l) = (A(k, l) - A(k + 1, l)) / dx`` [1/Pa] for the cell offsets ``(k, l)``.
"""
from __future__ import annotations

import functools
import math

import numpy as np

from ballbench.lowmodel import checks

__all__ = [
    "combined_material",
    "tangential_coefficients",
    "coupling_coefficients",
    "plane_strain_coefficients",
    "grid_kernels",
]


def combined_material(shear_modulus, poisson_ratio, shear_modulus_2=None, poisson_ratio_2=None):
    """Kalker's combined ``(G [Pa], nu, K)`` of two bodies (module docstring); body 2 defaults to body 1.

    ``K`` is Kalker's difference parameter (0 for quasi-identical bodies: no normal-tangential coupling).
    """
    g1 = checks.positive("shear_modulus", shear_modulus, "Pa")
    n1 = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    g2 = g1 if shear_modulus_2 is None else checks.positive("shear_modulus_2", shear_modulus_2, "Pa")
    n2 = n1 if poisson_ratio_2 is None else checks.bounded("poisson_ratio_2", poisson_ratio_2, -1.0, 0.5,
                                                             upper_closed=True)
    inverse = 0.5 * (1.0 / g1 + 1.0 / g2)
    shear = 1.0 / inverse
    nu = shear * 0.5 * (n1 / g1 + n2 / g2)
    coupling = 0.25 * shear * ((1.0 - 2.0 * n1) / g1 - (1.0 - 2.0 * n2) / g2)
    return float(shear), float(nu), float(coupling)


def _asinh_terms(X: np.ndarray, Y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    # X asinh(Y/|X|) and Y asinh(X/|Y|), each 0 on its axis (their limits)
    ax, ay = np.abs(X), np.abs(Y)
    first = np.zeros(np.broadcast(X, Y).shape)
    second = np.zeros_like(first)
    xs, ys = np.broadcast_arrays(X, Y)
    on = ax > 0.0
    on = np.broadcast_to(on, first.shape)
    first[on] = xs[on] * np.arcsinh(ys[on] / np.abs(xs[on]))
    on = np.broadcast_to(ay > 0.0, first.shape)
    second[on] = ys[on] * np.arcsinh(xs[on] / np.abs(ys[on]))
    return first, second


def _corners(X: np.ndarray, Y: np.ndarray, dx: float, dy: float):
    for sx, sy, sign in ((1.0, 1.0, 1.0), (1.0, -1.0, -1.0), (-1.0, 1.0, -1.0), (-1.0, -1.0, 1.0)):
        yield X + 0.5 * sx * dx, Y + 0.5 * sy * dy, sign


def tangential_coefficients(x_offsets, y_offsets, dx: float, dy: float, shear_modulus: float,
                            poisson_ratio: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(A_xx, A_xy, A_yy)`` [m/Pa] at the field-minus-source offsets ``x_offsets[:, None], y_offsets[None, :]`` [m].

    Uniform unit traction on a ``dx x dy`` [m] rectangle, displacement difference at the field point;
    combined ``shear_modulus`` G [Pa] and ``poisson_ratio`` nu (:func:`combined_material`).  ``A_yx = A_xy``.
    """
    dx = checks.positive("dx", dx, "m")
    dy = checks.positive("dy", dy, "m")
    shear = checks.positive("shear_modulus", shear_modulus, "Pa")
    nu = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    X = np.asarray(x_offsets, dtype=float)[:, None]
    Y = np.asarray(y_offsets, dtype=float)[None, :]
    xx = np.zeros(np.broadcast(X, Y).shape)
    yy = np.zeros_like(xx)
    xy = np.zeros_like(xx)
    for x, y, sign in _corners(X, Y, dx, dy):
        first, second = _asinh_terms(x, y)
        xx += sign * ((1.0 - nu) * first + second)
        yy += sign * (first + (1.0 - nu) * second)
        xy -= sign * np.hypot(x, y)
    scale = 1.0 / (math.pi * shear)
    return xx * scale, xy * (nu * scale), yy * scale


def coupling_coefficients(x_offsets, y_offsets, dx: float, dy: float, shear_modulus: float,
                          coupling: float) -> tuple[np.ndarray, np.ndarray]:
    """``(A_xn, A_yn)`` [m/Pa]: tangential displacement difference per unit normal pressure on a cell.

    Kalker's difference parameter ``coupling`` K (:func:`combined_material`); zero for quasi-identical
    bodies.  Offsets as :func:`tangential_coefficients`.
    """
    dx = checks.positive("dx", dx, "m")
    dy = checks.positive("dy", dy, "m")
    shear = checks.positive("shear_modulus", shear_modulus, "Pa")
    k = checks.finite("coupling", coupling)
    X = np.asarray(x_offsets, dtype=float)[:, None]
    Y = np.asarray(y_offsets, dtype=float)[None, :]
    xn = np.zeros(np.broadcast(X, Y).shape)
    yn = np.zeros_like(xn)
    for x, y, sign in _corners(X, Y, dx, dy):
        xs, ys = np.broadcast_arrays(x, y)
        r2 = xs * xs + ys * ys
        log = np.log(np.where(r2 > 0.0, r2, 1.0))
        with np.errstate(divide="ignore", invalid="ignore"):
            at_x = np.where(xs != 0.0, xs * np.arctan(ys / np.where(xs != 0.0, xs, 1.0)), 0.0)
            at_y = np.where(ys != 0.0, ys * np.arctan(xs / np.where(ys != 0.0, ys, 1.0)), 0.0)
        xn += sign * (at_x + 0.5 * ys * log)  # int int X / r^2 dX dY
        yn += sign * (at_y + 0.5 * xs * log)  # int int Y / r^2 dX dY
    scale = -k / (math.pi * shear)
    return xn * scale, yn * scale


def plane_strain_coefficients(x_offsets, dx: float, shear_modulus: float, poisson_ratio: float) -> np.ndarray:
    """``A_xx`` [m/(Pa)] of two bodies in plane strain at the offsets ``x_offsets`` [m] (module docstring).

    Uniform unit tangential traction on a strip of width ``dx``; defined up to a constant (a 2D
    displacement is), which cancels in the steady-state operator.
    """
    dx = checks.positive("dx", dx, "m")
    shear = checks.positive("shear_modulus", shear_modulus, "Pa")
    nu = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    X = np.asarray(x_offsets, dtype=float)

    def primitive(t):
        at = np.abs(t)
        return np.where(at > 0.0, t * np.log(np.where(at > 0.0, at, 1.0)) - t, 0.0)

    return -(2.0 * (1.0 - nu) / (math.pi * shear)) * (primitive(X + 0.5 * dx) - primitive(X - 0.5 * dx))


@functools.lru_cache(maxsize=32)
def _grid_kernels(nx: int, ny: int, dx: float, dy: float, shear: float, nu: float, coupling: float,
                  steady: bool, plane: bool):
    kx = np.arange(-(nx - 1), nx + (1 if steady else 0), dtype=float) * dx
    ly = np.arange(-(ny - 1), ny, dtype=float) * dy
    if plane:
        a = plane_strain_coefficients(kx, dx, shear, nu)[:, None] * np.ones((1, ly.size))
        kernels = [a, np.zeros_like(a), a]
        normal = [np.zeros_like(a), np.zeros_like(a)] if coupling else []
    else:
        kernels = list(tangential_coefficients(kx, ly, dx, dy, shear, nu))
        normal = list(coupling_coefficients(kx, ly, dx, dy, shear, coupling)) if coupling else []
    out = []
    for kernel in kernels + normal:
        if steady:
            kernel = (kernel[:-1] - kernel[1:]) / dx
        kernel = np.ascontiguousarray(kernel)
        kernel.setflags(write=False)
        out.append(kernel)
    return tuple(out)


def grid_kernels(nx: int, ny: int, dx: float, dy: float, shear_modulus: float, poisson_ratio: float, *,
                 coupling: float = 0.0, steady: bool = True, plane_strain: bool = False) -> tuple:
    """Convolution kernels of an ``nx x ny`` grid of ``dx x dy`` [m] cells, each ``(2 nx - 1, 2 ny - 1)``.

    Index ``[k + nx - 1, l + ny - 1]`` is the cell offset (field minus source) ``(k, l)``.  Returns
    ``(xx, xy, yy)`` and, if ``coupling`` K is nonzero, ``(xn, yn)`` (the normal pressure's part).
    ``steady=True``: the steady-state rolling operator ``C`` [1/Pa] (module docstring; slip per unit
    rolling distance), else the displacement coefficients ``A`` [m/Pa] (a shift).
    ``plane_strain``: the 2D plane-strain kernel (``ny`` must be 1; ``xy = 0``).  Cached, read-only.
    """
    nx = checks.count("nx", nx, 1, 8192)
    ny = checks.count("ny", ny, 1, 8192)
    if plane_strain and ny != 1:
        raise ValueError(f"plane_strain needs ny = 1 (a line contact), got ny = {ny}")
    return _grid_kernels(nx, ny, float(checks.positive("dx", dx, "m")), float(checks.positive("dy", dy, "m")),
                         float(checks.positive("shear_modulus", shear_modulus, "Pa")),
                         float(checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)),
                         float(checks.finite("coupling", coupling)), bool(steady), bool(plane_strain))
