"""Reference solutions for Hertz contact, kept apart from ``lowmodel.contact.hertz``.

Raw inputs only: the contact modulus from ``E, nu`` (:func:`contact_modulus`), the
half curvature sums ``A, B`` of a ball in a straight groove from ``R_B`` and the
conformity (:func:`groove_half_curvatures`); nothing here calls ``lowmodel``.

Two independent routes:

* closed forms for a sphere on a flat and sphere on sphere (Johnson 1985,
  eqs 4.22-4.25): ``a^3 = 3 F R / (4 E*)``, ``delta = a^2 / R``,
  ``p0 = 3 F / (2 pi a^2)``;
* direct quadrature of the Boussinesq pressure-displacement relation for an
  elliptical Hertz pressure ``p = p0 sqrt(1 - x^2/a^2 - y^2/b^2)``:
  ``u(x0, 0) = 1/(pi E*) * integral p / r dA``.  In polar coordinates about
  the field point the ``1/r`` singularity cancels, the radial integral is
  done in closed form and the angular one by adaptive quadrature.  Given
  trial semi-axes this returns the approach and the curvatures
  ``A = (delta - u(x0, 0)) / x0^2`` and ``B = (delta - u(0, y0)) / y0^2``
  that the pressure field produces; it never calls elliptic integrals.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy.integrate import quad
from scipy.optimize import minimize_scalar


def contact_modulus(youngs_modulus: float, poisson_ratio: float, youngs_modulus_2: float | None = None,
                    poisson_ratio_2: float | None = None) -> float:
    """E* [Pa] from the raw material data: ``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2`` (Johnson eq 4.22)."""
    e2 = youngs_modulus if youngs_modulus_2 is None else youngs_modulus_2
    n2 = poisson_ratio if poisson_ratio_2 is None else poisson_ratio_2
    return 1.0 / ((1.0 - poisson_ratio**2) / youngs_modulus + (1.0 - n2**2) / e2)


def groove_half_curvatures(ball_radius: float, conformity: float) -> tuple[float, float]:
    """``(A, B)`` [1/m] of a ball in a straight groove of radius ``2 f R_B`` (Johnson eq 4.20).

    Across the groove the ball (``1/R_B``) meets the concave groove (``-1/(2 f R_B)``),
    along it the straight groove (0): ``A = (1/R_B - 1/(2 f R_B))/2``, ``B = 1/(2 R_B)``.
    """
    return 0.5 * (1.0 / ball_radius - 1.0 / (2.0 * conformity * ball_radius)), 0.5 / ball_radius


def sphere_closed_form(force: float, radius: float, contact_modulus: float) -> dict[str, float]:
    """Hertz sphere on flat with equivalent radius ``radius`` [m]: a [m], delta [m], p0 [Pa]."""
    a = (3.0 * force * radius / (4.0 * contact_modulus)) ** (1.0 / 3.0)
    return {"a": a, "b": a, "delta": a * a / radius, "p0": 3.0 * force / (2.0 * math.pi * a * a)}


def _radial_integral(x0: float, y0: float, a: float, b: float, theta: float) -> float:
    """integral_0^r_edge sqrt(1 - (x0 + r c)^2/a^2 - (y0 + r s)^2/b^2) dr along direction theta."""
    c, s = math.cos(theta), math.sin(theta)
    gamma = c * c / (a * a) + s * s / (b * b)
    beta = x0 * c / (a * a) + y0 * s / (b * b)
    alpha = 1.0 - x0 * x0 / (a * a) - y0 * y0 / (b * b)
    # q(r) = alpha - 2 beta r - gamma r^2 = gamma (D - (r + beta/gamma)^2)
    shift = beta / gamma
    big_d = alpha / gamma + shift * shift
    root = math.sqrt(big_d)
    s0 = shift
    inner = (big_d / 2.0) * (math.pi / 2.0 - math.asin(max(-1.0, min(1.0, s0 / root)))) \
        - (s0 / 2.0) * math.sqrt(max(0.0, big_d - s0 * s0))
    return math.sqrt(gamma) * inner


def surface_displacement(x0: float, y0: float, a: float, b: float, p0: float, contact_modulus: float) -> float:
    """Sum of the normal surface displacements of both bodies [m] at (x0, y0) inside the ellipse."""
    integral, _ = quad(lambda t: _radial_integral(x0, y0, a, b, t), 0.0, 2.0 * math.pi,
                       epsabs=0.0, epsrel=1e-12, limit=400)
    return p0 * integral / (math.pi * contact_modulus)


def ellipse_quadrature(a: float, b: float, p0: float, contact_modulus: float) -> dict[str, float]:
    """Approach and curvatures A, B [1/m] that a Hertz pressure on the ellipse (a, b) produces."""
    delta = surface_displacement(0.0, 0.0, a, b, p0, contact_modulus)
    x0, y0 = 0.5 * a, 0.5 * b
    A = (delta - surface_displacement(x0, 0.0, a, b, p0, contact_modulus)) / (x0 * x0)
    B = (delta - surface_displacement(0.0, y0, a, b, p0, contact_modulus)) / (y0 * y0)
    return {"delta": delta, "A": A, "B": B, "force": 2.0 * math.pi * a * b * p0 / 3.0}


# --------------------------------------------------------------------------- subsurface stress on the axis
@lru_cache(maxsize=4)
def _gauss_legendre(order: int):
    return np.polynomial.legendre.leggauss(order)


def axis_stress(a: float, b: float, p0: float, poisson_ratio: float, depth, order: int = 160):
    """Stresses (sigma_xx, sigma_yy, sigma_zz) [Pa] on the axis x = y = 0 below a Hertz pressure.

    The elliptical pressure ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)`` [Pa] on the
    half-space is integrated against Boussinesq's point-load stresses (Johnson
    1985 eq 3.87, compression negative) at each ``depth`` [m] (> 0; array):
    Gauss-Legendre in ``x = a s cos(t), y = b s sin(t)`` with ``s = sin(phi)``,
    which makes the integrand smooth.  On the axis the shear stresses vanish by
    symmetry, so these are the principal stresses.  Independent of
    lowmodel.contact.hertz (no elliptic integral).
    """
    depth = np.atleast_1d(np.asarray(depth, dtype=float))
    if not (a > 0 and b > 0 and np.all(depth > 0)):
        raise ValueError("a, b [m] and every depth [m] must be > 0")
    nodes, weights = _gauss_legendre(order)
    phi = (nodes + 1) * math.pi / 4          # [0, pi/2]
    w_phi = weights * math.pi / 4
    t = (nodes + 1) * math.pi / 4            # a quarter of the ellipse; x^2, y^2 make the rest equal
    w_t = weights * math.pi / 4
    s = np.sin(phi)
    # dA = a b s ds dt, ds = cos(phi) dphi, p = p0 cos(phi)
    S, T = np.meshgrid(s, t, indexing="ij")
    weight = 4 * a * b * S * np.cos(phi)[:, None] ** 2 * p0 * np.outer(w_phi, w_t)
    x2 = (a * S * np.cos(T)) ** 2
    y2 = (b * S * np.sin(T)) ** 2
    r2 = x2 + y2
    nu = poisson_ratio
    out = np.empty((3, depth.size))
    for k, z in enumerate(depth):
        rho = np.sqrt(r2 + z * z)
        common = (1 - 2 * nu) / r2
        sx = common * ((1 - z / rho) * (x2 - y2) / r2 + z * y2 / rho**3) - 3 * z * x2 / rho**5
        sy = common * ((1 - z / rho) * (y2 - x2) / r2 + z * x2 / rho**3) - 3 * z * y2 / rho**5
        sz = -3 * z**3 / rho**5
        out[:, k] = [np.sum(weight * sx), np.sum(weight * sy), np.sum(weight * sz)]
    return out / (2 * math.pi)


def axis_von_mises_maximum(a: float, b: float, p0: float, poisson_ratio: float) -> tuple[float, float]:
    """Depth [m] and value [Pa] of the largest von Mises stress on the axis below a Hertz pressure."""
    scale = min(a, b)

    def negative(z):
        sx, sy, sz = axis_stress(a, b, p0, poisson_ratio, z * scale)[:, 0]
        return -math.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2))

    grid = np.linspace(0.1, 2.0, 16)
    values = [negative(z) for z in grid]
    k = int(np.argmin(values))
    best = minimize_scalar(negative, bracket=(grid[max(k - 1, 0)], grid[k], grid[min(k + 1, grid.size - 1)]),
                           tol=1e-8) if 0 < k < grid.size - 1 else None
    z = best.x if best is not None else grid[k]
    return float(z * scale), float(-negative(z))
