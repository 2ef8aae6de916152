"""Friction over a Hertz contact ellipse whose slip field rotates about an offset centre.

lin2019 Appendix eqs A4-A7 (and Sec 2.1, eqs 1-3): in the contact plane of
contact ``i`` (local ``x`` along the major semi-axis ``a``, local ``z`` along the
rolling direction and the minor semi-axis ``b``) the slip velocity of the ball
relative to the groove is (eq 3)::

    dv_x = omega z,        dv_z = omega (c - x)

i.e. a rigid rotation with angular velocity ``omega`` about the *velocity
centre* ``(x, z) = (c, 0)``.  With the Hertz pressure
``p = p0 sqrt(1 - x^2/a^2 - z^2/b^2)``, ``p0 = 3 F / (2 pi a b)`` (eq A7) and
Coulomb friction ``mu p`` opposing the slip, the paper's integrals reduce to
three dimensionless functions of ``kappa = c/a`` and ``beta = b/a``
(``t = x/a``, ``s = z/b``, ``D = sqrt((t - kappa)^2 + (beta s)^2)``,
``p_hat = (3/(2 pi)) sqrt(1 - t^2 - s^2)`` on the unit disc)::

    force(kappa)  =  iint p_hat (t - kappa) / D                    f_{i,z}  = sgn(omega) mu F   * force   (eq A4)
    moment(kappa) =  iint p_hat (t^2 - kappa t + beta^2 s^2) / D   M_{i,O}  = sgn(omega) mu F a * moment  (eq A5)
    loss(kappa)   =  iint p_hat D                                  P_{f,i}  = |omega|   mu F a * loss    (eq A6)

Sign conventions (those of the paper):

* ``force`` is the friction force *on the ball* along ``+z_i``; it is odd in
  ``kappa``, ``force -> -sign(kappa)`` as ``|kappa| -> inf`` (pure sliding,
  lin2019 eq 12: ``f_{i,z} -> -+ sgn(omega) mu F``) and
  ``force ~ -k_f kappa`` near 0 (lin2019 eq 14).
* ``moment`` is the friction moment on the ball about the contact centre,
  measured about ``-y_i`` (lin2019 Sec 2.1, the minus sign of eq 4); it is even,
  ``moment(0) = (3/8) E(e)`` (lin2019 eq 11, ``e = sqrt(1 - beta^2)``) and
  ``moment -> 0`` as ``|kappa| -> inf`` (eq 12).
* ``loss`` is the dissipated power; even; ``loss ~ |kappa|`` as
  ``|kappa| -> inf`` (so ``P -> mu F |omega c|``, sliding at speed
  ``|omega c|``).

Exact identities used throughout (differentiate the integrands)::

    d loss / d kappa   = -force
    moment             = loss + kappa force                  (power balance)
    d force / d kappa  = -curvature,   curvature = iint p_hat beta^2 s^2 / D^3 > 0
    d moment / d kappa = -kappa curvature

so ``k_f = curvature(0) = (beta^2/2) R_D(0, 1, beta^2)
= 3 (E(e) - beta^2 K(e)) / (2 e^2)`` exactly.

Quadrature (:func:`friction_exact`): polar coordinates centred on the
velocity centre (in the scaled plane ``X = t - kappa``, ``Y = beta s``), where
the slip direction is the polar angle, so the radial integrals are closed forms
(integrals of ``rho^n sqrt(quadratic)``) and the integrable singularity of the
curvature (``1/rho``) and the kink of the slip direction are integrated
exactly.  The remaining smooth angular integral uses tanh-sinh quadrature
(inside the ellipse, split where the integrand loses smoothness as
``|kappa| -> 1``) or Gauss-Legendre over the cone of rays that meet the
ellipse (outside).

Tabulation (:func:`friction`, :func:`friction_velocity`): the three functions
are smooth functions of the *slip-direction angle*
``phi = atan2(omega c, omega a)`` (``phi = arctan(kappa)`` for ``omega > 0``),
including across ``omega = 0`` (pure sliding, ``kappa = +-inf``).  They are
tabulated once on a ``(phi, log(b/a))`` grid, cached on disk
(``lowmodel.cache``, kind ``ellipse_friction``) and interpolated by a bicubic
spline (C2), whose analytic derivatives are returned for Newton's method.

One concept in one file (about 800 lines): the three functions of eqs A4-A6, their
closed forms near the ends, the exact quadrature and the table of that same
quadrature that the solvers evaluate; the table is built from :func:`friction_exact`
and checked against it (tests), so a change of the integrals and of their table
belongs in one review.  The quadrature rules are :mod:`lowmodel.quadrature`'s.
"""
from __future__ import annotations

import math
import os
import time
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from scipy.special import ellipe, ellipkm1, elliprd

from ballbench.lowmodel import checks
from ballbench.lowmodel.cache import cache_dir, parameter_hash
from ballbench.lowmodel.quadrature import gauss_legendre, tanh_sinh

__all__ = [
    "EllipseFriction",
    "SlipFriction",
    "AngleFriction",
    "friction_angle",
    "friction_angle_at",
    "patch_table",
    "log_ratio_cells",
    "friction",
    "friction_exact",
    "friction_velocity",
    "k_f_exact",
    "k_f_least_squares",
    "cubic_coefficient",
    "friction_inside",
    "spin_moment",
    "friction_map",
    "FrictionMap",
    "B_OVER_A_RANGE",
]

B_OVER_A_RANGE = (0.02, 1.0)  # tabulated range of b/a (a >= b by convention)
SLIP_FLOOR = 1e-300  # m/s: friction_velocity treats a slip speed below this as zero (contact at rest)
_PREFACTOR = 3.0 / (2.0 * math.pi)  # lin2019 eq A7: p0 a b / F


# --------------------------------------------------------------------------
# results
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class EllipseFriction:
    """Normalised friction of one Hertz ellipse (lin2019 eqs A4-A6 with A7).

    All attributes are arrays broadcast from ``c_over_a`` and ``b_over_a``;
    dimensionless.  Dimensional values for contact ``i`` with normal load
    ``F`` [N], semi-major axis ``a`` [m] and spin ``omega`` [rad/s]::

        f_{i,z} = sgn(omega) * mu * F     * force      [N]
        M_{i,O} = sgn(omega) * mu * F * a * moment     [N m], about -y_i
        P_{f,i} = |omega|    * mu * F * a * loss       [W]

    ``dforce_dc``, ``dmoment_dc``, ``dloss_dc`` are derivatives with respect
    to ``c/a`` at fixed ``b/a``.  ``loss`` is ``inf`` at ``c/a = +-inf``
    (use :func:`friction_velocity` when ``omega -> 0``).
    """

    force: np.ndarray
    moment: np.ndarray
    loss: np.ndarray
    dforce_dc: np.ndarray
    dmoment_dc: np.ndarray
    dloss_dc: np.ndarray


@dataclass(frozen=True)
class SlipFriction:
    """Friction of one Hertz ellipse in terms of slip velocities (finite as omega -> 0).

    Inputs were ``spin_velocity = omega a`` [m/s] and
    ``slide_velocity = omega c`` [m/s] (the slip velocity of the ball at the
    contact centre along ``z_i``: ``(dv)_z`` of lin2019 eq 1 at ``x = 0``).
    Dimensional values::

        f_{i,z} = mu * F     * force     [N]
        M_{i,O} = mu * F * a * moment    [N m], about -y_i
        P_{f,i} = mu * F     * loss      [W]   (loss in m/s)

    ``d<q>_dspin``, ``d<q>_dslide``: partial derivatives with respect to
    ``spin_velocity`` and ``slide_velocity`` [1/(m/s)] (loss: dimensionless).
    At ``spin = slide = 0`` force and moment are undefined (returned as the
    pure-spin value ``force = 0``, ``moment = (3/8) E``, derivatives 0); slip speeds
    below ``SLIP_FLOOR`` (1e-300 m/s) count as zero.
    """

    force: np.ndarray
    moment: np.ndarray
    loss: np.ndarray
    dforce_dspin: np.ndarray
    dforce_dslide: np.ndarray
    dmoment_dspin: np.ndarray
    dmoment_dslide: np.ndarray
    dloss_dspin: np.ndarray
    dloss_dslide: np.ndarray


@dataclass(frozen=True)
class AngleFriction:
    """Friction of one Hertz ellipse as a function of the slip-direction angle (see :func:`friction_angle`).

    ``phi = atan2(omega c, omega a)``: the slip at the contact centre and the spin velocity are
    ``(omega c, omega a) = r (sin phi, cos phi)`` with slip speed scale ``r >= 0`` [m/s].
    Dimensional values::

        f_{i,z} = mu * F     * force         [N]
        M_{i,O} = mu * F * a * moment        [N m], about -y_i
        P_{f,i} = mu * F * r * loss          [W]   (loss per unit r, dimensionless)

    ``d<q>_dphi``: derivatives with respect to ``phi`` [1/rad].
    """

    force: np.ndarray
    moment: np.ndarray
    loss: np.ndarray
    dforce_dphi: np.ndarray
    dmoment_dphi: np.ndarray
    dloss_dphi: np.ndarray


# --------------------------------------------------------------------------
# input checks
# --------------------------------------------------------------------------
def _check_ratio(b_over_a, *, lower: float = B_OVER_A_RANGE[0]) -> np.ndarray:
    return np.asarray(checks.bounded("b_over_a", b_over_a, lower, 1.0, lower_closed=True, upper_closed=True,
                                     note="a is the semi-major axis"))


def _check_kappa(c_over_a) -> np.ndarray:
    kappa = checks.real("c_over_a", c_over_a)
    if np.any(np.isnan(kappa)):  # +-inf is pure sliding, allowed
        raise ValueError("c_over_a must not be NaN (+-inf is allowed: pure sliding)")
    return kappa


# --------------------------------------------------------------------------
# closed forms
# --------------------------------------------------------------------------
def spin_moment(b_over_a) -> np.ndarray:
    """``moment`` at ``c/a = 0``: ``(3/8) E(e)``, ``e = sqrt(1 - (b/a)^2)`` (lin2019 eq 11)."""
    beta = _check_ratio(b_over_a, lower=0.0)
    return 0.375 * ellipe(1.0 - beta**2)  # scipy's ellipe takes the parameter m = e^2


def k_f_exact(b_over_a) -> np.ndarray:
    """Exact slope ``k_f = -d force / d(c/a)`` at ``c/a = 0`` (lin2019 eq 14).

    ``k_f = iint p_hat beta^2 s^2/(t^2 + beta^2 s^2)^(3/2) = (beta^2/2) R_D(0, 1, beta^2)
    = 3 (E(e) - beta^2 K(e)) / (2 e^2)``; ``3 pi/8`` for a circle, ``-> 3/2`` as
    ``b/a -> 0``.  Dimensionless.
    """
    beta = _check_ratio(b_over_a, lower=0.0)
    beta2 = beta**2
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        value = 0.5 * beta2 * elliprd(0.0, 1.0, beta2)
    # R_D(0, 1, beta^2) ~ 3 / beta^2 overflows below beta^2 ~ 1e-308; there k_f = 3/2 - O(beta^2 ln(1/beta)) is
    # 3/2 to double precision (the limit b/a -> 0)
    return np.where(beta2 > 1e-300, value, 1.5)


def cubic_coefficient(b_over_a) -> np.ndarray:
    """``g3`` of ``force = -k_f (c/a) + g3 (c/a)^3``, exact for ``|c/a| <= 1``.

    Polar integration about the velocity centre shows that the curvature
    ``-d force/d kappa`` is exactly ``k_f - 3 g3 kappa^2`` inside the ellipse
    (the odd part of the radial integral cancels), with
    ``k_f = (3/2) int_0^(pi/2) cos^2 / Delta`` and
    ``g3 = (1/2) int_0^(pi/2) cos^4 / Delta^3``, ``Delta = sqrt(1 - e^2 sin^2)``, i.e.
    ``g3 = ((1 + beta^2) E(e) - 2 beta^2 K(e)) / (2 e^4)``; ``3 pi/32`` for a circle.
    Dimensionless.
    """
    beta = _check_ratio(b_over_a, lower=0.0)
    shape = beta.shape
    b = np.atleast_1d(beta).astype(float).ravel()
    m = 1.0 - b**2
    result = np.empty_like(b)
    tiny = b * b == 0.0  # b/a below 1e-154: b^2 K(e) ~ b^2 ln(4/b) underflows, the limit itself
    far = (b <= 0.5) & ~tiny  # no cancellation in the closed form (e^4 >= 0.56)
    # K(m) through ellipkm1(1 - m = b^2): exact also where m = 1 - b^2 rounds to 1 (tiny b)
    b2 = b[far] ** 2
    result[far] = ((1.0 + b2) * ellipe(m[far]) - 2.0 * b2 * ellipkm1(b2)) / (2.0 * m[far] ** 2)
    result[tiny] = 0.5  # limit b/a -> 0: E(1) = 1 and b^2 K ~ b^2 ln(4/b) -> 0
    far |= tiny
    if np.any(~far):  # near-circular: smooth integrand, 48-point Gauss-Legendre
        x, w = gauss_legendre(48)
        psi = 0.5 * math.pi * x
        delta = np.sqrt(1.0 - m[~far, None] * np.sin(psi) ** 2)
        result[~far] = 0.5 * (0.5 * math.pi) * (np.cos(psi) ** 4 / delta**3) @ w
    return result.reshape(shape)


def friction_inside(c_over_a, b_over_a) -> EllipseFriction:
    """Closed form of lin2019 eqs A4-A6 while the velocity centre lies in the ellipse (``|c/a| <= 1``).

    ``force = -k_f kappa + g3 kappa^3``, ``loss = (3/8) E(e) + (k_f/2) kappa^2 - (g3/4) kappa^4``,
    ``moment = loss + kappa force = (3/8) E(e) - (k_f/2) kappa^2 + (3/4) g3 kappa^4``
    (:func:`k_f_exact`, :func:`cubic_coefficient`).  Raises ValueError for ``|c/a| > 1``.
    """
    kappa = _check_kappa(c_over_a)
    if np.any(np.abs(kappa) > 1.0):
        raise ValueError("c_over_a must lie in [-1, 1] for the closed form (velocity centre inside the ellipse)")
    beta = _check_ratio(b_over_a, lower=1e-3)
    k_f, g3, spin = k_f_exact(beta), cubic_coefficient(beta), spin_moment(beta)
    k2 = kappa**2
    force = -k_f * kappa + g3 * kappa * k2
    loss = spin + 0.5 * k_f * k2 - 0.25 * g3 * k2**2
    return EllipseFriction(force, loss + kappa * force, loss, -k_f + 3.0 * g3 * k2,
                           -kappa * (k_f - 3.0 * g3 * k2), -force)


# --------------------------------------------------------------------------
# direct quadrature
# --------------------------------------------------------------------------
def _radial(kappa, beta, phi):
    """Radial integrals ``J_n = int rho^n sqrt(q(rho)) d rho`` (n = 0, 1, 2) along a ray, centre inside.

    Ray from the velocity centre in the scaled plane: ``t = kappa + rho cos(phi)``,
    ``s = rho sin(phi)/beta``; ``q = 1 - t^2 - s^2 = A (R^2 - w^2)``, ``w = rho + b0``.
    """
    cos, sin = np.cos(phi), np.sin(phi)
    big_a = cos**2 + (sin / beta) ** 2
    b0 = kappa * cos / big_a
    r2 = (cos**2 + (1.0 - kappa) * (1.0 + kappa) * (sin / beta) ** 2) / big_a**2  # > 0 for |kappa| < 1
    radius = np.sqrt(r2)
    root_a = np.sqrt(big_a)
    def anti(w):
        ratio = np.clip(np.divide(w, radius, out=np.zeros_like(w), where=radius > 0), -1.0, 1.0)
        root = np.sqrt(np.maximum(r2 - w**2, 0.0))
        asin = np.arcsin(ratio)
        return (0.5 * (w * root + r2 * asin), -(root**3) / 3.0,
                0.125 * w * (2.0 * w**2 - r2) * root + 0.125 * r2**2 * asin)
    lo = anti(np.minimum(np.maximum(b0, -radius), radius))
    k0 = 0.25 * math.pi * r2 - lo[0]
    k1 = 0.0 - lo[1]
    k2 = 0.0625 * math.pi * r2**2 - lo[2]
    j0 = root_a * k0
    j1 = root_a * (k1 - b0 * k0)
    j2 = root_a * (k2 - 2.0 * b0 * k1 + b0**2 * k0)
    return j0, j1, j2


def _integrals(kappa: np.ndarray, beta: np.ndarray, level: int = 6):
    """(force, loss, curvature) by the velocity-centre polar quadrature; 1-D arrays of equal length."""
    force = np.empty(kappa.shape)
    loss = np.empty(kappa.shape)
    curvature = np.empty(kappa.shape)
    inside = np.abs(kappa) <= 1.0
    if np.any(inside):
        x, w = tanh_sinh(level)
        # phi in [0, pi] (integrands are even in phi), split at pi/2 where smoothness is lost as |kappa| -> 1
        phi = np.concatenate([0.5 * math.pi * x, 0.5 * math.pi * (1.0 + x)])
        weights = np.concatenate([w, w]) * 0.5 * math.pi * 2.0  # factor 2: phi in [-pi, 0]
        k = kappa[inside][:, None]
        b = beta[inside][:, None]
        j0, j1, j2 = _radial(k, b, phi[None, :])
        scale = _PREFACTOR / beta[inside]
        force[inside] = scale * ((np.cos(phi) * j1) @ weights)
        loss[inside] = scale * (j2 @ weights)
        curvature[inside] = scale * ((np.sin(phi) ** 2 * j0) @ weights)
    outside = ~inside & np.isfinite(kappa)
    if np.any(outside):
        # rays from the centre that meet the ellipse: angle phi' from the direction -sign(kappa) with
        # tan(phi') = tau beta / sqrt(kappa^2 - 1), |tau| <= 1; along such a ray the whole chord lies at
        # rho > 0 and R^2 = cos(phi')^2 (1 - tau^2) / A^2 (no cancellation for large |kappa|)
        x, w = tanh_sinh(level)
        k = kappa[outside][:, None]
        b = beta[outside][:, None]
        excess = (np.abs(k) - 1.0) * (np.abs(k) + 1.0)       # kappa^2 - 1 > 0
        half = np.arctan2(b, np.sqrt(excess))                # half-angle of the cone of rays
        phi_p = half * x[None, :]
        cos_p, sin_p = np.cos(phi_p), np.sin(phi_p)
        tau2 = np.minimum((sin_p / cos_p) ** 2 * excess / b**2, 1.0)
        cos = -np.sign(k) * cos_p               # ray direction (cos(phi), |sin(phi)|)
        big_a = cos_p**2 + (sin_p / b) ** 2
        b0 = k * cos / big_a
        r2 = cos_p**2 * (1.0 - tau2) / big_a**2
        root_a = np.sqrt(big_a)
        j0 = root_a * 0.5 * math.pi * r2
        j1 = -root_a * b0 * 0.5 * math.pi * r2
        j2 = root_a * (0.125 * math.pi * r2**2 + b0**2 * 0.5 * math.pi * r2)
        weights = 2.0 * half * w[None, :]  # both sides of the axis
        scale = _PREFACTOR / beta[outside]
        force[outside] = scale * np.sum(cos * j1 * weights, axis=1)
        loss[outside] = scale * np.sum(j2 * weights, axis=1)
        curvature[outside] = scale * np.sum(sin_p**2 * j0 * weights, axis=1)
    infinite = ~np.isfinite(kappa)
    force[infinite] = -np.sign(kappa[infinite])
    loss[infinite] = np.inf
    curvature[infinite] = 0.0
    return force, loss, curvature


ASYMPTOTIC_C_OVER_A = 200.0  # |c/a| above which friction_exact uses the far-field series (error < 1e-16 there)


def _far_field(kappa: np.ndarray, beta: np.ndarray):
    """(force, moment, loss, curvature, d moment/d kappa) for a distant velocity centre, ``|kappa| >> 1``.

    With ``u = |kappa| - sign(kappa) t``, ``q = beta^2 s^2``, ``D = sqrt(u^2 + q)`` the integrands are
    expanded in ``e = 1/|kappa|`` and integrated term by term against ``p_hat`` (its odd moments vanish;
    ``iint p_hat t^m s^n`` in closed form), to ``e^6``::

        force  = -sign(kappa) (1 - c2 e^2 - c4 e^4 - c6 e^6)
        loss   = |kappa| + c2 e + l3 e^3 + l5 e^5
        moment = beta^2 e (56 + (16 - 12 beta^2) e^2 + (8 - 12 beta^2 + 5 beta^4) e^4) / 280
        c2 = beta^2/10,  c4 = 3 beta^2/70 - 9 beta^4/280,  c6 = beta^2/42 - beta^4/28 + 5 beta^6/336
        l3 = beta^2/70 - 3 beta^4/280,  l5 = beta^2/210 - beta^4/140 + beta^6/336

    relative error O(e^8); ``moment = loss + kappa force`` holds term by term, without the
    cancellation (absolute error ``eps |kappa|``) of that identity in floating point.
    """
    e = 1.0 / np.abs(kappa)
    sign = np.sign(kappa)
    b2 = beta**2
    e2 = e * e
    c2 = 0.1 * b2
    c4 = b2 * (3.0 / 70.0 - 9.0 / 280.0 * b2)
    c6 = b2 * (1.0 / 42.0 - b2 / 28.0 + 5.0 / 336.0 * b2 * b2)
    force = -sign * (1.0 - e2 * (c2 + e2 * (c4 + e2 * c6)))
    loss = np.abs(kappa) + e * (c2 + e2 * (b2 * (1.0 / 70.0 - 3.0 / 280.0 * b2)
                                           + e2 * b2 * (1.0 / 210.0 - b2 / 140.0 + b2 * b2 / 336.0)))
    moment = b2 * e * (56.0 + e2 * ((16.0 - 12.0 * b2) + e2 * (8.0 - 12.0 * b2 + 5.0 * b2 * b2))) / 280.0
    curvature = e2 * e * (2.0 * c2 + e2 * (4.0 * c4 + e2 * 6.0 * c6))  # -d force / d kappa
    return force, moment, loss, curvature, -kappa * curvature


def friction_exact(c_over_a, b_over_a) -> EllipseFriction:
    """Friction integrals of lin2019 eqs A4-A6 by direct quadrature (no table).

    Parameters
    ----------
    c_over_a : array_like, velocity-centre offset ``c/a`` along the major axis
        (any real, ``+-inf`` for pure sliding).
    b_over_a : array_like, axis ratio ``b/a`` in ``(0, 1]``; broadcast with ``c_over_a``.

    Returns
    -------
    EllipseFriction with arrays of the broadcast shape.  Accuracy about 1e-12
    (tests compare it with an independent adaptive Cartesian quadrature).
    For ``|c/a| > ASYMPTOTIC_C_OVER_A`` the far-field series (:func:`_far_field`)
    replaces the quadrature, whose ``moment = loss + (c/a) force`` would cancel.
    Derivatives use the exact identities of the module docstring.
    """
    kappa = _check_kappa(c_over_a)
    beta = _check_ratio(b_over_a, lower=1e-3)
    kappa, beta = np.broadcast_arrays(kappa, beta)
    shape = kappa.shape
    k = kappa.ravel().astype(float)
    b = beta.ravel().astype(float)
    far = np.isfinite(k) & (np.abs(k) > ASYMPTOTIC_C_OVER_A)
    force, loss, curvature = _integrals(np.where(far, 0.0, k), b)
    with np.errstate(invalid="ignore"):
        moment = np.where(np.isfinite(k), loss + k * force, 0.0)
        dmoment = np.where(np.isfinite(k), -k * curvature, 0.0)
    if np.any(far):  # loss + kappa force cancels (absolute error eps |kappa|): the series instead
        kf, bf = k[far], b[far]
        force[far], moment[far], loss[far], curvature[far], dmoment[far] = _far_field(kf, bf)
    return EllipseFriction(force.reshape(shape), moment.reshape(shape), loss.reshape(shape),
                           (-curvature).reshape(shape), dmoment.reshape(shape), (-force).reshape(shape))




def k_f_least_squares(b_over_a, c_max: float = 0.5) -> np.ndarray:
    """Least-squares slope ``k_f`` of ``-force`` against ``c/a`` over ``|c/a| <= c_max``.

    Continuous least squares of a line through the origin (``force`` is odd,
    so a free intercept is exactly zero): ``k = -int force kappa / int kappa^2``
    over ``[-c_max, c_max]``, integrated by 24-point Gauss-Legendre on the exact
    integrals.  For ``c_max <= 1`` ``force`` is the odd cubic
    ``-k_f kappa + g3 kappa^3`` and this equals ``k_f - (3/5) c_max^2 g3``.
    The paper reads ``k_f = 1.38`` off its Fig 5 over ``|c/a| < 0.5``
    (lin2019 Sec 2.3.1 and eq A8).  Dimensionless.
    """
    c_max = checks.positive("c_max", c_max)
    beta = _check_ratio(b_over_a, lower=1e-3)
    if c_max < 1e-3:  # the quadrature's absolute accuracy (~1e-16) would swamp c_max: the exact cubic instead
        return k_f_exact(beta) - 0.6 * c_max**2 * cubic_coefficient(beta)
    x, w = gauss_legendre(24)
    kappa = c_max * x  # (0, c_max]; the integrand force*kappa is even
    shape = beta.shape
    b = beta.ravel()
    result = friction_exact(kappa[None, :], b[:, None])
    numerator = -(result.force * kappa[None, :]) @ w
    denominator = float((kappa**2) @ w)
    return (numerator / denominator).reshape(shape)


# --------------------------------------------------------------------------
# table on (phi, log b/a) and its bicubic spline
# --------------------------------------------------------------------------
_MAP_VERSION = "2"


def _phi_nodes(n_uniform: int, n_cluster: int) -> np.ndarray:
    """Nodes of lambda = arctan(c/a) in [0, pi/2], clustered at c/a = 1 (lambda = pi/4).

    The integrals lose smoothness where the velocity centre crosses the rim of
    the ellipse (|c/a| = 1); a node sits exactly there.
    """
    quarter = 0.25 * math.pi
    uniform = np.linspace(0.0, 0.5 * math.pi, n_uniform)
    offsets = np.geomspace(2e-5, 0.2, n_cluster)
    nodes = np.concatenate([uniform, quarter - offsets, quarter + offsets, [quarter]])
    nodes = np.sort(nodes)
    return nodes[np.concatenate([[True], np.diff(nodes) > 1e-12])]


@dataclass(frozen=True)
class FrictionMap:
    """Tabulated ``force``, ``moment`` and ``loss/|(1, c/a)|`` on ``(phi, log(b/a))``.

    ``phi`` is the slip-direction angle ``atan2(omega c, omega a)`` covering
    ``[-pi - margin, pi + margin]`` (by the symmetries of the integrals) so that
    every query point is interior; ``splines`` are scipy RectBivariateSpline
    (bicubic, s = 0) of ``force``, ``moment`` and ``loss cos(phi)`` (the last
    one equals ``loss / sqrt(1 + (c/a)^2)``, bounded).

    The five arrays are read-only (the splines and patches are cached on the instance and built from
    them; :func:`friction_map` shares one map with every caller; lowmodel.checks.freeze_arrays).
    """

    phi: np.ndarray
    log_b_over_a: np.ndarray
    force: np.ndarray
    moment: np.ndarray
    loss_direction: np.ndarray
    build_time_s: float
    from_cache: bool

    def __post_init__(self):
        checks.freeze_arrays(self, "phi", "log_b_over_a", "force", "moment", "loss_direction")

    def __reduce__(self):
        return checks.rebuilt_through_init(self)

    @property
    def splines(self):
        """scipy RectBivariateSpline of (force, moment, loss_direction) over (phi, log b/a)."""
        return _patches(self)[0]

    @cached_property
    def _patch_set(self):
        # on the instance, not in a dict keyed on id(self): a map built at a freed map's address got its splines
        return _build_patches(self)


def _patches(table: FrictionMap):
    """The splines and bicubic patches of ``table`` (:func:`_build_patches`), built once per map."""
    return table._patch_set


def _build_patches(table: FrictionMap):
    """Splines and their bicubic patches, Taylor coefficients about each cell centre.

    ``coefficients[i, j, q, m, n]`` multiplies ``dphi^m dlogb^n`` for quantity ``q``
    in cell ``(i, j)``; exact for the spline (its knots are a subset of the nodes), so
    evaluating the patches is evaluating the spline, only without fitpack's
    per-call overhead.
    """
    from scipy.interpolate import RectBivariateSpline
    splines = tuple(RectBivariateSpline(table.phi, table.log_b_over_a, values, kx=3, ky=3, s=0)
                    for values in (table.force, table.moment, table.loss_direction))
    mid_x = 0.5 * (table.phi[1:] + table.phi[:-1])
    mid_y = 0.5 * (table.log_b_over_a[1:] + table.log_b_over_a[:-1])
    width_x = np.diff(table.phi)
    width_y = np.diff(table.log_b_over_a)
    # sample each cell at 4 x 4 interior points and solve the (fixed) Vandermonde system
    unit = np.array([-0.375, -0.125, 0.125, 0.375])
    inverse = np.linalg.inv(np.vander(unit, 4, increasing=True))   # samples -> coefficients in unit
    xs = (mid_x[:, None] + width_x[:, None] * unit).ravel()
    ys = (mid_y[:, None] + width_y[:, None] * unit).ravel()
    scale_x = width_x[:, None] ** -np.arange(4.0)                  # (nx-1, 4)
    scale_y = width_y[:, None] ** -np.arange(4.0)
    coefficients = np.empty((mid_x.size, mid_y.size, 3, 4, 4))
    for q, spline in enumerate(splines):
        samples = spline(xs, ys, grid=True).reshape(mid_x.size, 4, mid_y.size, 4)
        unit_coefficients = np.einsum("ma,iajb,nb->ijmn", inverse, samples, inverse)
        coefficients[:, :, q] = unit_coefficients * scale_x[:, None, :, None] * scale_y[None, :, None, :]
    for array in (mid_x, mid_y, coefficients):
        array.setflags(write=False)
    return splines, mid_x, mid_y, coefficients


def _build_table(n_uniform: int, n_cluster: int, n_beta: int):
    half = _phi_nodes(n_uniform, n_cluster)                    # lambda in [0, pi/2]
    log_beta = np.linspace(math.log(B_OVER_A_RANGE[0]), 0.0, n_beta)
    lam, lb = np.meshgrid(half, log_beta, indexing="ij")
    kappa = np.tan(lam)
    kappa[np.isclose(lam, 0.5 * math.pi)] = np.inf
    result = friction_exact(kappa, np.exp(lb))
    cos = np.cos(lam)
    with np.errstate(invalid="ignore"):
        direction = np.where(np.isfinite(kappa), result.loss * cos, 1.0)
    # extend lambda in [0, pi/2] to phi in [-pi - margin, pi + margin] by the symmetries
    # force(-k) = -force(k), moment and loss even; (omega -> -omega): force, moment flip, loss same
    lam_full = np.concatenate([-half[:0:-1], half])             # [-pi/2, pi/2]
    f_full = np.concatenate([-result.force[:0:-1], result.force])
    m_full = np.concatenate([result.moment[:0:-1], result.moment])
    d_full = np.concatenate([direction[:0:-1], direction])
    margin = 0.3  # rad beyond +-pi, so that every phi = atan2(...) in [-pi, pi] is interior
    low = lam_full >= -margin        # phi = lambda - pi in [-pi - margin, -pi/2]
    high = lam_full <= margin        # phi = lambda + pi in [pi/2, pi + margin]
    phi = np.concatenate([lam_full[low] - math.pi, lam_full, lam_full[high] + math.pi])
    force = np.concatenate([-f_full[low], f_full, -f_full[high]])
    moment = np.concatenate([-m_full[low], m_full, -m_full[high]])
    direction_full = np.concatenate([d_full[low], d_full, d_full[high]])
    order = np.argsort(phi, kind="stable")
    phi = phi[order]
    keep = np.concatenate([[True], np.diff(phi) > 1e-9])  # +-pi/2 appear twice
    return phi[keep], log_beta, force[order][keep], moment[order][keep], direction_full[order][keep]


_GRID = {"n_uniform": 161, "n_cluster": 24, "n_beta": 65}


@lru_cache(maxsize=4)
def friction_map(n_uniform: int = _GRID["n_uniform"], n_cluster: int = _GRID["n_cluster"],
                 n_beta: int = _GRID["n_beta"], use_cache: bool = True) -> FrictionMap:
    """The tabulated friction map (built once, cached on disk and in memory).

    Grid: ``n_uniform`` uniform nodes of ``arctan(c/a)`` on ``[0, pi/2]`` plus
    ``2 n_cluster`` nodes clustered geometrically at ``|c/a| = 1``, mirrored by
    symmetry; ``n_beta`` uniform nodes of ``log(b/a)`` on
    ``[log 0.02, 0]``.  Disk cache: ``lowmodel.cache.cache_dir("ellipse_friction")``.
    """
    n_uniform = checks.count("n_uniform", n_uniform, 9)  # integers, not bools or floats
    n_cluster = checks.count("n_cluster", n_cluster, 1)
    n_beta = checks.count("n_beta", n_beta, 4)
    params = {"n_uniform": n_uniform, "n_cluster": n_cluster, "n_beta": n_beta,
              "b_over_a_range": list(B_OVER_A_RANGE)}
    path = cache_dir("ellipse_friction") / f"map-{parameter_hash(params, _MAP_VERSION)}.npz"
    start = time.perf_counter()
    if use_cache and path.exists():
        try:
            with np.load(path) as data:
                arrays = tuple(np.array(data[name])
                               for name in ("phi", "log_b_over_a", "force", "moment", "loss_direction"))
            return FrictionMap(*arrays, build_time_s=time.perf_counter() - start, from_cache=True)
        except (OSError, KeyError, ValueError):
            pass  # unreadable entry: rebuild below
    arrays = _build_table(n_uniform, n_cluster, n_beta)
    table = FrictionMap(*arrays, build_time_s=time.perf_counter() - start, from_cache=False)
    if use_cache:
        tmp = path.with_name(f"{path.stem}.{os.getpid()}.tmp.npz")  # unique per process, then atomic rename
        np.savez(tmp, phi=table.phi, log_b_over_a=table.log_b_over_a, force=table.force,
                 moment=table.moment, loss_direction=table.loss_direction)
        tmp.replace(path)
    return table


_ACTIVE: list = []  # [(phi nodes, log b/a nodes, cell centres x, y, coefficients (cells, 3, 16))] of the default map


def _active_patches():
    if not _ACTIVE:
        table = friction_map()
        _, mid_x, mid_y, coefficients = _patches(table)
        flat = np.ascontiguousarray(coefficients.reshape(mid_x.size * mid_y.size, 3, 16))
        _ACTIVE.append((table.phi, table.log_b_over_a, mid_x, mid_y, flat))
    return _ACTIVE[0]


def _evaluate(phi: np.ndarray, beta: np.ndarray):
    """(force, d force/d phi, moment, d moment/d phi, loss_direction, d loss_direction/d phi).

    ``phi`` and ``beta`` arrays of the same shape; evaluates the bicubic patch of the cell of each point.
    """
    nodes_x, nodes_y, mid_x, mid_y, flat = _active_patches()
    shape = np.shape(phi)
    x = np.ravel(phi)
    y = np.log(np.ravel(beta))
    i = np.searchsorted(nodes_x, x) - 1
    np.clip(i, 0, mid_x.size - 1, out=i)
    j = np.searchsorted(nodes_y, y) - 1
    np.clip(j, 0, mid_y.size - 1, out=j)
    dx = x - mid_x[i]
    dy = y - mid_y[j]
    ones = np.ones_like(dx)
    power_x = np.stack([ones, dx, dx * dx, dx * dx * dx], axis=1)                  # (n, 4)
    slope_x = np.stack([0.0 * dx, ones, 2.0 * dx, 3.0 * dx * dx], axis=1)
    power_y = np.stack([ones, dy, dy * dy, dy * dy * dy], axis=1)
    basis = np.stack([(power_x[:, :, None] * power_y[:, None, :]).reshape(-1, 16),
                      (slope_x[:, :, None] * power_y[:, None, :]).reshape(-1, 16)], axis=2)  # (n, 16, 2)
    values = flat[i * mid_y.size + j] @ basis                                      # (n, 3, 2)
    return [values[:, q, d].reshape(shape) for q in range(3) for d in range(2)]


def patch_table():
    """The bicubic patches of the default map as plain arrays, for compiled kernels that evaluate them
    (:mod:`lowmodel.linear_bearing.ball_kernels`): ``(phi nodes, log(b/a) nodes, cell centres in phi, cell
    centres in log(b/a), coefficients (cells, 3, 16))``, cell ``(i, j)`` at row ``i * len(centres in log(b/a)) + j``,
    coefficient ``4 p + q`` multiplying ``dphi^p dlog(b/a)^q`` of (force, moment, loss direction); read-only."""
    return _active_patches()


def log_ratio_cells(b_over_a):
    """The ``log(b/a)`` cells of the map and the powers ``(1, dy, dy^2, dy^3)`` of the offset ``dy`` from their
    centres, for axis ratios ``b_over_a`` (any shape, checked in ``[0.02, 1]``): ``(cells (shape), powers
    (shape + (4,)))``, what :func:`friction_angle_at` computes once per set of axis ratios."""
    beta = _check_ratio(b_over_a)
    _, nodes_y, _, mid_y, _ = _active_patches()
    y = np.log(beta.ravel())
    j = np.clip(np.searchsorted(nodes_y, y) - 1, 0, mid_y.size - 1)
    dy = y - mid_y[j]
    powers = np.stack([np.ones_like(dy), dy, dy * dy, dy * dy * dy], axis=1)
    return j.reshape(beta.shape), powers.reshape(beta.shape + (4,))


def friction_angle_at(b_over_a, *, stacked: bool = False):
    """:func:`friction_angle` for fixed axis ratios, for solvers that call it many times.

    ``b_over_a`` (any shape, in ``[0.02, 1]``) is checked once and its table cells and powers of
    ``log(b/a)`` are computed once.  Returns ``evaluate(phi)`` -> ``(force, d force/d phi, moment,
    d moment/d phi, loss)`` for finite ``phi`` [rad] of the shape of ``b_over_a`` (not checked: the
    caller's Newton iterates are finite); the same spline and values as :func:`friction_angle`
    (lin2019 eqs A4-A6 tabulated).  With ``stacked=True``, ``evaluate(phi)`` returns one array of shape
    ``b_over_a.shape + (3, 2)``: (force, moment, loss) x (value, d/d phi) (``d loss/d phi`` included).

    One batched product per call (the cost of a Newton step of a ball chain is mostly numpy call
    overhead): the bicubic patch of each point, ``(3, 16)`` coefficients, times the ``(16, 2)`` basis
    ``(dphi^p, p dphi^(p-1)) dlog(b/a)^q``.
    """
    beta = _check_ratio(b_over_a)
    nodes_x, nodes_y, mid_x, mid_y, flat = _active_patches()
    shape = beta.shape
    y = np.log(beta.ravel())
    j = np.clip(np.searchsorted(nodes_y, y) - 1, 0, mid_y.size - 1)
    dy = y - mid_y[j]
    power_y = np.stack([np.ones_like(dy), dy, dy * dy, dy * dy * dy], axis=1)[:, None, :]  # (m, 1, 4)
    count, last = y.size, mid_x.size - 1
    two_pi = 2.0 * math.pi
    exponents = np.arange(1.0, 4.0)  # d dphi^p / d dphi = p dphi^(p-1), p = 1..3

    def table(phi):
        x = np.remainder(np.ravel(phi) + math.pi, two_pi) - math.pi  # [-pi, pi), as friction_angle
        i = np.searchsorted(nodes_x, x)
        i -= 1  # >= 0: the nodes reach beyond -pi
        np.minimum(i, last, out=i)  # x = NaN sorts last
        basis = np.empty((count, 4, 4, 2))  # (m, p, q, value | slope)
        powers = np.empty((count, 4))  # 1, dphi, dphi^2, dphi^3
        powers[:, 0] = 1.0
        np.subtract(x, mid_x[i], out=powers[:, 1])
        np.multiply(powers[:, 1], powers[:, 1], out=powers[:, 2])
        np.multiply(powers[:, 2], powers[:, 1], out=powers[:, 3])
        np.multiply(powers[:, :, None], power_y, out=basis[..., 0])
        basis[:, 0, :, 1] = 0.0
        np.multiply((exponents * powers[:, :3])[:, :, None], power_y, out=basis[:, 1:, :, 1])
        i *= mid_y.size
        i += j
        return (flat[i] @ basis.reshape(count, 16, 2)).reshape(shape + (3, 2))

    if stacked:
        return table

    def evaluate(phi):
        values = table(phi)
        return values[..., 0, 0], values[..., 0, 1], values[..., 1, 0], values[..., 1, 1], values[..., 2, 0]

    return evaluate


def friction(c_over_a, b_over_a) -> EllipseFriction:
    """Normalised friction force, moment and loss of a Hertz ellipse (lin2019 eqs A4-A7), tabulated.

    Parameters
    ----------
    c_over_a : array_like, velocity-centre offset ``c/a`` along the major axis
        (``c`` of lin2019 eq 2); any real value, ``+-inf`` for pure sliding.
    b_over_a : array_like in ``[0.02, 1]``, axis ratio; broadcast with ``c_over_a``.

    Returns
    -------
    EllipseFriction (normalisation and signs in its docstring and the module
    docstring): ``force -> -sign(c/a)`` and ``moment -> 0`` as
    ``|c/a| -> inf``; ``force = 0``, ``moment = (3/8) E(e)`` at ``c/a = 0``.
    Values and ``d/d(c/a)`` come from one C2 bicubic spline of the table
    (:func:`friction_map`), so the derivatives are exactly those of the
    returned values (Newton converges quadratically on them).
    """
    kappa = _check_kappa(c_over_a)
    beta = _check_ratio(b_over_a)
    kappa, beta = np.broadcast_arrays(kappa, beta)
    lam = np.arctan(kappa)
    force, dforce, moment, dmoment, direction, ddirection = _evaluate(lam, beta)
    cos = np.cos(lam)
    sin = np.sin(lam)
    finite = np.isfinite(kappa)
    cos2 = cos**2
    with np.errstate(divide="ignore", invalid="ignore"):
        loss = np.where(finite, direction / np.where(finite, cos, 1.0), np.inf)
        dloss = np.where(finite, ddirection * cos + direction * sin, -force)
    return EllipseFriction(force, moment, loss, dforce * cos2, dmoment * cos2, dloss)


def friction_velocity(spin_velocity, slide_velocity, b_over_a) -> SlipFriction:
    """Friction of a Hertz ellipse from its slip velocities; finite as ``omega -> 0``.

    Parameters
    ----------
    spin_velocity : array_like [m/s], ``omega_i a_i`` (``omega_i`` of lin2019 eq 2).
    slide_velocity : array_like [m/s], ``omega_i c_i`` = slip of the ball
        relative to the groove at the contact centre along ``z_i``
        (the numerator of ``c_i`` in lin2019 eq 2).
    b_over_a : array_like in ``[0.02, 1]``.  All three broadcast.

    Returns
    -------
    SlipFriction: ``f_{i,z} = mu F force``, ``M_{i,O} = mu F a moment``,
    ``P_{f,i} = mu F loss`` (see its docstring), with partial derivatives in
    both velocities.  Same table and spline as :func:`friction`;
    ``force = sgn(omega) force(c/a)`` etc., continuous through ``omega = 0``
    where ``force = -sign(slide_velocity)`` (pure sliding, lin2019 eq 12).
    """
    spin = np.asarray(checks.finite("spin_velocity", spin_velocity, "m/s"))
    slide = np.asarray(checks.finite("slide_velocity", slide_velocity, "m/s"))
    beta = _check_ratio(b_over_a)
    spin, slide, beta = np.broadcast_arrays(spin, slide, beta)
    phi = np.arctan2(slide, spin)
    force, dforce, moment, dmoment, direction, ddirection = _evaluate(phi, beta)
    speed = np.hypot(spin, slide)  # no overflow of spin^2 + slide^2 for huge velocities
    speed = np.where(speed > SLIP_FLOOR, speed, 0.0)  # below: at rest (1/speed of the derivatives overflows)
    safe = np.where(speed > 0.0, speed, 1.0)
    cos, sin = spin / safe, slide / safe  # (cos phi, sin phi)
    dphi_dspin = np.where(speed > 0.0, -sin / safe, 0.0)
    dphi_dslide = np.where(speed > 0.0, cos / safe, 0.0)
    loss = speed * direction
    dloss_dspin = np.where(speed > 0.0, cos * direction - sin * ddirection, 0.0)
    dloss_dslide = np.where(speed > 0.0, sin * direction + cos * ddirection, 0.0)
    return SlipFriction(force, moment, loss,
                        dforce * dphi_dspin, dforce * dphi_dslide,
                        dmoment * dphi_dspin, dmoment * dphi_dslide,
                        dloss_dspin, dloss_dslide)


def friction_angle(slip_angle, b_over_a) -> AngleFriction:
    """Friction of a Hertz ellipse as a smooth function of the slip-direction angle ``phi``.

    Parameters
    ----------
    slip_angle : array_like [rad], ``phi = atan2(omega c, omega a)``, any real value
        (periodic, period ``2 pi``); ``phi = arctan(c/a)`` for ``omega > 0`` and
        ``phi = +-pi/2`` for pure sliding (``omega = 0``).
    b_over_a : array_like in ``[0.02, 1]``; broadcast with ``slip_angle``.

    Returns
    -------
    AngleFriction: ``force``, ``moment``, ``loss`` per unit slip scale and their
    ``d/d phi`` from the same C2 spline as :func:`friction`.  Symmetries:
    ``force(phi + pi) = -force(phi)``, ``moment(phi + pi) = -moment(phi)``,
    ``loss(phi + pi) = loss(phi)``; ``loss = cos(phi) moment - sin(phi) force``
    (power balance, to map accuracy).
    """
    phi = np.asarray(checks.finite("slip_angle", slip_angle, "rad"))
    beta = _check_ratio(b_over_a)
    if phi.shape != beta.shape:
        phi, beta = np.broadcast_arrays(phi, beta)
    wrapped = np.remainder(phi + math.pi, 2.0 * math.pi) - math.pi   # [-pi, pi)
    force, dforce, moment, dmoment, loss, dloss = _evaluate(wrapped, beta)
    return AngleFriction(force, moment, loss, dforce, dmoment, dloss)
