"""The stick/slip rung of a case of one's own (docs/b2b_rolling.md, 'Validity of full slip'): lin2019's two-ball
module of a linear-guide or ball-screw case solved with stick/slip ball-to-groove contacts (the steady rolling solve
of :mod:`lowmodel.contact.rolling_friction` on two half-spaces) and with lin2019's full slip (eqs A4-A7) on the same
cells, touching and apart (:func:`lowmodel.linear_bearing.b2b_rolling.module_b2b`,
:func:`lowmodel.screw.b2b_rolling.module_b2b`; each solve checks its power balance to 1e-6).

Hertz pressure on ``CELLS[fidelity]`` cells per contact (along x across the ellipse); the map of full slip's
validity ran on 8 x 32 (docs/b2b_rolling.md), the rolling-b2b scenes on 12 x 48.
"""
from __future__ import annotations

from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase

__all__ = ["CELLS", "module", "drive_speed"]

CELLS = {"quick": (8, 32), "default": (12, 48), "fine": (16, 64)}


def drive_speed(case) -> float:
    """The speed the friction is read against: the carriage's [m/s] (force = power / speed) or the nut's [rad/s]
    (torque = power / speed)."""
    return abs(case.guide.groove_velocity) if isinstance(case, LinearGuideCase) else abs(case.screw.nut_speed)


def module(case, fidelity: str):
    """Both laws on the case's balls: a RollingModuleB2B (guide) or ScrewRollingModule (screw) with ``touching``,
    ``free`` (stick/slip) and ``full_slip``, ``full_slip_free`` on the same cells."""
    cells = CELLS[fidelity]
    if isinstance(case, LinearGuideCase):
        from ballbench.lowmodel.linear_bearing import b2b_rolling
        from ballbench.validation.studies import bearing_results

        guide = case.guide
        contacts = bearing_results.guide_contacts(case)
        balls = [b2b_rolling.hertz_contacts(contacts, j, cells=cells, conformity=guide.conformity,
                                            **guide.material.keywords) for j in range(contacts.n_balls)]
        return b2b_rolling.module_b2b(balls, ball_radius=guide.ball_radius,
                                      friction_coefficient=guide.friction_coefficient,
                                      groove_velocity=guide.groove_velocity)
    if isinstance(case, BallScrewCase):
        from ballbench.lowmodel.screw import b2b_rolling
        from ballbench.validation.studies import screw_two_ball

        contacts = screw_two_ball.ball_contacts(case)
        _, touching = screw_two_ball.two_ball(case)
        balls = [b2b_rolling.hertz_contacts(touching, contacts, j, cells=cells)
                 for j in range(len(case.deviations))]
        return b2b_rolling.module_b2b(balls, screw_two_ball.screw_module(case.screw))
    raise TypeError(f"the stick/slip rung runs on a LinearGuideCase or BallScrewCase, got {type(case).__name__}")
