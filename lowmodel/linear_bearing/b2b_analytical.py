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
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing.fourpoint import contact_limits

__all__ = [
    "K_F_PAPER",
    "velocity_deviation",
    "diagonal_forces",
    "side_force_deviation",
    "contact_force",
    "friction_loss",
    "mitigating_top_deviations",
    "two_ball_case",
    "from_case",
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
    checks.contact_angle("contact angles beta_0 + delta_beta", beta0[..., None] + deviations)
    return _epsilon(*np.moveaxis(deviations, -1, 0), up, down, beta0)


def _epsilon(bl, br, tr, tl, up, down, beta0):
    """lin2019 eq 22 without input checks; ``up``, ``down`` are F_U^(2/3), F_D^(2/3)."""
    return _geometric(beta0) * _weighted(bl, br, tr, tl, up, down)


def _geometric(beta0):
    """``1 - cos(2 beta_0)`` of eqs 22 and 30, written ``2 sin^2(beta_0)`` (no cancellation at small beta_0)."""
    return 2.0 * np.sin(beta0) ** 2


def _weighted(bl, br, tr, tl, up, down):
    """eq 22 divided by ``1 - cos(2 beta_0)``."""
    return ((-bl + tr) * up + (-br + tl) * down) / (2.0 * (up + down))


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
    sin, cos = np.sin(beta0), np.cos(beta0)
    # four-point contact |N_x| < N_y tan(beta_0), tested without dividing (beta_0 near 0 or 90 deg)
    if not np.all(np.abs(n_x) * cos < n_y * sin):
        with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
            limit = float(np.min(np.tan(beta0)))
        raise ValueError("loss of four-point contact: |side_load| must be < normal_load * tan(nominal_contact_angle) "
                         f"(|rho| < {limit:.6g})")
    with np.errstate(over="ignore"):
        vertical = 0.5 * n_y / cos
        lateral = 0.5 * n_x / sin  # |lateral| < vertical by the test above
    if not np.all(np.isfinite(vertical)):
        raise ValueError(f"nominal_contact_angle = {float(np.max(beta0))!r} rad is too close to pi/2 for normal_load = "
                         f"{float(np.max(n_y))!r} N: the diagonal forces N_y / (2 cos(beta_0)) overflow (lin2019 Sec "
                         "2.4.1); beta_0 must lie in (0, pi/2) with N_y / cos(beta_0) finite")
    return vertical - lateral, vertical + lateral


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
                  ball_radius, nominal_contact_angle=NOMINAL_CONTACT_ANGLE, touching=True,
                  groove_velocity=1.0) -> np.ndarray:
    """B2B contact force ``F_B2B`` [N] (lin2019 eq 30).

    ``F_B2B = 2 k_f mu R_B^(2/3) / (Psi (1 - cos 2 beta_0)) * S_1 S_2 / (S_1 + S_2) * |epsilon_1 - epsilon_2|``
    with ``S_j = F_jU^(2/3) + F_jD^(2/3)``, when the balls touch
    (``d_12 <= 2 R_B``) and approach; zero otherwise (eq 9).  Ball 1 sits behind
    ball 2 along +z, so with the top groove moving along +z (``groove_velocity > 0``,
    the paper's case) they approach when ``epsilon_1 > epsilon_2``; moving along -z
    (``groove_velocity < 0``: ball velocities ``(1 + epsilon_j) v/2 < 0``) they
    approach when ``epsilon_2 > epsilon_1`` (the mirror image of eq 30); at ``v = 0``
    nothing moves and the force is zero.

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
    groove_velocity : v [m/s] of the top groove; only its sign (direction of motion) is used.
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
    direction = np.sign(checks.finite("groove_velocity", groove_velocity, "m/s"))
    geometric = _geometric(beta0)
    if np.any(geometric <= 0.0):
        raise ValueError(f"nominal_contact_angle must be well inside (0, pi/2) rad: 1 - cos(2 beta_0) of eq 30 "
                         f"underflows to 0 at beta_0 = {float(np.min(beta0))!r}")
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        difference = (eps_1 - eps_2) / geometric
        force = _force(difference, s_1, s_2, k_f, mu, psi, radius, np.asarray(touching, dtype=bool), direction)
    if not np.all(np.isfinite(force)):
        raise ValueError(f"nominal_contact_angle must lie in (0, pi/2) rad with (epsilon_1 - epsilon_2) / (1 - cos 2 "
                         f"beta_0) of eq 30 finite: at beta_0 = {float(np.min(beta0))!r} rad F_B2B overflows (the "
                         "epsilons of eq 22 carry the factor 1 - cos 2 beta_0: pass epsilons of that beta_0)")
    return force


def _force(difference, s_1, s_2, k_f, mu, psi, radius, touching, direction):
    """lin2019 eq 30 without input checks; ``difference = (epsilon_1 - epsilon_2) / (1 - cos 2 beta_0)``,
    ``s_j = F_jU^(2/3) + F_jD^(2/3)``, ``direction = sign(v)``.

    The approach rate of ball 1 (behind) on ball 2 is ``(epsilon_1 - epsilon_2) v/2``.
    """
    approach = difference * direction
    force = 2.0 * k_f * mu * radius ** (2.0 / 3.0) / psi * s_1 * s_2 / (s_1 + s_2) * approach
    return np.where((approach > 0.0) & touching, force, 0.0)


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
    return _loss(mu, force, speed, beta0)


def _loss(mu, force, speed, beta0):
    """lin2019 eq 32 without input checks; ValueError where ``1 / cos(beta_0)`` overflows it (beta_0 near 90 deg)."""
    with np.errstate(over="ignore", invalid="ignore"):
        loss = mu * force * speed / np.cos(beta0)  # lin2019 eq 32
    if not np.all(np.isfinite(loss)):
        raise ValueError(f"nominal_contact_angle = {float(np.max(beta0))!r} rad: the B2B loss mu F_B2B v / cos(beta_0) "
                         "of eq 32 overflows; beta_0 must lie in (0, pi/2) with that loss finite")
    return loss


@dataclass(frozen=True)
class TwoBallCase:
    """Result of :func:`two_ball_case` (arrays of the broadcast shape).

    epsilon_1, epsilon_2 : velocity deviations of ball 1 (behind) and 2 (eq 22)
    ball_velocity_1, ball_velocity_2 : ``(1 + epsilon_j) v/2`` before contact [m/s] (eq 21)
    b2b_force : ``F_B2B`` [N] (eq 30, touching balls)
    b2b_friction_loss : ``P_fB2B`` [W] (eq 32)
    common_velocity : ``(1 + (S_1 epsilon_1 + S_2 epsilon_2)/(S_1 + S_2)) v/2`` [m/s], the S-weighted mean
        of the free velocities: where ``b2b_force > 0`` it is the velocity of both balls in contact,
        ``(1 + epsilon_1 + Delta epsilon_1) v/2`` (eqs 25-29); where the balls separate they share no
        velocity (see ``final_velocity_1/2``) and it is only that mean
    final_velocity_1, final_velocity_2 : velocity of each ball with the B2B contact resolved [m/s]:
        ``common_velocity`` where ``b2b_force > 0``, the free velocity ``ball_velocity_j`` otherwise
    """

    epsilon_1: np.ndarray
    epsilon_2: np.ndarray
    ball_velocity_1: np.ndarray
    ball_velocity_2: np.ndarray
    b2b_force: np.ndarray
    b2b_friction_loss: np.ndarray
    common_velocity: np.ndarray
    final_velocity_1: np.ndarray
    final_velocity_2: np.ndarray


def two_ball_case(theta, rho, *, normal_load, groove_velocity, friction_coefficient, psi, ball_radius,
                  k_f=K_F_PAPER, delta_beta_top=(0.0, 0.0),
                  nominal_contact_angle=NOMINAL_CONTACT_ANGLE) -> TwoBallCase:
    """Two touching balls of the lin2019 Sec 2.4 setup (Fig 7) by the analytical model.

    Bottom groove ``Delta beta_BL = -theta``, ``Delta beta_BR = theta``; top
    groove ``delta_beta_top = (Delta beta_TR, Delta beta_TL)`` (case (b) of Table 2:
    ``(-theta, theta)``); ball 1 (behind) carries ``N_x = rho N_y``, ball 2
    ``-rho N_y``; contact forces from :func:`diagonal_forces`; eq 22 for
    ``epsilon``, eq 30 for ``F_B2B`` (balls touching), eq 32 for the loss.
    The direction of motion is honoured (``groove_velocity < 0``: ball 2 is behind,
    see :func:`contact_force`).  Validity: four-point contact of both balls at their
    actual contact angles ``beta_0 + (-theta, theta, Delta beta_TR, Delta beta_TL)``,
    i.e. each in (0, pi/2) and ``rho`` inside the lin2017 eq 37 range for ball 1 and
    ``-rho`` for ball 2 (:func:`lowmodel.linear_bearing.fourpoint.contact_limits`); ValueError otherwise.

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
    top_tr, top_tl = _top_pair(delta_beta_top)
    _check_four_point(theta, rho, top_tr, top_tl, beta0)
    side = rho * n_y
    powers = [f ** (2.0 / 3.0) for f in (*_diagonal(n_y, side, beta0), *_diagonal(n_y, -side, beta0))]
    # (BL, BR, TR, TL) = (-theta, theta, top_tr, top_tl) for both balls
    weighted_1 = _weighted(-theta, theta, top_tr, top_tl, powers[0], powers[1])   # ball 1: N_x = rho N_y
    weighted_2 = _weighted(-theta, theta, top_tr, top_tl, powers[2], powers[3])   # ball 2: N_x = -rho N_y
    epsilon_1 = _geometric(beta0) * weighted_1  # lin2019 eq 22
    epsilon_2 = _geometric(beta0) * weighted_2
    s_1 = powers[0] + powers[1]
    s_2 = powers[2] + powers[3]
    force = _force(weighted_1 - weighted_2, s_1, s_2, k_f, mu, psi, radius, True, np.sign(v))  # eq 30
    loss = _loss(mu, force, np.abs(v), beta0)  # lin2019 eq 32
    # common velocity (eqs 25-29): Delta epsilon_1 = -F_B2B / (C S_1), Delta epsilon_2 = +F_B2B / (C S_2)
    # with C the prefactor of eq 30, so the contact velocity is the S-weighted mean of the free ones
    common = (1.0 + (s_1 * epsilon_1 + s_2 * epsilon_2) / (s_1 + s_2)) * 0.5 * v
    free_1, free_2 = (1.0 + epsilon_1) * 0.5 * v, (1.0 + epsilon_2) * 0.5 * v
    pressed = force > 0.0
    return TwoBallCase(epsilon_1, epsilon_2, free_1, free_2, force, loss, common,
                       np.where(pressed, common, free_1), np.where(pressed, common, free_2))


def from_case(case, *, k_f=K_F_PAPER, psi=None) -> TwoBallCase:
    """:func:`two_ball_case` of a :class:`lowmodel.bearing.GuideLoadCase` (bottom deviations ``(-theta, +theta)``,
    its top deviations, nominal contact angle, load, speed and friction): ``psi`` (eq 15) from the exact Hertz
    contact of its groove (:func:`lowmodel.contact.hertz.psi_constant`) unless given, the paper's ``k_f`` = 1.38
    unless given."""
    guide = case.guide
    if psi is None:
        psi = hertz.psi_constant(hertz.groove_geometry(guide), guide.ball_radius)
    return two_ball_case(case.theta, case.side_force_ratio, normal_load=case.vertical_force,
                         groove_velocity=guide.groove_velocity, friction_coefficient=guide.friction_coefficient,
                         psi=psi, ball_radius=guide.ball_radius, k_f=k_f, delta_beta_top=case.top_deviations,
                         nominal_contact_angle=guide.nominal_angle)


def _top_pair(delta_beta_top):
    """``(Delta beta_TR, Delta beta_TL)`` from a pair of array_like [rad]; ValueError unless exactly two."""
    if isinstance(delta_beta_top, np.ndarray):
        pair = list(delta_beta_top) if delta_beta_top.ndim >= 1 else [delta_beta_top]
    else:
        try:
            pair = list(delta_beta_top)
        except TypeError:
            pair = [delta_beta_top]
    if len(pair) != 2:
        raise ValueError("delta_beta_top must be a pair (Delta beta_TR, Delta beta_TL) [rad], "
                         f"got {len(pair)} entries")
    return checks.finite("delta_beta_top", pair[0], "rad"), checks.finite("delta_beta_top", pair[1], "rad")


def _check_four_point(theta, rho, top_tr, top_tl, beta0) -> None:
    """ValueError unless both balls keep four-point contact at their actual angles (lin2017 eq 37).

    Ball 1 needs ``rho`` and ball 2 ``-rho`` inside the eq 37 range
    ``(-min(tan beta_BL, tan beta_TR), min(tan beta_BR, tan beta_TL))``; for the pair
    this is ``|rho| < tan(min_i beta_i)`` (tan rises on (0, pi/2)), the fast test used
    here; the message quotes :func:`lowmodel.linear_bearing.fourpoint.contact_limits`.
    """
    # worst case over the whole batch first (reductions only): the common case needs no elementwise tan
    theta_max = float(np.max(np.abs(theta)))
    low_all = float(np.min(beta0)) - max(theta_max, float(np.max(-top_tr)), float(np.max(-top_tl)))
    high_all = float(np.max(beta0)) + max(theta_max, float(np.max(top_tr)), float(np.max(top_tl)))
    if 0.0 < low_all and high_all < 0.5 * math.pi and float(np.max(np.abs(rho))) < math.tan(low_all):
        return
    spread = np.maximum(np.abs(theta), np.maximum(np.abs(top_tr), np.abs(top_tl)))
    low = beta0 - np.maximum(np.abs(theta), np.maximum(-top_tr, -top_tl))
    high = beta0 + np.maximum(np.abs(theta), np.maximum(top_tr, top_tl))
    if not (np.all(low > 0.0) and np.all(high < 0.5 * math.pi)):
        angles = np.stack(np.broadcast_arrays(beta0 - theta, beta0 + theta, beta0 + top_tr, beta0 + top_tl), axis=-1)
        checks.contact_angle("contact angles beta_0 + (-theta, theta, delta_beta_top) (theta, delta_beta_top)",
                             angles)
    bad = ~(np.abs(rho) < np.tan(low))
    if np.any(bad):
        shape = np.broadcast_shapes(bad.shape, np.shape(spread))
        bad = np.broadcast_to(bad, shape)
        index = np.unravel_index(np.argmax(bad), shape)
        pick = [float(np.broadcast_to(value, shape)[index]) for value in (theta, rho, top_tr, top_tl, beta0)]
        angles = np.array([pick[4] - pick[0], pick[4] + pick[0], pick[4] + pick[2], pick[4] + pick[3]])
        lower, upper = contact_limits(angles)  # lin2017 eq 37
        raise ValueError(
            "rho: loss of four-point contact (lin2017 eq 37 at the actual contact angles); ball 1 carries "
            f"N_x/N_y = rho = {pick[1]:.6g} and ball 2 -rho, both must lie in ({float(lower):.6g}, "
            f"{float(upper):.6g}) = (-min(tan beta_BL, tan beta_TR), min(tan beta_BR, tan beta_TL)) "
            f"at theta = {math.degrees(pick[0]):.6g} deg")
