"""Steady rolling contact with stick and slip on a grid (Kalker's exact theory, discretised).

Problem (Kalker 1990, Ch 2 and 5; CONTACT user guide, 'The contact conditions'): two bodies roll over each
other with speed ``V`` along ``+x`` of the contact plane (the contact moves along ``+x`` over both surfaces,
material passes through it along ``-x``: leading edge at ``x = +a``).  Given the normal pressure ``p_n``
(Hertz, or any field from the BEM or the FE) and the rigid slip ``w(x, y)`` of body 1 relative to body 2
per unit rolling distance (for creepages ``xi, eta`` and spin ``phi`` [rad/m]:
``w = (xi - phi y, eta + phi x)``), find the tangential traction ``p`` on body 1 such that with the slip
(per unit rolling distance)::

    s = w + (u(x) - u(x + dx)) / dx,   u = A * p          (steady state, rolling step = cell size dx)

Coulomb's law holds in every contact cell with the traction bound ``g = mu p_n``::

    |p| <= g;   stick: |p| < g  and  s = 0;   slip: |p| = g  and  p = -g s / |s|.

``A`` are the influence coefficients of :mod:`lowmodel.contact.influence` (half-space, closed form over
rectangles) or a condensed FE compliance (``W = B K^-1 B^T``, :class:`MatrixOperator`).  A shift
(Cattaneo-Mindlin: the bodies start unloaded and are shifted by ``W``) is the same problem with
``s = W + u`` (:func:`shift`).

This module is the public entry and the result; the concept is split over single-concept modules, whose
public names it re-exports (``rolling.hertz_grid``, ``rolling.MatrixOperator``, ...):

* :mod:`lowmodel.contact.rolling_input`: grids, Hertz pressure, rigid slip, the spin parameter;
* :mod:`lowmodel.contact.rolling_operators`: the operator ``C`` (half-space convolution, dense FE matrix);
* :mod:`lowmodel.contact.rolling_newton`: the semismooth Newton solver and the check of the defining conditions.

Solution: semismooth Newton on ``F(p) = p - Proj_g(p - c s(p)) = 0`` (:mod:`lowmodel.contact.rolling_newton`).
Costs (docs/rolling_contact.md): one product ``O(n log n)`` (FFT) or ``O(n^2)`` (dense), the line inverses
``O(n_y n_x^3)`` per Newton step, 4 to 12 Newton steps with 2 to 8 GMRES steps each.

Before returning, the solver re-evaluates the slip from the final traction and checks the conditions
that define the answer (Coulomb bound, zero slip in stick cells, traction opposite to the slip in slip
cells, non-negative dissipation in every cell); a failed check raises ConvergenceError naming it.

Conventions (Kalker's; docs/rolling_contact.md has the drawing): ``x`` rolling, ``y`` lateral, ``z``
normal pointing into body 1; forces and moment on body 1; ``xi = (v1 - v2)_x / V`` at the contact
centre, ``eta`` likewise, ``phi = (omega_1 - omega_2)_z / V`` [rad/m].  With these, the linear theory reads
``F_x = -G c^2 C11 xi``, ``F_y = -G c^2 (C22 eta + c C23 phi)`` (``c = sqrt(a b)``, Kalker 1990 Table E.3).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import rolling_newton
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.influence import combined_material
from ballbench.lowmodel.contact.rolling_input import (LineGrid, hertz_grid, hertz_pressure, rigid_slip,
                                                      rigid_slip_field, spin_parameter)
from ballbench.lowmodel.contact.rolling_newton import DENSE_CELLS, DIRECT_CELLS, TangentialProblem
from ballbench.lowmodel.contact.rolling_operators import (ConvolutionOperator, MatrixOperator, half_space_operator,
                                                          one_blas_thread)

__all__ = [
    "RollingContact",
    "ConvolutionOperator",
    "MatrixOperator",
    "half_space_operator",
    "rigid_slip",
    "rigid_slip_field",
    "hertz_grid",
    "LineGrid",
    "steady_rolling_line",
    "hertz_pressure",
    "solve",
    "shift",
    "steady_rolling",
    "prepare_rolling",
    "PreparedRolling",
    "spin_parameter",
    "DENSE_CELLS",
    "DIRECT_CELLS",
]


@dataclass(frozen=True)
class RollingContact:
    """Tangential solution on a grid (Kalker's frame: ``x`` rolling, ``y`` lateral, tractions on body 1).

    grid : the :class:`~lowmodel.contact.halfspace.SurfaceGrid` (arrays ``(nx, ny)``, ``[i, j]`` at
        ``(grid.x[i], grid.y[j])``; ``x`` along rolling)
    pressure : (nx, ny) normal pressure [Pa]
    traction : (nx, ny, 2) tangential traction on body 1 [Pa]
    slip : (nx, ny, 2) slip of body 1 relative to body 2, per unit rolling distance [-] (a shift: [m]); zero
        outside the contact
    rigid_slip : (nx, ny, 2) the rigid (kinematic) part ``w`` as given (same units)
    stick : (nx, ny) bool, contact cells in stick (``|p| < g``); slip cells are ``contact & ~stick``
    contact : (nx, ny) bool, cells with ``p_n > 0``
    friction_coefficient : mu; rolling_speed : V [m/s] (the power's scale)
    force_rolling, force_lateral : [N] on body 1, ``sum p dA``
    spin_moment : [N m] on body 1 about ``+z`` through the grid origin, ``sum (x p_y - y p_x) dA``
    frictional_power : [W] ``-V sum p . s dA`` (>= 0; a shift: the frictional work [J])
    rigid_power : [W] ``-V sum p . w dA``, the power of the tractions on the rigid slip: what the bodies'
        equilibrium sees (``-(F . v + M_z omega_z + ...)``, so a power balance of a ball closes on it exactly);
        it exceeds ``frictional_power`` by the discretisation's elastic term, O(dx): 0.2 % at 16 x 16 cells,
        0.06 % at 64 x 64 (docs/rolling_contact.md)
    stick_fraction : stick cells / contact cells
    normal_force : [N] ``sum p_n dA``
    iterations, krylov_iterations, residual : Newton steps, GMRES steps, final ``max|F| / max g``
    traction_sensitivity : (nx, ny, 2, k) the traction's derivative along the ``k`` changes of the rigid slip given
        to :func:`solve` as ``sensitivity_directions`` [Pa per unit of ``w``], None without them
    """

    grid: SurfaceGrid
    pressure: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    rigid_slip: np.ndarray
    stick: np.ndarray
    contact: np.ndarray
    friction_coefficient: float
    rolling_speed: float
    force_rolling: float
    force_lateral: float
    spin_moment: float
    frictional_power: float
    rigid_power: float
    stick_fraction: float
    normal_force: float
    iterations: int
    krylov_iterations: int
    residual: float
    traction_sensitivity: np.ndarray | None = None

    def __post_init__(self):
        checks.freeze_arrays(self, "pressure", "traction", "slip", "rigid_slip", "stick", "contact")
        if self.traction_sensitivity is not None:
            checks.freeze_arrays(self, "traction_sensitivity")

    @property
    def slip_area(self) -> np.ndarray:
        """(nx, ny) bool, contact cells in slip."""
        return self.contact & ~self.stick

    @property
    def slip_velocity(self) -> np.ndarray:
        """(nx, ny, 2) slip velocity [m/s], ``V s``."""
        return self.rolling_speed * self.slip

    @property
    def traction_bound(self) -> np.ndarray:
        """(nx, ny) ``mu p_n`` [Pa]."""
        return self.friction_coefficient * self.pressure



def _check_pressure(pressure, grid: SurfaceGrid, edge: bool = True) -> np.ndarray:
    pressure = np.asarray(checks.real("pressure", pressure), dtype=float)
    if pressure.shape != (grid.nx, grid.ny):
        raise ValueError(f"pressure must have the grid's shape {(grid.nx, grid.ny)}, got {pressure.shape}")
    if not np.all(np.isfinite(pressure)):
        raise ValueError("pressure must be finite (got NaN or inf) [Pa]")
    if np.any(pressure < 0.0):
        raise ValueError(f"pressure must be >= 0 Pa everywhere (compressive), got min {float(pressure.min())!r} Pa")
    if not np.any(pressure > 0.0):
        raise ValueError("pressure must be > 0 Pa somewhere: no contact on the grid")
    if edge and grid.ny > 1:
        ring = np.concatenate([pressure[0], pressure[-1], pressure[:, 0], pressure[:, -1]])
        if np.any(ring > 0.0):
            raise ValueError("the grid does not cover the contact: the pressure is > 0 in the outermost cells; "
                             "enlarge the grid so that the contact lies inside it")
    elif edge and (pressure[0, 0] > 0.0 or pressure[-1, 0] > 0.0):
        raise ValueError("the grid does not cover the contact: the pressure is > 0 in the first or last cell")
    return pressure


def _check_rigid(rigid, grid: SurfaceGrid, name: str) -> np.ndarray:
    rigid = np.asarray(checks.real(name, rigid), dtype=float)
    if rigid.shape != (grid.nx, grid.ny, 2):
        raise ValueError(f"{name} must have shape {(grid.nx, grid.ny, 2)}, got {rigid.shape}")
    if not np.all(np.isfinite(rigid)):
        raise ValueError(f"{name} must be finite (got NaN or inf)")
    return rigid


def solve(pressure, operator, friction_coefficient: float, rigid, *, rolling_speed: float = 1.0,
          tolerance: float = 1e-10, max_iterations: int = 60, dense: bool | None = None,
          initial_traction: np.ndarray | None = None, sensitivity_directions=None,
          initial_sensitivity: np.ndarray | None = None, workspace: dict | None = None) -> RollingContact:
    """Tangential tractions of a contact with stick and slip (module docstring).

    Parameters
    ----------
    pressure : (nx, ny) normal pressure [Pa] on ``operator.grid`` (>= 0; zero in the outermost cells)
    operator : :class:`ConvolutionOperator` (:func:`half_space_operator`) or :class:`MatrixOperator`;
        steady rolling (slip per unit rolling distance) or a shift, as built
    friction_coefficient : mu > 0
    rigid : (nx, ny, 2) the rigid slip ``w`` (:func:`rigid_slip`, :func:`rigid_slip_field`) [-] (a shift: [m])
    rolling_speed : V [m/s], scales the frictional power only
    tolerance : on ``max|F| / max(mu p_n)`` (traction units)
    dense : force dense (True) or FFT (False) products; default by :data:`DENSE_CELLS`
    initial_traction : (nx, ny, 2) start [Pa] (e.g. a nearby case)
    sensitivity_directions : (nx, ny, 2, k) changes of ``rigid``; the result's ``traction_sensitivity`` is the
        traction's derivative along each (the implicit function theorem at the solution,
        :func:`~lowmodel.contact.rolling_newton.sensitivity`: one linear solve per direction, no new Newton solve)
    initial_sensitivity : (nx, ny, 2, k) a first guess of ``traction_sensitivity`` (e.g. a nearby solve's), for the
        iterative linear solves (the same tolerance, fewer steps)
    workspace : a dict the caller keeps for one contact across solves (e.g. the Newton steps of a ball's
        equilibrium): the iterative solver's preconditioner carries over in it (fewer rebuilds; the result then
        depends on the solves before to within ``tolerance``, not to the last bit)

    Raises ValueError for bad input, ConvergenceError when Newton does not converge or a defining
    condition fails its check.
    """
    grid = operator.grid
    pressure = _check_pressure(pressure, grid)
    mu = checks.positive("friction_coefficient", friction_coefficient)
    rigid = _check_rigid(rigid, grid, "rigid (the rigid slip)")
    speed = checks.positive("rolling_speed", rolling_speed, "m/s")
    checks.positive("tolerance", tolerance)
    max_iterations = checks.count("max_iterations", max_iterations, 1)
    coupled = operator.normal_slip(pressure)  # the pressure's slip through the normal-tangential coupling
    bound = mu * pressure
    problem = TangentialProblem(operator, bound, rigid if coupled is None else rigid + coupled, dense)
    if workspace is not None:
        if not isinstance(workspace, dict):
            raise ValueError(f"workspace must be a dict (kept by the caller for one contact), got {type(workspace)}")
        problem.workspace = workspace
    start = None
    if initial_traction is not None:
        start = _check_rigid(initial_traction, grid, "initial_traction").reshape(-1, 2)[problem.cells]
    directions = None
    if sensitivity_directions is not None:
        directions = np.asarray(checks.real("sensitivity_directions", sensitivity_directions), dtype=float)
        if directions.ndim != 4 or directions.shape[:3] != (grid.nx, grid.ny, 2) or not np.all(np.isfinite(directions)):
            raise ValueError(f"sensitivity_directions must be finite with shape {(grid.nx, grid.ny, 2)} + (k,), got "
                             f"{directions.shape}")
    guess = None
    if initial_sensitivity is not None and directions is not None:
        guess = np.asarray(initial_sensitivity, dtype=float)
        if guess.shape != directions.shape or not np.all(np.isfinite(guess)):
            raise ValueError(f"initial_sensitivity must be finite with the shape of sensitivity_directions, "
                             f"{directions.shape}, got {guess.shape}")
        guess = guess.reshape(-1, 2, guess.shape[3])[problem.cells]
    p, s, stick, iterations, krylov, residual = _newton(problem, tolerance, max_iterations, start)
    result = _result(problem, grid, grid.x, grid.y, pressure, float(pressure.sum()) * grid.cell_area, p, s, stick,
                     rigid, mu, speed, iterations, krylov, residual)
    if directions is None:
        return result
    with one_blas_thread():
        cells = rolling_newton.sensitivity(problem, p, directions.reshape(-1, 2, directions.shape[3])[problem.cells],
                                           start=guess)
    derivative = np.zeros(directions.shape)
    derivative.reshape(-1, 2, directions.shape[3])[problem.cells] = cells
    return dataclasses.replace(result, traction_sensitivity=derivative)


def _newton(problem: TangentialProblem, tolerance: float, max_iterations: int, start):
    with one_blas_thread():
        compiled = rolling_newton.compiled_solve(problem, tolerance, max_iterations, start)
        if compiled is not None:
            return compiled
        p, iterations, krylov, residual = rolling_newton.semismooth_newton(problem, tolerance, max_iterations, start)
        s, stick = rolling_newton.check_solution(problem, p, tolerance)
    return p, s, stick, iterations, krylov, residual


def _result(problem, grid, x, y, pressure, normal_force, p, s, stick, rigid, mu, speed, iterations, krylov,
            residual) -> RollingContact:
    traction = np.zeros((grid.nx, grid.ny, 2))
    slip = np.zeros((grid.nx, grid.ny, 2))
    traction.reshape(-1, 2)[problem.cells] = p
    slip.reshape(-1, 2)[problem.cells] = s
    stick_grid = np.zeros((grid.nx, grid.ny), dtype=bool)
    stick_grid.reshape(-1)[problem.cells] = stick
    area = grid.cell_area
    force = traction.reshape(-1, 2).sum(axis=0) * area
    moment = float(np.sum(x[:, None] * traction[..., 1] - y[None, :] * traction[..., 0])) * area
    power = -speed * float(np.sum(p * s)) * area
    rigid_power = -speed * float(np.sum(p * rigid.reshape(-1, 2)[problem.cells])) * area
    return RollingContact(grid, pressure, traction, slip, rigid, stick_grid, problem.contact, mu, speed,
                          float(force[0]), float(force[1]), moment, power, rigid_power, float(stick.sum()) / problem.n,
                          normal_force, iterations, krylov, residual)


def shift(pressure, grid: SurfaceGrid, shear_modulus: float, poisson_ratio: float, friction_coefficient: float,
          rigid_shift, *, tolerance: float = 1e-10, max_iterations: int = 60) -> RollingContact:
    """A shift from the unloaded state (Cattaneo-Mindlin; CONTACT's 'shift', T = 1): ``s = W + u``.

    ``rigid_shift`` (2,) [m]: the rigid shift ``W`` of body 1 relative to body 2 (uniform), or an
    (nx, ny, 2) field.  Returns a :class:`RollingContact` whose ``slip`` is the shift [m] and whose
    ``frictional_power`` is the frictional work [J] (``rolling_speed`` 1).
    """
    operator = half_space_operator(grid, shear_modulus, poisson_ratio, steady=False)
    value = np.asarray(checks.real("rigid_shift", rigid_shift), dtype=float)
    if value.shape == (2,):
        value = np.broadcast_to(value, (grid.nx, grid.ny, 2))
    elif value.shape != (grid.nx, grid.ny, 2):
        raise ValueError(f"rigid_shift must have shape (2,) or {(grid.nx, grid.ny, 2)} [m], got {value.shape}")
    value = _check_rigid(value, grid, "rigid_shift")
    return solve(pressure, operator, friction_coefficient, value, tolerance=tolerance,
                 max_iterations=max_iterations)


def _plain(value) -> float | None:
    # a float, numpy float or modest int as a finite Python float in a few hundred nanoseconds, else None
    kind = type(value)
    if (kind is float or kind is np.float64) and math.isfinite(value):
        return float(value)
    if kind is int and -(1 << 1000) < value < (1 << 1000):
        return float(value)
    return None


def _finite_scalar(name: str, value, unit: str = "") -> float:
    plain = _plain(value)
    return checks.scalar(name, value, unit) if plain is None else plain  # converts, or raises naming the parameter


@dataclass(frozen=True, eq=False)
class PreparedRolling:
    """A Hertz contact on its grid, ready for many steady-rolling solves (:func:`prepare_rolling`).

    Everything that depends on the contact alone is built and checked once: the grid, the Hertz pressure,
    the half-space operator, the contact cells and their dense ``C`` block, the marching start's flexibility and,
    up to :data:`DIRECT_CELLS` contact cells, ``(c C)^-1`` for the low-rank Newton steps
    (:func:`lowmodel.contact.rolling_newton.low_rank_step`).  A solve (:meth:`solve`) builds the rigid slip of its
    creepages and spin, runs the semismooth Newton and checks the defining conditions as :func:`solve` does; its
    answer equals :func:`solve`'s on the same input to round-off (docs/rolling_contact.md, 'Solver').

    grid, pressure : as :class:`RollingContact`; operator : the :func:`half_space_operator` on ``grid``
    friction_coefficient, tolerance, max_iterations : as :func:`steady_rolling`
    normal_force : ``sum p_n dA`` [N]
    """

    grid: SurfaceGrid
    pressure: np.ndarray
    operator: ConvolutionOperator
    friction_coefficient: float
    tolerance: float
    max_iterations: int
    normal_force: float
    _problem: TangentialProblem = field(repr=False)
    _x: np.ndarray = field(repr=False)
    _y: np.ndarray = field(repr=False)

    def __post_init__(self):
        checks.freeze_arrays(self, "pressure", "_x", "_y")

    def solve(self, creepage_rolling: float, creepage_lateral: float, spin: float, *,
              rolling_speed: float = 1.0) -> RollingContact:
        """Steady rolling at creepages ``xi, eta`` [-] and spin ``phi`` [rad/m] (Kalker's signs, module
        docstring); ``rolling_speed`` V [m/s] for the frictional power.  Returns a :class:`RollingContact`."""
        xi = _finite_scalar("creepage_rolling", creepage_rolling)
        eta = _finite_scalar("creepage_lateral", creepage_lateral)
        phi = _finite_scalar("spin", spin, "rad/m")
        speed = _plain(rolling_speed)
        if speed is None or not speed > 0.0:
            speed = checks.positive("rolling_speed", rolling_speed, "m/s")
        grid = self.grid
        w = np.empty((grid.nx, grid.ny, 2))  # rigid_slip's field, centre (0, 0)
        w[..., 0] = xi - phi * self._y[None, :]
        w[..., 1] = eta + phi * self._x[:, None]
        problem = self._problem.with_rigid(w.reshape(-1, 2)[self._problem.cells])
        p, s, stick, iterations, krylov, residual = _newton(problem, self.tolerance, self.max_iterations, None)
        return _result(problem, grid, self._x, self._y, self.pressure, self.normal_force, p, s, stick, w,
                       self.friction_coefficient, float(speed), iterations, krylov, residual)


def prepare_rolling(semi_axis_rolling: float, semi_axis_lateral: float, normal_force: float, shear_modulus: float,
                    poisson_ratio: float, friction_coefficient: float, cells=(35, 35), *, tolerance: float = 1e-10,
                    max_iterations: int = 60) -> PreparedRolling:
    """A Hertz contact prepared for many :meth:`PreparedRolling.solve` calls (a creep curve, a sweep over spin).

    Parameters as :func:`steady_rolling` (SI), all checked here once.  ``prepare_rolling(a, b, F, G, nu, mu,
    cells).solve(xi, eta, phi)`` equals ``steady_rolling(a, b, F, G, nu, mu, xi, eta, phi, cells)`` to the last
    bit; :func:`steady_rolling` itself keeps the last few prepared contacts.
    """
    grid = hertz_grid(semi_axis_rolling, semi_axis_lateral, cells)
    pressure = hertz_pressure(grid, semi_axis_rolling, semi_axis_lateral, normal_force)
    shear, nu, _ = combined_material(shear_modulus, poisson_ratio)
    operator = half_space_operator(grid, shear, nu)
    pressure = _check_pressure(pressure, grid)
    mu = checks.positive("friction_coefficient", friction_coefficient)
    checks.positive("tolerance", tolerance)
    max_iterations = checks.count("max_iterations", max_iterations, 1)
    with one_blas_thread():  # prepare() inverts c C on dense grids
        problem = TangentialProblem(operator, mu * pressure, np.zeros((grid.nx, grid.ny, 2)), None).prepare()
    return PreparedRolling(grid, pressure, operator, mu, float(tolerance), max_iterations,
                           float(pressure.sum()) * grid.cell_area, problem, grid.x, grid.y)


_PREPARED: dict = {}  # the last prepared contacts of steady_rolling, oldest first
_PREPARED_KEPT = 8


def _typed(value):
    # a cache key that tells 1 from 1.0 and True (a bool is refused where a number is checked)
    if isinstance(value, tuple):
        return tuple(_typed(v) for v in value)
    return type(value), value


def _prepared(args: tuple, cells, tolerance, max_iterations) -> PreparedRolling:
    key = (_typed(args), _typed(cells), _typed(tolerance), _typed(max_iterations))
    try:
        prepared = _PREPARED.pop(key, None)
    except TypeError:  # arrays and other unhashable inputs: prepared (and checked) for this call only
        return prepare_rolling(*args, cells, tolerance=tolerance, max_iterations=max_iterations)
    if prepared is None:
        prepared = prepare_rolling(*args, cells, tolerance=tolerance, max_iterations=max_iterations)
        while len(_PREPARED) >= _PREPARED_KEPT:
            _PREPARED.pop(next(iter(_PREPARED)))
    _PREPARED[key] = prepared  # the most recent last
    return prepared


def steady_rolling(semi_axis_rolling: float, semi_axis_lateral: float, normal_force: float, shear_modulus: float,
                   poisson_ratio: float, friction_coefficient: float, creepage_rolling: float,
                   creepage_lateral: float, spin: float, cells=(35, 35), *, rolling_speed: float = 1.0,
                   tolerance: float = 1e-10, max_iterations: int = 60) -> RollingContact:
    """Steady rolling of a Hertz contact with stick and slip on two elastic half-spaces (Kalker's exact theory).

    Parameters (SI)
    ---------------
    semi_axis_rolling, semi_axis_lateral : Hertz semi-axes ``a`` (along rolling) and ``b`` [m]
    normal_force : F [N] (Hertz pressure ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``, ``p0 = 3 F / (2 pi a b)``,
        cell-averaged)
    shear_modulus, poisson_ratio : combined G [Pa] and nu of the two bodies
        (:func:`lowmodel.contact.influence.combined_material`; quasi-identical bodies)
    friction_coefficient : mu > 0
    creepage_rolling, creepage_lateral : xi, eta [-]; spin : phi [rad/m] (Kalker's signs, module docstring)
    cells : (n_rolling, n_lateral) cells across the ellipse's ``2a x 2b`` box, each in [2, 4096] (the grid has
        one more empty cell on each side, :func:`hertz_grid`); an int for both
    rolling_speed : V [m/s] for the frictional power [W]

    Returns
    -------
    :class:`RollingContact`: ``force_rolling``, ``force_lateral`` [N], ``spin_moment`` [N m] (about the
    contact centre), ``stick_fraction``, ``frictional_power`` [W], the traction, slip and stick fields.

    The contact (everything but the creepages, spin and speed) is prepared by :func:`prepare_rolling` and the
    last eight are kept, keyed on the inputs and their types (a value is checked when its contact is prepared);
    a sweep over creepages may call :func:`prepare_rolling` itself and :meth:`PreparedRolling.solve`.
    """
    prepared = _prepared((semi_axis_rolling, semi_axis_lateral, normal_force, shear_modulus, poisson_ratio,
                          friction_coefficient), cells, tolerance, max_iterations)
    return prepared.solve(creepage_rolling, creepage_lateral, spin, rolling_speed=rolling_speed)


def steady_rolling_line(semi_width: float, normal_load: float, shear_modulus: float, poisson_ratio: float,
                        friction_coefficient: float, creepage_rolling: float, cells: int = 200, *,
                        tolerance: float = 1e-10, max_iterations: int = 60) -> RollingContact:
    """Steady rolling of two cylinders (plane strain, Carter's problem) with stick and slip.

    ``semi_width`` a [m] of the Hertz strip ``p0 sqrt(1 - x^2/a^2)``, ``normal_load`` per unit length [N/m]
    (``p0 = 2 F / (pi a)``), combined ``shear_modulus`` [Pa] and ``poisson_ratio``, ``friction_coefficient``,
    ``creepage_rolling`` xi; ``cells`` across ``2a`` (plus one empty cell each side).  Forces per metre.
    """
    a = checks.positive("semi_width", semi_width, "m")
    n = checks.count("cells", cells, 4, 1 << 20)
    grid = LineGrid(n + 2, 2.0 * a / n)
    pressure = hertz_pressure(grid, a, 1.0, normal_load)
    shear, nu, _ = combined_material(shear_modulus, poisson_ratio)
    operator = half_space_operator(grid, shear, nu, plane_strain=True)
    w = rigid_slip(grid, creepage_rolling, 0.0, 0.0)
    return solve(pressure, operator, friction_coefficient, w, tolerance=tolerance, max_iterations=max_iterations)
