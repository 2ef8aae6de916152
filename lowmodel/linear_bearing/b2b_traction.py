"""FE-informed ball-to-ball (B2B) model: lin2019 eqs 4-10 with sampled contact tractions.

The low-order model of :mod:`lowmodel.linear_bearing.b2b` integrates Coulomb
friction over a planar Hertz ellipse at a rigid contact angle (lin2019 eqs
A4-A7).  Here each ball-to-groove contact is instead given as *sampled points*
of the (curved) contact surface, each with the normal force it carries (an FE
pressure times its quadrature area, or samples of Hertz's ellipse in tests):

    point r_k [m] relative to the ball centre (lin2019 Fig 2 frame: x right, y up, z along the raceway),
    unit normal N_k of the contact surface at r_k (outward from the ball),
    normal force F_k >= 0 [N] (traction x area).

(:class:`~lowmodel.contact.traction.TractionPatch`; the pointwise friction below is
:class:`~lowmodel.contact.traction.SampledCoulomb`, shared with the ball screw's
:mod:`lowmodel.screw.b2b_traction`.)

Full-slip Coulomb friction at every point, opposite to the rigid-body slip of
the ball against its groove projected on the tangent plane of the contact
surface (lin2019 eqs 1-3 without the contact-plane approximation):

    s_k = (v_B - V_k) e_z + Omega x r_k,     Omega = (omega_x, omega_y, 0),  V_k = 0 (bottom) or v (top)
    f_k = -mu F_k P_k s_k / |P_k s_k|,       P_k = I - N_k N_k^T

On a planar patch at ``R_B n_i`` this is exactly lin2019 eq 3 (the in-plane
part of ``Omega`` gives the slide ``omega_i c_i``, its normal part the spin
``omega_i = -Omega . n_i``), so Hertz samples on the plane reproduce eqs A4-A5
up to the quadrature (tests/test_b2b_traction.py).

Ball equilibrium and the B2B conditions are those of the low-order model: the
three rows of lin2019 eq 4 (z force, x and y moments about the ball centre),
with the B2B loads of eqs 5-8 and the complementarity of eqs 9-10 from
:func:`lowmodel.linear_bearing.b2b.coupled_system` (the chain of
:mod:`lowmodel.b2b_chain`: one implementation for all B2B models).
Unknowns per ball: ``(v_B, omega_x R_B, omega_y R_B)/|v|``.
The residual of one ball is ``-grad`` of the regularised dissipation
``sum_k mu F_k sqrt(|P_k s_k|^2 + eps^2)``, so its Jacobian is symmetric and
negative semi-definite (a single ball has a unique state); Newton with
Levenberg-Marquardt damping (:func:`lowmodel.solvers.newton`).

Assumptions kept from lin2019's low-order model: full sliding at every point
(no stick zone), Coulomb friction with one ``mu``, ball-to-groove normal loads
decoupled from friction and from the B2B force (the sampled tractions are
given), quasi-static equilibrium in z force and x, y moments only (``omega_z =
0``; friction's x, y forces and z moment are not balanced, as in eq 4), rigid
ball kinematics, B2B contact a point at ``+-R_B e_z`` (eqs 5-8).
Assumptions removed: Hertz's elliptical pressure (any sampled traction field),
the planar contact (points on the real curved surface, slip projected on the
local tangent plane), the rigid contact angle (the patch sits where the loaded
FE contact is).

Power balance (checked in every solve): the input power of the top groove
``v sum_top f_z`` equals the friction loss ``-sum_k f_k . s_k`` plus the B2B
loss ``mu F_B2B |dv|`` (eq 7) at equilibrium, independent of ``eps``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.bearing import guide_values
from ballbench.lowmodel.contact.traction import (SampledCoulomb, TractionPatch, check_patch, ellipse_samples,
                                                 solve_chain, stack_patches)
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_normals
from ballbench.lowmodel.linear_bearing.b2b import b2b_terms, pair_function, touching_pairs
from ballbench.lowmodel.linear_bearing.contacts import BallContacts
from ballbench.lowmodel.solvers import check_solver_options
from ballbench.lowmodel.state import BallStateBase

__all__ = ["TractionPatch", "TractionState", "hertz_patches", "solve", "slip_field", "POWER_BALANCE_TOLERANCE",
           "N_UNKNOWNS"]

POWER_BALANCE_TOLERANCE = 1e-6  # relative: every solve checks it (docs/b2b_traction.md)
N_UNKNOWNS = 3  # per ball: (v_B, omega_x R_B, omega_y R_B)/|v|


@dataclass(frozen=True)
class TractionState(BallStateBase):
    """Quasi-static solution of ``n`` balls (leading shape ``(n,)``; patches in the given order); the power, B2B
    and loss fields of :class:`lowmodel.state.BallStateBase`:

    ball_velocity : (n,) m/s;  omega : (n, 2) rad/s ``(omega_x, omega_y)``
    velocity_deviation : (n,) ``2 v_B / v - 1`` (lin2019 eq 21)
    friction_force : (n, p) N, z friction force of each patch on the ball
    friction_moment : (n, p, 3) N m, friction moment of each patch about the ball centre
    friction_loss : (n, p) W, ``-sum f . s`` of each patch
    input_power : W, ``v sum_top f_z``
    b2b_force, b2b_friction_loss, b2b_slip : (n-1,) N, W, m/s (eqs 5-7)
    power_balance : |input - losses| / input
    iterations, residual : Newton iterations, final max residual / (mu F_ref)
    """

    ball_velocity: np.ndarray
    omega: np.ndarray
    velocity_deviation: np.ndarray
    friction_force: np.ndarray
    friction_moment: np.ndarray
    power_balance: float


class _Samples(SampledCoulomb):
    """All points of all balls, flattened, with their ball and patch indices (units mu F_ref and |v|)."""

    def __init__(self, balls, radius: float, reference_force: float, velocity_sign: float, eps: float):
        self.n_patches = len(balls[0])
        stacked = stack_patches(balls, self.n_patches, reference_force, velocity_sign)
        self.r = stacked.points
        self.patch = stacked.patch
        slip_matrix, groove = slip_field(self.r, radius, stacked.moving)
        super().__init__(stacked.ball, slip_matrix, groove, stacked.normals, stacked.load,
                         len(balls), eps)


def slip_field(points: np.ndarray, radius: float, moving: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The rigid slip of the ball against its groove at ``points`` (k, 3) [m] (relative to the ball centre,
    lin2019 Fig 2 frame), ``s_k = D_k x - g_k`` in units of ``|v|`` (lin2019 eqs 1, A1-A3 as a field):
    ``D`` (k, 3, 3) = d s / d x for the unknowns ``x = (v_B, omega_x R_B, omega_y R_B)/|v|`` (column 0 the ball
    centre's velocity, the carrier of the contact points), ``g`` (k, 3) the groove's velocity ``moving e_z``
    (``moving`` (k,): ``sign(v)`` on the top groove, 0 on the bottom one)."""
    rx, ry, rz = np.asarray(points, dtype=float).T / radius
    zero, one = np.zeros_like(rx), np.ones_like(rx)
    # D[k, :, j] = d s_k / d x_j; also the moment rows (D^T f)
    slip_matrix = np.stack([np.stack([zero, zero, one], 1), np.stack([zero, -rz, ry], 1),
                            np.stack([rz, zero, -rx], 1)], axis=2)
    groove = np.zeros((len(rx), 3))
    groove[:, 2] = moving  # groove velocity along +z (units |v|)
    return slip_matrix, groove


def hertz_patches(contacts: BallContacts, ball: int = 0, *, n_radial: int = 24, n_angular: int = 96,
                  planar: bool = True) -> tuple[TractionPatch, ...]:
    """Samples of the Hertz pressure of the low-order model's contacts of ``ball`` (BL, BR, TR, TL).

    Each ellipse (lin2019 eq A7: ``p = p0 sqrt(1 - x^2/a^2 - z^2/b^2)``, ``a`` in the
    cross-section, ``b`` along z) is sampled by Gauss-Jacobi in ``1 - rho^2`` (weight
    ``sqrt``, exact for the radial pressure profile) times ``n_angular`` equal angles;
    the weights sum to ``F_i`` exactly.  ``planar=True``: points on the tangent plane at
    ``R_B n_i`` with normal ``n_i`` (the low-order model's contact); ``False``: the same
    points projected radially onto the sphere, with the sphere's normal (a curved Hertz patch).
    """
    ball = checks.count("ball", ball, 0, contacts.n_balls - 1)
    u, v, w = ellipse_samples(n_radial, n_angular)  # Gauss-Jacobi, weights sum to 1 (lowmodel.contact.traction)
    radius = contacts.ball_radius
    normals2 = contact_normals(contacts.contact_angles[ball])  # (4, 2)
    patches = []
    for i, name in enumerate(CONTACT_NAMES):
        a = contacts.semi_major[ball, i]
        b = a * contacts.b_over_a[ball, i]
        n = np.array([normals2[i, 0], normals2[i, 1], 0.0])
        e1 = np.array([-n[1], n[0], 0.0])  # in-plane tangent (major axis a)
        xi, zeta = a * u, b * v
        points = radius * n[None, :] + xi[:, None] * e1[None, :] + zeta[:, None] * np.array([0.0, 0.0, 1.0])
        forces = contacts.normal_forces[ball, i] * w
        if planar:
            normals = np.repeat(n[None, :], len(w), axis=0)
        else:
            normals = points / np.linalg.norm(points, axis=1)[:, None]
            points = radius * normals
        patches.append(TractionPatch(points, normals, forces, top=i >= 2, name=name))
    return tuple(patches)


def solve(balls, guide=None, *, ball_radius: float | None = None, friction_coefficient: float | None = None,
          groove_velocity: float | None = None, gaps=None, tolerance: float = 1e-11, max_iterations: int = 100,
          regularisation: float = 1e-12, start=None, name: str = "FE-informed") -> TractionState:
    """Quasi-static motion of ``n >= 1`` balls with sampled contact tractions and B2B contact.

    Parameters
    ----------
    balls : sequence of ``n`` sequences of :class:`TractionPatch` (the same number of patches per ball),
        balls ordered along +z (ball 0 behind, lin2019 "ball 1"); the ball centre is the origin of its points
    guide : a :class:`lowmodel.bearing.LinearGuide` (its ball radius, friction and speed), or these one by one:
    ball_radius : m;  friction_coefficient : mu (> 0, ball-to-groove and ball-to-ball)
    groove_velocity : m/s, velocity of the top groove along +z (nonzero)
    gaps : (n-1,) m, ``d_{j,j+1} - 2 R_B`` (default all touching)
    tolerance : max residual of eq 4 in units of ``mu F_ref`` (F_ref the largest patch force) and of eqs 9-10
    regularisation : eps, slip floor in units of ``|v|`` in ``s / sqrt(|s|^2 + eps^2)``
    start : a state of the same balls and gaps (``ball_velocity`` (n,) m/s, ``omega`` (n, 2) rad/s, ``b2b_force``
        (n-1,) N; e.g. :func:`lowmodel.linear_bearing.b2b.solve`'s) the chain starts from (default: from every
        ball solved on its own, without B2B force)
    name : the model in the messages of ConvergenceError ("FE-informed"; "full slip on the stick/slip cells" where
        the patches are the cells of :mod:`lowmodel.linear_bearing.b2b_rolling`)

    Raises ValueError for bad input, ConvergenceError (with its residual) if Newton fails or if the power
    balance misses POWER_BALANCE_TOLERANCE.
    """
    check_solver_options(tolerance, max_iterations)
    ball_radius, friction_coefficient, groove_velocity = guide_values(guide, dict(
        ball_radius=ball_radius, friction_coefficient=friction_coefficient, groove_velocity=groove_velocity)).values()
    radius = float(ball_radius)
    if not math.isfinite(radius) or radius <= 0.0 or not math.isfinite(1.0 / radius):
        raise ValueError(f"ball_radius must be a finite number > 0 m with a finite inverse, got {ball_radius!r}")
    mu = float(friction_coefficient)
    if not math.isfinite(mu) or mu <= 0.0:
        raise ValueError(f"friction_coefficient must be a finite number > 0, got {friction_coefficient!r}")
    velocity = float(groove_velocity)
    if not math.isfinite(velocity) or velocity == 0.0:
        raise ValueError(f"groove_velocity must be finite and nonzero m/s, got {groove_velocity!r}")
    eps = float(regularisation)
    if not math.isfinite(eps) or not 0.0 < eps <= 1e-6:
        raise ValueError(f"regularisation must lie in (0, 1e-6], got {regularisation!r}")
    balls = [[check_patch(patch, i) for i, patch in enumerate(patches)] for patches in balls]
    n = len(balls)
    if n < 1 or len({len(p) for p in balls}) != 1 or len(balls[0]) < 1:
        raise ValueError("balls must hold n >= 1 balls with the same number (>= 1) of patches each")
    touching = touching_pairs(gaps, n, radius)
    reference_force = max(p.normal_force for patches in balls for p in patches)  # F_ref [N]
    sign = math.copysign(1.0, velocity)
    samples = _Samples(balls, radius, reference_force, sign, eps)
    guess = _initial_guess(balls, sign)

    chain_start = None
    if start is not None and touching.size:
        speed = abs(velocity)
        chain_start = (np.column_stack([np.asarray(start.ball_velocity, dtype=float) / speed,
                                        np.asarray(start.omega, dtype=float) * radius / speed]),
                       np.asarray(start.b2b_force, dtype=float) / (mu * reference_force))
    states, forces, iterations, residual_norm = solve_chain(
        samples, guess, touching, lambda layout: pair_function(layout, mu), complementarity="min",
        tolerance=tolerance, max_iterations=max_iterations, what_ball=f"{name} ball",
        what_chain=f"{name} {n}-ball B2B contact" + ("" if chain_start is None else " from the given start"),
        start=chain_start)
    return _state(samples, states, forces, balls, radius, mu, velocity, reference_force, iterations,
                  residual_norm, name)


def _initial_guess(balls, sign: float) -> np.ndarray:
    """Rolling about x at v_B = v/2 (the theta = 0 state of lin2019), from the patch centres."""
    guess = np.zeros((len(balls), N_UNKNOWNS))
    for b, patches in enumerate(balls):
        cos = [abs(p.centre[1]) / np.linalg.norm(p.centre[:2]) for p in patches]
        guess[b] = (0.5 * sign, 0.5 * sign / float(np.mean(cos)), 0.0)
    return guess


def _state(samples: _Samples, states, forces, balls, radius, mu, velocity, reference_force, iterations,
           residual_norm, name: str = "FE-informed") -> TractionState:
    speed = abs(velocity)
    n, p = samples.n_balls, samples.n_patches
    _, _, slip, force = samples.evaluate(states, jacobian=False)
    force_n = force * mu * reference_force  # N
    slip_ms = slip * speed  # m/s
    friction_force = np.bincount(samples.patch, force_n[:, 2], minlength=n * p).reshape(n, p)
    moment_k = np.cross(samples.r, force_n)
    friction_moment = np.stack([np.bincount(samples.patch, moment_k[:, c], minlength=n * p) for c in range(3)],
                               axis=1).reshape(n, p, 3)
    loss = np.bincount(samples.patch, -np.einsum("ki,ki->k", force_n, slip_ms), minlength=n * p).reshape(n, p)
    top = np.array([[patch.top for patch in patches] for patches in balls])
    input_power = float(velocity * friction_force[top].sum())
    b2b_slip = b2b_terms(states, forces, mu)[3] * speed
    b2b_force = forces * mu * reference_force
    b2b_loss = mu * b2b_force * b2b_slip  # lin2019 eq 7
    losses = float(loss.sum() + b2b_loss.sum())
    balance = abs(input_power - losses) / max(abs(input_power), 1e-300)
    if not balance <= POWER_BALANCE_TOLERANCE:
        raise ConvergenceError(f"{name} B2B: power balance missed", residual=balance, iterations=iterations,
                               tolerance=POWER_BALANCE_TOLERANCE, reason="power balance missed")
    ball_velocity = states[:, 0] * speed
    return TractionState(ball_velocity, states[:, 1:3] * speed / radius, 2.0 * ball_velocity / velocity - 1.0,
                         friction_force, friction_moment, balance, friction_loss=loss, input_power=input_power,
                         b2b_force=b2b_force, b2b_friction_loss=b2b_loss, b2b_slip=b2b_slip, iterations=iterations,
                         residual=residual_norm)
