"""Ball-to-groove friction from the steady rolling solve: the stick/slip contact law of a ball's equilibrium.

The full-slip models of lin2019 (eqs A4-A7, 44-47; :mod:`lowmodel.contact.ellipse_friction`) and the FE-informed
models (:mod:`lowmodel.contact.traction`) give every point of a contact the Coulomb traction ``mu p`` opposite
to the rigid slip.  Here the traction of each ball-to-groove contact comes from Kalker's steady rolling
problem (:mod:`lowmodel.contact.rolling`): stick and slip areas, elastic creep and the tangential compliance
of the bodies (two half-spaces, or a compliance condensed from the FE, :mod:`fem.rolling_compliance`), with
the creepages and spin of every point following from the ball's rigid-body state (docs/b2b_rolling.md).

A contact (:class:`GridContact`) is fixed to the ball: a regular grid in its tangent plane, centred on the
contact centre ``c`` (relative to the ball centre) with the outward normal ``n`` (ball into groove), the
grid's ``x`` along the groove ``axis`` and ``y`` along ``lateral = axis x n``; the normal pressure on the
cells (Hertz's, or an FE pressure binned onto the grid, :func:`sampled_pressure`); the surface point of cell
``(X, Y)`` is ``c + X axis + Y lateral - (k Y^2 / 2) n`` (the contact surface curved across the groove with
the curvature ``k`` of the deformed surface, as :func:`lowmodel.contact.rolling.rigid_slip_field`: Heathcote's
slip).  The product models give the rigid slip of the ball against its groove at those points as a linear
field of the ball's unknowns ``x`` (``s_k = D_k x - g_k``, the fields ``slip_field`` of
:mod:`lowmodel.linear_bearing.b2b_traction` and :mod:`lowmodel.screw.b2b_traction`), whose first unknown
carries the contact points (the ball centre's velocity ``D_k[:, 0] x_0``).

Per contact and ball state (:class:`StickSlipFriction`):

* the mean velocity of the two surfaces relative to the contact, ``u_m = (D_c x + g_c)/2 - D_c[:, 0] x_0`` at
  the centre: the material flows along ``sign(u_m . axis) axis``, so Kalker's rolling direction is
  ``x_K = -sign(u_m . axis) axis`` (``z_K = -n``, ``y_K = z_K x x_K``) and the rolling speed ``V = |u_m . axis|``;
  where ``x_K = -axis`` the grid's fields are turned by pi about ``z_K`` (a symmetric grid: cell ``(i, j)`` ->
  ``(nx-1-i, ny-1-j)``, vector components negated);
* the rigid slip per unit rolling distance ``w = (s . x_K, s . y_K) / V`` on the contact cells;
* the tractions ``p`` of :func:`lowmodel.contact.rolling.solve` (warm-started from the contact's last solution);
* the generalised force of the ball's unknowns ``R = sum_cells D_k^T p_k dA`` (the tractions' power per unit of
  each unknown: lin2019 eq 4's force and moment rows for the linear bearing, eq 54's for the screw), whose
  Jacobian is taken by forward differences (step :data:`FD_STEP` in the unknowns' units, each solve
  warm-started from the unperturbed tractions: 1-2 Newton steps); the rolling solver returns no sensitivities.

The power of the tractions on the rigid motion is each contact's ``rigid_power`` (``-V sum p . w dA``); at
``R = 0`` the input power ``sum p_k . g_k dA`` equals their sum exactly (to the Newton tolerance), which is
the power balance every solve checks.  The full-slip limit of this law on the same cells is pointwise
Coulomb (:class:`lowmodel.contact.traction.SampledCoulomb` on :meth:`GridContact.patch`): the two differ only
by stick/slip and elastic creep.

The evaluator has the interface of :class:`~lowmodel.contact.traction.SampledCoulomb` (``evaluate(balls,
jacobian, ball)``, ``n_balls``), so :func:`lowmodel.contact.traction.solve_chain` solves the B2B chain of
:mod:`lowmodel.b2b_chain` with it unchanged.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ballbench.lowmodel import checks
from ballbench.lowmodel.b2b_chain import COMPLEMENTARITY_SCALE, BallBlocks, ChainLayout, chain_forces, chain_system
from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.traction import TractionPatch, free_ball_starts
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.solvers import newton

__all__ = ["GridContact", "grid_contact", "hertz_contact", "sampled_contact", "sampled_pressure", "StickSlipFriction",
           "ContactSummary", "contact_frame", "solve_balls", "check_start", "solve_from_either_start", "STARTS",
           "ROLLING_ITERATIONS", "LAWS", "FD_STEP", "SOLVE_TOLERANCE", "FULL_SLIP_NAME"]

LAWS = ("stick-slip", "full-slip")
# the full-slip limit on a stick/slip solve's cells (pointwise Coulomb, the b2b_traction solves) in its messages
FULL_SLIP_NAME = "full slip on the stick/slip cells (pointwise Coulomb)"
FD_STEP = 1e-6  # forward-difference step of the Jacobian, in the units of the ball's unknowns (O(1))
SOLVE_TOLERANCE = 1e-12  # of each rolling solve (max|F| / max mu p_n); its Newton converges quadratically to it


def contact_frame(normal, axis) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(n, axis, lateral)``: the unit outward normal, the groove axis made normal to it, ``lateral = axis x n``
    (ValueError if ``axis`` is parallel to ``normal``)."""
    n = np.asarray(checks.finite("normal", normal), dtype=float).reshape(3)
    n = n / np.linalg.norm(n)
    t = np.asarray(checks.finite("axis", axis), dtype=float).reshape(3)
    t = t - (t @ n) * n
    norm = float(np.linalg.norm(t))
    if not norm > 1e-9:
        raise ValueError("axis must not be parallel to the contact normal")
    t = t / norm
    return n, t, np.cross(t, n)


@dataclass(frozen=True)
class GridContact:
    """One ball-to-groove contact on a rolling grid, fixed to the ball (module docstring).

    name : e.g. "BL", "SL";  top : on the driven groove (top rail, nut)
    grid : :class:`~lowmodel.contact.halfspace.SurfaceGrid` centred on (0, 0): ``x`` along ``axis``, ``y`` along
        ``lateral`` [m] (the grid of :func:`lowmodel.contact.rolling.hertz_grid`)
    pressure : (nx, ny) normal pressure [Pa], zero in the outermost cells
    centre : (3,) contact centre relative to the ball centre [m] (the ball's frame)
    normal : (3,) outward unit normal (ball into groove);  axis : (3,) unit tangent along the groove
    lateral_curvature : k [1/m] of the contact surface across the groove (0: planar)
    operator : the rolling operator on ``grid`` (:func:`~lowmodel.contact.rolling.half_space_operator` or an FE
        :class:`~lowmodel.contact.rolling.MatrixOperator`), in Kalker's frame with ``x_K = axis``; it must be
        symmetric under the turn by pi about the normal (half-space; a symmetric FE pair)
    shear_modulus : combined G [Pa] (the spin parameter)
    """

    name: str
    top: bool
    grid: SurfaceGrid
    pressure: np.ndarray
    centre: np.ndarray
    normal: np.ndarray
    axis: np.ndarray
    lateral_curvature: float
    operator: object
    shear_modulus: float

    def __post_init__(self):
        checks.freeze_arrays(self, "pressure", "centre", "normal", "axis")

    @property
    def lateral(self) -> np.ndarray:
        """(3,) ``axis x normal``: the grid's ``y`` (Kalker's ``y_K`` where ``x_K = axis``, ``z_K = -normal``)."""
        return np.cross(self.axis, self.normal)

    @property
    def cells(self) -> np.ndarray:
        """Flat indices of the contact cells (``pressure > 0``)."""
        return np.flatnonzero(self.pressure.reshape(-1) > 0.0)

    def points(self) -> np.ndarray:
        """(nx, ny, 3) the surface points of the cells relative to the ball centre [m] (module docstring)."""
        X, Y = self.grid.coordinates()
        return (self.centre + X[..., None] * self.axis + Y[..., None] * self.lateral
                - (0.5 * self.lateral_curvature * Y * Y)[..., None] * self.normal)

    @property
    def normal_force(self) -> float:
        """``sum p dA`` [N]."""
        return float(self.pressure.sum() * self.grid.cell_area)

    def semi_axes(self) -> tuple[float, float]:
        """Semi-axes ``(a, b)`` [m] along the groove and across it of the ellipse with the pressure's second moments
        (``<x^2> = a^2 / 5`` for Hertz's pressure): the Hertz semi-axes for a Hertz pressure."""
        X, Y = self.grid.coordinates()
        weight = self.pressure / self.pressure.sum()
        mx, my = float((weight * X).sum()), float((weight * Y).sum())
        return (math.sqrt(5.0 * float((weight * (X - mx) ** 2).sum())),
                math.sqrt(5.0 * float((weight * (Y - my) ** 2).sum())))

    def central_pressure(self) -> float:
        """``p0 = 3 F / (2 pi a b)`` of :meth:`semi_axes` [Pa] (Hertz's maximum for a Hertz pressure)."""
        a, b = self.semi_axes()
        return 1.5 * self.normal_force / (math.pi * a * b)

    def patch(self) -> TractionPatch:
        """The contact cells as sampled points with the cell forces ``p dA`` and the contact normal: the same
        contact for the pointwise full-slip law (:class:`~lowmodel.contact.traction.SampledCoulomb`)."""
        cells = self.cells
        points = self.points().reshape(-1, 3)[cells]
        forces = self.pressure.reshape(-1)[cells] * self.grid.cell_area
        return TractionPatch(points, np.repeat(self.normal[None, :], len(cells), axis=0), forces, top=self.top,
                             name=self.name)


def grid_contact(name: str, top: bool, grid: SurfaceGrid, pressure, centre, normal, axis, *,
                 lateral_curvature: float, shear_modulus: float, poisson_ratio: float,
                 operator=None) -> GridContact:
    """A :class:`GridContact` with its inputs checked; ``operator`` default the half-space of the combined
    ``shear_modulus`` [Pa] and ``poisson_ratio`` (:func:`lowmodel.contact.rolling.half_space_operator`)."""
    if abs(grid.x_centre) > 0.0 or abs(grid.y_centre) > 0.0:
        raise ValueError("grid must be centred on (0, 0) (the contact centre): the turn by pi maps it onto itself")
    pressure = np.asarray(checks.non_negative("pressure", pressure, "Pa"), dtype=float)
    if pressure.shape != (grid.nx, grid.ny):
        raise ValueError(f"pressure must have the grid's shape {(grid.nx, grid.ny)}, got {pressure.shape}")
    if not np.any(pressure > 0.0):
        raise ValueError(f"contact {name}: pressure must be > 0 somewhere on the grid")
    ring = np.concatenate([pressure[0], pressure[-1], pressure[:, 0], pressure[:, -1]])
    if np.any(ring > 0.0):
        raise ValueError(f"contact {name}: the grid does not cover the contact (pressure > 0 in the outermost cells)")
    n, t, _ = contact_frame(normal, axis)
    centre = np.asarray(checks.finite("centre", centre, "m"), dtype=float).reshape(3)
    shear = checks.positive("shear_modulus", shear_modulus, "Pa")
    nu = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    curvature = checks.finite("lateral_curvature", lateral_curvature, "1/m")
    if operator is None:
        operator = rolling.half_space_operator(grid, shear, nu)
    elif operator.grid != grid:
        raise ValueError(f"contact {name}: the operator's grid differs from the contact's grid")
    return GridContact(str(name), bool(top), grid, pressure, centre, n, t, float(curvature), operator, float(shear))


def hertz_contact(name: str, top: bool, centre, normal, axis, semi_axis_along: float, semi_axis_across: float,
                  normal_force: float, cells, *, lateral_curvature: float, shear_modulus: float, poisson_ratio: float,
                  operator_for=None) -> GridContact:
    """A Hertz contact (semi-axes [m] along and across the groove, force [N]) on the grid of
    :func:`lowmodel.contact.rolling.hertz_grid` with ``cells = (n_along, n_across)``, or on ``cells`` itself if it is
    a :class:`SurfaceGrid` (a fixed grid, e.g. an FE compliance's); ``operator_for(grid)`` gives the operator
    (default the half-space)."""
    grid = cells if isinstance(cells, SurfaceGrid) else rolling.hertz_grid(semi_axis_along, semi_axis_across, cells)
    pressure = rolling.hertz_pressure(grid, semi_axis_along, semi_axis_across, normal_force)
    return grid_contact(name, top, grid, pressure, centre, normal, axis, lateral_curvature=lateral_curvature,
                        shear_modulus=shear_modulus, poisson_ratio=poisson_ratio,
                        operator=None if operator_for is None else operator_for(grid))


def sampled_pressure(grid: SurfaceGrid, x, y, pressure, weights, normal_force: float | None = None, *,
                     order: int = 4, outside: float = 0.0) -> np.ndarray:
    """A sampled pressure (e.g. an FE pressure at its quadrature points) as cell values on ``grid`` [Pa].

    ``x``, ``y`` (q,) [m]: the samples' coordinates in the grid's frame; ``pressure`` (q,) [Pa] >= 0; ``weights``
    (q,) [m^2] their quadrature areas.  At ``order x order`` Gauss-Legendre points of each cell the field takes
    the value of the nearest sample (scipy ``cKDTree``; zero farther than twice the samples' median spacing
    from any sample), and the mean over a cell's points is the cell's value: a cell average of the sampled field
    whatever the samples' distribution (the mean of the samples inside a cell is biased where their areas vary
    across it); then all cells are scaled so that ``sum p dA`` is the samples' force ``sum pressure weights`` (or
    ``normal_force`` [N]).  Samples with ``pressure > 0`` outside the grid's inner cells raise ValueError (the
    grid must cover the contact with one empty cell on each side) unless they carry at most the share
    ``outside`` of the force (a fixed grid, e.g. an FE compliance's, and an FE pressure whose piecewise-linear
    tail reaches one element beyond the contact): those are dropped and their force restored by the scaling.
    """
    x = np.asarray(checks.finite("x", x, "m"), dtype=float).reshape(-1)
    y = np.asarray(checks.finite("y", y, "m"), dtype=float).reshape(-1)
    p = np.asarray(checks.non_negative("pressure", pressure, "Pa"), dtype=float).reshape(-1)
    w = np.asarray(checks.non_negative("weights", weights, "m^2"), dtype=float).reshape(-1)
    if not (x.shape == y.shape == p.shape == w.shape):
        raise ValueError(f"x, y, pressure and weights must have one shape, got {x.shape}, {y.shape}, {p.shape}, "
                         f"{w.shape}")
    order = checks.count("order", order, 1, 16)
    i = np.floor((x - grid.x[0]) / grid.dx + 0.5).astype(int)
    j = np.floor((y - grid.y[0]) / grid.dy + 0.5).astype(int)
    inner = (i >= 1) & (i <= grid.nx - 2) & (j >= 1) & (j <= grid.ny - 2)
    share = float((p * w)[~inner].sum() / max((p * w).sum(), 1e-300))
    if share > checks.non_negative("outside", outside):
        raise ValueError(f"the grid does not cover the sampled contact: pressure > 0 outside its inner cells "
                         f"(a share {share:.3g} of the force, allowed {outside:g})")
    p = np.where(inner, p, 0.0)
    nodes, gauss_weights = np.polynomial.legendre.leggauss(order)
    gx = (grid.x[1:-1, None] + 0.5 * grid.dx * nodes[None, :]).reshape(-1)
    gy = (grid.y[1:-1, None] + 0.5 * grid.dy * nodes[None, :]).reshape(-1)
    GX, GY = np.meshgrid(gx, gy, indexing="ij")
    tree = cKDTree(np.column_stack([x, y]))
    spacing = float(np.median(tree.query(np.column_stack([x, y]), k=2)[0][:, 1])) if x.size > 1 else math.inf
    distance, nearest = tree.query(np.column_stack([GX.reshape(-1), GY.reshape(-1)]))
    field = np.where(distance <= 2.0 * spacing, p[nearest], 0.0).reshape(grid.nx - 2, order, grid.ny - 2, order)
    cells = np.zeros((grid.nx, grid.ny))
    cells[1:-1, 1:-1] = 0.25 * np.einsum("iajb,a,b->ij", field, gauss_weights, gauss_weights)
    target = float((p * w).sum()) if normal_force is None else checks.positive("normal_force", normal_force, "N")
    total = float(cells.sum() * grid.cell_area)
    if not total > 0.0:
        raise ValueError("the samples carry no force on the grid")
    return cells * (target / total)


@dataclass(frozen=True)
class ContactSummary:
    """One contact of a solved ball (the ball's frame; forces and moments on the ball).

    name; normal_force [N]; force (3,) [N] the friction force; moment (3,) [N m] about the ball centre;
    along_groove [N] ``force . axis``; lateral [N] ``force . lateral`` (zero in the full-slip maps of lin2019);
    spin_moment [N m] about the outward normal through the contact centre (lin2019's ``M_{i,O}``);
    rigid_power [W] ``-V sum p . w dA`` (the loss of the power balance); frictional_power [W] ``-V sum p . s dA``;
    drive_power [W] ``sum f . g``: the power the groove puts into the ball through the contact (0 on a groove at
    rest; the input power of the power balance is their sum);
    stick_fraction; spin_parameter Lambda ``= |phi| b G / (mu p0)``; creepage [-] ``|w|`` at the centre over
    ``mu p0 / G`` (the creepage parameter); rolling_speed V [m/s]; solution the
    :class:`~lowmodel.contact.rolling.RollingContact` (Kalker's frame), None for the full-slip law;
    spin_to_roll [-] ``|phi| R``: the spin about the contact normal over the rolling angular speed (the spin per unit
    rolling distance times the distance of the contact from the ball centre; Harris's spin-to-roll ratio)
    """

    name: str
    normal_force: float
    force: np.ndarray
    moment: np.ndarray
    along_groove: float
    lateral: float
    spin_moment: float
    rigid_power: float
    frictional_power: float
    drive_power: float
    stick_fraction: float
    spin_parameter: float
    creepage: float
    rolling_speed: float
    solution: object = None
    spin_to_roll: float = math.nan


class _Item:
    """The static data of one contact of one ball for :class:`StickSlipFriction`."""

    def __init__(self, contact: GridContact, slip_field, moving: float):
        self.contact = contact
        self.cells = contact.cells
        points = contact.points().reshape(-1, 3)[self.cells]
        self.D, self.g = slip_field(points, np.full(len(self.cells), moving))
        centre_D, centre_g = slip_field(contact.centre[None, :], np.array([moving]))
        self.centre_D, self.centre_g = centre_D[0], centre_g[0]
        self.area = contact.grid.cell_area
        self.start = None  # the last traction (Kalker's frame) and its direction, for a warm start
        self.last = None


class StickSlipFriction:
    """The stick/slip friction of ``n`` balls' grid contacts as generalised forces of their unknowns (module
    docstring); the interface of :class:`~lowmodel.contact.traction.SampledCoulomb` for
    :func:`lowmodel.contact.traction.solve_chain`.

    balls : per ball a sequence of :class:`GridContact` (the ball's frame)
    slip_field : ``(points (m, 3), moving (m,)) -> (D (m, 3, k), g (m, 3))``, the rigid slip ``s = D x - g`` of the
        ball against its groove in the model's velocity unit (first unknown: the carrier of the contact points)
    friction_coefficient : mu;  reference_force : F_ref [N] (residuals in units of ``mu F_ref``)
    moving_sign : the ``moving`` value of the driven groove's points (``sign`` of its speed)
    speed_unit : m/s per unit of ``s`` (powers in W)
    law : ``"stick-slip"`` (the rolling solve) or ``"full-slip"`` (its limit on the same cells: the Coulomb
        traction ``-mu p_n w / |w|`` at every cell, for the summaries of a state solved by the full-slip model)
    """

    def __init__(self, balls, slip_field, friction_coefficient: float, reference_force: float, moving_sign: float,
                 speed_unit: float, *, law: str = "stick-slip", tolerance: float = SOLVE_TOLERANCE,
                 step: float = FD_STEP):
        self.law = checks.choice("law", law, LAWS)
        self.mu = checks.positive("friction_coefficient", friction_coefficient)
        self.reference_force = checks.positive("reference_force", reference_force, "N")
        self.speed_unit = checks.positive("speed_unit", speed_unit, "m/s")
        self.tolerance = checks.positive("tolerance", tolerance)
        self.step = checks.positive("step", step)
        self.items = [[_Item(c, slip_field, moving_sign if c.top else 0.0) for c in contacts] for contacts in balls]
        self.n_balls = len(self.items)
        self.n_unknowns = self.items[0][0].D.shape[2]
        self.solves = 0

    # -- one contact -----------------------------------------------------------------------------------------
    def _motion(self, item: _Item, x: np.ndarray):
        contact = item.contact
        mean = 0.5 * (item.centre_D @ x + item.centre_g) - item.centre_D[:, 0] * x[0]
        flow = float(mean @ contact.axis)
        if not (math.isfinite(flow) and flow != 0.0):
            raise ConvergenceError(f"contact {contact.name}: no rolling (mean surface velocity {flow!r} along the "
                                   "groove): steady rolling needs V > 0", residual=math.inf, iterations=0,
                                   tolerance=0.0, reason="no rolling")
        slip = np.einsum("mik,k->mi", item.D, x) - item.g
        speed = abs(flow)
        w = np.zeros((contact.grid.nx * contact.grid.ny, 2))
        w[item.cells, 0] = slip @ contact.axis / speed
        w[item.cells, 1] = slip @ contact.lateral / speed
        return w.reshape(contact.grid.nx, contact.grid.ny, 2), speed, flow < 0.0  # forward: x_K = +axis

    def _solve(self, item: _Item, x: np.ndarray, *, keep: bool):
        """The contact's tractions (nx, ny, 2) in the grid's frame, its Kalker solution, rigid slip and speed."""
        contact = item.contact
        w, speed, forward = self._motion(item, x)
        pressure = contact.pressure
        if not forward:  # Kalker's x_K = -axis: turn the fields by pi about the normal
            w, pressure = -w[::-1, ::-1], pressure[::-1, ::-1]
        if self.law == "full-slip":
            solution = _full_slip(pressure, self.mu, w, speed * self.speed_unit, contact.grid)
        else:
            start = None
            if item.start is not None and item.start[1] == forward:
                start = item.start[0]
            solution = rolling.solve(pressure, contact.operator, self.mu, w, rolling_speed=speed * self.speed_unit,
                                     tolerance=self.tolerance, initial_traction=start)
        self.solves += 1
        if keep:
            item.start = (solution.traction, forward)
        traction = solution.traction if forward else -solution.traction[::-1, ::-1]
        return traction, solution, speed, forward

    def _force(self, item: _Item, traction: np.ndarray) -> np.ndarray:
        """(m, 3) friction force of each contact cell on the ball, in units of ``mu F_ref``."""
        contact = item.contact
        p = traction.reshape(-1, 2)[item.cells]
        return (p[:, :1] * contact.axis + p[:, 1:] * contact.lateral) * (item.area / (self.mu * self.reference_force))

    def _generalised(self, item: _Item, x: np.ndarray, *, keep: bool) -> np.ndarray:
        traction = self._solve(item, x, keep=keep)[0]
        return np.einsum("mik,mi->k", item.D, self._force(item, traction))

    # -- the SampledCoulomb interface --------------------------------------------------------------------------
    def evaluate(self, balls: np.ndarray, jacobian: bool = True, ball: int | None = None):
        """Residual (n, k) (the generalised forces, units ``mu F_ref``) and Jacobian (n, k, k) by forward
        differences at ``balls`` (n, k); ``ball``: that ball only (residual (k,), Jacobian (k, k)).  The third and
        fourth entries (slips and forces of :class:`SampledCoulomb`) are None."""
        balls = np.asarray(balls, dtype=float)
        which = range(self.n_balls) if ball is None else [int(ball)]
        k = self.n_unknowns
        residual = np.zeros((len(which), k))
        jac = np.zeros((len(which), k, k)) if jacobian else None
        for row, b in enumerate(which):
            x = balls[b]
            for item in self.items[b]:
                base = self._generalised(item, x, keep=True)
                residual[row] += base
                if jacobian:  # each perturbed solve starts from the unperturbed tractions (kept above)
                    for j in range(k):
                        shifted = x.copy()
                        shifted[j] += self.step
                        jac[row, :, j] += (self._generalised(item, shifted, keep=False) - base) / self.step
        if ball is not None:
            return residual[0], None if jac is None else jac[0], None, None
        return residual, jac, None, None

    def rolling_start(self) -> np.ndarray:
        """(n, k) the state of each ball nearest to rolling without slip: the least-squares minimum of
        ``sum_cells p dA |s_t|^2`` (``s_t`` the rigid slip's components along ``axis`` and ``lateral``), the
        kinematics where the most loaded contacts roll and spin least.  The start of a stick/slip solve where the
        full-slip law has no state to start from (docs/b2b_rolling.md, "Where full sliding has no state"): near
        the four-point limit the heavy contacts stick, and their rolling is close to the state."""
        starts = np.zeros((self.n_balls, self.n_unknowns))
        for b, items in enumerate(self.items):
            rows, rhs = [], []
            for item in items:
                contact = item.contact
                weight = np.sqrt(contact.pressure.reshape(-1)[item.cells] * item.area)[:, None]
                tangent = np.stack([contact.axis, contact.lateral])  # (2, 3)
                rows.append((weight[:, :, None] * np.einsum("ti,mik->mtk", tangent, item.D)).reshape(-1,
                                                                                                     self.n_unknowns))
                rhs.append((weight * (item.g @ tangent.T)).reshape(-1))
            matrix, vector = np.vstack(rows), np.concatenate(rhs)
            starts[b] = np.linalg.lstsq(matrix, vector, rcond=None)[0]
        return starts

    # -- the solved state --------------------------------------------------------------------------------------
    def summaries(self, balls: np.ndarray) -> list[list[ContactSummary]]:
        """Per ball and contact the :class:`ContactSummary` at the state ``balls`` (n, k)."""
        out = []
        for b, items in enumerate(self.items):
            x = np.asarray(balls[b], dtype=float)
            row = []
            for item in items:
                traction, solution, speed, _ = self._solve(item, x, keep=True)
                row.append(self._summary(item, x, traction, speed, solution))
            out.append(row)
        return out

    def _summary(self, item: _Item, x, traction, speed, solution) -> ContactSummary:
        contact = item.contact
        force_cells = self._force(item, traction) * (self.mu * self.reference_force)  # N
        points = contact.points().reshape(-1, 3)[item.cells]
        force = force_cells.sum(axis=0)
        moment = np.cross(points, force_cells).sum(axis=0)
        spin_moment = float(np.cross(points - contact.centre, force_cells).sum(axis=0) @ contact.normal)
        drive = float(np.einsum("mi,mi->", force_cells, item.g)) * self.speed_unit
        w, _, _ = self._motion(item, x)
        lam, creep = self.indicators(item, w)
        spin = lam * self.mu * contact.central_pressure() / (contact.semi_axes()[1] * contact.shear_modulus)  # |phi|
        return ContactSummary(contact.name, contact.normal_force, force, moment, float(force @ contact.axis),
                              float(force @ contact.lateral), spin_moment, float(solution.rigid_power),
                              float(solution.frictional_power), drive, float(solution.stick_fraction), lam, creep,
                              speed * self.speed_unit, solution, spin * float(np.linalg.norm(contact.centre)))

    def indicators(self, item: _Item, w: np.ndarray) -> tuple[float, float]:
        """Spin parameter ``Lambda = |phi| b G / (mu p0)`` and creepage parameter ``|w_c| G / (mu p0)`` of a
        contact with rigid slip ``w`` (grid frame): ``phi = d w_y / d x`` and ``w_c`` the slip at the centre (a
        rigid field: ``w_y = eta + phi x - omega_x k y^2 / 2``, ``w_x = xi - phi y + omega_y k y^2 / 2``, fitted
        exactly by least squares)."""
        contact = item.contact
        X, Y = contact.grid.coordinates()
        cells = item.cells
        basis = np.column_stack([np.ones(cells.size), X.reshape(-1)[cells], Y.reshape(-1)[cells],
                                 Y.reshape(-1)[cells] ** 2])
        wx = np.linalg.lstsq(basis, w.reshape(-1, 2)[cells, 0], rcond=None)[0]
        wy = np.linalg.lstsq(basis, w.reshape(-1, 2)[cells, 1], rcond=None)[0]
        a, b = contact.semi_axes()
        scale = contact.shear_modulus / (self.mu * contact.central_pressure())
        return abs(float(wy[1])) * b * scale, math.hypot(float(wx[0]), float(wy[0])) * scale


@dataclass(frozen=True)
class _FullSlip:
    """What :meth:`StickSlipFriction._summary` reads of a solution, for the full-slip law."""

    traction: np.ndarray
    rigid_power: float
    frictional_power: float
    stick_fraction: float = 0.0


def _full_slip(pressure: np.ndarray, mu: float, w: np.ndarray, speed: float, grid: SurfaceGrid) -> _FullSlip:
    """Coulomb's traction ``-mu p_n w / |w|`` at every contact cell (Kalker's frame), its power ``-V sum p . w dA``."""
    norm = np.hypot(w[..., 0], w[..., 1])
    traction = -(mu * pressure / np.where(norm > 0.0, norm, np.inf))[..., None] * w
    power = -speed * float(np.sum(traction * w)) * grid.cell_area
    return _FullSlip(traction, power, power)


def sampled_contact(name: str, top: bool, points, pressure, areas, axis, *, cells=None, grid: SurfaceGrid | None = None,
                    lateral_curvature: float, shear_modulus: float, poisson_ratio: float, operator=None,
                    outside: float = 0.0) -> GridContact:
    """A contact from a sampled pressure on the ball's surface (e.g. an FE pressure at its quadrature points).

    ``points`` (q, 3) [m] relative to the ball centre, ``pressure`` (q,) [Pa], ``areas`` (q,) [m^2]; ``axis`` (3,)
    the groove's direction.  The contact centre is the force-weighted centre of the points moved radially onto
    their mean radius (a point of the ball's surface), the normal its radial direction; the samples' coordinates
    in the tangent plane give the cell pressure (:func:`sampled_pressure`).  ``cells = (n_along, n_across)``: a
    grid of that many cells over the pressure's support (one empty cell on each side); or a given ``grid``
    centred on the contact centre (e.g. the grid of an FE compliance, ``operator``; ``outside``: the share of the
    force that may lie beyond its inner cells, :func:`sampled_pressure`).
    """
    points = np.asarray(checks.finite("points", points, "m"), dtype=float).reshape(-1, 3)
    p = np.asarray(checks.non_negative("pressure", pressure, "Pa"), dtype=float).reshape(-1)
    w = np.asarray(checks.non_negative("areas", areas, "m^2"), dtype=float).reshape(-1)
    if not (len(points) == len(p) == len(w)):
        raise ValueError(f"points, pressure and areas must have one length, got {len(points)}, {len(p)}, {len(w)}")
    force = p * w
    if not force.sum() > 0.0:
        raise ValueError(f"contact {name}: the samples carry no force")
    centroid = force @ points / force.sum()
    radius = float(np.average(np.linalg.norm(points, axis=1), weights=force))
    centre = centroid * (radius / float(np.linalg.norm(centroid)))
    n, t, lateral = contact_frame(centre, axis)
    X, Y = (points - centre) @ t, (points - centre) @ lateral
    if grid is None:
        if cells is None:
            raise ValueError("give cells or grid")
        loaded = p > 0.0
        margin = 1.0 + 1e-6
        grid = rolling.hertz_grid(margin * float(np.abs(X[loaded]).max()), margin * float(np.abs(Y[loaded]).max()),
                                  cells)
    cell_pressure = sampled_pressure(grid, X, Y, p, w, outside=outside)
    return grid_contact(name, top, grid, cell_pressure, centre, n, t, lateral_curvature=lateral_curvature,
                        shear_modulus=shear_modulus, poisson_ratio=poisson_ratio, operator=operator)


STARTS = ("full-slip", "rolling", "auto")  # the stick/slip solves' starts (docs/b2b_rolling.md)
ROLLING_ITERATIONS = 4  # start="auto" from rolling: Newton's step budget times this (docs/b2b_rolling.md)


def check_start(start: str, law: str, full_slip) -> str:
    """``start`` of a stick/slip solve, checked: "rolling" and "auto" are the stick/slip law's own starts."""
    start = checks.choice("start", start, STARTS)
    if start != "full-slip" and (law != "stick-slip" or full_slip is not None):
        raise ValueError(f"start={start!r} is the stick/slip law's own start: law must be 'stick-slip' and "
                         "full_slip None")
    return start


def solve_from_either_start(solve, max_iterations: int, what: str, warm=None):
    """``start="auto"``: ``solve(start, max_iterations)`` from full slip on the cells, else (``warm()``, a solve from
    a nearby state, where given, else) from rolling with :data:`ROLLING_ITERATIONS` times the steps (near stick/slip
    switches Newton converges linearly from there); ConvergenceError naming ``what`` and both failures when neither
    converges."""
    try:
        return solve("full-slip", max_iterations)
    except ConvergenceError as error:
        if warm is not None:
            try:
                return warm()
            except ConvergenceError:
                pass
        try:
            return solve("rolling", ROLLING_ITERATIONS * max_iterations)
        except ConvergenceError as again:
            raise ConvergenceError(f"{what}: converged neither from full slip on the cells ({error}) nor from "
                                   f"rolling ({again})", residual=again.residual, iterations=again.iterations,
                                   tolerance=again.tolerance, reason=again.reason) from again


def solve_balls(friction: StickSlipFriction, start: np.ndarray, touching, pair_function_of, *, forces=None,
                complementarity: str, tolerance: float, max_iterations: int, what: str):
    """The balls of ``friction`` in equilibrium, with B2B contact of the ``touching`` pairs (the chain of
    :mod:`lowmodel.b2b_chain`; rate: unknown 0; ``pair_function_of(layout)`` the model's B2B loads), by
    Levenberg-Marquardt Newton (:func:`lowmodel.solvers.newton`) from ``start`` (n, k) and the pair ``forces``
    (force-slot units; e.g. a full-slip solution of the same balls).  Without touching pairs every ball is solved
    on its own.  Returns ``(states (n, k), forces (n-1,) in slot units, iterations, max residual)``;
    ConvergenceError naming ``what``.
    """
    start = np.asarray(start, dtype=float)
    n, k = start.shape
    touching = np.asarray(touching, dtype=int)
    if touching.size == 0:
        states, iterations = free_ball_starts(friction.evaluate, start, tolerance=tolerance,
                                              max_iterations=max_iterations, what=what)
        residual = float(np.max(np.abs(friction.evaluate(states, jacobian=False)[0])))
        return states, np.zeros(max(n - 1, 0)), iterations, residual

    def ball_function(states, _extra=None):
        residual, jac = friction.evaluate(states)[:2]
        return BallBlocks(residual, jac)

    layout = ChainLayout(n, k, touching)
    function = chain_system(ball_function, pair_function_of(layout), layout, rate_index=0,
                            rate_scale=COMPLEMENTARITY_SCALE, complementarity=complementarity)
    z, residual, iterations = newton(function, layout.pack(start, forces), tolerance=tolerance,
                                     max_iterations=max_iterations, what=what)
    states, slots, _ = chain_forces(z, layout, rate_index=0, rate_scale=COMPLEMENTARITY_SCALE, tolerance=tolerance,
                                    iterations=iterations, what=what)
    return states, slots, iterations, float(np.max(np.abs(residual)))
