"""Quasi-static motion and friction of balls in a four-point-contact ball screw (lin2019 Sec 3.1).

lin2019 eqs 34-55 and Appendix A9-A11; the friction of each contact ellipse with
its velocity centre offset in both directions comes from
:func:`lowmodel.contact.ellipse_friction_offset.friction_offset`.

The module and the contacts of the balls (frames, flank arcs, eqs 37-53 in closed form) are
:mod:`lowmodel.screw.contacts`.

Kinematics (eqs 36, 40, 43-47): the ball orbits at ``omega_B`` and spins at
``omega`` relative to CS3, so its absolute angular velocity is
``omega_B z_hat + omega``.  Screw (at rest) and nut (``omega_N``) move with the
helical field ``Omega_g H(r)``, ``H(r) = z_hat x r + p z_hat``, and so does the
nominal ball centre (``omega_B H``), hence the slip of the ball on flank ``i`` at
``r = q_B + q_i + xi`` is the rigid field

    dv_i = (omega_B - Omega_i) H(q_B + q_i) + omega x q_i + W_i x xi,   W_i = (omega_B - Omega_i) z_hat + omega

with ``q_i = R_B e_i`` (eq 37) and ``H(q_B + q) = (s q_z, L/(2 pi) + c q_x, -s q_x)``
in CS3 (``s, c = sin, cos alpha``, ``L`` of eq 45).  In the contact plane (minor
axis ``y3`` along the helix, major axis ``n_i x y3`` across the groove,
``n_i = -e_i`` the inward normal) this is lin2019 eq 47: spin ``omega_i = W_i . n_i``
about ``n_i``, slip at the contact centre ``(slip_minor, slip_major) =
(dv . y3, dv . major) = (omega_i c_i, -omega_i d_i)``; tested term by term against
eq 44 and A9-A11.  Friction on the ball: ``mu F_i (f_major major + f_minor y3)``
and the moment ``mu F_i a_i m e_i`` about the contact centre.

Equilibrium of each ball (eq 54): normal forces ``-F_i e_i``, friction forces
and moments, summed about the ball centre (6 equations); unknowns
``p_B = (x_B3, z_B3)``, ``omega_B`` and ``omega = (omega_x, omega_y, omega_z)``
(6; eq 55's 18-vector with the contact points and angles eliminated by the
closed form above).  The axial load: the screw pushes the balls with
``sum_screw contacts (force on the ball) . z_hat = axial_load`` [N], with the
nut shift ``u`` as the extra unknown.

Power: the screw is at rest, so all the friction loss is put in by the nut,
``P_in = omega_N sum_nut (F_f,i . H(r_i) + M_i . z_hat)`` (normal forces do no
work on the helical field: ``n_i . H(r_i) = 0``).  ``P_in = sum_i P_f,i`` holds
to the Newton tolerance in every solve (tests); the friction torque is
``P / omega_N``.

Newton with the analytic Jacobian: every quantity carries its derivatives
with respect to the ball's unknowns and ``u`` (forward-mode chain rule,
:class:`lowmodel.dual.Dual`), through the Jacobian of ``friction_offset``; globalised by
the Levenberg-Marquardt ``newton`` of :mod:`lowmodel.solvers`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache, partial

import numpy as np

from ballbench.lowmodel import checks, kernels
from ballbench.lowmodel.calibration import law_force
from ballbench.lowmodel.dual import Dual, constant, cross, dot, variable
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.quadrature import tanh_sinh
from ballbench.lowmodel.screw.contacts import ON_NUT, SIGN_U, SIGN_W, BallContacts, ball_contacts, screw_module
from ballbench.lowmodel.screw.convergence import row_tolerances, row_weights, stall_reason
from ballbench.lowmodel.solvers import check_solver_options, newton
from ballbench.lowmodel.state import BallStateBase

__all__ = [
    "ScrewBallState", "solve", "N_UNKNOWNS", "ball_terms", "free_rolling_guess", "scales_for", "solve_preloaded",
    "continuation_start", "reference_force", "state_from", "Scales", "BallTerms", "FRICTION_LEVEL", "KERNELS",
    "kernel_scalars", "kernel_tables", "kernel_outputs", "terms_of_kernel", "warm_up_kernel",
]

N_UNKNOWNS = 6  # per ball: x_B3, z_B3, omega_B, omega_x, omega_y, omega_z
# tanh-sinh level of friction_offset: 3 where every b/a >= 0.2 (outputs' error < 3e-8 there, tests; the Jacobian's
# error is larger next to the rim, docs/speed.md 'The offset friction's quadrature'), else 4
FRICTION_LEVEL = {"coarse": 3, "fine": 4, "coarse_min_b_over_a": 0.2}


# --------------------------------------------------------------------------
# residual of eq 54 for every ball, with its Jacobian
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Scales:
    """Units of the scaled unknowns and residuals (per solve)."""

    length: float      # m: x_B3, z_B3, nut shift
    orbit: float       # rad/s: omega_B
    spin: float        # rad/s: omega
    force: float       # N: residual rows (mu F_ref)


def scales_for(contacts: BallContacts, reference_force: float) -> Scales:
    """Scales of one solve: Hertz approach of the reference force, omega_N, omega_N R_P / R_B, mu F_ref."""
    module = contacts.module
    constant = float(np.max(contacts.hertz_constant))
    speed = abs(module.nut_speed)
    return Scales(constant * reference_force ** (2.0 / 3.0), speed, speed * module.pitch_radius / module.ball_radius,
                  module.friction_coefficient * reference_force)


@dataclass(frozen=True)
class BallTerms:
    """Per-ball residual of eq 54 (n, 6) in units ``Scales.force`` (moments / R_B) and Jacobian (n, 6, 7)
    with respect to the 6 scaled ball unknowns and the scaled nut shift; ``axial`` (n,) the scaled axial
    force of the screw on each ball and its gradient (n, 7); contact quantities (n, 4) in SI."""

    residual: np.ndarray
    jacobian: np.ndarray
    axial: np.ndarray
    axial_gradient: np.ndarray
    normal_force: np.ndarray
    contact_direction: np.ndarray   # (n, 4, 2): e_i in (x3, z3)
    approach: np.ndarray
    semi_major: np.ndarray
    spin: np.ndarray                # omega_i [rad/s] about the inward normal
    slip_minor: np.ndarray          # m/s
    slip_major: np.ndarray
    friction_force: np.ndarray      # (n, 4, 3) N in CS3
    friction_moment: np.ndarray     # (n, 4, 3) N m about the contact centre, CS3
    friction_loss: np.ndarray       # (n, 4) W (eq A6 with the offset, friction_offset)
    input_power: np.ndarray         # (n,) W put in by the nut through each ball


def ball_terms(unknowns: np.ndarray, nut_shift: float, contacts: BallContacts, scales: Scales, *,
               oversize: float | None = None) -> BallTerms:
    """lin2019 eqs 36-54 for every ball at scaled ``unknowns`` (n, 6) and scaled ``nut_shift`` (scalar or (n,)).

    Unknowns: ``(x_B3, z_B3)/length``, ``omega_B/orbit``, ``(omega_x, omega_y, omega_z)/spin``.
    ``oversize`` [m] overrides the module's preload (continuation).
    """
    fast = _compiled_terms(unknowns, nut_shift, contacts, scales, oversize)
    if fast is not None:
        return fast
    from ballbench.lowmodel.contact.ellipse_friction_offset import friction_offset

    module = contacts.module
    n = unknowns.shape[0]
    m = 4 * n
    k = N_UNKNOWNS + 1
    radius = module.ball_radius
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    z_hat = (0.0, s, c)

    def var(column, scale):
        return variable(np.repeat(unknowns[:, column], 4), k, column, scale)

    x_b, z_b = var(0, scales.length), var(1, scales.length)
    orbit = var(2, scales.orbit)
    omega = (var(3, scales.spin), var(4, scales.spin), var(5, scales.spin))
    shift = Dual(np.repeat(np.broadcast_to(np.asarray(nut_shift, dtype=float), (n,)) * scales.length, 4),
                  np.zeros((m, k)))
    shift.g[:, N_UNKNOWNS] = scales.length
    on_nut = np.tile(ON_NUT, n)
    centre = contacts.arc_centres.reshape(m, 2)
    # eqs 49-53 in closed form: direction from the arc centre through the ball centre
    dx = x_b - centre[:, 0]
    dz = z_b - (shift * (c * on_nut)) - centre[:, 1]
    distance = (dx * dx + dz * dz).sqrt()
    ex, ez = dx / distance, dz / distance
    preload = module.oversize if oversize is None else oversize
    approach = distance + (radius + preload - module.groove_radius)
    hertz_c = contacts.hertz_constant.reshape(m)
    loaded = approach.v > 0.0
    if contacts.bulk_compliance is None:
        ratio = np.where(loaded, approach.v, 0.0) / hertz_c
        force_v = ratio**1.5
        force = Dual(force_v, approach.g * (1.5 * np.sqrt(ratio) / hertz_c)[:, None])  # eq 53
    else:  # calibrated law delta = C F^(2/3) + C_b F (eq 53 + finite-body compliance), lowmodel.calibration
        force_v, slope = law_force(approach.v, hertz_c, contacts.bulk_compliance.reshape(m))
        force = Dual(force_v, approach.g * slope[:, None])
    semi = Dual(contacts.semi_major_unit.reshape(m) * np.cbrt(force_v), np.zeros((m, k)))
    with np.errstate(divide="ignore", invalid="ignore"):
        da_dF = np.where(loaded, semi.v / (3.0 * np.where(loaded, force_v, 1.0)), 0.0)
    semi.g = force.g * da_dF[:, None]
    # kinematics (module docstring): q = R_B e, W = (omega_B - Omega_g) z_hat + omega
    relative = orbit - module.nut_speed * on_nut
    q = (ex * radius, constant(np.zeros(m), k), ez * radius)
    helical = (q[2] * s, q[0] * c + module.helix_radius, q[0] * (-s))
    spin_vector = tuple(relative * z_hat[j] + omega[j] for j in range(3))
    turn = cross(omega, q)
    slip = tuple(relative * helical[j] + turn[j] for j in range(3))
    inward = (-ex, constant(np.zeros(m), k), -ez)
    major = (ez, constant(np.zeros(m), k), -ex)          # n_i x y3
    spin = dot(spin_vector, inward)                    # omega_i about the inward normal
    spin_velocity = spin * semi
    slip_minor = slip[1]
    slip_major = dot(slip, major)
    mu = module.friction_coefficient
    fr_force_major = constant(np.zeros(m), k)
    fr_force_minor = constant(np.zeros(m), k)
    fr_moment = constant(np.zeros(m), k)
    loss_unit = np.zeros(m)
    idx = np.flatnonzero(loaded)
    if idx.size:
        ratio_ba = contacts.b_over_a.reshape(m)[idx]
        level = FRICTION_LEVEL["coarse" if ratio_ba.min() >= FRICTION_LEVEL["coarse_min_b_over_a"] else "fine"]
        fr = friction_offset(spin_velocity.v[idx], slip_minor.v[idx], slip_major.v[idx], ratio_ba, level=level)
        jac = fr.jacobian
        grads = (spin_velocity.g[idx], slip_minor.g[idx], slip_major.g[idx])
        for target, row in ((fr_force_major, 0), (fr_force_minor, 1), (fr_moment, 2)):
            target.v[idx] = (fr.force_major, fr.force_minor, fr.moment)[row]
            target.g[idx] = sum(jac[:, row, j, None] * grads[j] for j in range(3))
        loss_unit[idx] = fr.loss
    mu_force = force * mu
    f_major, f_minor = fr_force_major * mu_force, fr_force_minor * mu_force
    friction = tuple(major[j] * f_major for j in range(3))
    friction = (friction[0], friction[1] + f_minor, friction[2])
    moment_mag = fr_moment * mu_force * semi              # about major x minor = -n_i = e_i
    contact_moment = (ex * moment_mag, constant(np.zeros(m), k), ez * moment_mag)
    arm_moment = cross(q, friction)
    normal = (ex * (-1.0) * force, constant(np.zeros(m), k), ez * (-1.0) * force)
    total_force = tuple(normal[j] + friction[j] for j in range(3))
    total_moment = tuple(arm_moment[j] + contact_moment[j] for j in range(3))
    rows = [total_force[0], total_force[1], total_force[2]] + [t * (1.0 / radius) for t in total_moment]
    residual = np.empty((n, 6))
    jacobian = np.empty((n, 6, k))
    for r, quantity in enumerate(rows):
        residual[:, r] = quantity.v.reshape(n, 4).sum(axis=1) / scales.force
        jacobian[:, r] = quantity.g.reshape(n, 4, k).sum(axis=1) / scales.force
    axial_contrib = dot(total_force, z_hat) * (1.0 - on_nut)
    axial = axial_contrib.v.reshape(n, 4).sum(axis=1) / scales.force
    axial_gradient = axial_contrib.g.reshape(n, 4, k).sum(axis=1) / scales.force
    # power put in by the nut (screw at rest): omega_N sum_nut (F_f . H + M . z_hat)
    nut_power = (dot(friction, helical).v + dot(contact_moment, z_hat).v) * module.nut_speed * on_nut
    loss = mu * force_v * loss_unit
    return BallTerms(residual, jacobian, axial, axial_gradient, force_v.reshape(n, 4),
                     np.stack([ex.v, ez.v], axis=-1).reshape(n, 4, 2), approach.v.reshape(n, 4),
                     semi.v.reshape(n, 4), spin.v.reshape(n, 4), slip_minor.v.reshape(n, 4),
                     slip_major.v.reshape(n, 4),
                     np.stack([f.v for f in friction], axis=-1).reshape(n, 4, 3),
                     np.stack([f.v for f in contact_moment], axis=-1).reshape(n, 4, 3),
                     loss.reshape(n, 4), nut_power.reshape(n, 4).sum(axis=1))


KERNELS = "screw.ball_kernels"  # the compiled twin of ball_terms (lowmodel.kernels.load)


@lru_cache(maxsize=1)
def kernel_tables():
    from ballbench.lowmodel.contact.ellipse_friction_offset import FAR_CENTRE, SMALLEST_SLIP, disc_rule
    return (FRICTION_LEVEL["coarse_min_b_over_a"], *tanh_sinh(FRICTION_LEVEL["coarse"]),
            *tanh_sinh(FRICTION_LEVEL["fine"]), *disc_rule(), FAR_CENTRE, SMALLEST_SLIP)


@lru_cache(maxsize=64)
def _module_scalars(module) -> tuple:
    """R_B, sin and cos alpha, omega_N, L / (2 pi), oversize, r_g, mu of a module (the kernel's scalars 4-11)."""
    return (module.ball_radius, math.sin(module.lead_angle), math.cos(module.lead_angle), module.nut_speed,
            module.helix_radius, module.oversize, module.groove_radius, module.friction_coefficient)


def kernel_scalars(scales: Scales, module, oversize) -> tuple:
    """The ``scalars`` of :func:`lowmodel.screw.ball_kernels.ball_terms`: the scales, then the module's (the
    ``oversize`` [m] in place of its preload unless None)."""
    values = _module_scalars(module)
    if oversize is not None:
        values = values[:5] + (float(oversize),) + values[6:]
    return (scales.length, scales.orbit, scales.spin, scales.force) + values


def _compiled_terms(unknowns, nut_shift, contacts: BallContacts, scales: Scales, oversize) -> BallTerms | None:
    """:func:`ball_terms` by the compiled kernel, or None (no kernels, a calibrated contact law, or an evaluation
    the kernel hands back: a contact at rest or a slip outside the float range; the numpy code runs)."""
    if contacts.bulk_compliance is not None:
        return None
    compiled = kernels.load(KERNELS)
    if compiled is None:
        return None
    return _run_kernel(compiled, unknowns, nut_shift, contacts, scales, oversize)


def _run_kernel(compiled, unknowns, nut_shift, contacts, scales, oversize):
    module = contacts.module
    n = unknowns.shape[0]
    data = contacts.kernel_geometry
    scalars = np.array(kernel_scalars(scales, module, oversize))
    shift = np.array(np.broadcast_to(np.asarray(nut_shift, dtype=float), (n,)))   # writable always: one kernel type
    outputs = kernel_outputs(n)
    status = compiled.ball_terms(np.ascontiguousarray(unknowns, dtype=float), shift, data, scalars,
                                 *kernel_tables(), *outputs)
    if status != compiled.CONVERGED:
        return None
    return terms_of_kernel(outputs)


def kernel_outputs(n: int) -> tuple:
    """The output arrays of :func:`lowmodel.screw.ball_kernels.ball_terms` for ``n`` balls (residual, Jacobian,
    axial, its gradient, contact fields, nut input power)."""
    return (np.empty((n, 6)), np.empty((n, 6, N_UNKNOWNS + 1)), np.empty(n), np.empty((n, N_UNKNOWNS + 1)),
            np.empty((n, 4, 15)), np.empty(n))


def terms_of_kernel(outputs: tuple) -> BallTerms:
    """:class:`BallTerms` of the kernel's :func:`kernel_outputs` (views, no copy)."""
    residual, jacobian, axial, axial_gradient, contact, power = outputs
    return BallTerms(residual, jacobian, axial, axial_gradient, contact[..., 0], contact[..., 1:3], contact[..., 3],
                     contact[..., 4], contact[..., 5], contact[..., 6], contact[..., 7], contact[..., 8:11],
                     contact[..., 11:14], contact[..., 14], power)


def warm_up_kernel(compiled) -> None:
    """Compile (or load from the cache) :mod:`lowmodel.screw.ball_kernels` for the argument types of
    :func:`ball_terms` (two balls of lin2019 Table 4)."""
    contacts = ball_contacts(screw_module(), np.zeros(2))
    scales = scales_for(contacts, 100.0)
    _run_kernel(compiled, np.zeros((2, N_UNKNOWNS)), 0.0, contacts, scales, None)


# --------------------------------------------------------------------------
# solution
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class ScrewBallState(BallStateBase):
    """Quasi-static state of ``n`` balls (leading shape (n,); contacts (SL, SR, NR, NL)); the power, B2B and loss
    fields of :class:`lowmodel.state.BallStateBase`:

    centre : (n, 2) m, ball centre ``(x_B3, z_B3)`` from the nominal helix
    orbit_speed : (n,) rad/s, ``omega_B``; omega : (n, 3) rad/s, spin relative to CS3
    nut_shift : m, axial shift of the nut relative to the screw (scalar, or (n,) per ball)
    normal_force : (n, 4) N; contact_angle : (n, 4) rad (actual); approach : (n, 4) m
    semi_major : (n, 4) m; spin : (n, 4) rad/s about the inward normal; slip_minor, slip_major : (n, 4) m/s
    friction_force : (n, 4, 3) N; friction_moment : (n, 4, 3) N m (CS3, on the ball)
    axial_load : N, force of the screw on the balls along +z
    friction_loss : (n, 4) W; input_power : W (by the nut); b2b_force, b2b_friction_loss, b2b_slip : (pairs,) N, W,
    m/s; iterations; residual (max scaled residual)
    """

    centre: np.ndarray
    orbit_speed: np.ndarray
    omega: np.ndarray
    nut_shift: float
    normal_force: np.ndarray
    contact_angle: np.ndarray
    approach: np.ndarray
    semi_major: np.ndarray
    spin: np.ndarray
    slip_minor: np.ndarray
    slip_major: np.ndarray
    friction_force: np.ndarray
    friction_moment: np.ndarray
    axial_load: float


def _contact_angles(direction: np.ndarray) -> np.ndarray:
    return np.arctan2(SIGN_W * direction[..., 1], SIGN_U * direction[..., 0])


def free_rolling_guess(contacts: BallContacts) -> np.ndarray:
    """Orbit and spin (n, 4) [rad/s] with least-squares zero slip at the four nominal contact centres (read-only;
    computed once per ``contacts``, :attr:`BallContacts.solver_memo`)."""
    memo = contacts.solver_memo
    if "free_rolling" not in memo:
        memo["free_rolling"] = checks.read_only(_free_rolling(contacts))
    return memo["free_rolling"]


def _free_rolling(contacts: BallContacts) -> np.ndarray:
    module = contacts.module
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    guess = np.empty((contacts.n_balls, 4))
    radius, helix_radius, nut_speed = module.ball_radius, module.helix_radius, module.nut_speed
    for j in range(contacts.n_balls):
        rows, rhs = np.zeros((12, 4)), np.empty(12)
        for i in range(4):
            beta = float(contacts.contact_angles[j, i])
            qx, qz = radius * (SIGN_U[i] * math.cos(beta)), radius * (SIGN_W[i] * math.sin(beta))   # q = R_B e
            helical = (s * qz, helix_radius + c * qx, -s * qx)
            # slip = (omega_B - Omega) H + omega x q; omega x q = -[q]x omega (q_y = 0)
            block = rows[3 * i:3 * i + 3]
            block[:, 0] = helical
            block[0, 2], block[1, 1], block[1, 3], block[2, 2] = qz, -qz, qx, -qx
            block[0, 1] = block[1, 2] = block[0, 3] = block[2, 3] = -0.0   # -[q]x entry by entry, signed zeros too
            rhs[3 * i:3 * i + 3] = helical
            rhs[3 * i:3 * i + 3] *= nut_speed * ON_NUT[i]
        guess[j] = np.linalg.lstsq(rows, rhs, rcond=None)[0]
    return guess


def solve(contacts: BallContacts, axial_load: float, *, tolerance: float = 1e-10,
                max_iterations: int = 80) -> ScrewBallState:
    """Each ball on its own (no ball-to-ball contact) under ``axial_load`` [N] per ball (lin2019 eqs 49-55).

    ``axial_load``: force of the screw on each ball along +z [N], one number (its sign picks the
    loaded diagonal); the nut shift is solved for it, ball by ball: ``nut_shift`` of the result is
    (n,), one per ball (a float for one ball).  ``tolerance``:
    max residual of eq 54 in units of ``mu F_ref`` (F_ref = |axial_load| / (sin beta_0 cos alpha) / 2
    for the loaded pair, forces and moments / R_B) and of the axial balance.
    Raises ConvergenceError with its residual if Newton fails.
    """
    check_solver_options(tolerance, max_iterations)
    load = checks.scalar("axial_load", axial_load, "N", note="the load on each ball")
    states = [_solve_one(contacts, j, load, tolerance, max_iterations) for j in range(contacts.n_balls)]
    return _stack(states)


MEMO_SIZE = 64  # loads (or load and gap patterns) remembered per BallContacts (BallContacts.solver_memo)


def reference_force(contacts: BallContacts, axial_load: float) -> float:
    """Normal force scale [N]: the axial load over one loaded pair, at least the preload force (remembered per
    ``contacts`` and load, :attr:`BallContacts.solver_memo`)."""
    load = checks.scalar("axial_load", axial_load, "N")
    forces = contacts.solver_memo.setdefault("reference_force", {})
    if load not in forces:
        if len(forces) >= MEMO_SIZE:
            forces.clear()
        forces[load] = _reference_force(contacts, load, axial_load)
    return forces[load]


def _reference_force(contacts: BallContacts, load: float, axial_load) -> float:
    module = contacts.module
    with np.errstate(over="ignore"):
        pair = abs(load) / np.float64(math.sin(module.nominal_angle) * math.cos(module.lead_angle))
    preload = (module.oversize / float(np.min(contacts.hertz_constant))) ** 1.5 if module.oversize > 0 else 0.0
    force = checks.finite_result("axial_load", max(pair, preload, 1e-3), "N")
    with np.errstate(over="ignore"):
        approach = float(float(np.max(contacts.hertz_constant)) * np.float64(force) ** (2.0 / 3.0))  # lin2019 eq 53
    if not approach < module.ball_radius:
        raise ValueError(f"axial_load: its Hertz approach {approach!r} m (per loaded pair, {float(force)!r} N) "
                         f"exceeds the ball radius {module.ball_radius!r} m: no Hertz contact at this load, "
                         f"got {axial_load!r} N")
    return force


def _solve_one(contacts: BallContacts, index: int, axial_load: float, tolerance: float, max_iterations: int):
    """One ball with its own nut shift (:func:`solve_preloaded`)."""
    single = contacts.ball(index)
    scales = scales_for(single, reference_force(single, axial_load))
    guess = np.zeros(N_UNKNOWNS + 1)
    rates = free_rolling_guess(single)[0]
    guess[2] = rates[0] / scales.orbit
    guess[3:6] = rates[1:] / scales.spin
    target = axial_load / scales.force

    def make_function(oversize):
        def function(z):
            terms = ball_terms(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], single, scales, oversize=oversize)
            residual = np.concatenate([terms.residual[0], [terms.axial[0] - target]])
            jacobian = np.vstack([terms.jacobian[0], terms.axial_gradient[0][None, :]])
            return residual, jacobian
        return function

    rows = row_tolerances(tolerance, friction_coefficient=single.module.friction_coefficient,
                          groove_radius=single.module.groove_radius, ball_radius=single.module.ball_radius,
                          approach=scales.length, balls=1, axial=1)
    z, residual, iterations = solve_preloaded(
        make_function, guess, single, axial_load, tolerance=tolerance, max_iterations=max_iterations,
        what=f"screw ball {index}", row_tolerance=rows,
        row_weight=row_weights(friction_coefficient=single.module.friction_coefficient, balls=1, axial=1),
        contacts_at=lambda z, oversize: ball_terms(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], single, scales,
                                                   oversize=oversize))
    terms = ball_terms(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], single, scales)
    return z, terms, scales, iterations, float(np.max(np.abs(residual))), axial_load


def continuation_start(contacts: BallContacts, axial_load: float) -> float:
    """Oversize [m] where the preload continuation starts: twice the approach of the reference force,
    so that all four contacts stay loaded (well-conditioned four-point state); remembered per ``contacts`` and
    load like :func:`reference_force`."""
    load = checks.scalar("axial_load", axial_load, "N")
    starts = contacts.solver_memo.setdefault("continuation_start", {})
    if load not in starts:
        if len(starts) >= MEMO_SIZE:
            starts.clear()
        starts[load] = _continuation_start(contacts, axial_load)
    return starts[load]


def _continuation_start(contacts: BallContacts, axial_load: float) -> float:
    with np.errstate(over="ignore"):
        start = 2.0 * float(np.max(contacts.hertz_constant)) * np.float64(reference_force(contacts, axial_load)) ** (
            2.0 / 3.0)
    return checks.finite_result("axial_load", start, "m")


def solve_preloaded(make_function, guess: np.ndarray, contacts: BallContacts, load_per_ball: float, *,
                    tolerance: float, max_iterations: int, what: str, steps: int = 6, max_halvings: int = 10,
                    step_iterations: int = 15, direct_fraction: float = 0.2, direct_iterations: int = 12,
                    row_tolerance=None, row_weight=None, contacts_at=None, solver=None):
    """Newton (:func:`lowmodel.solvers.newton`) on ``make_function(oversize)`` at the module's preload.

    Between ``direct_fraction`` and half of :func:`continuation_start` Newton is tried
    directly for ``direct_iterations``.  Below (little or no preload: two- and three-point
    contact, where Newton from free rolling wanders) or if that fails, the solve starts at that
    four-point preload and steps the oversize down to the module's value, each step
    from the previous solution (step grown 1.5x after a success, halved after a failure).
    ``row_tolerance``, ``row_weight``: per-row tolerances and step weights for :func:`lowmodel.solvers.newton`
    (:func:`.convergence.row_tolerances`, :func:`.convergence.row_weights`);
    ``contacts_at(z, oversize)``: the :class:`BallTerms` (or any object with ``normal_force``, ``slip_minor``,
    ``spin``, ``semi_major``) at a converged point, from which a stall's reason is read
    (:func:`.convergence.stall_reason`); ``solver``: a replacement of :func:`lowmodel.solvers.newton` with its
    signature (the compiled solver of :mod:`lowmodel.screw.b2b`), default that function.  Returns
    ``(z, residual, iterations)``; ConvergenceError if a step keeps failing.
    """
    newton_solve = partial(solver or newton, row_tolerance=row_tolerance, row_weight=row_weight)

    target = contacts.module.oversize
    start = continuation_start(contacts, load_per_ball)
    if target >= 0.5 * start:
        return newton_solve(make_function(target), guess, tolerance=tolerance, max_iterations=max_iterations,
                            what=what)
    if target >= direct_fraction * start:   # some preload: try Newton directly, briefly
        try:
            return newton_solve(make_function(target), guess, tolerance=tolerance,
                                max_iterations=min(direct_iterations, max_iterations), what=what)
        except ConvergenceError:
            pass
    z, residual, total = newton_solve(make_function(start), guess, tolerance=tolerance,
                                      max_iterations=max_iterations, what=what)
    current, step, halvings = start, (start - target) / steps, 0
    while current > target:
        trial = max(target, current - step)
        try:
            z_new, residual, iterations = newton_solve(make_function(trial), z, tolerance=tolerance,
                                                       max_iterations=min(step_iterations, max_iterations),
                                                       what=what)
        except ConvergenceError as error:
            halvings += 1
            if halvings > max_halvings:
                reason, detail = "preload continuation stalled", ""
                if contacts_at is not None:
                    terms = contacts_at(z, current)
                    reason, detail = stall_reason(terms.normal_force, terms.slip_minor, terms.spin, terms.semi_major,
                                                  where=f"(oversize {current:.3e} m)")
                    detail = f": {reason}: {detail}"
                raise ConvergenceError(f"{what}: preload continuation stalled at oversize {current:.3e} m "
                                       f"(target {target:.3e} m){detail}", residual=error.residual,
                                       iterations=total, tolerance=tolerance, reason=reason) from None
            step *= 0.5
            continue
        z, current = z_new, trial
        total += iterations
        step *= 1.5
    return z, residual, total


def state_from(z_balls: np.ndarray, shift: float, terms: BallTerms, scales: Scales, *, axial_load: float,
               b2b_force=None, b2b_loss=None, b2b_slip=None, iterations: int, residual: float) -> ScrewBallState:
    """ScrewBallState from scaled unknowns (n, 6), the scaled nut shift and the terms at that point; the B2B
    force [N], loss [W] and slip [m/s] of the pairs default to zeros (n - 1,)."""
    n = z_balls.shape[0]
    if b2b_force is None:
        b2b_force, b2b_loss, b2b_slip = (np.zeros(max(n - 1, 0)) for _ in range(3))
    shift = np.asarray(shift, dtype=float) * scales.length
    return ScrewBallState(z_balls[:, :2] * scales.length, z_balls[:, 2] * scales.orbit, z_balls[:, 3:6] * scales.spin,
                          float(shift) if shift.ndim == 0 else shift, terms.normal_force,
                          _contact_angles(terms.contact_direction),
                          terms.approach, terms.semi_major, terms.spin, terms.slip_minor, terms.slip_major,
                          terms.friction_force, terms.friction_moment, axial_load, friction_loss=terms.friction_loss,
                          input_power=float(terms.input_power.sum()), b2b_force=np.asarray(b2b_force, dtype=float),
                          b2b_friction_loss=np.asarray(b2b_loss, dtype=float),
                          b2b_slip=np.asarray(b2b_slip, dtype=float), iterations=iterations, residual=residual)


def _stack(states) -> ScrewBallState:
    """Join single-ball solutions (each with its own nut shift: ``nut_shift`` (n,)) into one state."""
    if len(states) == 1:
        z, terms, scales, iterations, residual, load = states[0]
        return state_from(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], terms, scales, axial_load=load,
                          iterations=iterations, residual=residual)
    parts = [state_from(z[None, :N_UNKNOWNS], z[N_UNKNOWNS], t, sc, axial_load=ld, iterations=it, residual=r)
             for z, t, sc, it, r, ld in states]

    def cat(name):
        return np.concatenate([getattr(p, name) for p in parts])

    n = len(parts)
    return ScrewBallState(cat("centre"), cat("orbit_speed"), cat("omega"),
                          np.array([p.nut_shift for p in parts]), cat("normal_force"), cat("contact_angle"),
                          cat("approach"), cat("semi_major"), cat("spin"), cat("slip_minor"), cat("slip_major"),
                          cat("friction_force"), cat("friction_moment"), float(sum(p.axial_load for p in parts)),
                          friction_loss=cat("friction_loss"), input_power=float(sum(p.input_power for p in parts)),
                          b2b_force=np.zeros(n - 1), b2b_friction_loss=np.zeros(n - 1), b2b_slip=np.zeros(n - 1),
                          iterations=max(p.iterations for p in parts), residual=max(p.residual for p in parts))
