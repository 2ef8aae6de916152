"""Where lin2019's full-slip friction holds: stick/slip against full slip for one case, and over the models' domain
(docs/b2b_rolling.md, 'Validity of full slip').

lin2019's friction of a ball-to-groove contact (eqs A4-A7, 44-47) is full slip: ``mu p`` opposite to the rigid
slip at every point.  The steady rolling solve (:mod:`lowmodel.contact.rolling_friction`) adds stick zones,
elastic creep and the bodies' tangential compliance; how much that changes a ball's friction and the B2B force
depends mostly on the spin parameter ``Lambda = |phi| b G / (mu p0)`` of the contacts (full slip for
``Lambda >> 1``), i.e. on ``mu`` (``Lambda ~ 1 / mu``) and the conformity (through ``b`` and ``p0``), little on the
load (``b / p0`` does not depend on it for Hertz contacts).

:func:`linear_point` and :func:`screw_point` solve lin2019's two-ball module of one case with both laws on the
same cells (Hertz pressure on two half-spaces, :mod:`lowmodel.linear_bearing.b2b_rolling`,
:mod:`lowmodel.screw.b2b_rolling`) and return the differences (:class:`ValidityPoint`): of the B2B force of the
touching balls and of each free ball's friction (the drag force on the top groove, or the drag torque on the
nut).  :func:`required_rung` tells which rung is enough for a tolerance; :func:`validity_map` runs a grid of
cases (the map of the docs, scene ``full-slip-validity-map``).

**Grid error.**  Both laws run on the same cells, but the stick/slip solve's steady-state operator differences
the elastic displacement along the rolling direction on the grid (docs/rolling_contact.md), and the B2B force is
a small difference of the balls' equilibria (lin2019 eq 9): on coarse cells the difference of the laws is the
grid's, not the law's, and it does not converge monotonically with the cells (docs/b2b_rolling.md, 'Grid error
of the comparison').  Every point therefore solves the comparison on two sets of cells and reports the change of
the differences between them as ``grid_error``: by default on :data:`GRID_LEVELS` (the two coarsest, and finer
ones while the grid error could flip the verdict at ``tolerance``), reporting the finest; with ``cells`` given,
at ``cells`` against :func:`finer_cells` of them.  :func:`required_rung` refuses a verdict the grid error could
flip.

```python
from ballbench.lowmodel import full_slip_validity as fsv
point = fsv.linear_point(0.035, friction_coefficient=0.3, conformity=0.6)    # theta 2 deg, rho -0.6, 100 N
point.b2b_difference, point.friction_difference, point.spin_parameter, point.cells, point.grid_error
fsv.required_rung(point, tolerance=0.01)       # "full slip" or "stick/slip on a half-space"
```
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_rolling as screw_b2b_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts

__all__ = ["ValidityPoint", "linear_point", "screw_point", "required_rung", "validity_map", "finer_cells",
           "RUNGS", "TOLERANCE", "GRID_LEVELS"]

RUNGS = ("full slip", "stick/slip on a half-space")
TOLERANCE = 0.01  # default: full slip is enough where it is within 1 % of stick/slip
# the cells (along, across each contact's Hertz ellipse) of a point's comparison, coarse to fine: the two coarsest
# always, finer ones while the grid error could flip the verdict (docs/b2b_rolling.md, 'Grid error of the
# comparison': the grid error table and the rule)
GRID_LEVELS = ((16, 64), (24, 96), (32, 128))


@dataclass(frozen=True)
class ValidityPoint:
    """Stick/slip against full slip for lin2019's two-ball module of one case (both laws on the same cells).

    product : "linear bearing" or "ball screw";  parameters : the case's inputs (dict)
    spin_parameter : the smallest Lambda of the touching balls' contacts;  creepage_parameter : the smallest
        creepage parameter ``|w_c| G / (mu p0)``;  stick_fraction : the largest stick fraction
    b2b_force, b2b_force_full_slip : N, touching balls, stick/slip and full slip
    b2b_difference : ``F_full slip / F_stick/slip - 1`` (0 without B2B contact)
    friction_difference : the largest ``|D_full slip / D_stick/slip - 1|`` of a free ball's drag ``D`` (the
        friction force on the top groove, or the friction torque on the nut: input power over speed)
    friction_increase, friction_increase_full_slip : % (lin2019's friction increase by B2B contact)
    cells : (along, across) the cells of the values above;  grid_cells : the other cells of the grid error
    b2b_grid_error, friction_grid_error : the change of ``b2b_difference`` and of ``friction_difference``
        between ``cells`` and ``grid_cells`` (nan without a state on both); ``grid_error`` the larger
    time_s : wall time of every solve;  error : "" or the reason why no state was found (ConvergenceError of
        either law)
    """

    product: str
    parameters: dict = field(default_factory=dict)
    spin_parameter: float = math.nan
    creepage_parameter: float = math.nan
    stick_fraction: float = math.nan
    b2b_force: float = math.nan
    b2b_force_full_slip: float = math.nan
    b2b_difference: float = math.nan
    friction_difference: float = math.nan
    friction_increase: float = math.nan
    friction_increase_full_slip: float = math.nan
    cells: tuple = ()
    grid_cells: tuple = ()
    b2b_grid_error: float = math.nan
    friction_grid_error: float = math.nan
    time_s: float = 0.0
    error: str = ""

    @property
    def worst(self) -> float:
        """The larger of ``|b2b_difference|`` and ``friction_difference`` (nan without a state)."""
        return max(abs(self.b2b_difference), self.friction_difference)

    @property
    def grid_error(self) -> float:
        """The larger of ``b2b_grid_error`` and ``friction_grid_error`` (nan where either is)."""
        return float(np.fmax(self.b2b_grid_error, self.friction_grid_error)) if not math.isnan(
            self.b2b_grid_error + self.friction_grid_error) else math.nan

    def verdict(self, tolerance: float) -> bool | None:
        """Full slip within ``tolerance`` (True), not within it (False), or None where a grid error could flip
        the answer: False as soon as one difference exceeds ``tolerance`` by more than its grid error, True where
        both stay below it by more than theirs."""
        pairs = ((abs(self.b2b_difference), self.b2b_grid_error),
                 (self.friction_difference, self.friction_grid_error))
        if any(value - error > tolerance for value, error in pairs):
            return False
        if all(value + error < tolerance for value, error in pairs):
            return True
        return None


def _drag(state, speed: float) -> np.ndarray:
    """(n,) each ball's drag: the power its driven contacts put in over the drive's speed."""
    return np.array([sum(c.drive_power for c in row) for row in state.contacts]) / speed


def _point(product: str, parameters: dict, result, speed: float, cells: tuple) -> ValidityPoint:
    touching, full = result.touching, result.full_slip
    lam = [c.spin_parameter for row in touching.contacts for c in row]
    creep = [c.creepage for row in touching.contacts for c in row]
    stick = [c.stick_fraction for row in touching.contacts for c in row]
    force, force_full = float(touching.b2b_force[0]), float(full.b2b_force[0])
    difference = force_full / force - 1.0 if force > 0.0 else (0.0 if force_full <= 0.0 else math.inf)
    drag, drag_full = _drag(result.free, speed), _drag(result.full_slip_free, speed)
    return ValidityPoint(product, parameters, min(lam), min(creep), max(stick), force, force_full, difference,
                         float(np.max(np.abs(drag_full / drag - 1.0))), float(result.friction_increase),
                         float(result.full_slip_increase), cells=tuple(cells))


def finer_cells(cells) -> tuple[int, int]:
    """The cells a point at ``cells`` is compared with for its grid error: 1.5 times as many each way."""
    along, across = (checks.count("cells", c, 2) for c in cells)
    return math.ceil(1.5 * along), math.ceil(1.5 * across)


def _with_grid_error(solve, cells, tolerance: float, start: float) -> ValidityPoint:
    """``solve(cells) -> ValidityPoint`` at ``cells`` against its finer cells, or (``cells`` None) over
    :data:`GRID_LEVELS` until the grid error cannot flip the verdict at ``tolerance``; the point's time from
    ``start``."""
    tolerance = checks.positive("tolerance", tolerance)
    if cells is not None:
        pairs = [(tuple(cells), finer_cells(cells))]
    else:
        pairs = list(zip(GRID_LEVELS, GRID_LEVELS[1:]))
    solved = {}
    for reported, other in pairs:
        for c in (reported, other):
            if c not in solved:
                solved[c] = solve(c)
                if solved[c].error:
                    return dataclasses.replace(solved[c], time_s=time.perf_counter() - start)
        # default levels: the finer of the pair is reported; given cells: those cells
        point, comparison = (solved[other], solved[reported]) if cells is None else (solved[reported], solved[other])
        point = dataclasses.replace(
            point, grid_cells=comparison.cells,
            b2b_grid_error=abs(point.b2b_difference - comparison.b2b_difference),
            friction_grid_error=abs(point.friction_difference - comparison.friction_difference))
        if point.verdict(tolerance) is not None:
            break
    return dataclasses.replace(point, time_s=time.perf_counter() - start)


def linear_point(theta: float, side_force_ratio: float = -0.6, *, friction_coefficient: float = 0.1,
                 conformity: float = 0.56, vertical_force: float = 100.0, ball_radius: float = 5e-3,
                 groove_velocity: float = 0.01, youngs_modulus: float = 2.1e11, poisson_ratio: float = 0.28,
                 cells=None, tolerance: float = TOLERANCE) -> ValidityPoint:
    """lin2019's linear-bearing module (Fig 7: ``beta_BL,BR = 45 deg -+ theta`` [rad], ``N_x = +-rho N_y`` [N])
    with both laws on Hertz contacts (Table 1 defaults) of :data:`GRID_LEVELS` (``cells`` None: refined while the
    grid error could flip the verdict at ``tolerance``) or of ``cells`` (along, across; the grid error against
    :func:`finer_cells`); a point with ``error`` where either law has no state.  The full-slip chain starts from
    the low-order state (:func:`lowmodel.linear_bearing.b2b.solve`) where it does not converge from the free
    balls."""
    parameters = dict(theta=float(theta), side_force_ratio=float(side_force_ratio), mu=float(friction_coefficient),
                      conformity=float(conformity), load=float(vertical_force))
    start = time.perf_counter()
    contacts = b2b.module_contacts(theta, side_force_ratio, vertical_force=vertical_force, ball_radius=ball_radius,
                                   conformity=conformity, friction_coefficient=friction_coefficient,
                                   groove_velocity=groove_velocity, youngs_modulus=youngs_modulus,
                                   poisson_ratio=poisson_ratio)

    def low_order(gaps):
        return b2b.solve(contacts, gaps)

    def solve(cells_):
        balls = [b2b_rolling.hertz_contacts(contacts, j, cells=cells_, conformity=conformity,
                                            youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)
                 for j in range(2)]
        try:
            result = b2b_rolling.module_b2b(balls, ball_radius=ball_radius, friction_coefficient=friction_coefficient,
                                            groove_velocity=groove_velocity, low_order=low_order)
        except ConvergenceError as error:
            return ValidityPoint("linear bearing", parameters, cells=tuple(cells_), error=str(error))
        return _point("linear bearing", parameters, result, abs(groove_velocity), cells_)

    return _with_grid_error(solve, cells, tolerance, start)


def screw_point(theta: float, *, oversize: float, friction_coefficient: float = 0.1, conformity: float = 0.56,
                axial_load: float = 50.0, cells=None, tolerance: float = TOLERANCE, reading: str = "tilted",
                **module_options) -> ValidityPoint:
    """lin2019's ball-screw module (Sec 3.3: ball 1 theta 0, ball 2 ``theta`` [rad], ``axial_load`` [N] on the
    screw, preload ``oversize`` [m], Table 4 defaults for the rest) with both laws on Hertz contacts at the
    low-order state's forces, on the cells of :func:`linear_point` (``cells``, ``tolerance``: the grid error the
    same way); a point with ``error`` where a model has no state."""
    parameters = dict(theta=float(theta), mu=float(friction_coefficient), conformity=float(conformity),
                      load=float(axial_load), oversize=float(oversize))
    start = time.perf_counter()
    module = screw_contacts.screw_module(friction_coefficient=friction_coefficient, conformity=conformity,
                                         oversize=oversize, **module_options)
    try:
        contacts = screw_contacts.ball_contacts(module, np.array([0.0, theta]), reading=reading)
        low = screw_b2b.solve(contacts, axial_load)
    except ConvergenceError as error:
        return ValidityPoint("ball screw", parameters, time_s=time.perf_counter() - start, error=str(error))

    def solve(cells_):
        try:
            balls = [screw_b2b_rolling.hertz_contacts(low, contacts, j, cells=cells_) for j in range(2)]
            result = screw_b2b_rolling.module_b2b(balls, module)
        except ConvergenceError as error:
            return ValidityPoint("ball screw", parameters, cells=tuple(cells_), error=str(error))
        return _point("ball screw", parameters, result, abs(module.nut_speed), cells_)

    return _with_grid_error(solve, cells, tolerance, start)


def required_rung(point: ValidityPoint, tolerance: float = TOLERANCE) -> str:
    """The cheapest rung of :data:`RUNGS` whose error for ``point`` is within ``tolerance`` (relative): "full slip"
    where full slip is within ``tolerance`` of stick/slip in the B2B force and in every free ball's friction, else
    "stick/slip on a half-space".  The FE compliance changes the stick/slip results by less than the half-space
    rung's own difference to full slip at the worst point of the models' domain (scene ``full-slip-validity``,
    docs/b2b_rolling.md), so within that domain it is never the rung that decides.  ValueError for a point
    without a state (``point.error``: neither law has a quasi-static state there), and for a point whose grid
    error could flip the verdict (:meth:`ValidityPoint.verdict` None, or no grid error): the comparison then
    judges the cells, not the law (refine them: ``cells`` of :func:`linear_point`)."""
    tolerance = checks.positive("tolerance", tolerance)
    if point.error:
        raise ValueError(f"point: no state ({point.error}); the models do not apply there")
    verdict = point.verdict(tolerance)
    if verdict is None:
        cells = "x".join(str(c) for c in point.cells) or "?"
        other = "x".join(str(c) for c in point.grid_cells) or "?"
        raise ValueError(f"point: the grid error ({cells} against {other} cells: B2B force "
                         f"{100 * point.b2b_grid_error:.2f} %, friction {100 * point.friction_grid_error:.2f} %) "
                         f"could flip the verdict: full slip / stick-slip - 1 = {100 * point.b2b_difference:+.2f} % "
                         f"(B2B force), {100 * point.friction_difference:.2f} % (friction) against the tolerance "
                         f"{100 * tolerance:g} %; no verdict on these cells (refine them)")
    return RUNGS[0] if verdict else RUNGS[1]


def validity_map(product: str, friction_coefficients, conformities, thetas, loads, *, progress=None,
                 **options) -> list[ValidityPoint]:
    """:func:`linear_point` (``product="linear"``; ``loads`` the vertical force N_y [N]) or :func:`screw_point`
    (``"screw"``; ``loads`` the axial load [N], ``options`` must give ``oversize``) over every combination of the
    friction coefficients, conformities, deviations ``thetas`` [rad] and loads; ``progress`` wraps the iterable."""
    product = checks.choice("product", product, ("linear", "screw"))
    cases = [(mu, f, t, load) for mu in friction_coefficients for f in conformities for t in thetas for load in loads]
    points = []
    for mu, f, t, load in (cases if progress is None else progress(cases)):
        if product == "linear":
            points.append(linear_point(t, friction_coefficient=mu, conformity=f, vertical_force=load, **options))
        else:
            points.append(screw_point(t, friction_coefficient=mu, conformity=f, axial_load=load, **options))
    return points
