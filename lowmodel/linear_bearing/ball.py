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

import numpy as np

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import ball_fast
from ballbench.lowmodel.linear_bearing.contacts import TOP, BallContacts, spin_capacity_ratio
from ballbench.lowmodel.solvers import ContinuationStep, check_solver_options, continuation, solve_with_restarts
from ballbench.lowmodel.state import BallStateBase

__all__ = [
    "BallState",
    "BallTerms",
    "solve",
    "solve_cases",
    "ContinuationPath",
    "homotopy_paths",
    "solve_with_continuation",
    "ball_terms",
    "case_state",
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
    "SPIN_CAPACITY_REASON",
]

SPIN_CAPACITY_REASON = "spin-capacity ratio < 1"  # no full-sliding state of a free ball (docs/b2b_bearing.md)
STICK_REASON = "a contact stops sliding (full-sliding branch ends: its continuation slips against its friction)"


@dataclass(frozen=True)
class BallState(BallStateBase):
    """Quasi-static solution for ``n`` balls (arrays have leading shape ``(n,)``); the power, B2B and loss fields
    of :class:`lowmodel.state.BallStateBase` with these units:

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
    friction_loss_table: np.ndarray
    continuation: tuple = ()


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
# residual of the ball equilibrium (vectorised over balls)
# --------------------------------------------------------------------------
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
    nx, ny, arm, dslide, dspin, top = contacts.kinematics
    rows, per_contact, scales = contacts.equilibrium
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
    table = contacts.friction_at(phi)  # (n, 4, 3, 2): unit slip speed along phi
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


def case_state(states, case: int) -> BallState:
    """The :class:`BallState` of case ``case`` of the compiled path's
    :class:`lowmodel.linear_bearing.ball_fast.CaseStates` (its arrays are views of the batch's)."""
    ball, contact, pair = states.ball[case], states.contact[case], states.pair[case]
    return BallState(ball[:, 0], ball[:, 1:3], ball[:, 3], contact[..., 0], contact[..., 1], contact[..., 2],
                     contact[..., 3], contact[..., 4], contact[..., 5],
                     friction_loss=np.ascontiguousarray(contact[..., 6]),  # its sum: that of a batch's (m, 8) rows
                     input_power=float(states.input_power[case]), b2b_force=pair[:, 0], b2b_friction_loss=pair[:, 2],
                     b2b_slip=pair[:, 1], iterations=int(states.iterations[case]),
                     residual=float(states.residual[case]))


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
    _, _, _, dslide, dspin, top = contacts.kinematics
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
    input_power = float(contacts.groove_velocity * (force * TOP).sum())
    n_pairs = contacts.n_balls - 1
    if b2b_force is None:
        b2b_force = np.zeros(n_pairs)
        b2b_slip = np.zeros(n_pairs)
    b2b_loss = contacts.friction_coefficient * b2b_force * b2b_slip  # lin2019 eq 7
    return BallState(velocity, omega, 2.0 * velocity / contacts.groove_velocity - 1.0, spin, slide, c_over_a,
                     force, moment, terms.loss_table * mu_f * speed, friction_loss=loss, input_power=input_power,
                     b2b_force=b2b_force, b2b_friction_loss=b2b_loss, b2b_slip=b2b_slip, iterations=iterations,
                     residual=residual)


# --------------------------------------------------------------------------
# solution (the damped Newton of lowmodel.solvers)
# --------------------------------------------------------------------------
def solve(contacts: BallContacts, *, tolerance: float = 1e-12, max_iterations: int = 60) -> BallState:
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
    fast = ball_fast.solve_free(contacts, contacts.n_balls, reference_force, tolerance=tolerance,
                                max_iterations=max_iterations)
    if fast is not None and fast.status[0] == 0:  # the compiled kernels solved every ball (else: the numpy path)
        return case_state(fast, 0)
    paths = []
    unknowns, iterations, residual = solve_free(contacts, reference_force, tolerance, max_iterations, paths)
    terms = ball_terms(unknowns, contacts, reference_force)
    state = ball_state(unknowns, terms, contacts, reference_force, iterations=iterations, residual=residual)
    return dataclasses.replace(state, continuation=tuple(paths)) if paths else state


def solve_cases(contacts: BallContacts, balls_per_case: int, *, tolerance: float = 1e-12, max_iterations: int = 60):
    """Many independent cases at once, every ball alone: balls ``c b .. c b + b - 1`` of ``contacts`` are case ``c``
    (``b = balls_per_case``).  Returns :class:`lowmodel.linear_bearing.ball_fast.CaseStates`, case ``c`` equal
    to :func:`solve` of its contacts (:func:`lowmodel.linear_bearing.ball_fast.case_contacts`) to the last bit:
    the compiled kernels solve the batch, and the cases they cannot (all cases without kernels) are solved by
    :func:`solve` one by one.  Raises what :func:`solve` raises for the first case without a state.
    """
    check_solver_options(tolerance, max_iterations)
    reference = ball_fast.case_reference_forces(contacts, balls_per_case)
    states = ball_fast.solve_free(contacts, balls_per_case, reference, tolerance=tolerance,
                                  max_iterations=max_iterations)
    if states is None:
        states = ball_fast.empty_states(reference.size, balls_per_case)
        states.status[:] = -1
    for case in np.flatnonzero(states.status):
        state = solve(ball_fast.case_contacts(contacts, balls_per_case, case), tolerance=tolerance,
                      max_iterations=max_iterations)
        ball_fast.store_state(states, case, state)
    return states


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
                terms = ball_terms(z[None, :], ball_contacts, reference_force)  # noqa: B023 - called within this iteration
                return terms.residual[0], terms.jacobian[0]
            return solve_branch(function, z0, lambda z: z[None, :], ball_contacts,  # noqa: B023 - called within this iteration
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
    reason = (SPIN_CAPACITY_REASON if ratio < 1.0 else
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


def solve_branch(function, z0, balls_of, contacts: BallContacts, *, tolerance: float, max_iterations: int, what: str,
                 attempts: int = 4, with_balls=None):
    """Newton on the slip-angle formulation, then keep only the physical branch.

    ``slide_i cos phi_i = spin_i sin phi_i`` also holds for ``phi_i + pi``
    (friction reversed against the slip); a converged point with a slip speed
    ``r_i < 0`` is such a spurious root and is restarted with ``phi_i + pi``
    (:func:`lowmodel.solvers.solve_with_restarts`).  ``balls_of(z)`` returns
    the (n, 7) ball unknowns of the state vector ``z`` and ``with_balls(z, balls)`` a copy of ``z``
    with them replaced (default: ``z`` starts with the ball unknowns).
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
                            reason=SPIN_CAPACITY_REASON if ratio < 1.0 else error.reason,
                            last_converged=error.last_converged)


def _replace_balls(z: np.ndarray, balls: np.ndarray) -> np.ndarray:
    z = z.copy()
    z[:balls.size] = balls.reshape(-1)
    return z
