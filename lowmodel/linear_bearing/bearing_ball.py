"""Quasi-static motion and friction of one ball in a four-point-contact linear ball bearing.

lin2019 Sec 2.1 (eqs 1-4, Appendix A1-A7), normal forces from lin2017 eq 36.

Frame (lin2019 Fig 2): ``z`` along the raceway (direction of motion of the
top groove, velocity ``v``), ``y`` up, ``x`` to the right; ball centre at the
origin.  Contact ``i`` in the order (BL, BR, TR, TL) sits at
``r_i = R_B n_i`` with the outward unit normal

    n_BL = (-sin b, -cos b),  n_BR = (sin b, -cos b),
    n_TR = ( sin b,  cos b),  n_TL = (-sin b,  cos b)      (b = beta_i)

(checked against eqs 1, A1-A3: ``(Omega x r_i)_z`` reproduces each bracket).
Unknowns: ball velocity ``v_B`` and ``Omega = (omega_x, omega_y, 0)``.

Per contact (lin2019 eqs 1-3, A1-A3), with ``V_i`` the groove velocity
(0 bottom, ``v`` top):

    slide_i = v_B - V_i + (Omega x r_i)_z     slip of the ball at the contact centre [m/s]
            = omega_i c_i                      (numerator of eq 2)
    omega_i = -Omega . n_i                     spin about the inward normal y_i (eq 2)
    spin_i  = omega_i a_i                      [m/s]

Friction comes from the map of :mod:`lowmodel.contact.ellipse_friction`
(:func:`~lowmodel.contact.ellipse_friction.friction_angle_at`) and depends only
on the slip-direction angle ``phi_i = atan2(slide_i, spin_i)`` (``c_i/a_i = tan phi_i``);
the velocity-centre offset ``c_i`` is never formed, so ``omega_i -> 0`` (``c_i -> inf``, pure sliding) is an
ordinary point ``phi_i = +-pi/2``.

    f_i   = mu F_i force_i                 friction force on the ball along +z [N]      (eq A4)
    M_i   = mu F_i a_i moment_i            spin moment on the ball about -y_i [N m]     (eq A5)

Equilibrium (lin2019 eq 4; ``m_i = -M_i`` is the moment about ``+y_i = -n_i``):

    sum_i f_i                                 = -F_ext,z
    sum_i (n_i,y f_i + n_i,x M_i / R_B)       = -M_ext,x / R_B
    sum_i (-n_i,x f_i + n_i,y M_i / R_B)      = -M_ext,y / R_B

(the rows of eq 4: e.g. BL has ``n_y = -cos``, ``-n_x = sin``).  ``F_ext``
and ``M_ext`` carry the ball-to-ball terms of :mod:`lowmodel.linear_bearing.b2b`.

Friction loss of contact ``i`` is the power of its tractions on the slip
field, ``P_i = -(f_i slide_i + m_i omega_i) = mu F_i (a_i omega_i moment_i
- slide_i force_i)``; this is the exact identity ``loss = moment - (c/a)
force`` of eqs A4-A6, evaluated from the same force and moment that enter the
equilibrium, so the power balance ``v sum_top f_i = sum_i P_i`` holds to the
Newton tolerance (it checks kinematics, moment arms and signs, not the
quadrature).  The tabulated loss of eq A6 is reported alongside
(``friction_loss_table``) and agrees to the accuracy of the friction map.

Unknowns of Newton's method, per ball: ``(v_B, omega_x R_B, omega_y
R_B)/|v|`` and the four ``phi_i``; equations: eq 4 (in ``phi``) and the
kinematics ``slide_i cos phi_i - spin_i sin phi_i = 0`` (see
:func:`ball_terms`: smooth also where a contact's slip vanishes).  Analytic
Jacobian (chain rule through the map's spline derivatives), globalised by
Levenberg-Marquardt (:func:`lowmodel.solvers.newton`); residuals in units of ``mu max(F_i)``
and ``|v|``.  Near the four-point limit the full-sliding model stops having a
solution (:func:`spin_capacity_ratio`); the solver then raises
ConvergenceError with that diagnosis.
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from functools import cached_property, lru_cache

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import contact_normals
from ballbench.lowmodel.solvers import ContinuationStep, check_solver_options, continuation, solve_with_restarts

__all__ = [
    "BallContacts",
    "BallState",
    "BallTerms",
    "ball_contacts",
    "contacts_from_forces",
    "solve_ball",
    "ContinuationPath",
    "homotopy_paths",
    "solve_with_continuation",
    "spin_capacity_ratio",
    "minimum_conformity",
    "ball_terms",
    "initial_guess",
    "with_slip_angles",
    "slip_kinematics",
    "ball_state",
    "solve_free",
    "solve_branch",
    "with_spin_capacity_diagnosis",
    "slip_speeds",
    "N_UNKNOWNS",
    "STICK_REASON",
]

_TOP = np.array([0.0, 0.0, 1.0, 1.0])  # contacts on the moving (top) groove
STICK_REASON = "a contact stops sliding (full-sliding branch ends: its continuation slips against its friction)"


# --------------------------------------------------------------------------
# data
# --------------------------------------------------------------------------
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
    def _geometry(self):
        """Load-independent arrays of :func:`ball_terms` (computed once per instance)."""
        normals = contact_normals(self.contact_angles)
        nx, ny = normals[..., 0], normals[..., 1]
        arm = self.semi_major / self.ball_radius  # a_i / R_B
        dslide = np.stack([np.ones_like(nx), ny, -nx], axis=-1)  # d slide / d x, (n, 4, 3)
        dspin = np.stack([np.zeros_like(nx), -nx * arm, -ny * arm], axis=-1)  # d spin / d x
        top = math.copysign(1.0, self.groove_velocity) * _TOP
        derived = nx, ny, arm, dslide, dspin, top
        for array in derived:  # fresh arrays (or views of them) held by this instance only: no copy needed
            array.setflags(write=False)
        return derived

    @cached_property
    def _friction_at(self):
        """The friction map at this instance's axis ratios (lin2019 eqs A4-A6), as a function of the slip angles:
        ``phi`` (n, 4) -> (n, 4, 3, 2), (force, moment, loss) x (value, d/d phi) per unit slip speed."""
        return _friction_angle_function(self.b_over_a)

    @cached_property
    def _equilibrium(self):
        """(n, 3, 8): the rows of lin2019 eq 4 as a matrix on ``(force_i, moment_i)`` (columns interleaved
        ``f_0, M_0, f_1, M_1, ...``), the same as (n, 4, 3, 2) (contact, row, force | moment), and the
        friction scales ``[load, load_arm, load]`` of each contact per reference force (a dict, filled by
        :func:`ball_terms`)."""
        nx, ny = self._geometry[:2]
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


@dataclass(frozen=True)
class BallState:
    """Quasi-static solution for ``n`` balls (arrays have leading shape ``(n,)``).

    ball_velocity : (n,) m/s, ``v_B``
    omega : (n, 2) rad/s, ``(omega_x, omega_y)``
    velocity_deviation : (n,) ``epsilon = 2 v_B / v - 1`` (lin2019 eq 21)
    spin : (n, 4) rad/s, ``omega_i`` (eq 2)
    slide : (n, 4) m/s, ``omega_i c_i`` (slip at the contact centre)
    c_over_a : (n, 4) velocity-centre offset ``c_i/a_i`` (+-inf at pure sliding)
    friction_force : (n, 4) N, ``f_{i,z}`` on the ball
    friction_moment : (n, 4) N m, ``M_{i,O}`` about -y_i (lin2019 sign)
    friction_loss : (n, 4) W, ``P_{f,i}`` from the power of the tractions
    friction_loss_table : (n, 4) W, eq A6 from the friction map
    input_power : W, power put in by the top groove, ``v sum_top f_i``
    b2b_force : (n - 1,) N, ball-to-ball normal force between balls j and j+1
    b2b_friction_loss : (n - 1,) W, lin2019 eq 7
    b2b_slip : (n - 1,) m/s, ``|Delta v_B2B|`` (eq 5)
    iterations : Newton iterations; residual : final max residual / (mu max F)
    continuation : the continuation paths taken where Newton from the cheap start failed, a tuple of
        :class:`ContinuationPath` (empty when the direct solve converged)
    """

    ball_velocity: np.ndarray
    omega: np.ndarray
    velocity_deviation: np.ndarray
    spin: np.ndarray
    slide: np.ndarray
    c_over_a: np.ndarray
    friction_force: np.ndarray
    friction_moment: np.ndarray
    friction_loss: np.ndarray
    friction_loss_table: np.ndarray
    input_power: float
    b2b_force: np.ndarray
    b2b_friction_loss: np.ndarray
    b2b_slip: np.ndarray
    iterations: int
    residual: float
    continuation: tuple = ()

    @property
    def total_loss(self) -> float:
        """Ball-to-groove plus ball-to-ball friction loss [W]."""
        return float(self.friction_loss.sum() + self.b2b_friction_loss.sum())

    @property
    def groove_loss(self) -> float:
        """Ball-to-groove friction loss [W]."""
        return float(self.friction_loss.sum())


@dataclass(frozen=True)
class ContinuationPath:
    """A continuation path taken by a solver (:func:`solve_with_continuation`).

    balls : indices of the balls solved along it; kind : ``"arm"`` (Hertz semi-axes scaled by
    ``start_scale^(1 - s)``: the spin moments grow back from a larger arm to the target),
    ``"theta"`` (contact angles blended from their mean, the symmetric ball, to the target),
    ``"mu"`` (:func:`lowmodel.linear_bearing.b2b.solve`: mu from ``mu / start_scale``) or ``"mu from a probe"``
    (:mod:`lowmodel.linear_bearing.branch_end`: mu from ``start_scale mu``, a state found beside the target);
    start_scale : the arm scale at ``s = 0`` (1 for ``"theta"``); steps : the converged
    :class:`lowmodel.solvers.ContinuationStep` (``s``, Newton iterations), ``s = 1`` last.
    """

    balls: tuple
    kind: str
    start_scale: float
    steps: tuple


# --------------------------------------------------------------------------
# input checks and construction
# --------------------------------------------------------------------------
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
    mu = checks.positive("friction_coefficient", friction_coefficient,
                         note="mu = 0 leaves the ball motion undetermined")
    velocity = checks.finite("groove_velocity", groove_velocity, "m/s")
    if velocity == 0.0:
        raise ValueError(f"groove_velocity must be finite and nonzero m/s, got {groove_velocity!r}")
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

    Normal forces from :func:`lowmodel.fourpoint.normal_forces` (lin2017 eq
    36; ValueError at loss of four-point contact), semi-axes from
    :func:`lowmodel.contact.hertz.ball_in_groove` / ``solve_load``.
    """
    from ballbench.lowmodel import fourpoint
    from ballbench.lowmodel.contact import hertz

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
    from scipy.optimize import brentq

    from ballbench.lowmodel.contact import hertz
    from ballbench.lowmodel.contact.ellipse_friction import B_OVER_A_RANGE

    def excess(f):
        return hertz.ball_in_groove(1.0, f).axis_ratio - B_OVER_A_RANGE[0]

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
    from scipy.special import ellipe

    force, axis = contacts.normal_forces, contacts.semi_major
    m0 = 0.375 * ellipe(1.0 - contacts.b_over_a[:, 0] ** 2)  # lin2019 eq 11 (scipy: parameter m = e^2)
    radius = contacts.ball_radius
    up = radius * (force[:, 1] + force[:, 3]) / (m0 * (force[:, 0] * axis[:, 0] + force[:, 2] * axis[:, 2]))
    down = radius * (force[:, 0] + force[:, 2]) / (m0 * (force[:, 1] * axis[:, 1] + force[:, 3] * axis[:, 3]))
    return np.minimum(up, down)


# --------------------------------------------------------------------------
# residual of the ball equilibrium (vectorised over balls)
# --------------------------------------------------------------------------
def _friction_angle_function(b_over_a):
    """``phi`` (n, 4) -> (n, 4, 3, 2): (force, moment, loss) x (value, d/d phi) per unit slip speed at fixed
    ``b/a`` (lin2019 eqs A4-A6; :func:`lowmodel.contact.ellipse_friction.friction_angle_at`)."""
    from ballbench.lowmodel.contact.ellipse_friction import friction_angle_at

    return friction_angle_at(b_over_a, stacked=True)


@dataclass(frozen=True)
class BallTerms:
    """Residual, Jacobian and contact terms of :func:`ball_terms` for ``n`` balls (dimensionless units).

    Forces and moments in units of ``mu F_ref``, velocities in units of ``|v|``.
    """

    residual: np.ndarray  # (n, 7): eq 4 rows in units mu F_ref, then 4 kinematic rows in units |v|
    jacobian: np.ndarray  # (n, 7, 7) d residual / d unknowns
    slide: np.ndarray  # (n, 4) units |v|
    spin_velocity: np.ndarray  # (n, 4) omega_i a_i, units |v|
    slip_speed: np.ndarray  # (n, 4) signed |(slide, spin)| along (sin phi, cos phi), units |v|
    force: np.ndarray  # (n, 4) units mu F_ref, on the ball along +z
    moment: np.ndarray  # (n, 4) M_{i,O}/R_B, units mu F_ref
    loss_table: np.ndarray  # (n, 4) units mu F_ref |v|


N_UNKNOWNS = 7  # per ball: (v_B, omega_x R_B, omega_y R_B)/|v| and the four slip angles phi_i


def ball_terms(unknowns: np.ndarray, contacts: BallContacts, reference_force: float) -> BallTerms:
    """Residual of lin2019 eq 4 and of the slip kinematics for each ball, and its Jacobian.

    ``unknowns`` (n, 7): ``x = (v_B, omega_x R_B, omega_y R_B)/|v|`` and the
    slip-direction angles ``phi_i`` of the four contacts.  Friction of each
    contact depends on its slip direction only, ``(slide_i, spin_i) =
    r_i (sin phi_i, cos phi_i)``, so eq 4 is written in ``phi`` and the
    kinematics (eqs 1-2, A1-A3) as ``slide_i cos phi_i - spin_i sin phi_i = 0``
    (linear in ``x``).  Smooth everywhere, also where a contact's slip
    vanishes (``r_i -> 0``: the rolling limit, where ``atan2(slide, spin)`` is
    singular and Newton in ``x`` alone fails); the branch ``r_i >= 0`` is
    checked after convergence.
    """
    x = unknowns[:, :3]
    phi = unknowns[:, 3:]
    nx, ny, arm, dslide, dspin, top = contacts._geometry
    rows, per_contact, scales = contacts._equilibrium
    scale = scales.get(reference_force)
    if scale is None:  # the friction map's (force, moment, loss) per unit mu F_ref: (load, load a_i/R_B, load)
        load = contacts.normal_forces / reference_force
        scale = scales[reference_force] = np.stack([load, load * arm, load], axis=-1)[..., None]
        scale.setflags(write=False)
    # lin2019 eqs 1, A1-A3 (z slip at the centre): dslide = (1, n_y, -n_x);
    # eq 2 (omega_i a_i): dspin = -(0, n_x, n_y) a_i/R_B
    slide = np.matmul(dslide, x[:, :, None])[..., 0]
    slide -= top
    spin_velocity = np.matmul(dspin, x[:, :, None])[..., 0]
    cos, sin = np.cos(phi), np.sin(phi)
    table = contacts._friction_at(phi)  # (n, 4, 3, 2): unit slip speed along phi
    table *= scale  # eqs A4, A5 (M_{i,O}/R_B about -y_i), A6; and d/d phi
    n = x.shape[0]
    residual = np.empty((n, N_UNKNOWNS))
    residual[:, :3] = np.matmul(rows, table[:, :, :2, 0].reshape(n, 8, 1))[..., 0]  # lin2019 eq 4, rows 1-3
    residual[:, 3:] = slide * cos - spin_velocity * sin  # slip along (sin phi, cos phi)
    slip_speed = slide * sin + spin_velocity * cos
    jacobian = np.zeros((n, N_UNKNOWNS, N_UNKNOWNS))
    np.matmul(per_contact, table[:, :, :2, 1, None], out=jacobian[:, :3, 3:].transpose(0, 2, 1)[..., None])  # d/d phi_i
    jacobian[:, 3:, :3] = cos[..., None] * dslide - sin[..., None] * dspin
    jacobian.reshape(n, N_UNKNOWNS * N_UNKNOWNS)[:, 3 * N_UNKNOWNS + 3::N_UNKNOWNS + 1] = -slip_speed  # d/d phi_i
    force, moment = table[:, :, 0, 0], table[:, :, 1, 0]
    loss_table = table[:, :, 2, 0] * slip_speed  # eq A6 (loss is per unit slip speed here)
    return BallTerms(residual, jacobian, slide, spin_velocity, slip_speed, force, moment, loss_table)


def initial_guess(contacts: BallContacts) -> np.ndarray:
    """Rolling about x with v_B = v/2 (the theta = 0 solution), and its slip angles."""
    direction = math.copysign(1.0, contacts.groove_velocity)
    cos_mean = np.cos(contacts.contact_angles).mean(axis=1)
    guess = np.zeros((contacts.n_balls, N_UNKNOWNS))
    guess[:, 0] = 0.5 * direction
    guess[:, 1] = 0.5 * direction / cos_mean
    return with_slip_angles(guess, contacts)


def slip_kinematics(unknowns: np.ndarray, contacts: BallContacts):
    """Slip at the contact centres (units |v|): ``slide_i`` (eqs 1, A1-A3) and ``spin_i = omega_i a_i`` (eq 2)."""
    _, _, _, dslide, dspin, top = contacts._geometry
    x = unknowns[:, :3]
    return np.einsum("nk,nik->ni", x, dslide) - top, np.einsum("nk,nik->ni", x, dspin)


def slip_speeds(unknowns: np.ndarray, contacts: BallContacts) -> np.ndarray:
    """Signed slip speed ``r_i = slide_i sin phi_i + spin_i cos phi_i`` [units |v|] of every contact, (n, 4), at the
    ball unknowns (n, 7) (slip angles ``phi_i`` in columns 3-6): > 0 where friction opposes the slip."""
    slide, spin = slip_kinematics(unknowns, contacts)
    return slide * np.sin(unknowns[:, 3:]) + spin * np.cos(unknowns[:, 3:])


def with_slip_angles(guess: np.ndarray, contacts: BallContacts) -> np.ndarray:
    """A copy of the unknowns ``guess`` (n, 7) with the slip angles set from its velocities (atan2(slide, spin))."""
    slide, spin = slip_kinematics(guess, contacts)
    guess = guess.copy()
    guess[:, 3:] = np.arctan2(slide, spin)
    return guess


def ball_state(unknowns, terms: BallTerms, contacts: BallContacts, reference_force: float, *, b2b_force=None,
               b2b_slip=None, iterations: int, residual: float) -> BallState:
    """The :class:`BallState` [SI] of converged unknowns (n, 7) and their :func:`ball_terms`.

    ``b2b_force`` [N] and ``b2b_slip`` [m/s], shape (n-1,), default to zero (no ball-to-ball contact).
    """
    speed = abs(contacts.groove_velocity)
    radius = contacts.ball_radius
    mu_f = contacts.friction_coefficient * reference_force
    velocity = unknowns[:, 0] * speed
    omega = unknowns[:, 1:3] * speed / radius
    spin = terms.spin_velocity * speed / contacts.semi_major
    slide = terms.slide * speed
    phi = unknowns[:, 3:]
    c_over_a = np.where(np.abs(np.cos(phi)) > 1e-15, np.tan(phi), np.sign(np.sin(phi)) * np.inf)  # slide/spin
    force = terms.force * mu_f
    moment = terms.moment * mu_f * radius
    # power of the tractions on the slip field: P = -(f slide + m omega), m = -M (about +y_i)
    loss = -(force * slide - moment * spin)
    input_power = float(contacts.groove_velocity * (force * _TOP).sum())
    n_pairs = contacts.n_balls - 1
    if b2b_force is None:
        b2b_force = np.zeros(n_pairs)
        b2b_slip = np.zeros(n_pairs)
    b2b_loss = contacts.friction_coefficient * b2b_force * b2b_slip  # lin2019 eq 7
    return BallState(velocity, omega, 2.0 * velocity / contacts.groove_velocity - 1.0, spin, slide, c_over_a,
                     force, moment, loss, terms.loss_table * mu_f * speed, input_power, b2b_force,
                     b2b_loss, b2b_slip, iterations, residual)


# --------------------------------------------------------------------------
# solution (the damped Newton of lowmodel.solvers)
# --------------------------------------------------------------------------
def solve_ball(contacts: BallContacts, *, tolerance: float = 1e-12, max_iterations: int = 60) -> BallState:
    """Solve lin2019 eq 4 for each ball independently (no ball-to-ball contact).

    Parameters
    ----------
    contacts : BallContacts for ``n`` balls (see :func:`ball_contacts`)
    tolerance : max residual of eq 4 in units of ``mu max(F_i)`` (forces, and
        moments / R_B) and of the slip kinematics in units of ``|v|``
    max_iterations : Newton iterations per ball

    Returns
    -------
    BallState; ``iterations`` is the largest count over the balls; ``continuation`` the paths
    taken for balls whose Newton from the cheap start failed (:func:`solve_with_continuation`).
    Raises ConvergenceError (with the residual, ``reason`` and ``last_converged``) where no state
    is found.
    """
    check_solver_options(tolerance, max_iterations)
    reference_force = float(contacts.normal_forces.max())
    paths = []
    unknowns, iterations, residual = solve_free(contacts, reference_force, tolerance, max_iterations, paths)
    terms = ball_terms(unknowns, contacts, reference_force)
    state = ball_state(unknowns, terms, contacts, reference_force, iterations=iterations, residual=residual)
    return dataclasses.replace(state, continuation=tuple(paths)) if paths else state


def solve_free(contacts: BallContacts, reference_force: float, tolerance: float, max_iterations: int,
               paths: list | None = None):
    """Unknowns (n, 7) of every ball alone (no ball-to-ball contact); largest iteration count and residual.

    ``reference_force`` [N] is the unit of the force residuals (``mu F_ref``).  A ball whose
    Newton from the cheap start fails is solved by continuation (:func:`solve_with_continuation`);
    the paths taken are appended to ``paths`` (a list) when given.  Raises ConvergenceError with
    the spin-capacity diagnosis, the reason and the last converged parameter if a ball fails.
    """
    unknowns = initial_guess(contacts)
    worst_iterations, worst_residual = 0, 0.0
    for index in range(contacts.n_balls):
        single = contacts.ball(index)

        def solve_at(ball_contacts, z0, what):
            def function(z):
                terms = ball_terms(z[None, :], ball_contacts, reference_force)
                return terms.residual[0], terms.jacobian[0]
            return solve_branch(function, z0, lambda z: z[None, :], ball_contacts, reference_force,
                                tolerance=tolerance, max_iterations=max_iterations, what=what)

        try:
            z, residual, iterations = solve_at(single, unknowns[index], f"ball {index}")
        except ConvergenceError as error:
            (z, residual, iterations), taken = solve_with_continuation(
                single, solve_at, lambda c: initial_guess(c)[0], error, what=f"ball {index}")
            if paths is not None:
                paths.append(ContinuationPath((index,), taken.kind, taken.start_scale, taken.steps))
        unknowns[index] = z
        worst_iterations = max(worst_iterations, iterations)
        worst_residual = max(worst_residual, float(np.max(np.abs(residual))))
    return unknowns, worst_iterations, worst_residual


def homotopy_paths(contacts: BallContacts):
    """The homotopies tried by :func:`solve_with_continuation`, as ``(kind, start_scale, contacts_at)``.

    ``contacts_at(s)`` gives the BallContacts at homotopy parameter ``s`` in [0, 1] (the target at 1).
    Normal forces, ``b/a``, ``mu`` and ``v`` stay those of the target (``mu`` and ``v`` drop out of the
    scaled equations anyway); only what makes Newton hard changes:

    * ``"arm"``: the semi-axes ``a_i`` scaled by ``lambda^(1 - s)``, ``lambda`` up to 4 but keeping the
      spin-capacity ratio >= 3 at the start.  Light loads (small ``a/R_B``) bring the state close to the
      rigid lin2017 solution with sticking contacts, where the full-sliding equations are stiff; a
      larger arm is the same ball under a heavier load (``a ~ F^(1/3)``), which converges.
    * ``"theta"``: contact angles ``beta_mean + s (beta_i - beta_mean)`` from the symmetric ball (all
      four angles equal, converged in 2-3 iterations) to the target; follows misalignment up to the
      lin2017 eq 37 limit.
    """
    ratio = float(np.min(spin_capacity_ratio(contacts)))
    paths = []
    scale = min(4.0, ratio / 3.0)
    if scale > 1.2:
        def arm_at(s, scale=scale):
            return BallContacts(contacts.contact_angles, contacts.normal_forces,
                                contacts.semi_major * scale ** (1.0 - s), contacts.b_over_a, contacts.ball_radius,
                                contacts.friction_coefficient, contacts.groove_velocity)
        paths.append(("arm", scale, arm_at))
    mean = contacts.contact_angles.mean(axis=1, keepdims=True)

    def theta_at(s):
        return BallContacts(mean + s * (contacts.contact_angles - mean), contacts.normal_forces,
                            contacts.semi_major, contacts.b_over_a, contacts.ball_radius,
                            contacts.friction_coefficient, contacts.groove_velocity)
    paths.append(("theta", 1.0, theta_at))
    return paths


def solve_with_continuation(contacts: BallContacts, solve_at, start_guess, error: ConvergenceError, *, what: str,
                            balls_of=None, extra_paths=()):
    """Continuation along :func:`homotopy_paths` after Newton from the cheap start failed with ``error``.

    ``solve_at(contacts_s, z0, what)`` solves the problem (one ball, or the coupled B2B chain) for the
    contacts ``contacts_s`` from ``z0`` and returns ``(z, residual, iterations)``; ``start_guess(contacts_s)``
    is the cheap start at ``s = 0``.  Paths are tried in order; the first that reaches ``s = 1`` gives
    ``((z, residual, iterations), ContinuationPath)``.  Where none does, ConvergenceError with the
    spin-capacity diagnosis, the reason (spin-capacity ratio < 1, or the continuation stopped: a fold
    or no state beyond; or a contact stops sliding: the branch continues with a contact slipping against
    its friction) and the last converged parameter of the path that got furthest; its attribute
    ``min_slip_speed`` is the smallest contact slip speed ``r_i`` [units |v|] at that last converged point
    (``balls_of(z)`` gives the (n, 7) ball unknowns of a state; default one ball), NaN without one.
    ``extra_paths``: more ``(kind, start_scale, contacts_at)`` tried after :func:`homotopy_paths`.
    """
    if balls_of is None:
        def balls_of(z):
            return np.reshape(z, (-1, N_UNKNOWNS))
    furthest, furthest_at = None, None
    for kind, scale, contacts_at in (*homotopy_paths(contacts), *extra_paths):
        try:
            start = contacts_at(0.0)
            z0, _, iterations0 = solve_at(start, start_guess(start), f"{what}, {kind} path start")
        except ConvergenceError:
            continue

        def step(s, z, contacts_at=contacts_at, kind=kind):
            return solve_at(contacts_at(s), z, f"{what}, {kind} path")

        try:
            z, residual, steps = continuation(step, z0, what=f"{what}, {kind} path", name=f"s ({kind})")
        except ConvergenceError as stopped:
            if furthest is None or stopped.last_converged[1] > furthest.last_converged[1]:
                furthest, furthest_at = stopped, contacts_at
            continue
        steps = (ContinuationStep(0.0, iterations0),) + steps[1:]
        return (z, residual, sum(p.iterations for p in steps)), ContinuationPath((), kind, scale, steps)
    ratio = float(np.min(spin_capacity_ratio(contacts)))
    reason = ("spin-capacity ratio < 1" if ratio < 1.0 else
              furthest.reason if furthest is not None else "no continuation path could start")
    last = furthest.last_converged if furthest is not None else None
    min_slip = math.nan
    if furthest is not None:  # how close the last converged point is to a contact that stops sliding
        min_slip = float(np.min(slip_speeds(balls_of(furthest.last_state), furthest_at(last[1]))))
    where = (f"; continuation got to {last[0]} = {last[1]:.6g}, smallest contact slip speed there "
             f"{min_slip:.3g} |v|" if last is not None else "")
    diagnosed = with_spin_capacity_diagnosis(error, contacts)
    message = str(diagnosed).split(" (residual")[0] + where
    failure = ConvergenceError(message, residual=error.residual, iterations=error.iterations,
                               tolerance=error.tolerance, reason=reason, last_converged=last)
    failure.min_slip_speed = min_slip
    # the last converged point and its contacts, for a caller that judges the reason (linear_bearing.branch_end)
    failure.last_state = furthest.last_state if furthest is not None else None
    failure.last_contacts = furthest_at(last[1]) if furthest is not None else None
    raise failure from None


def solve_branch(function, z0, balls_of, contacts: BallContacts, reference_force: float, *, tolerance: float,
                 max_iterations: int, what: str, attempts: int = 4, with_balls=None):
    """Newton on the slip-angle formulation, then keep only the physical branch.

    ``slide_i cos phi_i = spin_i sin phi_i`` also holds for ``phi_i + pi``
    (friction reversed against the slip); a converged point with a slip speed
    ``r_i < 0`` is such a spurious root and is restarted with ``phi_i + pi``
    (:func:`lowmodel.solvers.solve_with_restarts`).  ``balls_of(z)`` returns
    the (n, 7) ball unknowns of the state vector ``z`` and ``with_balls(z, balls)`` a copy of ``z``
    with them replaced (default: ``z`` starts with the ball unknowns); ``reference_force`` [N]
    is the force unit of ``function``'s residual.
    """
    replace = _replace_balls if with_balls is None else with_balls

    def restart(z):
        balls = balls_of(z)
        slip_speed = slip_speeds(balls, contacts)
        wrong = slip_speed < -1e3 * tolerance
        if not np.any(wrong):
            return None
        balls = balls.copy()
        balls[:, 3:] = np.where(wrong, balls[:, 3:] + math.pi, balls[:, 3:])
        return replace(z, balls), float(-slip_speed.min())

    return solve_with_restarts(function, z0, restart, tolerance=tolerance, max_iterations=max_iterations, what=what,
                               rejection="converged only to slip directions against the slip", attempts=attempts,
                               rejection_reason=STICK_REASON)


def with_spin_capacity_diagnosis(error: ConvergenceError, contacts: BallContacts) -> ConvergenceError:
    """The ConvergenceError ``error`` with the spin-capacity diagnosis (:func:`spin_capacity_ratio`) added
    to its message (same residual and counts)."""
    ratio = float(np.min(spin_capacity_ratio(contacts)))
    reason = (f"; spin-capacity ratio {ratio:.3f} < 1: no quasi-static state with full sliding at all four "
              "contacts (near the four-point limit, outside lin2019's friction model)" if ratio < 1.0 else
              f"; spin-capacity ratio {ratio:.3f}")
    message = str(error).split(" (residual")[0] + reason
    return ConvergenceError(message, residual=error.residual, iterations=error.iterations,
                            tolerance=error.tolerance,
                            reason="spin-capacity ratio < 1" if ratio < 1.0 else error.reason,
                            last_converged=error.last_converged)


def _replace_balls(z: np.ndarray, balls: np.ndarray) -> np.ndarray:
    z = z.copy()
    z[:balls.size] = balls.reshape(-1)
    return z
