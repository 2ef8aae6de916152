"""The ball-screw B2B module of lin2019 Sec 3.3 from a :class:`BallScrewCase`: the friction increase in the paper's
percent, and the preload fitted on a printed B2B force.

The models are lowmodel's: the balls' contacts ``lowmodel.screw.b2b.contacts(case)`` (eqs 34-53), their free and
touching states ``lowmodel.bearing_results.screw_states`` (eqs 54-61).  Two readings the paper leaves open
(docs/ball_screw.md): the preload (Table 4 gives none: the oversize is fitted, :func:`fit_oversize`) and the
deviation (the case's ``reading``).
"""
from __future__ import annotations

from functools import lru_cache

from scipy.optimize import brentq

from ballbench.lowmodel.bearing_results import screw_states
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.state import friction_increase as increase_fraction
from ballbench.validation.cases.case import BallScrewCase

__all__ = ["two_ball", "friction_increase", "fit_oversize"]


def two_ball(case: BallScrewCase, oversize: float | None = None, reading: str | None = None, contact_law=None):
    """(free balls, touching balls) of ``case`` at the preload ``oversize`` [m] (default: the screw's), the deviation
    ``reading`` (default: the case's) and the calibrated ``contact_law`` of the grooves (None: Hertz)."""
    contacts = screw_b2b.contacts(case, oversize=oversize, reading=reading, contact_law=contact_law)
    return screw_states(case, contacts)


def friction_increase(free, state) -> float:
    """Friction increase by B2B contact [%]: total loss of the touching balls over the free balls' loss."""
    return 100.0 * increase_fraction(state, free)


@lru_cache(maxsize=8)
def fit_oversize(case: BallScrewCase, b2b_force: float, reading: str | None = None, contact_law=None) -> float:
    """Preload (oversize [m]) at which the touching balls of ``case`` press on each other with ``b2b_force`` [N]
    (brentq on [1e-6, 3e-6] m, xtol 1e-12 m; the fit of cases.lin2019.OVERSIZE_FIT)."""
    return float(brentq(lambda oversize: two_ball(case, oversize, reading, contact_law)[1].b2b_force[0] - b2b_force,
                        1.0e-6, 3.0e-6, xtol=1e-12))
