"""Frictionless statics of one ball of a ball-screw module: the reference of the FE screw module's contact forces.

The FE module (``fem.screw_module``) is frictionless; its four contact forces (SL, SR, NR, NL) are judged
against rigid grooves with Hertz contacts and no friction (:func:`hertz_statics`, lin2019 eqs 48 and 53), against
the three rigid equations the module must satisfy, computed from the low-order model's rigid flank normals
(:func:`statics_residual`, eq 37), and against the half-turn symmetry of a ball without deviation
(:func:`half_turn_asymmetry`).  The geometry and Hertz constants are those of the low-order model's contacts
(``lowmodel.screw.ball.BallContacts``); none of its friction enters.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import fsolve

from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["hertz_statics", "statics_residual", "half_turn_asymmetry"]


def hertz_statics(contacts, ball: int, axial_load: float) -> np.ndarray:
    """Frictionless reference forces (SL, SR, NR, NL) [N] of one ball: rigid grooves with Hertz contacts.

    Unknowns: ball centre ``(x3, z3)`` and nut shift ``u``; ``F_i = (delta_i / C_i)^(3/2)`` with
    ``delta_i = |p_B - C_i| + R_B + oversize - r_g`` (lin2019 eq 53, nut arc centres shifted by ``(0, u cos alpha)``,
    eq 48) and the ball's equilibrium without friction in x3 and z3 plus the screw's axial push ``axial_load`` [N].
    The same geometry and Hertz constants as the low-order model, none of its friction: the FE's reference.
    Solved by MINPACK (scipy fsolve); ConvergenceError if the residual exceeds ``1e-8 axial_load``."""
    module = contacts.module
    centres = contacts.arc_centres[ball]
    constant = contacts.hertz_constant[ball]
    cos_a = math.cos(module.lead_angle)
    r_g, radius = module.groove_radius, module.ball_radius

    def forces(z):
        p, u = z[:2] * 1e-6, z[2] * 1e-6
        c = centres.copy()
        c[2:, 1] += u * cos_a
        d = p - c
        dist = np.linalg.norm(d, axis=1)
        delta = np.maximum(dist + radius + module.oversize - r_g, 0.0)
        return (delta / constant) ** 1.5, d / dist[:, None]

    def residual(z):
        f, e = forces(z)
        on_ball = -(f[:, None] * e)
        return [on_ball[:, 0].sum(), on_ball[:, 1].sum(), on_ball[:2, 1].sum() * cos_a - axial_load]

    z, info, _, message = fsolve(residual, np.zeros(3), full_output=True, xtol=1e-13)
    # judged by the residual, not by fsolve's flag: with xtol 1e-13 MINPACK may stop with "not making good
    # progress" at a residual of 4e-12 N (case b, ball 1), a converged point
    if max(abs(r) for r in residual(z)) > 1e-8 * axial_load:
        raise ConvergenceError(f"hertz_statics: {message}", residual=float(np.max(np.abs(residual(z)))),
                               iterations=int(info["nfev"]), tolerance=1e-8 * axial_load)
    return forces(z)[0]


def statics_residual(contacts, ball: int, forces, axial_load: float) -> np.ndarray:
    """(3,) N: residuals of one ball's frictionless statics with the contact forces ``forces`` (SL, SR, NR, NL) [N]
    acting along the rigid flank normals of the low-order model (lin2019 eq 37, ``contacts.contact_angles``):
    ball equilibrium along x3 and z3, and the screw's axial push on the ball (screw contacts, along the screw axis
    ``z_hat = (0, sin alpha, cos alpha)`` in CS3) minus the ball's axial share ``axial_load`` [N].

    The FE module's three rigid equations (``fem.screw_module``) in independent form: computed from the low-order
    model's angles and the given share, not from the FE geometry.  Zero to the solver tolerance for a right
    module; a load on the wrong sign or ball, a flank at the wrong angle or a swapped screw/nut contact is not."""
    forces = np.asarray(forces, dtype=float)
    angles = contacts.contact_angles[ball]
    sign_u, sign_w = np.array([-1.0, -1.0, 1.0, 1.0]), np.array([-1.0, 1.0, 1.0, -1.0])
    on_ball = -forces[:, None] * np.column_stack([sign_u * np.cos(angles), sign_w * np.sin(angles)])  # (x3, z3)
    cos_a = math.cos(contacts.module.lead_angle)
    return np.array([on_ball[:, 0].sum(), on_ball[:, 1].sum(), on_ball[:2, 1].sum() * cos_a - axial_load])


def half_turn_asymmetry(forces) -> float:
    """Relative asymmetry ``max(|F_SL - F_NR|, |F_SR - F_NL|) / max F`` of a ball's forces (SL, SR, NR, NL) [N].
    With all four flanks at one angle (theta = 0) and no friction the module is symmetric under the half turn
    about y3 that maps screw onto nut (SL <-> NR, SR <-> NL); its statics alone (x3 and z3 balance) force the
    equality, whatever the bodies' stiffness."""
    forces = np.asarray(forces, dtype=float)
    return float(max(abs(forces[0] - forces[2]), abs(forces[1] - forces[3])) / forces.max())
