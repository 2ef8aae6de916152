"""Independent residual of lin2019 eqs 1-8 at a state, from raw inputs and adaptive quadrature.

Nothing here calls ``ballbench.lowmodel``.  Given the ball motion a model returns
(``v_B``, ``omega_x``, ``omega_y`` of each ball) and its B2B forces, this module
re-evaluates every term of the ball equilibrium from the paper's equations:

* Hertz semi-axes of each contact from ``E, nu, R_B``, conformity and the normal
  force, by Johnson's relations with the Legendre integrals of scipy
  (``ellipk``, ``ellipe``; the model uses Carlson's forms);
* normal forces from the loads by lin2017 eq 36 (statics of the ball);
* slip of each contact from the motion (lin2019 eqs 1-2);
* friction force and spin moment of each ellipse (eqs A4, A5 with A7) by adaptive
  Cartesian quadrature (scipy ``quad``; the model uses a tabulated map of a polar
  quadrature about the velocity centre);
* the B2B loads of eqs 5-8.

A model whose state leaves this residual above its tolerance solves a different
problem (wrong axis ratio, wrong E*, missing or mis-signed B2B friction, a wrong
friction map); the scene ``lin2019-b2b-residual`` uses it.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
from scipy import integrate
from scipy.optimize import brentq
from scipy.special import ellipe, ellipk

SIGN_X = np.array([-1.0, 1.0, 1.0, -1.0])  # (BL, BR, TR, TL), lin2017 Fig 2 / lin2019 Fig 2
SIGN_Y = np.array([-1.0, -1.0, 1.0, 1.0])
TOP = np.array([0.0, 0.0, 1.0, 1.0])


def normal_forces(side_force: float, vertical_force: float, angles) -> np.ndarray:
    """lin2017 eq 36: ``(F_BL, F_BR, F_TR, F_TL)`` [N] from ``N_x, N_y`` [N] on the top groove."""
    bl, br, tr, tl = angles
    bottom, top = math.sin(bl + br), math.sin(tl + tr)
    n_x, n_y = side_force, vertical_force
    return np.array([-(n_x * math.cos(br) - n_y * math.sin(br)) / bottom,
                     (n_x * math.cos(bl) + n_y * math.sin(bl)) / bottom,
                     -(n_x * math.cos(tl) - n_y * math.sin(tl)) / top,
                     (n_x * math.cos(tr) + n_y * math.sin(tr)) / top])


def groove_ellipse(force: float, ball_radius: float, conformity: float, youngs_modulus: float,
                   poisson_ratio: float) -> tuple[float, float]:
    """Semi-axes ``(a, b)`` [m] of a ball in a straight groove (Johnson 1985 eqs 4.36-4.39, Legendre form).

    ``B/A = ((a/b)^2 E(e) - K(e)) / (K(e) - E(e))``, ``a^3 = 3 F (K - E) / (2 pi e^2 E* A)``,
    ``A = (1/R_B - 1/(2 f R_B))/2`` across the groove, ``B = 1/(2 R_B)`` along it.
    """
    e_star = 1.0 / (2.0 * (1.0 - poisson_ratio**2) / youngs_modulus)
    big_a = 0.5 * (1.0 / ball_radius - 1.0 / (2.0 * conformity * ball_radius))
    big_b = 0.5 / ball_radius
    target = big_b / big_a

    def ratio(m):  # m = e^2
        k2 = 1.0 - m
        return (ellipe(m) / k2 - ellipk(m)) / (ellipk(m) - ellipe(m)) - target

    m = brentq(ratio, 1e-9, 1.0 - 1e-12, xtol=1e-15, rtol=1e-15)
    a = (3.0 * force * (ellipk(m) - ellipe(m)) / (2.0 * math.pi * m * e_star * big_a)) ** (1.0 / 3.0)
    return a, a * math.sqrt(1.0 - m)


def _disc_integral(function, kappa: float) -> float:
    """``iint p_hat function(t, s)`` over the unit disc, p_hat = (3/(2 pi)) sqrt(1 - t^2 - s^2).

    Substitutions ``t = sin(v)``, ``s = sqrt(1 - t^2) sin(u)`` take the square-root edges of the
    pressure out of the integrand (``sqrt(1 - t^2 - s^2) ds = (1 - t^2) cos^2(u) du``); the kink of the
    slip direction at the velocity centre ``(kappa, 0)`` is a break point of both integrals.
    """
    def inner(v):
        t = math.sin(v)
        width = 1.0 - t * t
        half = math.sqrt(width)
        value = integrate.quad(lambda u: math.cos(u) ** 2 * function(t, half * math.sin(u)), -0.5 * math.pi,
                               0.5 * math.pi, points=[0.0], epsabs=1e-11, epsrel=1e-9, limit=100)[0]
        return width * value * math.cos(v)

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        value = integrate.quad(inner, -0.5 * math.pi, 0.5 * math.pi,
                               points=[math.asin(kappa)] if abs(kappa) < 1.0 else None, epsabs=1e-10,
                               epsrel=1e-9, limit=100)[0]
    return 1.5 / math.pi * value


def ellipse_friction(kappa: float, beta: float) -> tuple[float, float]:
    """``(force, moment)`` of lin2019 eqs A4, A5 (normalised by ``mu F`` and ``mu F a``) for ``c/a = kappa``.

    ``force = iint p_hat (t - kappa)/D``, ``moment = iint p_hat (t^2 - kappa t + beta^2 s^2)/D``,
    ``D = sqrt((t - kappa)^2 + (beta s)^2)``; ``kappa = +-inf`` is pure sliding (force -+1, moment 0).
    """
    if not math.isfinite(kappa):
        return -math.copysign(1.0, kappa), 0.0

    def distance(t, s):
        return math.hypot(t - kappa, beta * s)

    force = _disc_integral(lambda t, s: (t - kappa) / distance(t, s) if distance(t, s) > 0 else 0.0, kappa)
    moment = _disc_integral(lambda t, s: (t * t - kappa * t + beta * beta * s * s) / distance(t, s)
                            if distance(t, s) > 0 else 0.0, kappa)
    return force, moment


def residual(state_velocity, state_omega, b2b_forces, *, angles, side_forces, vertical_force: float,
             ball_radius: float, conformity: float, friction_coefficient: float, groove_velocity: float,
             youngs_modulus: float, poisson_ratio: float):
    """Residual of lin2019 eqs 4 and 8 for ``n`` touching balls at a given motion, with independent terms.

    Parameters: ``state_velocity`` (n,) m/s, ``state_omega`` (n, 2) rad/s, ``b2b_forces`` (n-1,) N,
    ``angles`` (n, 4) rad, ``side_forces`` (n,) N, the rest scalars (SI).
    Returns ``(rows (n, 3) in units of mu max F_i, friction force on each contact (n, 4) [N],
    b2b_slip (n-1,) [m/s])``.  Rows: z force, moment about x / R_B, moment about y / R_B.
    """
    n = len(state_velocity)
    radius, mu = ball_radius, friction_coefficient
    forces = np.array([normal_forces(side_forces[j], vertical_force, angles[j]) for j in range(n)])
    reference = mu * forces.max()
    rows = np.zeros((n, 3))
    friction = np.zeros((n, 4))
    for j in range(n):
        beta = np.asarray(angles[j])
        nx, ny = SIGN_X * np.sin(beta), SIGN_Y * np.cos(beta)
        omega_x, omega_y = state_omega[j]
        for i in range(4):
            a, b = groove_ellipse(forces[j, i], radius, conformity, youngs_modulus, poisson_ratio)
            slide = state_velocity[j] - TOP[i] * groove_velocity + radius * (omega_x * ny[i] - omega_y * nx[i])  # eq 1
            spin = -(omega_x * nx[i] + omega_y * ny[i])  # eq 2, about the inward normal
            kappa = slide / (spin * a) if spin != 0.0 else math.copysign(math.inf, slide)
            force, moment = ellipse_friction(kappa, b / a)
            sign = math.copysign(1.0, spin) if spin != 0.0 else 1.0
            f = mu * forces[j, i] * sign * force  # eq A4
            m = mu * forces[j, i] * a * sign * moment  # eq A5, about -y_i
            friction[j, i] = f
            rows[j] += (f, ny[i] * f + nx[i] * m / radius, -nx[i] * f + ny[i] * m / radius)  # eq 4
    slips = np.zeros(n - 1)
    for j in range(n - 1):  # eqs 5-8
        dvx = radius * (state_omega[j, 1] + state_omega[j + 1, 1])
        dvy = -radius * (state_omega[j, 0] + state_omega[j + 1, 0])
        slip = math.hypot(dvx, dvy)
        slips[j] = slip
        fx, fy = (-mu * b2b_forces[j] * dvx / slip, -mu * b2b_forces[j] * dvy / slip) if slip > 0 else (0.0, 0.0)
        # moment of the B2B friction (+R_B z) x f on ball j and, with force and arm both flipped, on ball j+1
        rows[j] += (-b2b_forces[j], -fy, fx)
        rows[j + 1] += (b2b_forces[j], -fy, fx)
    return rows / reference, friction, slips
