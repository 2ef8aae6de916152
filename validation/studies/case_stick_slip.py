"""The stick/slip rung of a case of one's own (docs/b2b_rolling.md, 'Validity of full slip'): lin2019's two-ball
module of a linear-guide or ball-screw case solved with stick/slip ball-to-groove contacts (the steady rolling solve
of :mod:`lowmodel.contact.rolling_friction` on two half-spaces) and with lin2019's full slip (eqs A4-A7) on the same
cells, touching and apart (:func:`lowmodel.linear_bearing.b2b_rolling.module_b2b`,
:func:`lowmodel.screw.b2b_rolling.module_b2b`; each solve checks its power balance to 1e-6).

Hertz pressure on ``CELLS[fidelity]`` cells per contact (along x across the ellipse), and the same module on
``GRID_CELLS[fidelity]`` for the grid error of the comparison (:func:`grid_error`): on coarser cells the difference
of the laws is the grid's (docs/b2b_rolling.md, 'Grid error of the comparison', its table and the rule the cells
follow).

:func:`compliance_rungs` adds the FE compliance of the case's own groove (a ball of the case's radius in a straight
groove of its conformity and material, P2, condensed onto one grid over every contact:
``studies.rolling_b2b.pair_compliance``, the levels of ``cases.stick_slip``), as the paper modules' ladders do.
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import NamedTuple

from ballbench.lowmodel.bearing_results import screw_states
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_rolling as screw_b2b_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.validation.cases import stick_slip
from ballbench.validation.cases.case import BallScrewCase, LinearGuideCase
from ballbench.validation.studies import rolling_b2b

__all__ = ["CELLS", "GRID_CELLS", "FALLBACK_CELLS", "COMPLIANCE", "module", "ModuleRun", "stick_slip_alone",
           "StickSlipAlone", "drive_speed", "GridError",
           "grid_error", "ComplianceRung", "compliance_rungs"]

# the cells per contact of each fidelity, and the finer cells their grid error is measured against
# (docs/b2b_rolling.md, 'Grid error of the comparison': 16 x 64 is the coarsest set whose grid error stays inside
# the tolerances the rung judges by)
CELLS = {"quick": (16, 64), "default": (24, 96), "fine": (32, 128)}
GRID_CELLS = {"quick": (24, 96), "default": (32, 128), "fine": (48, 192)}
# where a law finds no state on CELLS (Newton can stall on one set of cells and not on the next: the full-slip chain
# of examples/catalogue/screw_12x2.toml on 16 x 64 cells), the rung runs on these, between CELLS and GRID_CELLS
FALLBACK_CELLS = {"quick": (20, 80), "default": (28, 112), "fine": (40, 160)}
# the FE compliance levels of a case's stick/slip rung per fidelity (cases.stick_slip.ComplianceLevel): none at the
# quick level (a condensation of the case's groove costs 1.5-3 min and 3-5 GB), the paper ladders' levels above
COMPLIANCE = {"quick": (), "default": stick_slip.LINEAR.compliance.default, "fine": stick_slip.LINEAR.compliance.fine}


def drive_speed(case) -> float:
    """The speed the friction is read against: the carriage's [m/s] (force = power / speed) or the nut's [rad/s]
    (torque = power / speed)."""
    return abs(case.guide.groove_velocity) if isinstance(case, LinearGuideCase) else abs(case.screw.nut_speed)


class ModuleRun(NamedTuple):
    """:func:`module`'s answer: the ``cells`` solved on, the ``result`` and a ``note`` ("" or why not on
    ``CELLS``)."""

    cells: tuple
    result: object
    note: str


def module(case, fidelity: str) -> ModuleRun:
    """Both laws on the case's balls: a RollingModuleB2B (guide) or ScrewRollingModule (screw) with ``touching``,
    ``free`` (stick/slip) and ``full_slip``, ``full_slip_free`` on the same cells (``CELLS[fidelity]`` per contact,
    two half-spaces; ``FALLBACK_CELLS[fidelity]`` where a law finds no state on those, ConvergenceError where it
    finds none on either)."""
    *_, balls_on, solve = _hertz_balls(case)
    try:
        return ModuleRun(CELLS[fidelity], solve(balls_on(CELLS[fidelity], None)), "")
    except ConvergenceError as error:
        cells, fallback = CELLS[fidelity], FALLBACK_CELLS[fidelity]
        note = (f"On {cells[0]} x {cells[1]} cells a law found no state ({error}); the rung runs on "
                f"{fallback[0]} x {fallback[1]} cells.")
        return ModuleRun(fallback, solve(balls_on(fallback, None)), note)


@dataclass(frozen=True)
class StickSlipAlone:
    """A guide's two-ball module by the stick/slip law alone (:func:`stick_slip_alone`): ``touching`` and ``free``
    RollingB2BStates on ``cells``."""

    cells: tuple
    touching: object
    free: object


def stick_slip_alone(case, fidelity: str) -> StickSlipAlone:
    """Where full slip on the cells has no state (a guide near its four-point limit, docs/b2b_rolling.md, 'Where
    full sliding has no state'): the stick/slip law alone on ``CELLS[fidelity]``, touching and apart (gaps of 1 mm),
    from full slip or rolling (``b2b_rolling.solve(..., start="auto")``)."""
    if not isinstance(case, LinearGuideCase):
        raise TypeError(f"the stick/slip law alone runs on a LinearGuideCase here, got {type(case).__name__}")
    *_, balls_on, _ = _hertz_balls(case)
    cells = CELLS[fidelity]
    balls = balls_on(cells, None)
    guide = case.guide
    options = dict(ball_radius=guide.ball_radius, friction_coefficient=guide.friction_coefficient,
                   groove_velocity=guide.groove_velocity, start="auto")
    return StickSlipAlone(cells, b2b_rolling.solve(balls, **options),
                          b2b_rolling.solve(balls, gaps=[1e-3] * (len(balls) - 1), **options))


def _differences(result, near_zero: float) -> tuple[float, float, float]:
    """``(F_B2B, friction apart, friction touching)``: full slip against stick/slip as the rung judges them,
    ``(full - stick) / |stick|`` (the B2B force against ``near_zero`` where it is smaller; the friction as the
    ratio of the input powers, read at one speed)."""
    stick, full = float(result.touching.b2b_force[0]), float(result.full_slip.b2b_force[0])
    b2b_scale = near_zero if abs(stick) < near_zero else abs(stick)
    return ((full - stick) / b2b_scale,
            *(f.input_power / s.input_power - 1.0 for s, f in ((result.free, result.full_slip_free),
                                                               (result.touching, result.full_slip))))


@dataclass(frozen=True)
class GridError:
    """The grid error of the stick/slip rung's comparison: the module on ``cells`` and on the finer ``finer``
    (``finer_result``, ``finer_s`` its wall time [s]); ``differences`` and ``finer_differences``:
    ``(F_B2B, friction apart, friction touching)`` of full slip against stick/slip as the rung judges them;
    ``b2b`` and ``friction``: the change of the B2B difference and the larger change of a friction difference."""

    cells: tuple
    finer: tuple
    differences: tuple
    finer_differences: tuple
    finer_result: object
    finer_s: float

    @property
    def b2b(self) -> float:
        return abs(self.differences[0] - self.finer_differences[0])

    @property
    def friction(self) -> float:
        return max(abs(a - b) for a, b in zip(self.differences[1:], self.finer_differences[1:]))


def grid_error(case, fidelity: str, run: ModuleRun, near_zero: float) -> GridError:
    """The grid error of ``run`` (:func:`module` at ``fidelity``): the same module on ``GRID_CELLS[fidelity]``;
    ``near_zero`` [N]: the B2B force below which its difference is judged against it."""
    *_, balls_on, solve = _hertz_balls(case)
    start = time.perf_counter()
    finer = solve(balls_on(GRID_CELLS[fidelity], None))
    seconds = time.perf_counter() - start
    result = run.result
    return GridError(run.cells, GRID_CELLS[fidelity], _differences(result, near_zero),
                     _differences(finer, near_zero), finer, seconds)


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
