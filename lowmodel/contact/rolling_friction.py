"""Ball-to-groove friction from the steady rolling solve: the stick/slip contact law of a ball's equilibrium.

The full-slip models of lin2019 (eqs A4-A7, 44-47; :mod:`lowmodel.contact.ellipse_friction`) and the FE-informed
models (:mod:`lowmodel.contact.traction`) give every point of a contact the Coulomb traction ``mu p`` opposite
to the rigid slip.  Here the traction of each ball-to-groove contact comes from Kalker's steady rolling
problem (:mod:`lowmodel.contact.rolling`): stick and slip areas, elastic creep and the tangential compliance
of the bodies (two half-spaces, or a compliance condensed from the FE, :mod:`fem.rolling_compliance`), with
the creepages and spin of every point following from the ball's rigid-body state (docs/b2b_rolling.md).

A contact (:class:`~lowmodel.contact.grid_contact.GridContact`, re-exported here with its constructors) is fixed to
the ball: a grid in its tangent plane with the normal pressure on the cells (:mod:`lowmodel.contact.grid_contact`).
The product models give the rigid slip of the ball against its groove at those points as a linear
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
  Jacobian is ``sum_cells D^T (dp/dw) (dw/dx) dA`` with ``dp/dw`` the rolling solve's sensitivity (the implicit
  function theorem at its solution, :func:`lowmodel.contact.rolling_newton.sensitivity`: one linear solve per
  unknown, no new Newton solve) and ``dw/dx = (T D - w dV/dx) / V``; ``jacobian_method="finite-difference"`` takes
  forward differences instead (step :data:`FD_STEP` in the unknowns' units, each solve warm-started from the
  unperturbed tractions), as the full-slip law always does (docs/b2b_rolling.md, "Costs").

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

import functools
import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.b2b_chain import COMPLEMENTARITY_SCALE, BallBlocks, ChainLayout, chain_forces, chain_system
from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.contact.grid_contact import (GridContact, contact_frame, grid_contact, hertz_contact,
                                                     sampled_contact, sampled_pressure)
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.traction import free_ball_starts
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.solvers import newton

__all__ = ["GridContact", "grid_contact", "hertz_contact", "sampled_contact", "sampled_pressure", "StickSlipFriction",
           "ContactSummary", "contact_frame", "solve_balls", "check_start", "solve_from_either_start", "STARTS",
           "ROLLING_ITERATIONS", "LAWS", "JACOBIANS", "FD_STEP", "SOLVE_TOLERANCE", "FULL_SLIP_NAME"]

LAWS = ("stick-slip", "full-slip")
JACOBIANS = ("analytic", "finite-difference")  # how StickSlipFriction.evaluate takes its Jacobian
# the full-slip limit on a stick/slip solve's cells (pointwise Coulomb, the b2b_traction solves) in its messages
FULL_SLIP_NAME = "full slip on the stick/slip cells (pointwise Coulomb)"
FD_STEP = 1e-6  # forward-difference step of the Jacobian, in the units of the ball's unknowns (O(1))
SOLVE_TOLERANCE = 1e-12  # of each rolling solve (max|F| / max mu p_n); its Newton converges quadratically to it


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
        self.last = None  # (x, what _solve returned) of the last kept solve: the same state is not solved twice
        self.workspace = {}  # the rolling solves' preconditioner, carried from one solve of this contact to the next


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
    jacobian_method : ``"analytic"`` (the rolling solve's sensitivity; the stick/slip law) or ``"finite-difference"``
        (module docstring)
    """

    def __init__(self, balls, slip_field, friction_coefficient: float, reference_force: float, moving_sign: float,
                 speed_unit: float, *, law: str = "stick-slip", tolerance: float = SOLVE_TOLERANCE,
                 step: float = FD_STEP, jacobian_method: str = "analytic"):
        self.law = checks.choice("law", law, LAWS)
        self.jacobian_method = checks.choice("jacobian_method", jacobian_method, JACOBIANS)
        if self.law == "full-slip":
            self.jacobian_method = "finite-difference"
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

    def _directions(self, item: _Item, w: np.ndarray, speed: float, forward: bool) -> np.ndarray:
        """(nx, ny, 2, k) ``dw/dx`` in the grid's frame: ``w = T (D x - g) / V`` with ``V = |u_m . axis|``
        (module docstring), so ``dw/dx = (T D - w dV/dx) / V``."""
        contact = item.contact
        k = self.n_unknowns
        flow_rate = contact.axis @ (0.5 * item.centre_D)  # d(u_m . axis)/dx
        flow_rate[0] -= float(contact.axis @ item.centre_D[:, 0])
        speed_rate = -flow_rate if forward else flow_rate   # forward: u_m . axis < 0, V = -u_m . axis
        out = np.zeros((contact.grid.nx * contact.grid.ny, 2, k))
        cells = w.reshape(-1, 2)[item.cells]
        out[item.cells, 0] = (np.einsum("i,mik->mk", contact.axis, item.D) - cells[:, :1] * speed_rate) / speed
        out[item.cells, 1] = (np.einsum("i,mik->mk", contact.lateral, item.D) - cells[:, 1:] * speed_rate) / speed
        return out.reshape(contact.grid.nx, contact.grid.ny, 2, k)

    def _solve(self, item: _Item, x: np.ndarray, *, keep: bool, derivative: bool = False):
        """The contact's tractions (nx, ny, 2) in the grid's frame, its Kalker solution, rigid slip and speed;
        with ``derivative`` also the tractions' derivative along the unknowns (nx, ny, 2, k) (grid frame)."""
        if not derivative and item.last is not None and np.array_equal(item.last[0], x):
            return item.last[1]  # this state was solved last (e.g. the converged state's summaries)
        contact = item.contact
        w, speed, forward = self._motion(item, x)
        directions = self._directions(item, w, speed, forward) if derivative else None
        pressure = contact.pressure
        if not forward:  # Kalker's x_K = -axis: turn the fields by pi about the normal
            w, pressure = -w[::-1, ::-1], pressure[::-1, ::-1]
            directions = None if directions is None else -directions[::-1, ::-1]
        if self.law == "full-slip":
            solution = _full_slip(pressure, self.mu, w, speed * self.speed_unit, contact.grid)
        else:
            start = rate = None
            if item.start is not None and item.start[1] == forward:
                traction, _, at, rate = item.start
                # a first-order prediction from the last solve's sensitivity, where it has one
                start = traction if rate is None else traction + rate @ (x - at)
            solution = rolling.solve(pressure, contact.operator, self.mu, w, rolling_speed=speed * self.speed_unit,
                                     tolerance=self.tolerance, initial_traction=start,
                                     sensitivity_directions=directions,
                                     initial_sensitivity=rate if directions is not None else None,
                                     workspace=item.workspace)
        self.solves += 1
        if keep:  # a solve without the sensitivity keeps the last one for the next prediction
            rate = solution.traction_sensitivity
            if rate is None and item.start is not None and item.start[1] == forward:
                rate = item.start[3]
            item.start = (solution.traction, forward, x.copy(), rate)
        traction = solution.traction if forward else -solution.traction[::-1, ::-1]
        if keep:
            item.last = (x.copy(), (traction, solution, speed, forward))
        if not derivative:
            return traction, solution, speed, forward
        rate = solution.traction_sensitivity
        return traction, solution, speed, forward, rate if forward else -rate[::-1, ::-1]

    def _force(self, item: _Item, traction: np.ndarray) -> np.ndarray:
        """(m, 3) friction force of each contact cell on the ball, in units of ``mu F_ref``."""
        contact = item.contact
        p = traction.reshape(-1, 2)[item.cells]
        return (p[:, :1] * contact.axis + p[:, 1:] * contact.lateral) * (item.area / (self.mu * self.reference_force))

    def _generalised(self, item: _Item, x: np.ndarray, *, keep: bool) -> np.ndarray:
        traction = self._solve(item, x, keep=keep)[0]
        return np.einsum("mik,mi->k", item.D, self._force(item, traction))

    def _generalised_with_jacobian(self, item: _Item, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The generalised force (k,) and its Jacobian (k, k) from the rolling solve's sensitivity (module
        docstring): ``dR/dx = sum_cells D^T (axis, lateral) dp/dx dA / (mu F_ref)``."""
        traction, _, _, _, rate = self._solve(item, x, keep=True, derivative=True)
        contact = item.contact
        scale = item.area / (self.mu * self.reference_force)
        cells = rate.reshape(-1, 2, self.n_unknowns)[item.cells] * scale  # (m, 2, k)
        force_rate = contact.axis[None, :, None] * cells[:, None, 0, :] + contact.lateral[None, :, None] * \
            cells[:, None, 1, :]
        return (np.einsum("mik,mi->k", item.D, self._force(item, traction)),
                np.einsum("mik,mij->kj", item.D, force_rate))

    # -- the SampledCoulomb interface --------------------------------------------------------------------------
    def evaluate(self, balls: np.ndarray, jacobian: bool = True, ball: int | None = None, lazy: bool = False):
        """Residual (n, k) (the generalised forces, units ``mu F_ref``) and Jacobian (n, k, k) (analytic or by
        forward differences, ``jacobian_method``) at ``balls`` (n, k); ``ball``: that ball only (residual (k,), Jacobian
        (k, k)).  The third and fourth entries (slips and forces of :class:`SampledCoulomb`) are None.  ``lazy``
        (analytic Jacobian): the Jacobian as a function of no arguments, computed when called (its sensitivity
        solves cost about as much as the residual's solves; :func:`lowmodel.solvers.newton` calls it only where a
        step needs it)."""
        balls = np.asarray(balls, dtype=float)
        if lazy and jacobian and self.jacobian_method == "analytic":
            residual = self.evaluate(balls, jacobian=False, ball=ball)[0]
            at = balls.copy()
            return residual, lambda: self.evaluate(at, ball=ball)[1], None, None
        which = range(self.n_balls) if ball is None else [int(ball)]
        k = self.n_unknowns
        residual = np.zeros((len(which), k))
        jac = np.zeros((len(which), k, k)) if jacobian else None
        for row, b in enumerate(which):
            x = balls[b]
            for item in self.items[b]:
                if jacobian and self.jacobian_method == "analytic":
                    base, rate = self._generalised_with_jacobian(item, x)
                    residual[row] += base
                    jac[row] += rate
                    continue
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
    traction_sensitivity: None = None


def _full_slip(pressure: np.ndarray, mu: float, w: np.ndarray, speed: float, grid: SurfaceGrid) -> _FullSlip:
    """Coulomb's traction ``-mu p_n w / |w|`` at every contact cell (Kalker's frame), its power ``-V sum p . w dA``."""
    norm = np.hypot(w[..., 0], w[..., 1])
    traction = -(mu * pressure / np.where(norm > 0.0, norm, np.inf))[..., None] * w
    power = -speed * float(np.sum(traction * w)) * grid.cell_area
    return _FullSlip(traction, power, power)


STARTS = ("full-slip", "rolling", "alone", "auto")  # the stick/slip solves' starts (docs/b2b_rolling.md)
ROLLING_ITERATIONS = 4  # start="auto" from rolling: Newton's step budget times this (docs/b2b_rolling.md)


def check_start(start: str, law: str, full_slip) -> str:
    """``start`` of a stick/slip solve, checked: "rolling", "alone" and "auto" are the stick/slip law's own
    starts."""
    start = checks.choice("start", start, STARTS)
    if start != "full-slip" and (law != "stick-slip" or full_slip is not None):
        raise ValueError(f"start={start!r} is the stick/slip law's own start: law must be 'stick-slip' and "
                         "full_slip None")
    return start


def solve_from_either_start(solve, max_iterations: int, what: str, warm=None, alone=None, full_slip: bool = True):
    """``start="auto"``: ``solve(start, max_iterations)`` from full slip on the cells (unless not ``full_slip``: balls
    without a full-slip state on the cells), else (``warm()``, a solve from a nearby state, where given; then
    ``alone()``, a chain's solve from the states of its balls each solved alone, where given, else) from rolling
    with :data:`ROLLING_ITERATIONS` times the steps (near stick/slip switches Newton converges linearly from there);
    ConvergenceError naming ``what`` and both failures when none converges."""
    error = "not tried: balls with different numbers of contacts"
    if full_slip:
        try:
            return solve("full-slip", max_iterations)
        except ConvergenceError as failed:
            error = failed
    for nearer in (warm, alone):
        if nearer is not None:
            try:
                return nearer()
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
        states, iterations = free_ball_starts(functools.partial(friction.evaluate, lazy=True), start,
                                              tolerance=tolerance, max_iterations=max_iterations, what=what)
        residual = float(np.max(np.abs(friction.evaluate(states, jacobian=False)[0])))
        return states, np.zeros(max(n - 1, 0)), iterations, residual

    def ball_function(states, _extra=None):
        residual, jac = friction.evaluate(states, lazy=True)[:2]
        return BallBlocks(residual, jac)

    layout = ChainLayout(n, k, touching)
    function = chain_system(ball_function, pair_function_of(layout), layout, rate_index=0,
                            rate_scale=COMPLEMENTARITY_SCALE, complementarity=complementarity)
    z, residual, iterations = newton(function, layout.pack(start, forces), tolerance=tolerance,
                                     max_iterations=max_iterations, what=what)
    states, slots, _ = chain_forces(z, layout, rate_index=0, rate_scale=COMPLEMENTARITY_SCALE, tolerance=tolerance,
                                    iterations=iterations, what=what)
    return states, slots, iterations, float(np.max(np.abs(residual)))
