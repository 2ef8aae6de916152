"""Preload loss of preloaded four-point ball-screw contacts: the axial load at which a contact of a ball unloads.

A ball preloaded by the oversize ``delta_0`` (every contact of a centred ball approaches by it; lin2019 eq 53,
docs/ball_screw.md) sits on two diagonals, SL-NR and SR-NL.  An axial load shifts the nut by ``u`` against the
screw: one diagonal approaches further, the other recedes, until a contact of the receding diagonal unloads,
the *preload loss*.  Beyond it the ball runs in two-point contact (SL-NR), where one contact rolls without spin
(race control, Jones 1960; Harris & Kotzalas, Rolling Bearing Analysis, ch. "ball spinning"): not the state of
lin2019's model, whose four contacts all slide (docs/ball_screw.md, "Preload loss").

:func:`preload_loss` solves the frictionless statics of the case's balls with the exact flank arcs and the Hertz
law of eq 53 (``F_i = (delta_i / C_i)^(3/2)``, ``delta_i = |p_B - C_i| + R_B + delta_0 - r_g``, the nut's arcs
shifted by ``(0, u cos alpha)``, eq 48): for a nut shift ``u`` each ball's centre balances its four normal forces
(``sum F_i e_i = 0`` in ``(x3, z3)``), and the axial load is the screw flanks' force along the screw axis (as in
lowmodel.screw.ball).  The preload loss is the smallest axial load at which an approach reaches zero.

For one nominal ball (no deviation) and a small oversize it has the closed form of a preloaded pair: along each
diagonal the ball centre balances ``F_S = F_N`` and the two approaches add up to ``2 delta_0 +- u cos alpha
sin beta_0``, so ``(C_S + C_N) F^(2/3) = 2 delta_0 +- s``; the receding diagonal unloads at ``s = 2 delta_0``,
where the loaded one carries ``F = (4 delta_0 / (C_S + C_N))^(3/2)`` (2^(3/2) times its preload force) and
the axial load is ``F sin beta_0 cos alpha`` (:func:`nominal_preload_loss`; the check of the solve, tests).
Friction is left out: lin2019's model with friction loses the contact at a slightly different load (friction
pushes the ball onto the unloading nut flank).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel.screw.contacts import CONTACT_NAMES, ON_NUT, BallContacts

__all__ = ["PreloadLoss", "preload_loss", "nominal_preload_loss"]


@dataclass(frozen=True)
class PreloadLoss:
    """The preload loss of a set of balls sharing one nut shift.

    axial_load : N, the total axial load on the screw at which the first contact unloads (0 without oversize)
    ball, contact : the ball (0-based) and the contact name (SL, SR, NR, NL) that unloads first
    nut_shift : m, the nut's axial shift against the screw there
    normal_forces : (n, 4) N, the frictionless normal forces at the preload loss
    """

    axial_load: float
    ball: int
    contact: str
    nut_shift: float
    normal_forces: np.ndarray


def nominal_preload_loss(contacts: BallContacts) -> float:
    """Closed form of the preload loss of ball 0 of ``contacts`` taken as nominal (module docstring) [N]:
    ``(4 delta_0 / (C_S + C_N))^(3/2) sin beta_0 cos alpha`` with ``C_S``, ``C_N`` of its SL and NR flanks."""
    module = contacts.module
    k = float(contacts.hertz_constant[0, 0] + contacts.hertz_constant[0, 2])
    return (4.0 * module.oversize / k) ** 1.5 * math.sin(module.nominal_angle) * math.cos(module.lead_angle)


def _forces(contacts: BallContacts, centres: np.ndarray, shift: float):
    """Approaches (n, 4) [m], forces (n, 4) [N] and unit vectors e_i (n, 4, 2) for ball centres (n, 2) [m]."""
    module = contacts.module
    arcs = contacts.arc_centres.copy()
    arcs[:, :, 1] += shift * math.cos(module.lead_angle) * ON_NUT
    d = centres[:, None, :] - arcs
    distance = np.sqrt(np.sum(d * d, axis=-1))
    e = d / distance[..., None]
    approach = distance + module.ball_radius + module.oversize - module.groove_radius
    forces = (np.maximum(approach, 0.0) / contacts.hertz_constant) ** 1.5
    return approach, forces, e


def _balanced(contacts: BallContacts, shift: float, guess: np.ndarray) -> np.ndarray:
    """The ball centres (n, 2) [m] at which each ball's frictionless normal forces balance, nut shift ``shift``."""
    from scipy.optimize import root

    from ballbench.lowmodel.errors import ConvergenceError

    scale = max(contacts.module.oversize, 1e-9)
    reference = float(np.max((scale / contacts.hertz_constant) ** 1.5))
    centres = np.empty_like(guess)
    for j in range(contacts.n_balls):
        ball = contacts.ball(j)

        def residual(x, ball=ball):
            _, f, e = _forces(ball, x[None, :] * scale, shift)
            return np.sum(f[0, :, None] * e[0], axis=0) / reference

        found = root(residual, guess[j] / scale, method="hybr", options={"xtol": 1e-13})
        error = float(np.max(np.abs(residual(found.x))))
        if error > 1e-9:
            raise ConvergenceError("preload_loss: the frictionless ball centre does not balance its normal forces",
                                   residual=error, iterations=int(found.nfev), tolerance=1e-9,
                                   reason="ball statics")
        centres[j] = found.x * scale
    return centres


def _axial(contacts: BallContacts, forces: np.ndarray, e: np.ndarray) -> float:
    """The screw flanks' force on the balls along the screw axis [N] (lowmodel.screw.ball's axial balance)."""
    screw = 1.0 - ON_NUT
    return float(np.sum(-forces * e[..., 1] * screw) * math.cos(contacts.module.lead_angle))


def preload_loss(contacts: BallContacts) -> PreloadLoss:
    """The preload loss of the balls of ``contacts`` under one nut shift (frictionless, exact flank arcs, eq 53;
    module docstring).  The load is positive in the sense of lowmodel.screw.b2b's ``axial_load``."""
    from scipy.optimize import brentq

    n = contacts.n_balls
    oversize = contacts.module.oversize
    guess = np.zeros((n, 2))

    def state(shift):
        centres = _balanced(contacts, shift, guess)
        guess[:] = centres
        approach, forces, e = _forces(contacts, centres, shift)
        return approach, forces, e

    # the sign of the nut shift that loads the screw along +axial_load
    probe = 1e-3 * oversize if oversize > 0.0 else 1e-6 * contacts.module.ball_radius
    _, forces, e = state(probe)
    sign = 1.0 if _axial(contacts, forces, e) > 0.0 else -1.0
    guess[:] = 0.0
    if oversize <= 0.0:  # no preload: the receding contacts are off under any load
        approach, forces, _ = state(sign * probe)
        j, i = np.unravel_index(int(np.argmin(approach)), approach.shape)
        return PreloadLoss(0.0, int(j), CONTACT_NAMES[int(i)], 0.0, np.zeros((n, 4)))

    def smallest(shift):
        return float(np.min(state(sign * shift)[0]))

    high = oversize
    while smallest(high) > 0.0:
        high *= 2.0
        if high > 1e3 * oversize:
            raise ValueError("contacts: no contact unloads under an axial nut shift of 1000 oversizes "
                             "(a flank geometry without a preload loss?)")
    guess[:] = 0.0
    shift = brentq(smallest, 0.0, high, xtol=1e-9 * oversize)
    approach, forces, e = state(sign * shift)
    j, i = np.unravel_index(int(np.argmin(approach)), approach.shape)
    return PreloadLoss(_axial(contacts, forces, e), int(j), CONTACT_NAMES[int(i)], sign * shift, forces)
