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

:func:`frictionless_statics` solves the same statics at a given total axial load ``F_a``, below or past the
preload loss: the nut shift ``u`` is the root of the axial balance ``F_a(u) = F_a`` (brentq on a bracket grown
from zero), each ball's centre balances its normal forces at that ``u``, and a contact whose approach is not
positive carries nothing (eq 53's ``max(0, delta_i)``: past the preload loss the ball runs in two-point contact on
SL-NR).  The actual contact angles follow from ``e_i = (s_u cos beta_i, s_w sin beta_i)`` (eq 37).  In the
one-ball nominal limit past the preload loss the ball centre lies on the line through the arc centres of the
loaded diagonal, so its two forces are equal and opposite along it, and the axial balance gives
``F = F_a / (sin beta cos alpha)`` with ``beta`` the diagonal's actual contact angle (the check of the solve, tests).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, root

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw.contacts import CONTACT_NAMES, ON_NUT, SIGN_U, SIGN_W, BallContacts

__all__ = ["PreloadLoss", "preload_loss", "nominal_preload_loss", "FrictionlessState", "frictionless_statics",
           "STATICS_TOLERANCE"]

# relative tolerance of the checks of frictionless_statics: each ball's force balance against its largest force,
# the axial balance against the axial load
STATICS_TOLERANCE = 1e-9


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


def _balanced(contacts: BallContacts, shift: float, guess: np.ndarray, scale: float | None = None) -> np.ndarray:
    """The ball centres (n, 2) [m] at which each ball's frictionless normal forces balance, nut shift ``shift``;
    ``scale`` [m] the length the solve works in (default: the oversize, at least 1 nm)."""
    scale = max(contacts.module.oversize, 1e-9) if scale is None else scale
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
            raise ConvergenceError("preload: the frictionless ball centre does not balance its normal forces",
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


@dataclass(frozen=True)
class FrictionlessState:
    """The frictionless statics of a set of balls at a total axial load (:func:`frictionless_statics`); arrays of
    shape (n, 4) in (SL, SR, NR, NL).

    axial_load : N, the axial load the state carries (positive as in lowmodel.screw.b2b's ``axial_load``)
    nut_shift : m, the nut's axial shift against the screw
    centres : (n, 2) m, the ball centres in ``(x3, z3)``
    approach : m, ``delta_i`` (eq 53; not positive: the contact is open)
    normal_force : N, ``F_i = max(0, delta_i / C_i)^(3/2)``
    contact_angle : rad, the actual contact angle ``beta_i`` of eq 37 (of the open contacts too: the direction to
        their arc centre)
    force_residual : the worst ball's ``|sum_i F_i e_i|`` over its largest force (checked against
        :data:`STATICS_TOLERANCE`)
    load_residual : ``|F_a(u) - F_a|`` over ``F_a``, or over the largest contact force's axial component where it is
        larger (a load far below the preload); ``|F_a(u)|`` at zero load; checked against :data:`STATICS_TOLERANCE`
    """

    axial_load: float
    nut_shift: float
    centres: np.ndarray
    approach: np.ndarray
    normal_force: np.ndarray
    contact_angle: np.ndarray
    force_residual: float
    load_residual: float

    @property
    def loaded(self) -> np.ndarray:
        """(n, 4) bool: the contacts that carry load."""
        return self.normal_force > 0.0


def frictionless_statics(contacts: BallContacts, axial_load: float) -> FrictionlessState:
    """The frictionless statics of the balls of ``contacts`` under the total ``axial_load`` [N] (>= 0), below or past
    the preload loss (module docstring; lin2019 eqs 37, 48, 53; contacts unload where ``delta_i <= 0``).

    The nut shift is the root of the axial balance (scipy.optimize.brentq on a bracket doubled from the oversize);
    the answer is checked before it is returned: each ball's force balance and the axial load balance within
    :data:`STATICS_TOLERANCE` (relative), else ConvergenceError naming the check.  ValueError for a negative or
    non-finite load, or one that needs a nut shift beyond a tenth of the ball radius (outside the small-strain
    Hertz law)."""
    axial_load = float(checks.non_negative("axial_load", axial_load, "N"))
    module = contacts.module
    n = contacts.n_balls
    # the length the solves work in: the oversize, or the approach of a nominal contact under the load per ball
    per_ball = axial_load / max(n, 1) / (math.sin(module.nominal_angle) * math.cos(module.lead_angle))
    scale = max(module.oversize, float(np.max(contacts.hertz_constant)) * per_ball ** (2.0 / 3.0), 1e-9)
    guess = np.zeros((n, 2))

    def state(shift):
        centres = _balanced(contacts, shift, guess, scale)
        guess[:] = centres
        approach, forces, e = _forces(contacts, centres, shift)
        return centres, approach, forces, e

    probe = 1e-3 * scale
    _, _, forces, e = state(probe)
    sign = 1.0 if _axial(contacts, forces, e) > 0.0 else -1.0
    guess[:] = 0.0
    if axial_load == 0.0:
        shift = 0.0
    else:
        def excess(s):
            _, _, f, e = state(sign * s)
            return _axial(contacts, f, e) - axial_load

        high = scale
        while excess(high) < 0.0:
            high *= 2.0
            if high > 0.1 * module.ball_radius:
                raise ValueError(f"axial_load {axial_load!r} N needs a nut shift beyond 0.1 ball_radius "
                                 f"({0.1 * module.ball_radius!r} m): outside the small-strain Hertz law (eq 53)")
        guess[:] = 0.0
        shift = brentq(excess, 0.0, high, xtol=1e-13 * scale, rtol=4.0 * np.finfo(float).eps, maxiter=200)
    centres, approach, forces, e = state(sign * shift)
    # the checks that define the answer
    balance = np.sqrt(np.sum(np.sum(forces[..., None] * e, axis=1) ** 2, axis=-1))
    largest = np.max(forces, axis=1)
    force_residual = float(np.max(np.where(largest > 0.0, balance / np.where(largest > 0.0, largest, 1.0), balance)))
    if not force_residual <= STATICS_TOLERANCE:
        raise ConvergenceError("frictionless_statics: a ball's normal forces do not balance (sum_i F_i e_i = 0, "
                               "relative to its largest force)", residual=force_residual, iterations=1,
                               tolerance=STATICS_TOLERANCE, reason="ball force balance")
    carried = _axial(contacts, forces, e)
    # over the load, or the largest axial component of a contact force where the preload dwarfs it (the shift is
    # found to round-off of the oversize: a load far below the preload forces cannot be met to 1e-9 of itself)
    axial_scale = float(np.max(forces)) * math.sin(module.nominal_angle) * math.cos(module.lead_angle)
    load_residual = abs(carried - axial_load) / max(axial_load, axial_scale) if axial_load > 0.0 else abs(carried)
    if not load_residual <= STATICS_TOLERANCE:
        raise ConvergenceError("frictionless_statics: the screw flanks' axial force does not carry the axial load "
                               "(relative to it, or to the largest contact force's axial part)",
                               residual=load_residual, iterations=1,
                               tolerance=STATICS_TOLERANCE, reason="axial load balance")
    angle = np.arctan2(SIGN_W * e[..., 1], SIGN_U * e[..., 0])
    return FrictionlessState(axial_load, sign * shift, centres, approach, forces, angle, force_residual,
                             load_residual)
