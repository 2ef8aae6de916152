"""The rigid carriage of a linear ball guide: the load of every ball of its rows, and its stiffness (docs/carriage.md).

A carriage rides on its rail on rows of balls (:class:`Row`): two-point rows (the four-row 45 deg carriages of the
catalogues, :func:`four_rows`) or gothic-arch rows with lin2019's four-point balls (:func:`gothic_rows`).  Each
contact ``i`` of a ball has its outward normal ``n_i`` (ball centre to contact, in the cross-section) and its groove's
curvature centre ``g_i = b0 - (r_g - R_B) n_i`` (``r_g = f D``, one conformity ``f`` for rail and carriage, as
:class:`lowmodel.bearing.LinearGuide`); the carriage's grooves move with the rigid carriage,
``q = (u_x, u_y, phi_x, phi_y, phi_z)``, by ``d_i = u + phi x g_i`` (the part in the cross-section: the grooves are
straight along the rail), the rail's stay, and each ball's centre moves by ``v`` in the cross-section.  Per contact
(Harris & Kotzalas, *Rolling Bearing Analysis*, load distribution by the distance of the curvature centres; Jones
1960; lin2019 eq 53)

    w_i = v + (r_g - R_B) n_i - d_i,   delta_i = |w_i| - (r_g - R_B) + s/2 - c_relief(z) [carriage contacts],
    Q_i = (max(delta_i, 0) / C)^(3/2),   e_i = w_i / |w_i|

with ``s`` the ball oversize (preload), ``c_relief(z)`` the end relief (crowning) of the carriage's grooves and ``C``
Hertz's constant of one ball-groove contact (``delta = C Q^(2/3)``).  Each ball is in equilibrium,
``sum_i Q_i e_i = 0``, and the carriage balances the external load ``(F_x, F_y, M_x, M_y, M_z)`` at the origin:
``sum_{carriage contacts} J_i^T (Q_i e_i) + F = 0`` (``J_i = d d_i / d q``).  Newton on ``(q, v)`` with the exact
tangent (per contact ``dQ/d delta e e^T + Q / |w| (I - e e^T)``), the balls condensed out (2 x 2 blocks), so that

    K = -(A - sum_balls B D^-1 C)      (5 x 5: the carriage's stiffness with its balls in equilibrium)

and a backtracking line search.  A ball whose every pair of opposite contacts is slack is loose: it carries nothing
and is held at the middle of its pairs (Newton would only creep towards ``delta = 0`` on ``Q ~ delta^(3/2)``).  The
answer is checked before it is returned (the carriage's and every ball's balance within :data:`BALANCE_TOLERANCE` of
the largest force), else ConvergenceError naming the check.

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
from dataclasses import dataclass, replace

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import carriage_elastic
from ballbench.lowmodel.geometry.fourpoint import contact_normals

__all__ = ["Row", "Carriage", "Load", "CarriageState", "two_point_row", "four_rows", "gothic_rows", "solve",
           "ball_positions", "relief", "groove_points", "BALANCE_TOLERANCE", "LOAD_NAMES", "DISPLACEMENT_NAMES"]

BALANCE_TOLERANCE = 1e-10  # the load balance of a solved carriage, relative to its largest force (and moment / L)
# a carriage without preload where Newton from the linear start stalls: solved with these oversizes (times a
# contact's approach under the mean ball load) in turn, each from the last, then without
PRELOAD_STEPS = np.array([2.0, 0.5, 0.125, 0.03125, 0.0078125])
STEP_REACH = 2.0  # a Newton step may grow no contact's approach beyond this times the largest one (_first_factor)
LOAD_NAMES = ("F_x", "F_y", "M_x", "M_y", "M_z")  # [N, N, N m, N m, N m] on the carriage at the origin
DISPLACEMENT_NAMES = ("u_x", "u_y", "phi_x", "phi_y", "phi_z")  # [m, m, rad, rad, rad] of the carriage


@dataclass(frozen=True)
class Row:
    """A row of balls: ``x``, ``y`` [m] the balls' centres in the cross-section (unloaded) and per contact the
    outward unit normal from the ball centre to the contact (``normals``, (c, 2), in the cross-section) and whether
    the contact is on the carriage (``carriage``, (c,) bool; else on the rail).  Two contacts on one line: a
    two-point row; four (two on the rail, two on the carriage): a gothic-arch row, lin2019's four-point ball."""

    x: float
    y: float
    normals: tuple
    carriage: tuple
    contact_angles: tuple | None = None  # a gothic-arch row's (BL, BR, TR, TL) [rad] in lin2019's frame

    def __post_init__(self):
        checks.finite("x", self.x, "m")
        checks.finite("y", self.y, "m")
        n = np.asarray(self.normals, dtype=float)
        if n.ndim != 2 or n.shape[1] != 2 or not 2 <= len(n) <= 4 or not np.all(np.isfinite(n)) \
                or np.max(np.abs(np.hypot(n[:, 0], n[:, 1]) - 1.0)) > 1e-12:
            raise ValueError(f"normals must be 2 to 4 unit vectors (n_x, n_y) in the cross-section, got "
                             f"{self.normals!r}")
        side = tuple(bool(c) for c in self.carriage)
        if len(side) != len(n) or all(side) or not any(side):
            raise ValueError(f"carriage must say for each contact whether it is on the carriage (some on the rail, "
                             f"some on the carriage), got {self.carriage!r}")
        object.__setattr__(self, "normals", tuple((float(a), float(b)) for a, b in n))
        object.__setattr__(self, "carriage", side)


def two_point_row(x: float, y: float, normal) -> Row:
    """A row in two-point contact: the rail contact at ``normal`` (unit vector from the ball centre towards the rail)
    and the carriage contact opposite it."""
    n = np.asarray(normal, dtype=float)
    return Row(x, y, (tuple(n), tuple(-n)), (False, True))


def four_rows(*, half_width: float, upper: float, lower: float, contact_angle: float) -> tuple[Row, ...]:
    """The four two-point rows of a four-row carriage in the 45 deg arrangement of the catalogues: two upper rows at
    height ``upper`` [m] carrying the carriage's downward load (the rail below and inside each ball) and two lower
    rows at ``lower`` [m] holding it against lift-off (the rail above and inside), at ``x = +-half_width`` [m], every
    load line at ``contact_angle`` [rad] to the lateral axis.  Order: upper right, upper left, lower right, lower
    left."""
    checks.positive("half_width", half_width, "m")
    alpha = checks.bounded("contact_angle", contact_angle, 0.0, math.pi / 2, lower_closed=False, upper_closed=False)
    c, s = math.cos(alpha), math.sin(alpha)
    return (two_point_row(half_width, upper, (-c, -s)), two_point_row(-half_width, upper, (c, -s)),
            two_point_row(half_width, lower, (-c, s)), two_point_row(-half_width, lower, (c, s)))


def gothic_rows(*, half_width: float, height: float, contact_angles) -> tuple[Row, ...]:
    """The two gothic-arch rows of a two-row carriage: at ``x = +-half_width``, ``y = height`` [m], each ball with
    lin2019's four contacts (lowmodel.geometry.fourpoint.contact_normals of ``contact_angles`` (BL, BR, TR, TL)
    [rad], from lin2019's vertical) turned so that its bottom (the rail's grooves) faces the rail: by -90 deg on the
    right row (the rail on its left), by +90 deg on the left row.  Order: right, left.  The rows keep
    ``contact_angles``: their friction is lin2019's (:mod:`lowmodel.linear_bearing.carriage_friction`)."""
    checks.positive("half_width", half_width, "m")
    angles = checks.trailing_axis("contact_angles", contact_angles, 4, "(BL, BR, TR, TL)", "rad")
    checks.contact_angle("contact_angles", angles)
    normals = contact_normals(angles)  # (4, 2), lin2019's frame: bottom = -y
    right = np.column_stack([normals[:, 1], -normals[:, 0]])  # -90 deg: -y -> -x
    left = np.column_stack([-normals[:, 1], normals[:, 0]])  # +90 deg: -y -> +x
    side = (False, False, True, True)
    rigid = tuple(float(a) for a in angles)
    return (Row(half_width, height, tuple(map(tuple, right)), side, rigid),
            Row(-half_width, height, tuple(map(tuple, left)), side, rigid))


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
    length ``l`` of the end balls' positions at rest ``+-L`` (and on by the same parabola to the groove's ends, half
    a pitch further, :func:`ball_positions`), 0 inside it."""
    z = np.abs(np.asarray(z, dtype=float))
    if body.relief_length == 0.0 or body.relief_depth == 0.0:
        return np.zeros_like(z)
    start = body.half_length - body.relief_length
    return body.relief_depth * (np.clip(z - start, 0.0, None) / body.relief_length) ** 2


def ball_positions(body: Carriage, travel: float = 0.0) -> np.ndarray:
    """(balls_per_row,) z [m] of the balls of every row, ascending: centred on the origin, shifted by ``travel`` [m]
    (the balls' advance against the carriage) and wrapped into the carriage's groove ``[-G, G)``, ``G = n p / 2``
    half a pitch beyond the end balls at rest: a ball leaving the loaded zone at ``+G`` enters it again at ``-G``
    (the recirculation), so that the same ``n`` balls are loaded at every travel and a travel of one pitch gives
    the positions at rest again."""
    k = np.arange(body.balls_per_row, dtype=float)
    groove = 0.5 * body.balls_per_row * body.pitch
    z = (k - 0.5 * (body.balls_per_row - 1)) * body.pitch + float(travel)
    return np.sort((z + groove) % (2.0 * groove) - groove)


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
    """The carriage in equilibrium under a load (:func:`solve`); arrays of shape (rows, balls_per_row, contacts)
    unless said (a row with fewer contacts than the most: its last entries zero).

    displacement : (5,) ``(u_x, u_y, phi_x, phi_y, phi_z)`` [m, m, rad, rad, rad];  z : (balls,) m
    ball_shift : (rows, balls, 2) m, each ball centre's move in the cross-section
    normal_force : N, each contact's load;  line : (..., 2) the loaded contact's unit normal (ball to groove)
    approach : m, each contact's approach (not positive: unloaded)
    a, b : m, Hertz's semi-axes of each contact (``a`` across the groove);  p0 : Pa
    stiffness : (5, 5) ``-dR/dq`` with the balls in equilibrium [N/m, N/rad, N m/m, N m/rad]: the carriage's
        tangent stiffness at the state
    balance : the load balance's residual (carriage: over the largest force, moments over the half-length; balls:
        over the largest contact force);  iterations : Newton steps
    """

    displacement: np.ndarray
    z: np.ndarray
    ball_shift: np.ndarray
    normal_force: np.ndarray
    line: np.ndarray
    approach: np.ndarray
    a: np.ndarray
    b: np.ndarray
    p0: np.ndarray
    stiffness: np.ndarray
    balance: float
    iterations: int

    def __post_init__(self):
        checks.freeze_arrays(self, "displacement", "z", "ball_shift", "normal_force", "line", "approach", "a", "b",
                             "p0", "stiffness")

    @property
    def contact_angle(self) -> np.ndarray:
        """rad, the loaded contact's normal against the lateral axis (0 to pi/2; a two-point row's load line)."""
        return np.arctan2(np.abs(self.line[..., 1]), np.abs(self.line[..., 0]))


class _Geometry:
    """The static arrays of a carriage at one travel (rows r, balls k, contacts c)."""

    def __init__(self, body: Carriage, travel: float):
        guide = body.guide
        radius, conformity = guide.ball_radius, guide.conformity
        self.hertz = hertz.groove_geometry(guide)
        self.constant = hertz.hertz_constant(self.hertz)  # m N^(-2/3), one contact
        self.gap = (2.0 * conformity - 1.0) * radius  # r_g - R_B: ball centre to groove curvature centre at rest
        z = ball_positions(body, travel)
        self.z = z
        rows = body.rows
        width = max(len(r.normals) for r in rows)
        self.normal = np.zeros((len(rows), width, 2))
        self.top = np.zeros((len(rows), width))
        self.mask = np.zeros((len(rows), width))
        for i, r in enumerate(rows):
            m = len(r.normals)
            self.normal[i, :m] = r.normals
            self.top[i, :m] = r.carriage
            self.mask[i, :m] = 1.0
            self.normal[i, m:] = r.normals[0]  # padding: masked out
        ball = np.array([[r.x, r.y] for r in rows])  # (r, 2)
        centre = ball[:, None, :] - self.gap * self.normal  # (r, c, 2) groove curvature centres at rest
        shape = (len(rows), len(z), width)
        zz = np.broadcast_to(z[None, :, None], shape)
        cx = np.broadcast_to(centre[:, None, :, 0], shape)
        cy = np.broadcast_to(centre[:, None, :, 1], shape)
        one, zero = np.ones(shape), np.zeros(shape)
        # J[r, k, c, i, j] = d d_i / d q_j of the carriage at the contact's groove curvature centre (i: x, y)
        self.jac = np.stack([np.stack([one, zero, zero, zz, -cy], axis=-1),
                             np.stack([zero, one, -zz, zero, cx], axis=-1)], axis=-2)
        self.jac *= (self.top * self.mask)[:, None, :, None, None]  # the rail's grooves do not move
        self.jac_t = np.ascontiguousarray(np.swapaxes(self.jac, -1, -2))
        # each rail contact's partner: the carriage contact most nearly opposite it (a two-point ball's other
        # contact; lin2017's diagonal pairs BL-TR, BR-TL of a gothic-arch ball)
        pairs = []
        for r in rows:
            rail = [c for c, top in enumerate(r.carriage) if not top]
            top = [c for c, t in enumerate(r.carriage) if t]
            pairs.append([(c, min(top, key=lambda t: float(np.dot(r.normals[c], r.normals[t])))) for c in rail])
        most = max(len(p) for p in pairs)  # the pairs as arrays (r, P), padded with a row's first pair
        padded = [p + p[:1] * (most - len(p)) for p in pairs]
        self.pair_rail = np.array([[c for c, _ in p] for p in padded], dtype=int)
        self.pair_top = np.array([[t for _, t in p] for p in padded], dtype=int)
        self.pair_share = np.array([[1.0 / len(p) if i < len(p) else 0.0 for i in range(most)] for p in pairs])
        relief_z = relief(body, z)  # (k,)
        self.offset = (0.5 * body.oversize - self.top[:, None, :] * relief_z[None, :, None]) * np.ones(shape)
        self.scale = max(body.half_length, radius)  # m: moments over it compare with forces
        self.hold_loose = True  # loose balls held at their pairs' mid-points (solve lets go where it stalls)

    def loose(self, d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``(loose (r, k) bool, centred (r, k, 2) m)``: the balls whose every pair of opposite contacts is slack at
        the carriage's displacement ``d`` (the distance of the pair's curvature centres short of the ball's): loose
        between their grooves, carrying nothing, held at the mean of their pairs' mid-points ``centred`` (Newton on
        ``Q ~ delta^(3/2)`` would only creep to ``delta = 0``)."""
        row = np.arange(d.shape[0])[:, None]
        rail, top = self.pair_rail, self.pair_top  # (r, P)
        n_rail, n_top = self.normal[row, rail], self.normal[row, top]  # (r, P, 2)
        d_rail, d_top = d[row, :, rail], d[row, :, top]  # (r, P, k, 2)
        # the carriage groove's curvature centre - the rail groove's, per pair (a padded pair repeats a real one)
        centres = (self.gap * (n_rail - n_top))[:, :, None, :] + d_top - d_rail
        approach = np.sqrt(np.einsum("rpki,rpki->rpk", centres, centres)) - 2.0 * self.gap \
            + self.offset[row, :, rail] + self.offset[row, :, top]
        slack = np.all(approach <= 0.0, axis=1)  # (r, k)
        middle = 0.5 * (d_top + d_rail - (self.gap * (n_rail + n_top))[:, :, None, :])  # (r, P, k, 2)
        centred = np.einsum("rp,rpki->rki", self.pair_share, middle)
        return slack, centred

    def contacts(self, q: np.ndarray, v: np.ndarray, slope_floor: float = 0.0, elastic=None):
        """Per contact: load Q, line e, approach, the local stiffness k (2x2) as a function (only a Newton step needs
        it) and the loose balls at (q, v); ``elastic`` (r, k, c, 2) m the carriage grooves' own displacement beyond
        the rigid carriage's (else none)."""
        d = self.jac @ q
        if elastic is not None:
            d = d + elastic
        w = v[:, :, None, :] + self.gap * self.normal[:, None, :, :] - d  # ball centre - groove centre
        length = np.sqrt(w[..., 0] * w[..., 0] + w[..., 1] * w[..., 1])
        e = w / length[..., None]
        approach = length - self.gap + self.offset
        positive = np.clip(approach, 0.0, None)
        loose, centred = self.loose(d)
        if slope_floor > 0.0 or not self.hold_loose:  # the linear start: every contact a spring; or no holding
            loose[:] = False
        active = self.mask[:, None, :] * ~loose[..., None]
        load = (positive / self.constant) ** 1.5 * active

        def local():
            slope = np.maximum(1.5 * np.sqrt(positive) / self.constant ** 1.5, slope_floor) * active
            outer = e[..., :, None] * e[..., None, :]
            return slope[..., None, None] * outer + (load / length)[..., None, None] * (np.eye(2) - outer)

        return load, e, approach, local, (loose, centred)

    def system(self, q: np.ndarray, v: np.ndarray, external: np.ndarray, slope_floor: float = 0.0, elastic=None,
               lazy: bool = False):
        """The residuals (carriage (5,), balls (r, k, 2)), the condensed step's blocks and the stiffness; ``lazy``:
        the blocks as a function that computes them (a line search's trial needs its residuals only)."""
        load, e, approach, local, held = self.contacts(q, v, slope_floor, elastic)
        force = load[..., None] * e  # on the groove, from the ball (r, k, c, 2)
        carriage = force.reshape(-1) @ self.jac.reshape(-1, 5) + external
        balls = -force.sum(axis=2)  # on the ball
        blocks = (lambda: self._blocks(local, held)) if lazy else self._blocks(local, held)
        return carriage, balls, blocks, load, e, approach

    def _blocks(self, local, held):
        jac = self.jac
        local = local()
        d_block = -local.sum(axis=2)  # d balls / d v  (r, k, 2, 2)
        jac_local = self.jac_t @ local  # (r, k, c, 5, 2): J^T K per contact
        b_block = jac_local.sum(axis=2)  # d carriage / d v  (r, k, 5, 2)
        c_block = (local @ jac).sum(axis=2)  # d balls / d q  (r, k, 2, 5)
        a_block = -np.swapaxes(jac_local, -1, -2).reshape(-1, 5).T @ jac.reshape(-1, 5)  # d carriage / d q
        return a_block, b_block, c_block, d_block, *held, local

    @property
    def grooves(self) -> np.ndarray:
        """(M, 3) int: the (row, ball, contact) of every carriage contact, in the order of a groove compliance."""
        top = (self.top * self.mask).astype(bool)  # (r, c)
        return np.array([(r, k, c) for r in range(top.shape[0]) for k in range(len(self.z))
                         for c in range(top.shape[1]) if top[r, c]], dtype=int).reshape(-1, 3)


def groove_points(body: Carriage, travel: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The carriage's contacts at rest, in the order of a groove compliance (:func:`solve`'s ``groove_compliance``):
    ``(points (M, 3), centres (M, 3), normals (M, 2))`` [m]: each contact point ``b0 + R_B n`` and its groove's
    curvature centre ``b0 - (r_g - R_B) n`` at the ball's ``z``, and the contact's outward normal ``n``."""
    geometry = _Geometry(body, travel)
    index = geometry.grooves
    ball = np.array([[row.x, row.y] for row in body.rows])[index[:, 0]]
    normal = geometry.normal[index[:, 0], index[:, 2]]
    z = geometry.z[index[:, 1]][:, None]
    radius = body.guide.ball_radius
    return (np.hstack([ball + radius * normal, z]), np.hstack([ball - geometry.gap * normal, z]), normal)


def solve(body: Carriage, load: Load, *, travel: float = 0.0, tolerance: float = BALANCE_TOLERANCE,
          max_iterations: int = 60, groove_compliance=None) -> CarriageState:
    """The rigid ``body`` (:class:`Carriage`) in equilibrium under ``load`` (:class:`Load`) with its balls at
    ``travel`` [m] (module docstring).  ValueError for bad input; ConvergenceError naming the check (the load balance
    of the carriage and of every ball within ``tolerance`` of the largest force) when Newton stops short, e.g. a load
    no row can carry (lift-off without rows against it).

    ``groove_compliance`` (2M, 2M) [m/N]: an elastic carriage, its grooves' curvature centres moving by
    ``w = G f`` beyond the rigid carriage's, ``f`` the balls' forces on the carriage's contacts (x, y of each of
    the M contacts of :func:`groove_points`, the carriage's mounting face held by the rigid ``q``;
    fem.carriage_fe computes it): solved from the rigid state by Newton on ``(q, v, w)`` with the dense Jacobian
    (docs/carriage.md, "Elastic carriage")."""
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

    def measure(carriage_residual, ball_residual, loads):
        reference = max(float(np.max(np.abs(external * weights))), float(np.max(loads, initial=0.0)), 1e-300)
        return max(float(np.max(np.abs(carriage_residual * weights))),
                   float(np.max(np.abs(ball_residual), initial=0.0))) / reference

    q, v = np.zeros(5), np.zeros((len(body.rows), len(geometry.z), 2))
    if not np.any(external) and body.oversize == 0.0:  # nothing pushes the balls: the carriage sits unloaded
        return _state(geometry, q, v, external, 0, measure)
    if groove_compliance is not None:
        rigid = solve(body, load, travel=travel, tolerance=tolerance, max_iterations=max_iterations)
        return _solve_elastic(geometry, rigid, external, groove_compliance, tolerance, max_iterations, measure)
    if body.oversize > 0.0:
        q, v, iterations = _newton(geometry, q, v, external, tolerance, max_iterations, measure)
        return _state(geometry, q, v, external, iterations, measure)
    try:  # at rest the tangent stiffness is zero: start from linear springs on every contact
        q, v = _linear_start(geometry, external)
        q, v, iterations = _newton(geometry, q, v, external, tolerance, max_iterations, measure)
    except ConvergenceError:  # contacts closing and opening on the way: a preload let go in steps, from rest
        q, v, iterations = np.zeros(5), np.zeros_like(v), 0
        for oversize in PRELOAD_STEPS * _approach(geometry, external):
            stage = _Geometry(replace(body, oversize=float(oversize)), travel)
            q, v, steps = _newton(stage, q, v, external, tolerance, max_iterations, measure)
            iterations += steps
        q, v, steps = _newton(geometry, q, v, external, tolerance, max_iterations, measure)
        iterations += steps
    return _state(geometry, q, v, external, iterations, measure)


def _approach(geometry: _Geometry, external: np.ndarray) -> float:
    """m, a contact's approach under the mean load the external force puts on a ball (Hertz)."""
    n_balls = geometry.normal.shape[0] * len(geometry.z)
    mean = max(float(np.max(np.abs(external[:2]))), float(np.max(np.abs(external[2:]))) / geometry.scale) / n_balls
    return geometry.constant * max(mean, 1e-12) ** (2.0 / 3.0)


def _newton(geometry: _Geometry, q, v, external, tolerance: float, max_iterations: int, measure):
    """Newton from ``(q, v)`` with the balls condensed and a backtracking line search; ``(q, v, iterations)``."""
    iterations = 0
    carriage, balls, blocks, loads, line, approach = geometry.system(q, v, external)
    norm = measure(carriage, balls, loads)
    reach = _approach(geometry, external)
    while norm > tolerance:
        if iterations >= max_iterations:
            raise ConvergenceError("carriage.solve: the load balance missed (the balls' forces and moments plus the "
                                   "external load on the carriage, and each ball's contact forces, over the largest "
                                   "force)", residual=norm, iterations=iterations, tolerance=tolerance,
                                   reason="load balance missed")
        dq, dv, loose, centred = _step(blocks, carriage, balls, geometry)
        v = np.where(loose[..., None], centred, v)  # loose balls held at their pairs' mid-points
        factor, accepted = _first_factor(geometry, dq, dv, line, approach, reach), False
        for _ in range(40):
            trial_q, trial_v = q + factor * dq, v + factor * dv
            c_t, b_t, k_t, l_t, e_t, a_t = geometry.system(trial_q, trial_v, external, lazy=True)
            n_t = measure(c_t, b_t, l_t)
            if n_t < norm or n_t <= tolerance:
                q, v, carriage, balls, loads, norm, accepted = trial_q, trial_v, c_t, b_t, l_t, n_t, True
                blocks = k_t() if norm > tolerance else None
                line, approach = e_t, a_t
                break
            factor *= 0.5
        iterations += 1
        if not accepted and geometry.hold_loose:  # a ball at the edge of loose flips: let go of the holding
            geometry.hold_loose = False
            carriage, balls, blocks, loads, line, approach = geometry.system(q, v, external)
            norm = measure(carriage, balls, loads)
            continue
        if not accepted:
            raise ConvergenceError("carriage.solve: no step reduces the load balance's residual (a load the rows "
                                   "cannot carry, e.g. lift-off without rows against it)", residual=norm,
                                   iterations=iterations, tolerance=tolerance, reason="no descent step")
    return q, v, iterations


def _first_factor(geometry: _Geometry, dq, dv, line, approach, reach: float) -> float:
    """The line search's first step factor: the whole Newton step unless it would push a contact's approach (to
    first order, ``e . (dv - J dq)``) beyond :data:`STEP_REACH` times the largest approach now or the approach of
    the mean ball load (``reach``): Hertz's ``Q ~ delta^(3/2)`` makes an overshoot's residual grow fast, and each
    halving back costs a whole evaluation."""
    change = np.einsum("rkci,rkci->rkc", line, dv[:, :, None, :] - geometry.jac @ dq) * geometry.mask[:, None, :]
    largest = float(np.max(np.abs(change)))
    limit = STEP_REACH * max(float(np.max(approach * geometry.mask[:, None, :])), reach)
    return 1.0 if largest <= limit else limit / largest


def _condensed(blocks, geometry: _Geometry):
    """The balls eliminated (each ball's 2 x 2 block): ``(S, B D^-1)`` with ``S = A - sum B D^-1 C`` the carriage's
    Jacobian with its balls in equilibrium (``-S`` its stiffness), rotations scaled by the half-length."""
    a_block, b_block, c_block, d_block = blocks[:4]
    scale = np.array([1.0, 1.0, geometry.scale, geometry.scale, geometry.scale])
    largest = float(np.max(np.abs(d_block)))
    floor = 1e-12 * largest if largest > 0.0 else 1.0  # N/m: no ball loaded at all, any floor keeps them still
    regular = d_block - floor * np.eye(2)  # a ball without load: its position is left as it is
    inverse = np.linalg.inv(regular)  # (r, k, 2, 2)
    bd = b_block @ inverse
    schur = a_block - np.swapaxes(bd, -1, -2).reshape(-1, 5).T @ c_block.reshape(-1, 5)
    return schur, bd, inverse, scale


def _step(blocks, carriage, balls, geometry: _Geometry):
    """Newton's step of the whole system with the balls condensed (least squares where the carriage's condensed
    Jacobian is singular: rows without load)."""
    schur, bd, inverse, scale = _condensed(blocks, geometry)
    c_block, loose, centred = blocks[2], blocks[4], blocks[5]
    rhs = -carriage + np.swapaxes(bd, -1, -2).reshape(-1, 5).T @ balls.reshape(-1)
    scaled = schur / np.outer(scale, scale)
    if not (np.all(np.isfinite(scaled)) and np.all(np.isfinite(rhs))):
        raise ConvergenceError("carriage.solve: the Newton system is not finite", residual=math.inf, iterations=0,
                               tolerance=0.0, reason="no descent step")
    try:
        dq = np.linalg.solve(scaled, rhs / scale)
        if not np.all(np.isfinite(dq)):
            raise np.linalg.LinAlgError
    except np.linalg.LinAlgError:
        dq = np.linalg.lstsq(scaled, rhs / scale, rcond=1e-12)[0]
    dq = dq / scale
    dv = -(inverse @ (balls + c_block @ dq)[..., None])[..., 0]
    return dq, dv, loose, centred


def _linear_start(geometry: _Geometry, external: np.ndarray):
    """A start for a carriage without preload (its tangent stiffness is zero at rest): every contact a linear spring
    of the Hertz stiffness at the mean load the external force puts on a ball, along its unloaded normal."""
    delta = _approach(geometry, external)
    spring = 1.5 * math.sqrt(delta) / geometry.constant ** 1.5
    q, v = np.zeros(5), np.zeros((geometry.normal.shape[0], len(geometry.z), 2))
    _, _, blocks, _, _, _ = geometry.system(q, v, external, slope_floor=spring)
    carriage = external.copy()
    balls = np.zeros_like(v)
    return _step(blocks, carriage, balls, geometry)[:2]


def _state(geometry: _Geometry, q, v, external, iterations: int, measure, elastic=None,
           schur=None) -> CarriageState:
    carriage, balls, blocks, load, e, approach = geometry.system(q, v, external, elastic=elastic)
    balance = measure(carriage, balls, load)
    if schur is None:
        schur, *_ = _condensed(blocks, geometry)
    contact = hertz.solve_load(geometry.hertz, load)
    mask = geometry.mask[:, None, :]
    return CarriageState(q.copy(), geometry.z.copy(), v.copy(), load, e * mask[..., None], approach * mask,
                         contact.a * mask, contact.b * mask, contact.p0 * mask, -schur, balance, iterations)


def _solve_elastic(geometry: _Geometry, rigid: CarriageState, external, compliance, tolerance: float,
                   max_iterations: int, measure) -> CarriageState:
    """The elastic carriage from the rigid state (lowmodel.linear_bearing.carriage_elastic)."""
    q, v, elastic, schur, iterations = carriage_elastic.newton(geometry, rigid.displacement, rigid.ball_shift,
                                                               external, compliance, tolerance, max_iterations,
                                                               measure)
    return _state(geometry, q, v, external, rigid.iterations + iterations, measure, elastic, schur)
