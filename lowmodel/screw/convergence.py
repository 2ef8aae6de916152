"""Tolerances and failure reasons of the ball-screw equilibrium solves (lin2019 eq 54 per ball, the axial balance,
eqs 60-61).

Tolerances (:func:`row_tolerances`):

The residual rows of :mod:`.ball` and :mod:`.b2b` are in units of ``mu F_ref``.  Three rows per ball
sum the normal contact forces as well as friction: the forces along ``x3`` and ``z3`` (the profile plane, where
the normal forces lie) and the axial balance.  Their round-off does not shrink with ``mu`` (the normal forces
are ``1 / mu`` in these units), so they get :func:`lowmodel.solvers.equilibrium_tolerance`; the rows of pure
friction (the force along ``y3``, the three moments) and the complementarity rows keep ``tolerance``, so the
kinematics (orbit and spin, set by friction) stay solved to ``tolerance`` in ``mu F_ref`` at any ``mu``.
docs/ball_screw.md ("Tolerances and failure reasons").

Reasons (:func:`stall_reason`): where a continuation of the solve stops, the reason is read from the last
converged state, not from the branch on which Newton happened to fail: a loaded contact sliding fully
(:func:`sliding_ratio` above :data:`FULL_SLIDING`) is lin2019's model running out of quasi-static states.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.solvers import equilibrium_tolerance

__all__ = ["row_tolerances", "row_weights", "MU_CONDITIONING", "NORMAL_FORCE_ROWS", "sliding_ratio", "stall_reason",
           "FULL_SLIDING"]

NORMAL_FORCE_ROWS = (0, 2)  # F_x3, F_z3 of the six rows of a ball (F_x3, F_y3, F_z3, M_x3, M_y3, M_z3 / R_B)


def row_tolerances(tolerance: float, *, friction_coefficient: float, groove_radius: float, ball_radius: float,
                   approach: float, balls: int, axial: int, extra: int = 0) -> np.ndarray:
    """Tolerances of the residual ``[6 rows per ball] + [axial rows] + [extra rows]`` (units ``mu F_ref``).

    ``approach`` [m] is the Hertz approach of ``F_ref`` (``Scales.length``); the lever of the round-off is the
    arc-centre distance ``groove_radius - ball_radius`` over it.  Equals ``tolerance`` everywhere while the
    round-off floor stays below it (lin2019 Table 4 at mu = 0.1: floor 1e-12 against the default 1e-10).
    """
    lever = (groove_radius - ball_radius) / approach
    normal = equilibrium_tolerance(tolerance, friction_coefficient, lever)
    per_ball = np.full(6, float(tolerance))
    per_ball[list(NORMAL_FORCE_ROWS)] = normal
    return np.concatenate([np.tile(per_ball, balls), np.full(axial, normal), np.full(extra, float(tolerance))])


MU_CONDITIONING = 0.1  # below this mu the normal-force rows are weighted by mu / MU_CONDITIONING in the steps


def row_weights(*, friction_coefficient: float, balls: int, axial: int, extra: int = 0) -> np.ndarray:
    """Weights of the same rows as :func:`row_tolerances` for the Newton steps (:func:`lowmodel.solvers.newton`).

    In units of ``mu F_ref`` the normal-force rows grow like ``1 / mu`` against the friction rows, and the
    normal equations of the Levenberg-Marquardt step square that: at mu = 1e-5 the friction rows stalled at
    ~2e-9.  Below ``MU_CONDITIONING`` those rows are weighted by ``mu / MU_CONDITIONING`` (the conditioning of
    mu = 0.1); at and above it every weight is 1 (the steps unchanged)."""
    weight = min(1.0, float(friction_coefficient) / MU_CONDITIONING)
    per_ball = np.ones(6)
    per_ball[list(NORMAL_FORCE_ROWS)] = weight
    return np.concatenate([np.tile(per_ball, balls), np.full(axial, weight), np.ones(extra)])


FULL_SLIDING = 10.0  # |c/a| above which a contact's friction is near its sliding limit mu F (lin2019 eqs A4-A7)


def sliding_ratio(normal_force, slip_minor, spin, semi_major) -> float:
    """Largest ``|c/a| = |slip_minor| / |spin a|`` over the loaded contacts (arrays of one shape, SI; inf at pure
    sliding, 0 if no contact is loaded): the slip against the spin of lin2019's ellipse friction (eq 14)."""
    loaded = np.asarray(normal_force) > 0.0
    spin = np.abs(np.asarray(spin) * np.asarray(semi_major))[loaded]
    slide = np.abs(np.asarray(slip_minor))[loaded]
    with np.errstate(divide="ignore"):
        return float(np.max(np.where(spin > 0.0, slide / np.where(spin > 0.0, spin, 1.0), np.inf), initial=0.0))


def stall_reason(normal_force, slip_minor, spin, semi_major, *, where: str) -> tuple[str, str]:
    """``(reason, detail)`` of a continuation that stopped ``where`` (e.g. "below oversize 9.1e-07 m"), from the
    contacts of its last converged state: ``"a contact slides fully"`` when the sliding ratio exceeds
    :data:`FULL_SLIDING`, else ``"continuation stalled"``; the detail gives the evidence (ratio, smallest loaded
    force)."""
    ratio = sliding_ratio(normal_force, slip_minor, spin, semi_major)
    force = np.asarray(normal_force, dtype=float)
    loaded = force[force > 0.0]
    lightest = float(loaded.min()) if loaded.size else 0.0
    evidence = (f"the last converged state {where} has |c/a| up to {ratio:.3g} and its lightest loaded contact "
                f"carries {lightest:.3g} N of {float(force.max(initial=0.0)):.3g} N")
    if ratio > FULL_SLIDING:
        return "a contact slides fully", (f"{evidence}: friction at its sliding limit mu F, no quasi-static state of "
                                          "lin2019's model found beyond (docs/ball_screw.md)")
    return "continuation stalled", evidence
