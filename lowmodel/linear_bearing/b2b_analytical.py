"""Analytical ball-to-ball (B2B) contact model of a four-point linear ball bearing (lin2019 Sec 2.3-2.4).

Closed forms, vectorised with numpy broadcasting:

* :func:`velocity_deviation`  -- eq 22, deviation ``epsilon`` of a ball's centre
  velocity from ``v/2`` (``v_B = (1 + epsilon) v / 2``, eq 21), from the four
  contact-angle deviations and the diagonal contact forces ``F_U`` (BL/TR pair)
  and ``F_D`` (BR/TL pair);
* :func:`diagonal_forces`     -- Sec 2.4.1, ``F_U, F_D`` from the external loads
  ``N_y, N_x`` on the top groove (``sqrt(2)/2 (N_y -+ N_x)`` at 45 deg);
* :func:`side_force_deviation` -- eq 33, ``epsilon`` of the Sec 2.4.1 case study
  (bottom groove ``-Delta beta_BL = Delta beta_BR = theta``, side-force ratio
  ``rho = N_x / N_y``);
* :func:`contact_force`       -- eq 30, the B2B contact force ``F_B2B`` of two
  balls that touch and approach;
* :func:`friction_loss`       -- eqs 31-32, ``P_fB2B = mu F_B2B v / cos(beta_0)``;
* :func:`mitigating_top_deviations` -- Sec 2.3.2 insight (3) / Sec 2.4.2:
  ``Delta beta_TR = Delta beta_BL``, ``Delta beta_TL = Delta beta_BR`` makes
  ``epsilon = 0`` for any load;
* :func:`two_ball_case`       -- the whole two-ball case of Sec 2.4 (eqs 22, 30, 32).

Conventions: SI units (rad, N, m, m/s, W).  Contact order ``(BL, BR, TR, TL)``
as lin2017 Fig 2 / docs/developing.md.  Ball 1 is the ball behind (Fig 1): it
carries ``N_x = rho N_y``, ball 2 carries ``-N_x`` (Sec 2.4.1, Fig 7); B2B
contact needs ``epsilon_1 > epsilon_2`` (ball 1 faster).
``k_f`` (slope of the linearised friction force, eq 14) and ``Psi`` (eq 15)
are inputs: :data:`K_F_PAPER` is the paper's 1.38,
``lowmodel.contact.ellipse_friction.k_f_exact`` / ``k_f_least_squares`` compute it,
``lowmodel.contact.hertz.psi_constant`` computes ``Psi``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks

__all__ = [
    "K_F_PAPER",
    "velocity_deviation",
    "diagonal_forces",
    "side_force_deviation",
    "contact_force",
    "friction_loss",
    "mitigating_top_deviations",
    "two_ball_case",
    "TwoBallCase",
]

K_F_PAPER = 1.38  # lin2019 Sec 2.3.2, "k_f = 1.38 is picked" from Fig 5
NOMINAL_CONTACT_ANGLE = 0.25 * math.pi  # beta_0 of the lin2019 case studies [rad]


# --------------------------------------------------------------------------
# input checks (lowmodel.checks; arrays, since the inputs broadcast)
# --------------------------------------------------------------------------
def _contact_forces(name: str, value) -> np.ndarray:
    return np.asarray(checks.positive(name, value, "N", note="four-point contact needs all four contact forces "
                                                             "positive"))


# --------------------------------------------------------------------------
# single ball
# --------------------------------------------------------------------------
def velocity_deviation(delta_beta, force_up, force_down,
                       nominal_contact_angle=NOMINAL_CONTACT_ANGLE) -> np.ndarray:
    """Ball-centre velocity deviation ``epsilon`` (lin2019 eq 22), ``v_B = (1 + epsilon) v/2``.

    Parameters
    ----------
    delta_beta : array_like (..., 4) [rad], contact-angle deviations
        ``Delta beta_i = beta_i - beta_0`` (eq 18) in the order (BL, BR, TR, TL).
    force_up : array_like [N], ``F_U ~ F_BL ~ F_TR`` (> 0).
    force_down : array_like [N], ``F_D ~ F_BR ~ F_TL`` (> 0).
    nominal_contact_angle : ``beta_0`` [rad] in (0, pi/2).

    Returns
    -------
    epsilon, dimensionless, broadcast shape of ``delta_beta[..., 0]``, the forces and ``beta_0``.
    Valid for small ``|Delta beta_i + Delta eta_i|`` and four-point contact (Sec 2.3.2).
    """
    deviations = np.asarray(checks.finite("delta_beta", delta_beta))
    if deviations.shape[-1:] != (4,):
        raise ValueError(f"delta_beta must have a last axis of length 4 (BL, BR, TR, TL), got shape {deviations.shape}")
    up = _contact_forces("force_up", force_up) ** (2.0 / 3.0)
    down = _contact_forces("force_down", force_down) ** (2.0 / 3.0)
    beta0 = np.asarray(checks.contact_angle("nominal_contact_angle", nominal_contact_angle))
    return _epsilon(*np.moveaxis(deviations, -1, 0), up, down, beta0)


def _epsilon(bl, br, tr, tl, up, down, beta0):
    """lin2019 eq 22 without input checks; ``up``, ``down`` are F_U^(2/3), F_D^(2/3)."""
    return (1.0 - np.cos(2.0 * beta0)) * ((-bl + tr) * up + (-br + tl) * down) / (2.0 * (up + down))


def diagonal_forces(normal_load, side_load, nominal_contact_angle=NOMINAL_CONTACT_ANGLE):
    """Diagonal contact forces ``(F_U, F_D)`` of one ball from the top-groove loads (lin2019 Sec 2.4.1).

    ``F_U = (N_y / cos(beta_0) - N_x / sin(beta_0)) / 2`` (BL/TR pair),
    ``F_D = (N_y / cos(beta_0) + N_x / sin(beta_0)) / 2`` (BR/TL pair), which at
    ``beta_0 = 45 deg`` are the paper's ``sqrt(2)/2 (N_y -+ N_x)``; the contact-angle
    deviations are neglected (the analytical model's approximation (iii)).

    Parameters: ``normal_load`` N_y [N] (> 0), ``side_load`` N_x [N], ``beta_0`` [rad].
    Raises ValueError when a diagonal loses contact (``|N_x| >= N_y tan(beta_0)``).
    """
    n_y = np.asarray(checks.positive("normal_load", normal_load, "N"))
    n_x = np.asarray(checks.finite("side_load", side_load))
    beta0 = np.asarray(checks.contact_angle("nominal_contact_angle", nominal_contact_angle))
    return _diagonal(n_y, n_x, beta0)


def _diagonal(n_y, n_x, beta0):
    vertical = 0.5 * n_y / np.cos(beta0)
    lateral = 0.5 * n_x / np.sin(beta0)
    up, down = vertical - lateral, vertical + lateral
    if not (np.all(up > 0.0) and np.all(down > 0.0)):
        raise ValueError("loss of four-point contact: |side_load| must be < normal_load * tan(nominal_contact_angle) "
                         f"(|rho| < {float(np.min(np.tan(beta0))):.6g})")
    return up, down


def side_force_deviation(theta, rho) -> np.ndarray:
    """``epsilon`` of the lin2019 Sec 2.4.1 case (eq 33): ball with ``N_x = rho N_y``, ``beta_0 = 45 deg``.

    Bottom-groove deviations ``Delta beta_BL = -theta``, ``Delta beta_BR = theta``,
    top groove exact.  ``epsilon_1 = side_force_deviation(theta, rho)`` for
    ball 1 and ``epsilon_2 = side_force_deviation(theta, -rho)`` for ball 2.
    ``theta`` [rad], ``rho`` in (-1, 1); dimensionless result.
    """
    theta = np.asarray(checks.finite("theta", theta))
    rho = np.asarray(checks.finite("rho", rho))
    if np.any(np.abs(rho) >= 1.0):
        raise ValueError("loss of four-point contact: rho = N_x/N_y must lie in (-1, 1) at beta_0 = 45 deg")
    ratio = ((1.0 + rho) / (1.0 - rho)) ** (2.0 / 3.0)
    return (1.0 - ratio) * theta / ((1.0 + ratio) * 2.0)  # lin2019 eq 33


def mitigating_top_deviations(delta_beta_bl, delta_beta_br):
    """Top-groove deviations ``(Delta beta_TR, Delta beta_TL) = (Delta beta_BL, Delta beta_BR)``.

    With them eq 22 gives ``epsilon = 0`` for every load (lin2019 Sec 2.3.2
    insight (3), Sec 2.4.2), so no two balls approach and ``F_B2B = 0``.  [rad]
    """
    return (np.array(checks.finite("delta_beta_bl", delta_beta_bl)),
            np.array(checks.finite("delta_beta_br", delta_beta_br)))


# --------------------------------------------------------------------------
# two balls
# --------------------------------------------------------------------------
def contact_force(epsilon_1, epsilon_2, forces_1, forces_2, *, k_f, friction_coefficient, psi,
                  ball_radius, nominal_contact_angle=NOMINAL_CONTACT_ANGLE, touching=True) -> np.ndarray:
    """B2B contact force ``F_B2B`` [N] (lin2019 eq 30).

    ``F_B2B = 2 k_f mu R_B^(2/3) / (Psi (1 - cos 2 beta_0)) * S_1 S_2 / (S_1 + S_2) * (epsilon_1 - epsilon_2)``
    with ``S_j = F_jU^(2/3) + F_jD^(2/3)``, when the balls touch
    (``d_12 <= 2 R_B``) and ball 1 (behind) is faster (``epsilon_1 > epsilon_2``);
    zero otherwise (eq 9).

    Parameters
    ----------
    epsilon_1, epsilon_2 : velocity deviations of ball 1 (behind) and ball 2 (eq 22).
    forces_1, forces_2 : pairs ``(F_U, F_D)`` [N] of each ball (> 0).
    k_f : slope of the linearised friction force (eq 14), > 0.
    friction_coefficient : ``mu`` (>= 0).
    psi : ``Psi`` of eq 15 [(m^2/N)^(1/3)], > 0.
    ball_radius : ``R_B`` [m], > 0.
    nominal_contact_angle : ``beta_0`` [rad].
    touching : bool array_like, ``d_12 <= 2 R_B``.
    """
    eps_1 = np.asarray(checks.finite("epsilon_1", epsilon_1))
    eps_2 = np.asarray(checks.finite("epsilon_2", epsilon_2))
    s_1 = sum(_contact_forces("forces_1", f) ** (2.0 / 3.0) for f in forces_1)
    s_2 = sum(_contact_forces("forces_2", f) ** (2.0 / 3.0) for f in forces_2)
    k_f = np.asarray(checks.positive("k_f", k_f, ""))
    mu = np.asarray(checks.non_negative("friction_coefficient", friction_coefficient, ""))
    psi = np.asarray(checks.positive("psi", psi, "(m^2/N)^(1/3)"))
    radius = np.asarray(checks.positive("ball_radius", ball_radius, "m"))
    beta0 = np.asarray(checks.contact_angle("nominal_contact_angle", nominal_contact_angle))
    return _force(eps_1, eps_2, s_1, s_2, k_f, mu, psi, radius, beta0, np.asarray(touching, dtype=bool))


def _force(eps_1, eps_2, s_1, s_2, k_f, mu, psi, radius, beta0, touching):
    """lin2019 eq 30 without input checks; ``s_j = F_jU^(2/3) + F_jD^(2/3)``."""
    force = (2.0 * k_f * mu * radius ** (2.0 / 3.0) / (psi * (1.0 - np.cos(2.0 * beta0)))
             * s_1 * s_2 / (s_1 + s_2) * (eps_1 - eps_2))
    return np.where((eps_1 > eps_2) & touching, force, 0.0)


def friction_loss(b2b_force, friction_coefficient, groove_velocity,
                  nominal_contact_angle=NOMINAL_CONTACT_ANGLE) -> np.ndarray:
    """B2B sliding friction loss ``P_fB2B = mu F_B2B v / cos(beta_0)`` [W] (lin2019 eqs 31-32).

    ``b2b_force`` [N] >= 0, ``groove_velocity`` v [m/s] of the top groove (its
    magnitude is used), ``beta_0`` [rad].  Eq 31 takes the sliding speed at the B2B
    contact as ``v / cos(beta_0)`` (both balls rolling about x at ``beta_0``).
    """
    force = np.asarray(checks.non_negative("b2b_force", b2b_force, "N"))
    mu = np.asarray(checks.non_negative("friction_coefficient", friction_coefficient, ""))
    speed = np.abs(np.asarray(checks.finite("groove_velocity", groove_velocity)))
    beta0 = np.asarray(checks.contact_angle("nominal_contact_angle", nominal_contact_angle))
    return mu * force * speed / np.cos(beta0)  # lin2019 eq 32


@dataclass(frozen=True)
class TwoBallCase:
    """Result of :func:`two_ball_case` (arrays of the broadcast shape).

    epsilon_1, epsilon_2 : velocity deviations of ball 1 (behind) and 2 (eq 22)
    ball_velocity_1, ball_velocity_2 : ``(1 + epsilon_j) v/2`` before contact [m/s] (eq 21)
    b2b_force : ``F_B2B`` [N] (eq 30, touching balls)
    b2b_friction_loss : ``P_fB2B`` [W] (eq 32)
    common_velocity : velocity of both balls in contact [m/s]: ``(1 + epsilon_1 + Delta epsilon_1) v/2``
        (eq 29), equal to the free velocity of each ball when they separate
    """

    epsilon_1: np.ndarray
    epsilon_2: np.ndarray
    ball_velocity_1: np.ndarray
    ball_velocity_2: np.ndarray
    b2b_force: np.ndarray
    b2b_friction_loss: np.ndarray
    common_velocity: np.ndarray


def two_ball_case(theta, rho, *, normal_load, groove_velocity, friction_coefficient, psi, ball_radius,
                  k_f=K_F_PAPER, delta_beta_top=(0.0, 0.0),
                  nominal_contact_angle=NOMINAL_CONTACT_ANGLE) -> TwoBallCase:
    """Two touching balls of the lin2019 Sec 2.4 setup (Fig 7) by the analytical model.

    Bottom groove ``Delta beta_BL = -theta``, ``Delta beta_BR = theta``; top
    groove ``delta_beta_top = (Delta beta_TR, Delta beta_TL)`` (case (b) of Table 2:
    ``(-theta, theta)``); ball 1 (behind) carries ``N_x = rho N_y``, ball 2
    ``-rho N_y``; contact forces from :func:`diagonal_forces`; eq 22 for
    ``epsilon``, eq 30 for ``F_B2B`` (balls touching), eq 32 for the loss.

    Parameters: ``theta`` [rad] and ``rho`` (broadcast), ``normal_load`` N_y [N],
    ``groove_velocity`` v [m/s], ``friction_coefficient`` mu, ``psi``
    [(m^2/N)^(1/3)], ``ball_radius`` [m], ``k_f``, ``delta_beta_top`` pair of
    array_like [rad] broadcasting with theta, ``nominal_contact_angle`` [rad].
    """
    theta = np.asarray(checks.finite("theta", theta))
    rho = np.asarray(checks.finite("rho", rho))
    n_y = np.asarray(checks.positive("normal_load", normal_load, "N"))
    v = np.asarray(checks.finite("groove_velocity", groove_velocity))
    mu = np.asarray(checks.non_negative("friction_coefficient", friction_coefficient, ""))
    psi = np.asarray(checks.positive("psi", psi, "(m^2/N)^(1/3)"))
    radius = np.asarray(checks.positive("ball_radius", ball_radius, "m"))
    k_f = np.asarray(checks.positive("k_f", k_f, ""))
    beta0 = np.asarray(checks.contact_angle("nominal_contact_angle", nominal_contact_angle))
    top_tr, top_tl = (np.asarray(checks.finite("delta_beta_top", value)) for value in delta_beta_top)
    side = rho * n_y
    powers = [f ** (2.0 / 3.0) for f in (*_diagonal(n_y, side, beta0), *_diagonal(n_y, -side, beta0))]
    # (BL, BR, TR, TL) = (-theta, theta, top_tr, top_tl) for both balls
    epsilon_1 = _epsilon(-theta, theta, top_tr, top_tl, powers[0], powers[1], beta0)   # ball 1: N_x = rho N_y
    epsilon_2 = _epsilon(-theta, theta, top_tr, top_tl, powers[2], powers[3], beta0)   # ball 2: N_x = -rho N_y
    s_1 = powers[0] + powers[1]
    s_2 = powers[2] + powers[3]
    force = _force(epsilon_1, epsilon_2, s_1, s_2, k_f, mu, psi, radius, beta0, True)
    loss = mu * force * np.abs(v) / np.cos(beta0)  # lin2019 eq 32
    # common velocity (eqs 25-29): Delta epsilon_1 = -F_B2B / (C S_1), Delta epsilon_2 = +F_B2B / (C S_2)
    # with C the prefactor of eq 30, so the contact velocity is the S-weighted mean of the free ones
    common = (s_1 * epsilon_1 + s_2 * epsilon_2) / (s_1 + s_2)
    return TwoBallCase(epsilon_1, epsilon_2, (1.0 + epsilon_1) * 0.5 * v, (1.0 + epsilon_2) * 0.5 * v,
                       force, loss, np.where(force > 0.0, (1.0 + common) * 0.5 * v, np.nan))
