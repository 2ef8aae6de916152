"""The ball-screw B2B module of lin2019 Sec 3.3 from a :class:`BallScrewCase`: balls free and touching, the
friction increase, and the preload fitted on a printed B2B force.

Models: lowmodel.screw.ball (eqs 34-55), lowmodel.screw.b2b (eqs 56-61).  Two readings the paper
leaves open (docs/ball_screw.md): the preload (Table 4 gives none: the oversize is fitted, :func:`fit_oversize`)
and the deviation (the case's ``reading``).
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np

from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases.case import BallScrew, BallScrewCase
from ballbench.lowmodel.state import friction_increase as increase_fraction

__all__ = ["screw_module", "ball_contacts", "two_ball", "friction_increase", "fit_oversize"]


def screw_module(screw: BallScrew, oversize: float | None = None) -> screw_contacts.ScrewModule:
    """The low-order module of ``screw`` with the preload ``oversize`` [m] (default: the screw's own)."""
    screw.need("conformity", "material", "friction_coefficient", "nut_speed",
               by="the ball-screw module (lowmodel.screw.ball)")
    return screw_contacts.screw_module(ball_radius=screw.ball_radius, conformity=screw.conformity,
                                   pitch_radius=screw.pitch_radius, lead=screw.lead,
                                   nominal_angle=screw.nominal_angle, nut_speed=screw.nut_speed,
                                   friction_coefficient=screw.friction_coefficient,
                                   oversize=screw.oversize if oversize is None else oversize,
                                   **screw.material.keywords)


def ball_contacts(case: BallScrewCase, oversize: float | None = None, reading: str | None = None,
                  contact_law=None) -> screw_contacts.BallContacts:
    """Contacts of the case's balls (lowmodel.screw.ball.ball_contacts); ``contact_law``: calibrated laws
    of the grooves (:class:`screw_contacts.GrooveContactLaws`), None: Hertz."""
    return screw_contacts.ball_contacts(screw_module(case.screw, oversize), np.array(case.deviations),
                                    reading=case.reading if reading is None else reading, contact_law=contact_law)


def two_ball(case: BallScrewCase, oversize: float | None = None, reading: str | None = None, contact_law=None):
    """(free balls, touching balls) of ``case`` at the preload ``oversize`` [m] (default: the screw's)."""
    contacts = ball_contacts(case, oversize, reading, contact_law)
    free = screw_b2b.solve(contacts, case.axial_load, with_b2b=False)
    state = screw_b2b.solve(contacts, case.axial_load)
    return free, state


def friction_increase(free, state) -> float:
    """Friction increase by B2B contact [%]: total loss of the touching balls over the free balls' loss."""
    return 100.0 * increase_fraction(state, free)


@lru_cache(maxsize=8)
def fit_oversize(case: BallScrewCase, b2b_force: float, reading: str | None = None, contact_law=None) -> float:
    """Preload (oversize [m]) at which the touching balls of ``case`` press on each other with ``b2b_force`` [N]
    (brentq on [1e-6, 3e-6] m, xtol 1e-12 m; the fit of cases.lin2019.OVERSIZE_FIT)."""
    from scipy.optimize import brentq

    return float(brentq(lambda oversize: two_ball(case, oversize, reading, contact_law)[1].b2b_force[0] - b2b_force,
                        1.0e-6, 3.0e-6, xtol=1e-12))
