"""The contacts of balls in a four-point-contact linear ball bearing: the input of the ball model
:mod:`lowmodel.linear_bearing.ball` (lin2019 Sec 2.1, Fig 2; normal forces from lin2017 eq 36).

:class:`BallContacts` holds the contact angles (BL, BR, TR, TL), normal forces, Hertz semi-axes
and axis ratios of ``n`` balls with the ball radius, ``mu`` and the groove velocity, and caches
what the equilibrium of :func:`lowmodel.linear_bearing.ball.ball_terms` derives from them
(:attr:`BallContacts.kinematics`, :attr:`BallContacts.friction_at`, :attr:`BallContacts.equilibrium`).
Built by :func:`ball_contacts` from the external loads (lin2017 eq 36, Hertz of the groove) or by
:func:`contacts_from_forces` from given forces and semi-axes.  :func:`spin_capacity_ratio` tells
whether a full-sliding state can exist (lin2019 eq 11); :func:`minimum_conformity` is the lower end
of the friction map's range of ``b/a``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np
from scipy.optimize import brentq
from scipy.special import ellipe

from ballbench.lowmodel import checks, model_inputs
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry.fourpoint import contact_normals

__all__ = ["BallContacts", "ball_contacts", "contacts_from_forces", "spin_capacity_ratio", "minimum_conformity", "TOP"]

TOP = np.array([0.0, 0.0, 1.0, 1.0])  # contacts on the moving (top) groove, (BL, BR, TR, TL)
TOP.setflags(write=False)


@dataclass(frozen=True)
class BallContacts:
    """Contact data of ``n`` balls (leading shape ``(n,)``; a single ball has ``n = 1``).

    contact_angles : (n, 4) rad, (BL, BR, TR, TL), measured from -+y (lin2019 Fig 2)
    normal_forces  : (n, 4) N, lin2017 eq 36
    semi_major     : (n, 4) m, Hertz semi-axis ``a_i`` (in the cross-section)
    b_over_a       : (n, 4) Hertz axis ratio
    ball_radius    : m
    friction_coefficient : mu (Coulomb, ball-to-groove and ball-to-ball)
    groove_velocity : m/s, velocity ``v`` of the top groove along +z (nonzero)

    The four arrays are read-only (copied on construction unless they already are, with their bases):
    the cached geometry, friction map and equilibrium rows are derived from them, so an in-place edit
    would leave them stale; edit with :func:`dataclasses.replace` (lowmodel.checks.freeze_arrays).
    """

    contact_angles: np.ndarray
    normal_forces: np.ndarray
    semi_major: np.ndarray
    b_over_a: np.ndarray
    ball_radius: float
    friction_coefficient: float
    groove_velocity: float

    def __post_init__(self):
        checks.freeze_arrays(self, "contact_angles", "normal_forces", "semi_major", "b_over_a")

    def __reduce__(self):
        return checks.rebuilt_through_init(self)

    @property
    def n_balls(self) -> int:
        return self.normal_forces.shape[0]

    @cached_property
    def kinematics(self):
        """Load-independent arrays of :func:`ball_terms` (computed once per instance)."""
        normals = contact_normals(self.contact_angles)
        nx, ny = normals[..., 0], normals[..., 1]
        arm = self.semi_major / self.ball_radius  # a_i / R_B
        dslide = np.stack([np.ones_like(nx), ny, -nx], axis=-1)  # d slide / d x, (n, 4, 3)
        dspin = np.stack([np.zeros_like(nx), -nx * arm, -ny * arm], axis=-1)  # d spin / d x
        top = math.copysign(1.0, self.groove_velocity) * TOP
        derived = nx, ny, arm, dslide, dspin, top
        for array in derived:  # fresh arrays (or views of them) held by this instance only: no copy needed
            array.setflags(write=False)
        return derived

    @cached_property
    def friction_at(self):
        """The friction map at this instance's axis ratios (lin2019 eqs A4-A6), as a function of the slip angles:
        ``phi`` (n, 4) -> (n, 4, 3, 2), (force, moment, loss) x (value, d/d phi) per unit slip speed."""
        return _friction_angle_function(self.b_over_a)

    @cached_property
    def friction_cells(self):
        """The friction map's ``log(b/a)`` cells and offset powers of the contacts (n, 4) and (n, 4, 4)
        (:func:`lowmodel.contact.ellipse_friction.log_ratio_cells`), for the compiled kernels."""
        from ballbench.lowmodel.contact.ellipse_friction import log_ratio_cells

        cells, powers = log_ratio_cells(self.b_over_a)
        cells.setflags(write=False)
        powers.setflags(write=False)
        return cells, powers

    @cached_property
    def kernel_geometry(self):
        """(n, 4, 12), read-only: the per-contact data of the compiled kernels, per contact ``n_x, n_y, a_i/R_B``,
        the groove velocity sign of the contact, ``F_i`` [N] (the kernels divide by each case's reference force),
        the friction map's ``log(b/a)`` cell and offset powers, ``a_i`` [m], ``beta_i`` [rad] (the layout of
        :mod:`lowmodel.linear_bearing.ball_kernels`, field ``FIELDS``)."""
        nx, ny, arm, _, _, top = self.kinematics
        cells, powers = self.friction_cells
        data = np.empty(nx.shape + (12,))
        data[..., 0] = nx
        data[..., 1] = ny
        data[..., 2] = arm
        data[..., 3] = top
        data[..., 4] = self.normal_forces
        data[..., 5] = cells
        data[..., 6:10] = powers
        data[..., 10] = self.semi_major
        data[..., 11] = self.contact_angles
        data.setflags(write=False)
        return data

    @cached_property
    def equilibrium(self):
        """(n, 3, 8): the rows of lin2019 eq 4 as a matrix on ``(force_i, moment_i)`` (columns interleaved
        ``f_0, M_0, f_1, M_1, ...``), the same as (n, 4, 3, 2) (contact, row, force | moment), and the
        friction scales ``[load, load_arm, load]`` of each contact per reference force (a dict, filled by
        :func:`ball_terms`)."""
        nx, ny = self.kinematics[:2]
        rows = np.empty((self.n_balls, 3, 4, 2))
        rows[:, 0, :, 0], rows[:, 0, :, 1] = 1.0, 0.0  # eq 4 row 1: sum f_i
        rows[:, 1, :, 0], rows[:, 1, :, 1] = ny, nx  # row 2: n_y f + n_x M
        rows[:, 2, :, 0], rows[:, 2, :, 1] = -nx, ny  # row 3: -n_x f + n_y M
        matrix, per_contact = rows.reshape(self.n_balls, 3, 8), np.ascontiguousarray(rows.transpose(0, 2, 1, 3))
        matrix.setflags(write=False)
        per_contact.setflags(write=False)
        return matrix, per_contact, {}

    def ball(self, index: int) -> "BallContacts":
        """The contacts of ball ``index`` alone (shape (1, 4))."""
        sl = slice(index, index + 1)
        return BallContacts(self.contact_angles[sl], self.normal_forces[sl], self.semi_major[sl],
                            self.b_over_a[sl], self.ball_radius, self.friction_coefficient,
                            self.groove_velocity)


def _check_angles(contact_angles) -> np.ndarray:
    angles = checks.trailing_axis("contact_angles", contact_angles, 4, "(BL, BR, TR, TL)", "rad")
    if angles.ndim == 1:
        angles = angles[None, :]
    if angles.ndim != 2:
        raise ValueError(f"contact_angles must have shape (4,) or (n, 4), got {angles.shape}")
    return checks.contact_angle("contact_angles", angles)


def contacts_from_forces(contact_angles, normal_forces, semi_major, b_over_a, *, ball_radius: float,
                         friction_coefficient: float, groove_velocity: float) -> BallContacts:
    """Build :class:`BallContacts` from given normal forces and Hertz semi-axes.

    Shapes ``(4,)`` or ``(n, 4)``; forces [N] must be > 0 (four-point contact).
    """
    radius = checks.positive("ball_radius", ball_radius, "m")
    mu = model_inputs.guide_friction_coefficient(friction_coefficient)
    velocity = model_inputs.groove_velocity(groove_velocity)
    angles = _check_angles(contact_angles)
    forces = np.broadcast_to(checks.positive("normal_forces", normal_forces, "N", note=(
        "at all four contacts; loss of four-point contact otherwise, lin2017 eq 37")), angles.shape)
    axes = np.broadcast_to(checks.positive("semi_major", semi_major, "m"), angles.shape)
    ratio = np.broadcast_to(checks.bounded("b_over_a", b_over_a, 0.0, 1.0, upper_closed=True), angles.shape)
    return BallContacts(angles, forces, axes, ratio, radius, mu, velocity)  # copied there (read-only)


def ball_contacts(contact_angles, side_force, vertical_force, *, ball_radius: float, conformity: float,
                  friction_coefficient: float, groove_velocity: float,
                  youngs_modulus: float = 2.1e11, poisson_ratio: float = 0.28) -> BallContacts:
    """Contact data from the external load of each ball.

    Parameters
    ----------
    contact_angles : (4,) or (n, 4) rad, (BL, BR, TR, TL)
    side_force, vertical_force : scalar or (n,) N, ``N_x`` and ``N_y`` applied
        through the top groove (lin2017 eq 35/36, lin2019 Fig 7)
    ball_radius : m; conformity : groove radius / ball diameter (> 0.5)
    friction_coefficient : mu; groove_velocity : m/s (top groove)
    youngs_modulus [Pa], poisson_ratio : ball and groove (same material)

    Normal forces from :func:`lowmodel.linear_bearing.fourpoint.normal_forces` (lin2017 eq
    36; ValueError at loss of four-point contact), semi-axes from
    :func:`lowmodel.contact.hertz.ball_in_groove` / ``solve_load``.
    """
    from ballbench.lowmodel.linear_bearing import fourpoint
    angles = _check_angles(contact_angles)
    n = angles.shape[0]
    side = np.broadcast_to(np.asarray(side_force, dtype=float), (n,))
    vertical = np.broadcast_to(np.asarray(vertical_force, dtype=float), (n,))
    forces = np.asarray(fourpoint.normal_forces(side, vertical, angles), dtype=float)  # lin2017 eq 36
    geometry = hertz.ball_in_groove(ball_radius, conformity, youngs_modulus=youngs_modulus,
                                    poisson_ratio=poisson_ratio)
    _check_axis_ratio(geometry.axis_ratio, conformity)
    if not np.all(np.isfinite(forces)) or np.any(forces <= 0.0):
        raise ValueError("side_force/vertical_force give a normal force <= 0: loss of four-point "
                         "contact (lin2017 eq 37)")
    contact = hertz.solve_load(geometry, forces)
    return contacts_from_forces(angles, forces, contact.a, contact.b / contact.a, ball_radius=ball_radius,
                                friction_coefficient=friction_coefficient, groove_velocity=groove_velocity)


def minimum_conformity() -> float:
    """Smallest conformity whose Hertz axis ratio ``b/a`` lies in the friction map's range (about 0.5007).

    In a straight groove ``b/a`` depends on the conformity only; below this value
    ``b/a < B_OVER_A_RANGE[0]`` of :mod:`lowmodel.contact.ellipse_friction` (lin2019 eqs A4-A7 tabulated).
    """
    return _minimum_conformity()


@lru_cache(maxsize=1)
def _minimum_conformity() -> float:
    from ballbench.lowmodel.contact.ellipse_friction import B_OVER_A_RANGE

    def excess(f):
        # b/a does not depend on the size; 1/16 m (a power of two: the curvatures scale exactly, so b/a is that
        # of any radius to the last bit) lies inside the plausible ball radii that ball_in_groove accepts
        return hertz.ball_in_groove(0.0625, f).axis_ratio - B_OVER_A_RANGE[0]

    return float(brentq(excess, 0.5 + 1e-9, 0.9, xtol=1e-12))


def _check_axis_ratio(axis_ratio: float, conformity) -> None:
    from ballbench.lowmodel.contact.ellipse_friction import B_OVER_A_RANGE

    if axis_ratio < B_OVER_A_RANGE[0]:
        raise ValueError(f"conformity = {float(conformity)!r} gives a Hertz axis ratio b/a = {axis_ratio:.4g}, below "
                         f"{B_OVER_A_RANGE[0]}, the range of the ellipse friction map (lin2019 eqs A4-A7): conformity "
                         f"must lie in [{minimum_conformity():.6f}, 1) for this model")


def spin_capacity_ratio(contacts: BallContacts) -> np.ndarray:
    """Can the friction forces of one diagonal balance the spin moments of the other? Shape (n,).

    ``min`` over the two diagonals of ``R_B (F_k + F_l) / (m0 (F_i a_i + F_j a_j))`` with
    ``(i, j) = (BL, TR), (k, l) = (BR, TL)`` and vice versa, ``m0 = (3/8) E(e)`` (lin2019 eq 11).
    Along a diagonal the spin moments of its two contacts add up (their spins have
    opposite signs in four-point rolling) and only the z-forces of the other diagonal,
    at most ``mu F`` each with arm ``R_B``, balance them; ``mu`` cancels.  Below 1 the
    full-sliding friction of lin2019 (eqs A4-A6) admits no quasi-static state: the
    solver then raises ConvergenceError (docs/b2b_bearing.md, validity).  Checked
    against the solver: the last converged rho towards the four-point limit and the
    zero of ``ratio - 1`` coincide (lin2019-stability).
    """
    force, axis = contacts.normal_forces, contacts.semi_major
    m0 = 0.375 * ellipe(1.0 - contacts.b_over_a[:, 0] ** 2)  # lin2019 eq 11 (scipy: parameter m = e^2)
    radius = contacts.ball_radius
    up = radius * (force[:, 1] + force[:, 3]) / (m0 * (force[:, 0] * axis[:, 0] + force[:, 2] * axis[:, 2]))
    down = radius * (force[:, 0] + force[:, 2]) / (m0 * (force[:, 1] * axis[:, 1] + force[:, 3] * axis[:, 3]))
    return np.minimum(up, down)


def _friction_angle_function(b_over_a):
    """``phi`` (n, 4) -> (n, 4, 3, 2): (force, moment, loss) x (value, d/d phi) per unit slip speed at fixed
    ``b/a`` (lin2019 eqs A4-A6; :func:`lowmodel.contact.ellipse_friction.friction_angle_at`)."""
    from ballbench.lowmodel.contact.ellipse_friction import friction_angle_at

    return friction_angle_at(b_over_a, stacked=True)
