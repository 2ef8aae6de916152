"""The rigid carriage of a linear ball guide: the load of every ball of its rows, and its stiffness (docs/carriage.md).

A carriage rides on its rail on rows of balls in two-point contact (the four-row 45 deg carriages of the catalogues):
each ball touches a rail groove and a carriage groove on one load line through its centre.  Per row the load line
makes the contact angle ``alpha`` with the lateral axis; ``n`` is its unit vector from the ball centre towards the
rail contact.  The two grooves' curvature centres lie on that line, ``A0 = (f_rail + f_carriage - 1) D = (2 f - 1) D``
apart (one conformity ``f`` for rail and carriage, as :class:`lowmodel.bearing.LinearGuide`); the carriage's lies
``(f D - R_B) n`` from the ball centre, on the rail side.  Under load the rigid carriage moves by
``q = (u_x, u_y, phi_x, phi_y, phi_z)`` (lateral and vertical translation; rotations about the lateral, vertical and
rail axes), its groove's curvature centre ``c`` by ``d = u + phi x c`` (the part in the cross-section: the groove is
straight along the rail), and (Harris & Kotzalas, *Rolling Bearing Analysis*, the load distribution of a rigid ring
by the distance of the curvature centres; Jones 1960)

    A = A0 n + d,   delta = |A| - A0 + s - c_relief(z),   Q = (max(delta, 0) / (2 C))^(3/2)

with ``s`` the ball oversize (preload), ``c_relief(z)`` the end relief (crowning) of the carriage's grooves, ``C``
Hertz's constant of one ball-groove contact (``delta_contact = C Q^(2/3)``, lin2019 eq 53; both contacts alike, so
the ball's approach is twice a contact's) and ``e = A / |A|`` the loaded line.  The ball pushes the carriage with
``-Q e`` at ``c``; the carriage is in equilibrium when its balls balance the external load
``(F_x, F_y, M_x, M_y, M_z)`` at the origin: ``sum_k J_k^T (-Q_k e_k) + F = 0`` (``J_k = d d_k / d q``).  Newton on
``q`` with the exact tangent stiffness

    K = sum_k J_k^T (dQ/d delta e e^T + Q / |A| (I - e e^T)) J_k      (5 x 5, the carriage's stiffness)

and a backtracking line search; the answer is checked before it is returned (the load balance within
:data:`BALANCE_TOLERANCE` of the largest force), else ConvergenceError naming the check.

Frame: lin2019 Fig 2, ``z`` along the rail (the travel), ``y`` vertical from the rail to the carriage, ``x`` lateral;
the origin is the carriage's reference point (the loads act there).

```python
from ballbench.lowmodel.linear_bearing import carriage
rows = carriage.four_rows(half_width=10e-3, upper=8e-3, lower=2e-3, contact_angle=math.radians(45))
body = carriage.Carriage(guide, rows, balls_per_row=13, pitch=4e-3, oversize=2e-6)
state = carriage.solve(body, carriage.Load(vertical=5e3, roll=20.0))
state.normal_force, state.contact_angle, state.stiffness, state.balance
```
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["Row", "Carriage", "Load", "CarriageState", "four_rows", "solve", "ball_positions", "relief",
           "BALANCE_TOLERANCE", "LOAD_NAMES", "DISPLACEMENT_NAMES"]

BALANCE_TOLERANCE = 1e-10  # the load balance of a solved carriage, relative to its largest force (and moment / L)
LOAD_NAMES = ("F_x", "F_y", "M_x", "M_y", "M_z")  # [N, N, N m, N m, N m] on the carriage at the origin
DISPLACEMENT_NAMES = ("u_x", "u_y", "phi_x", "phi_y", "phi_z")  # [m, m, rad, rad, rad] of the carriage


@dataclass(frozen=True)
class Row:
    """A row of balls in two-point contact: ``x``, ``y`` [m] the balls' centres in the cross-section (unloaded),
    ``normal`` the load line's unit vector from the ball centre towards the rail contact (2,), in the cross-section.
    """

    x: float
    y: float
    normal: tuple

    def __post_init__(self):
        checks.finite("x", self.x, "m")
        checks.finite("y", self.y, "m")
        n = np.asarray(self.normal, dtype=float)
        if n.shape != (2,) or not np.all(np.isfinite(n)) or abs(float(np.hypot(*n)) - 1.0) > 1e-12:
            raise ValueError(f"normal must be a unit vector (n_x, n_y) in the cross-section, got {self.normal!r}")
        object.__setattr__(self, "normal", (float(n[0]), float(n[1])))

    @property
    def contact_angle(self) -> float:
        """[rad] of the unloaded load line against the lateral axis (0 to pi/2)."""
        return math.atan2(abs(self.normal[1]), abs(self.normal[0]))


def four_rows(*, half_width: float, upper: float, lower: float, contact_angle: float) -> tuple[Row, ...]:
    """The four rows of a four-row carriage in the 45 deg arrangement of the catalogues: two upper rows at height
    ``upper`` [m] carrying the carriage's downward load (the rail below and inside each ball) and two lower rows at
    ``lower`` [m] holding it against lift-off (the rail above and inside), at ``x = +-half_width`` [m], every load line
    at ``contact_angle`` [rad] to the lateral axis.  Order: upper right, upper left, lower right, lower left."""
    checks.positive("half_width", half_width, "m")
    alpha = checks.bounded("contact_angle", contact_angle, 0.0, math.pi / 2, lower_closed=False, upper_closed=False)
    c, s = math.cos(alpha), math.sin(alpha)
    return (Row(half_width, upper, (-c, -s)), Row(-half_width, upper, (c, -s)),
            Row(half_width, lower, (-c, s)), Row(-half_width, lower, (c, s)))


@dataclass(frozen=True)
class Carriage:
    """A rigid carriage on its rail: the guide's balls and grooves (:class:`lowmodel.bearing.LinearGuide`: ball
    radius, conformity, material), its ``rows``, ``balls_per_row`` balls at ``pitch`` [m] in each row's loaded zone
    (centred on the origin, shifted by ``travel`` [m] in :func:`ball_positions`), the ball ``oversize`` [m] (the
    preload: each ball's two contacts approach by it when the carriage sits centred), and the end relief of the
    grooves (crowning): ``relief_depth`` [m] at the ends of the loaded zone, falling quadratically to zero over
    ``relief_length`` [m] (:func:`relief`)."""

    guide: object
    rows: tuple
    balls_per_row: int
    pitch: float
    oversize: float = 0.0
    relief_length: float = 0.0
    relief_depth: float = 0.0

    def __post_init__(self):
        if not self.rows or not all(isinstance(r, Row) for r in self.rows):
            raise ValueError(f"rows must be a non-empty sequence of carriage.Row, got {self.rows!r}")
        object.__setattr__(self, "rows", tuple(self.rows))
        checks.count("balls_per_row", self.balls_per_row, 1, 10_000)
        checks.positive("pitch", self.pitch, "m")
        if self.pitch < 2.0 * self.guide.ball_radius:
            raise ValueError(f"pitch {self.pitch!r} m is below the ball diameter {2 * self.guide.ball_radius!r} m: "
                             "the balls of a row would overlap")
        checks.non_negative("oversize", self.oversize, "m")
        checks.non_negative("relief_length", self.relief_length, "m")
        checks.non_negative("relief_depth", self.relief_depth, "m")

    @property
    def half_length(self) -> float:
        """[m] from the centre of the loaded zone to its end balls."""
        return 0.5 * (self.balls_per_row - 1) * self.pitch


def relief(body: Carriage, z) -> np.ndarray:
    """The end relief [m] of the grooves at ``z`` [m]: ``relief_depth ((|z| - (L - l)) / l)^2`` within the relief
    length ``l`` of the ends ``+-L`` of the loaded zone, 0 inside it."""
    z = np.abs(np.asarray(z, dtype=float))
    if body.relief_length == 0.0 or body.relief_depth == 0.0:
        return np.zeros_like(z)
    start = body.half_length - body.relief_length
    return body.relief_depth * (np.clip(z - start, 0.0, None) / body.relief_length) ** 2


def ball_positions(body: Carriage, travel: float = 0.0) -> np.ndarray:
    """(balls_per_row,) z [m] of the balls of every row, centred on the origin and shifted by ``travel`` [m]."""
    k = np.arange(body.balls_per_row, dtype=float)
    return (k - 0.5 * (body.balls_per_row - 1)) * body.pitch + float(travel)


@dataclass(frozen=True)
class Load:
    """External load on the carriage at its reference point [N, N m]: lateral ``lateral`` (F_x), ``vertical`` (F_y,
    positive pressing the carriage onto the rail, i.e. along -y), and the moments ``pitch`` (M_x, about the lateral
    axis), ``yaw`` (M_y, about the vertical) and ``roll`` (M_z, about the rail), right-handed about +x, +y, +z."""

    lateral: float = 0.0
    vertical: float = 0.0
    pitch: float = 0.0
    yaw: float = 0.0
    roll: float = 0.0

    def __post_init__(self):
        for name in ("lateral", "vertical", "pitch", "yaw", "roll"):
            checks.finite(name, getattr(self, name), "N or N m")

    @property
    def vector(self) -> np.ndarray:
        """(5,) the generalised force ``(F_x, F_y, M_x, M_y, M_z)`` conjugate to the carriage's displacements."""
        return np.array([self.lateral, -self.vertical, self.pitch, self.yaw, self.roll])


@dataclass(frozen=True)
class CarriageState:
    """The carriage in equilibrium under a load (:func:`solve`); arrays of shape (rows, balls_per_row).

    displacement : (5,) ``(u_x, u_y, phi_x, phi_y, phi_z)`` [m, m, rad, rad, rad];  z : (balls,) m
    normal_force : N, each ball's load (both its contacts);  contact_angle : rad, the loaded line against the
        lateral axis;  approach : m, the ball's total approach (both contacts; not positive: unloaded)
    a, b : m, Hertz's semi-axes of each contact (``a`` across the groove);  p0 : Pa
    stiffness : (5, 5) ``-dR/dq`` [N/m, N/rad, N m/m, N m/rad]: the carriage's tangent stiffness at the state
    balance : the load balance's residual over the largest force (moments over the half-length)
    iterations : Newton steps
    """

    displacement: np.ndarray
    z: np.ndarray
    normal_force: np.ndarray
    contact_angle: np.ndarray
    approach: np.ndarray
    a: np.ndarray
    b: np.ndarray
    p0: np.ndarray
    stiffness: np.ndarray
    balance: float
    iterations: int

    def __post_init__(self):
        checks.freeze_arrays(self, "displacement", "z", "normal_force", "contact_angle", "approach", "a", "b", "p0",
                             "stiffness")


class _Geometry:
    """The static arrays of a carriage at one travel: per ball its row's line, curvature centre and Jacobian."""

    def __init__(self, body: Carriage, travel: float):
        guide = body.guide
        radius, conformity = guide.ball_radius, guide.conformity
        self.hertz = hertz.groove_geometry(guide)
        self.constant = hertz.hertz_constant(self.hertz)  # m N^(-2/3), one contact
        self.a0 = (2.0 * conformity - 1.0) * 2.0 * radius
        z = ball_positions(body, travel)
        rows = body.rows
        normal = np.array([r.normal for r in rows])  # (r, 2)
        centre = np.array([[r.x, r.y] for r in rows]) + (conformity * 2.0 * radius - radius) * normal  # groove centre
        self.z = z
        self.normal = np.repeat(normal[:, None, :], len(z), axis=1)  # (r, n, 2)
        zz = np.broadcast_to(z, (len(rows), len(z)))
        cx = np.broadcast_to(centre[:, :1], zz.shape)
        cy = np.broadcast_to(centre[:, 1:], zz.shape)
        one, zero = np.ones_like(zz), np.zeros_like(zz)
        # J[r, k, i, j] = d d_i / d q_j at the ball's carriage-groove curvature centre (i: x, y)
        self.jac = np.stack([np.stack([one, zero, zero, zz, -cy], axis=-1),
                             np.stack([zero, one, -zz, zero, cx], axis=-1)], axis=-2)
        self.offset = body.oversize - relief(body, zz)  # (r, n) m
        self.scale = max(body.half_length, radius)  # m: moments over it compare with forces

    def forces(self, q: np.ndarray, tangent: bool = True):
        d = np.einsum("rkij,j->rki", self.jac, q)
        vector = self.a0 * self.normal + d
        length = np.linalg.norm(vector, axis=-1)
        e = vector / length[..., None]
        approach = length - self.a0 + self.offset
        positive = np.clip(approach, 0.0, None)
        load = (positive / (2.0 * self.constant)) ** 1.5
        generalised = -np.einsum("rkij,rki->j", self.jac, load[..., None] * e)
        if not tangent:
            return generalised, load, e, approach, None
        slope = 1.5 * np.sqrt(positive) / (2.0 * self.constant) ** 1.5  # dQ / d delta
        outer = e[..., :, None] * e[..., None, :]
        local = slope[..., None, None] * outer + (load / length)[..., None, None] * (np.eye(2) - outer)
        stiffness = np.einsum("rkaj,rkab,rkbl->jl", self.jac, local, self.jac)
        return generalised, load, e, approach, stiffness


def solve(body: Carriage, load: Load, *, travel: float = 0.0, tolerance: float = BALANCE_TOLERANCE,
          max_iterations: int = 60) -> CarriageState:
    """The rigid ``body`` (:class:`Carriage`) in equilibrium under ``load`` (:class:`Load`) with its balls at
    ``travel`` [m] (module docstring).  ValueError for bad input; ConvergenceError naming the check (the load balance
    within ``tolerance`` of the largest force) when Newton stops short, e.g. a load no row can carry (lift-off
    without rows against it)."""
    if not isinstance(body, Carriage):
        raise ValueError(f"body must be a carriage.Carriage, got {type(body).__name__}")
    if not isinstance(load, Load):
        raise ValueError(f"load must be a carriage.Load, got {type(load).__name__}")
    checks.finite("travel", travel, "m")
    checks.positive("tolerance", tolerance)
    checks.count("max_iterations", max_iterations, 1, 10_000)
    geometry = _Geometry(body, travel)
    external = load.vector
    weights = np.array([1.0, 1.0, 1.0 / geometry.scale, 1.0 / geometry.scale, 1.0 / geometry.scale])

    def measure(residual, loads):
        reference = max(float(np.max(np.abs(external * weights))), float(np.max(loads, initial=0.0)), 1e-300)
        return float(np.max(np.abs(residual * weights))) / reference

    q = np.zeros(5)
    if not np.any(external) and body.oversize == 0.0:  # nothing pushes the balls: the carriage sits unloaded
        return _state(geometry, q, external, 0, measure)
    if body.oversize == 0.0:
        q = _linear_start(geometry, external)
    iterations = 0
    generalised, loads, _, _, stiffness = geometry.forces(q)
    residual = generalised + external
    norm = measure(residual, loads)
    while norm > tolerance:
        if iterations >= max_iterations:
            raise ConvergenceError("carriage.solve: the load balance missed (sum of the balls' forces and moments "
                                   "plus the external load, over the largest force)", residual=norm,
                                   iterations=iterations, tolerance=tolerance, reason="load balance missed")
        step = _step(stiffness, residual, geometry)
        factor, accepted = 1.0, False
        for _ in range(40):
            trial = q + factor * step
            g_t, l_t, _, _, k_t = geometry.forces(trial)
            r_t = g_t + external
            n_t = measure(r_t, l_t)
            if n_t < norm or n_t <= tolerance:
                q, residual, loads, stiffness, norm, accepted = trial, r_t, l_t, k_t, n_t, True
                break
            factor *= 0.5
        iterations += 1
        if not accepted:
            raise ConvergenceError("carriage.solve: no step reduces the load balance's residual (a load the rows "
                                   "cannot carry, e.g. lift-off without rows against it)", residual=norm,
                                   iterations=iterations, tolerance=tolerance, reason="no descent step")
    return _state(geometry, q, external, iterations, measure)


def _step(stiffness: np.ndarray, residual: np.ndarray, geometry: _Geometry) -> np.ndarray:
    """Newton's step ``K^-1 R`` in scaled displacements (rotations times the half-length), least squares where
    ``K`` is singular (rows without load)."""
    scale = np.array([1.0, 1.0, geometry.scale, geometry.scale, geometry.scale])
    scaled = stiffness / np.outer(scale, scale)
    rhs = residual / scale
    try:
        solution = np.linalg.solve(scaled, rhs)
        if not np.all(np.isfinite(solution)):
            raise np.linalg.LinAlgError
    except np.linalg.LinAlgError:
        solution = np.linalg.lstsq(scaled, rhs, rcond=1e-12)[0]
    return solution / scale


def _linear_start(geometry: _Geometry, external: np.ndarray) -> np.ndarray:
    """A start for a carriage without preload (its tangent stiffness is zero at rest): every ball a linear spring of
    the Hertz stiffness at the mean load the external force puts on a ball, along its unloaded line."""
    n_balls = geometry.normal.shape[0] * geometry.normal.shape[1]
    mean = max(float(np.max(np.abs(external[:2]))), float(np.max(np.abs(external[2:]))) / geometry.scale) / n_balls
    delta = 2.0 * geometry.constant * max(mean, 1e-12) ** (2.0 / 3.0)
    spring = 1.5 * math.sqrt(delta) / (2.0 * geometry.constant) ** 1.5
    line = np.einsum("rkij,rki->rkj", geometry.jac, geometry.normal)  # J^T n per ball
    stiffness = spring * np.einsum("rki,rkj->ij", line, line)
    return _step(stiffness, external, geometry)


def _state(geometry: _Geometry, q: np.ndarray, external: np.ndarray, iterations: int, measure) -> CarriageState:
    generalised, load, e, approach, stiffness = geometry.forces(q)
    balance = measure(generalised + external, load)
    angle = np.arctan2(np.abs(e[..., 1]), np.abs(e[..., 0]))
    contact = hertz.solve_load(geometry.hertz, load)
    return CarriageState(q.copy(), geometry.z.copy(), load, angle, approach, contact.a, contact.b, contact.p0,
                         stiffness, balance, iterations)
