"""The stick/slip rung of a case of one's own (docs/b2b_rolling.md, 'Validity of full slip'): lin2019's two-ball
module of a linear-guide or ball-screw case solved with stick/slip ball-to-groove contacts (the steady rolling solve
of :mod:`lowmodel.contact.rolling_friction` on two half-spaces) and with lin2019's full slip (eqs A4-A7) on the same
cells, touching and apart (:func:`lowmodel.linear_bearing.b2b_rolling.module_b2b`,
:func:`lowmodel.screw.b2b_rolling.module_b2b`; each solve checks its power balance to 1e-6).

Hertz pressure on ``CELLS[fidelity]`` cells per contact (along x across the ellipse); the map of full slip's
validity ran on 8 x 32 (docs/b2b_rolling.md), the rolling-b2b scenes on 12 x 48.

:func:`compliance_rungs` adds the FE compliance of the case's own groove (a ball of the case's radius in a straight
groove of its conformity and material, P2, condensed onto one grid over every contact:
``studies.rolling_b2b.pair_compliance``, the levels of ``cases.stick_slip``), as the paper modules' ladders do.
"""
from __future__ import annotations

import time
from dataclasses import dataclass

from ballbench.lowmodel.bearing_results import screw_states
from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_rolling as screw_b2b_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases import stick_slip
from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
from ballbench.validation.studies import rolling_b2b

__all__ = ["CELLS", "COMPLIANCE", "module", "drive_speed", "ComplianceRung", "compliance_rungs"]

CELLS = {"quick": (8, 32), "default": (12, 48), "fine": (16, 64)}
# the FE compliance levels of a case's stick/slip rung per fidelity (cases.stick_slip.ComplianceLevel): none at the
# quick level (a condensation of the case's groove costs 1.5-3 min and 3-5 GB), the paper ladders' levels above
COMPLIANCE = {"quick": (), "default": stick_slip.LINEAR.compliance.default, "fine": stick_slip.LINEAR.compliance.fine}


def drive_speed(case) -> float:
    """The speed the friction is read against: the carriage's [m/s] (force = power / speed) or the nut's [rad/s]
    (torque = power / speed)."""
    return abs(case.guide.groove_velocity) if isinstance(case, LinearGuideCase) else abs(case.screw.nut_speed)


def module(case, fidelity: str):
    """Both laws on the case's balls: a RollingModuleB2B (guide) or ScrewRollingModule (screw) with ``touching``,
    ``free`` (stick/slip) and ``full_slip``, ``full_slip_free`` on the same cells (``CELLS[fidelity]`` per contact,
    two half-spaces)."""
    *_, balls_on, solve = _hertz_balls(case)
    return solve(balls_on(CELLS[fidelity], None))


@dataclass(frozen=True)
class ComplianceRung:
    """Stick/slip on one FE compliance level of the case's groove: ``level`` (a ``cases.stick_slip.ComplianceLevel``),
    ``ndofs`` of the condensed pair, ``fe`` the module (RollingModuleB2B / ScrewRollingModule, with full slip on the
    same cells) on the FE compliance, ``half_space`` the same module on the same grid with two half-spaces,
    ``condense_s`` / ``fe_s`` / ``half_space_s`` the wall times [s] (the condensation cached on disk)."""

    level: tuple
    ndofs: int
    fe: object
    half_space: object
    condense_s: float
    fe_s: float
    half_space_s: float


def _hertz_balls(case):
    """``(product, ball_radius, conformity, material, (along, across) largest Hertz semi-axes, balls_on(cells,
    operator), solve(balls))`` of the case's touching module: ``cells`` (along, across) per contact or one
    SurfaceGrid; ``operator`` None for two half-spaces."""
    if isinstance(case, LinearGuideCase):
        guide = case.guide
        contacts = b2b.contacts(case)
        along = float((contacts.semi_major * contacts.b_over_a).max())
        across = float(contacts.semi_major.max())

        def balls_on(cells, operator):
            return [b2b_rolling.hertz_contacts(contacts, j, cells=cells, guide=guide,
                                               operator_for=None if operator is None else (lambda _g: operator))
                    for j in range(contacts.n_balls)]

        def solve(balls):
            return b2b_rolling.module_b2b(balls, guide)

        return "linear", guide.ball_radius, guide.conformity, guide.material.pair, (along, across), balls_on, solve
    if isinstance(case, BallScrewCase):
        screw = case.screw
        contacts = screw_b2b.contacts(case)
        _, touching = screw_states(case, contacts)
        along = float((touching.semi_major * contacts.b_over_a).max())
        across = float(touching.semi_major.max())
        module_ = screw_contacts.module(screw)

        def balls_on(cells, operator):
            return [screw_b2b_rolling.hertz_contacts(touching, contacts, j, cells=cells,
                                                     operator_for=None if operator is None else (lambda _g: operator))
                    for j in range(len(case.deviations))]

        def solve(balls):
            return screw_b2b_rolling.module_b2b(balls, module_)

        return "screw", screw.ball_radius, screw.conformity, screw.material.pair, (along, across), balls_on, solve
    raise TypeError(f"the stick/slip rung runs on a LinearGuideCase or BallScrewCase, got {type(case).__name__}")


def compliance_rungs(case, fidelity: str, progress=lambda it, desc="": it) -> list[ComplianceRung]:  # noqa: ARG005 - Run.progress's signature
    """Stick/slip with Hertz's pressure on the FE compliance of the case's groove at each level of
    ``COMPLIANCE[fidelity]`` (none at quick, 8 x 32 cells at default, 6 x 24 and 8 x 32 at fine), and the same
    module on two half-spaces on the same grid.  The grid covers the case's largest Hertz semi-axes by the product's
    ``cover``."""
    product, radius, conformity, material, (along, across), balls_on, solve = _hertz_balls(case)
    levels = stick_slip.LEVELS[product]
    out = []
    for level in progress(COMPLIANCE[fidelity], desc="FE compliance levels"):
        half_along, half_across = levels.cover[0] * along, levels.cover[1] * across
        grid, fe_compliance, condense_s = rolling_b2b.pair_compliance(radius, conformity, half_along, half_across,
                                                                      level.cells_along, level.cells_across,
                                                                      level.h_factor, material)
        operator = fe_compliance.operator()
        start = time.perf_counter()
        fe = solve(balls_on(grid, operator))
        fe_s = time.perf_counter() - start
        start = time.perf_counter()
        half = solve(balls_on(grid, None))
        out.append(ComplianceRung(tuple(level), int(fe_compliance.ndofs), fe, half, condense_s, fe_s,
                                  time.perf_counter() - start))
    return out
