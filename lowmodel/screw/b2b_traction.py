"""FE-informed ball-to-ball (B2B) model of the ball screw: lin2019 eqs 54-61 with sampled contact tractions.

The low-order model (:mod:`lowmodel.screw.ball`, :mod:`lowmodel.screw.b2b`)
integrates Coulomb friction over a planar Hertz ellipse in each contact plane (lin2019
eqs 44-47, A9-A11).  Here each ball-to-groove contact is given as *sampled points* of
the (curved) contact surface (:class:`lowmodel.contact.traction.TractionPatch`):

    points r_k [m], relative to the ball centre, in the ball's CS3 (lin2019 eq 41, :func:`helix.cs3_frame`:
        x3 radial from the screw axis through the nominal ball centre, y3 the helix tangent
        (direction of increasing azimuth), z3 = x3 x y3; the screw axis is z_hat = (0, sin alpha, cos alpha)),
    unit normals N_k of the contact surface, outward from the ball (into the groove),
    normal forces F_k >= 0 [N] (FE traction x quadrature area, or Hertz samples),
    ``top`` = True for the nut's flanks (NR, NL), False for the screw's (SL, SR).

Slip of the ball against its groove at every point, from the rigid-body motions: screw
(at rest), nut (``omega_N``) and ball centre all move with the helical field
``H(r) = z_hat x r + p z_hat`` (lin2019 eqs 34-36, 43), so the slip is

    s_k = (omega_B - Omega_k) H(r_k) + omega x r_k,   Omega_k = 0 (screw) or omega_N (nut)
    H(r) = (s r_z - c r_y, L/(2 pi) + c r_x, -s r_x)  in CS3   (s, c = sin, cos alpha; L of eq 45)

with ``omega_B`` the orbit speed and ``omega`` the spin relative to CS3 (the unknowns of
eq 55 without the ball centre: 4 per ball).  ``H`` is taken at the nominal ball centre
plus ``r_k`` (as the low-order model does; the ball centre's micrometre offset is left
out).  On a plane at ``R_B e_i`` this is exactly eq 47 and A9-A11 (the field of
:func:`ball.ball_terms`).  Full-slip Coulomb friction on the local tangent plane
(:class:`lowmodel.contact.traction.SampledCoulomb`):

    f_k = -mu F_k P_k s_k / |P_k s_k|,   P_k = I - N_k N_k^T

Equilibrium of each ball: the generalised forces conjugate to ``(omega_B, omega)``,
``sum_k f_k . H(r_k)`` and ``sum_k r_k x f_k`` (plus the B2B loads), i.e. the force
along ``y3`` and the three moments of eq 54 (``F . H(c_0) + z_hat . M = (L/2 pi) F_y3
+ z_hat . M``).  The B2B loads are those of the low-order model (eqs 56-59,
:func:`b2b.b2b_loads` with the exact helix chord of :func:`b2b.pair_geometry`)
and so is the complementarity (eqs 60-61, the Fischer-Burmeister function of ``F / (mu F_ref)`` and
``10 (omega_B,j+1 - omega_B,j) / |omega_N|`` in the chain of :mod:`lowmodel.b2b_chain`).
Newton with Levenberg-Marquardt damping (:func:`lowmodel.solvers.newton`): each ball alone
first (its residual is minus the gradient of a convex dissipation, so its state is unique),
then the coupled system.

Assumptions kept from lin2019's low-order model: full sliding at every point (no stick
zone), one Coulomb ``mu``; ball-to-groove normal loads decoupled from friction and from
the B2B force (the sampled tractions are given: the x3, z3 components of friction and of
the B2B force are carried by the given normal loads, not re-balanced; the low-order model
moves the ball centre for them: in Table 5's cases the B2B force changes the
normal forces by up to 0.26 N, 1.7 % of the light SR contact, and the free-state loads move
F_B2B by +0.05 %, docs/b2b_traction.md);
quasi-static; rigid ball kinematics; the B2B contact a point on the exact helix chord.
Assumptions removed: Hertz's elliptical pressure (any sampled traction field), the planar
contact (points on the real curved surface, slip projected on the local tangent plane),
the rigid contact angle (the patches sit where the loaded contact is).

Power balance (checked in every solve): the nut puts in ``P_in = omega_N sum_nut f_k . H(r_k)``
(normal forces do no work: ``H`` is tangent to the helical flanks), which equals the
friction loss ``-sum_k f_k . s_k`` plus the B2B loss ``mu F_B2B |s|`` (eq 58) at
equilibrium, independent of the slip regularisation.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.b2b_chain import ChainLayout, PairBlocks
from ballbench.lowmodel.contact.traction import (SampledCoulomb, TractionPatch, check_patch, ellipse_samples,
                                                 solve_chain, stack_patches)
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.screw import b2b
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.solvers import check_solver_options
from ballbench.lowmodel.state import BallStateBase
from ballbench.lowmodel.state import friction_increase

__all__ = ["ScrewTractionState", "ModuleB2B", "hertz_patches", "solve", "module_b2b", "slip_field", "pair_function",
           "POWER_BALANCE_TOLERANCE", "N_UNKNOWNS", "RADIUS_TOLERANCE"]

POWER_BALANCE_TOLERANCE = 1e-6  # relative: every solve checks it (docs/b2b_traction.md)
N_UNKNOWNS = 4  # per ball: omega_B / |omega_N|, (omega_x, omega_y, omega_z) R_B / (|omega_N| L / 2 pi)
RADIUS_TOLERANCE = 0.05  # sample points must lie within 5 % of R_B from the ball centre (frame and unit check)


@dataclass(frozen=True)
class ScrewTractionState(BallStateBase):
    """Quasi-static solution of ``n`` balls (leading shape ``(n,)``; ``p`` the most patches of a ball); the power,
    B2B and loss fields of :class:`lowmodel.state.BallStateBase`:

    orbit_speed : (n,) rad/s ``omega_B``;  omega : (n, 3) rad/s, spin relative to CS3
    names : (n, p) the patch names ("" where a ball has fewer patches; their entries are 0)
    normal_force : (n, p) N, sum of each patch's forces;  contact_angle : (n, p) rad, of the patch's
        force-weighted centre, from -x3 (screw) or +x3 (nut) in the x3-z3 plane (lin2019 eq 37)
    friction_force : (n, p, 3) N, CS3;  friction_moment : (n, p, 3) N m about the ball centre
    friction_loss : (n, p) W, ``-sum f . s`` of each patch
    axial_force : (n,) N, force of the screw's patches on each ball along ``z_hat`` (normal + friction)
    input_power : W, put in by the nut;  b2b_force, b2b_friction_loss, b2b_slip : (n-1,) N, W, m/s
    power_balance : |input - losses| / input;  iterations; residual (max, units of mu F_ref)
    """

    orbit_speed: np.ndarray
    omega: np.ndarray
    names: tuple
    normal_force: np.ndarray
    contact_angle: np.ndarray
    friction_force: np.ndarray
    friction_moment: np.ndarray
    axial_force: np.ndarray
    power_balance: float


def hertz_patches(state: sb.ScrewBallState, contacts: screw_contacts.BallContacts, ball: int = 0, *, n_radial: int = 24,
                  n_angular: int = 96, planar: bool = True) -> tuple[TractionPatch, ...]:
    """Samples of the Hertz pressure of the low-order model's loaded contacts of ``ball`` (SL, SR, NR, NL).

    From the low-order ``state`` (:func:`b2b.solve` or :func:`ball.solve` on
    ``contacts``): each loaded contact's ellipse at the loaded contact angle, in the contact plane at
    ``R_B e_i`` (lin2019 eq 37), semi-axis ``a_i`` across the groove along ``n_i x y3`` and
    ``b_i = a_i (b/a)_i`` along ``y3`` (Sec 3.1: minor axis along the helix), Hertz's pressure
    sampled by :func:`lowmodel.contact.traction.ellipse_samples` (forces sum to ``F_i``).
    ``planar=True``: points on that plane with normal ``e_i`` (the low-order model's contact);
    ``False``: projected radially onto the sphere, with the sphere's normal (a curved Hertz patch).
    Unloaded contacts are left out.
    """
    ball = checks.count("ball", ball, 0, contacts.n_balls - 1)
    if state.normal_force.shape != contacts.contact_angles.shape:
        raise ValueError(f"state must be a solution of contacts: normal_force of shape {state.normal_force.shape}, "
                         f"contacts of {contacts.n_balls} balls")
    u, v, w = ellipse_samples(n_radial, n_angular)
    radius = contacts.module.ball_radius
    patches = []
    for i, name in enumerate(screw_contacts.CONTACT_NAMES):
        force = float(state.normal_force[ball, i])
        if force <= 0.0:
            continue
        beta = float(state.contact_angle[ball, i])
        sign_u, sign_w = (-1.0 if i < 2 else 1.0), (-1.0 if i in (0, 3) else 1.0)  # eq 37: SL, SR, NR, NL
        e = np.array([sign_u * math.cos(beta), 0.0, sign_w * math.sin(beta)])  # ball centre -> contact
        major = np.array([-e[2], 0.0, e[0]])  # n_i x y3 with n_i = -e_i (ball.ball_terms)
        a = float(state.semi_major[ball, i])
        b = a * float(contacts.b_over_a[ball, i])
        points = radius * e[None, :] + (a * u)[:, None] * major[None, :] + (b * v)[:, None] * np.array([0.0, 1.0, 0.0])
        if planar:
            normals = np.repeat(e[None, :], len(w), axis=0)
        else:
            normals = points / np.linalg.norm(points, axis=1)[:, None]
            points = radius * normals
        patches.append(TractionPatch(points, normals, force * w, top=i >= 2, name=name))
    return tuple(patches)


def _check_screw_patch(patch: TractionPatch, index: int, radius: float) -> TractionPatch:
    patch = check_patch(patch, index)
    name = patch.name or f"patch {index}"
    distance = np.linalg.norm(patch.points, axis=1)
    if np.any(np.abs(distance / radius - 1.0) > RADIUS_TOLERANCE):
        raise ValueError(f"{name}: points must lie within {100 * RADIUS_TOLERANCE:g} % of ball_radius "
                         f"({radius!r} m) from the ball centre (m, ball-centre origin, CS3), got |r| in "
                         f"[{distance.min()!r}, {distance.max()!r}] m")
    if np.any(np.einsum("ki,ki->k", patch.points, patch.normals) <= 0.0):
        raise ValueError(f"{name}: normals must point out of the ball (N . r > 0 at every point)")
    return patch


class _Samples(SampledCoulomb):
    """All points of all balls; slips in units ``|omega_N| L / 2 pi``, forces in units ``mu F_ref``."""

    def __init__(self, balls, module: screw_contacts.ScrewModule, reference_force: float, eps: float):
        self.n_patches = max(len(p) for p in balls)
        sign = math.copysign(1.0, module.nut_speed)
        stacked = stack_patches(balls, self.n_patches, reference_force, sign)
        self.r = stacked.points
        self.patch = stacked.patch
        slip_matrix, groove = slip_field(self.r, module, stacked.moving)
        self.helical = slip_matrix[:, :, 0]
        self.on_nut = stacked.moving
        super().__init__(stacked.ball, slip_matrix, groove, stacked.normals, stacked.load, len(balls), eps)


def slip_field(points: np.ndarray, module: screw_contacts.ScrewModule, moving: np.ndarray):
    """The rigid slip of the ball against its groove at ``points`` (k, 3) [m] (relative to the ball centre, in its
    CS3), ``s_k = D_k x - g_k`` in units of ``|omega_N| L / 2 pi`` (lin2019 eqs 36, 43-47 as a field, module
    docstring): ``D`` (k, 3, 4) = d s / d x for the unknowns ``x`` of :data:`N_UNKNOWNS` (column 0 the helical
    field ``H`` of the orbit, the carrier of the contact points; then ``e_j x r / R_B`` for the spin), ``g`` (k, 3)
    the groove's velocity ``moving H`` (``moving`` (k,): ``sign(omega_N)`` on the nut, 0 on the screw)."""
    radius, ell = module.ball_radius, module.helix_radius
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    rx, ry, rz = np.asarray(points, dtype=float).T
    # helical field at the nominal ball centre + r, in units of L / 2 pi (lin2019 eqs 36, 43)
    helical = np.stack([s * rz - c * ry, ell + c * rx, -s * rx], axis=1) / ell
    x, y, z = np.asarray(points, dtype=float).T / radius
    zero = np.zeros_like(x)
    # D[k, :, j] = d s_k / d x_j: orbit (H), then e_j x (r / R_B) for the spin (omega x r)
    slip_matrix = np.stack([helical, np.stack([zero, -z, y], 1), np.stack([z, zero, -x], 1),
                            np.stack([-y, x, zero], 1)], axis=2)
    return slip_matrix, np.asarray(moving, dtype=float)[:, None] * helical


def _b2b_rows(module: screw_contacts.ScrewModule) -> np.ndarray:
    """(4, 6): generalised forces (orbit / (L/2pi), moments / R_B) of a load (force, moment about the centre)."""
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    ell, radius = module.helix_radius, module.ball_radius
    rows = np.zeros((4, 6))
    rows[0, 1] = 1.0                       # F . H(c_0) / (L / 2 pi) = F_y3
    rows[0, 4:6] = (s / ell, c / ell)      # z_hat . M / (L / 2 pi)
    rows[1:, 3:] = np.eye(3) / radius
    return rows


def solve(balls, module: screw_contacts.ScrewModule, *, gaps=None, with_b2b: bool = True, tolerance: float = 1e-11,
          max_iterations: int = 100, regularisation: float = 1e-12, name: str = "FE-informed") -> ScrewTractionState:
    """Quasi-static motion of ``n >= 1`` balls of a ball screw with sampled contact tractions and B2B contact.

    Parameters
    ----------
    balls : sequence of ``n`` sequences of :class:`TractionPatch` (each ball's contacts, points relative to
        its centre in its own CS3, module docstring; ``top`` = nut), balls ordered along the orbit
        (ball 0 behind, lin2019's "ball 1"), touching neighbours a helix chord ``2 R_B`` apart
    module : :class:`ball.ScrewModule` (ball radius, pitch radius, lead, nut speed, mu; the normal
        loads come with the patches, so its preload and elastic constants are not used)
    gaps : (n-1,) rad, azimuth gaps beyond touching (default all touching); ``with_b2b=False``: no B2B contact
    tolerance : max residual (units ``mu F_ref``, F_ref the largest patch force; moments / R_B) and of eqs 60-61
    regularisation : eps, slip floor in units of ``|omega_N| L / 2 pi``
    name : the model in the messages of ConvergenceError ("FE-informed"; the stick/slip solve's full-slip limit
        on its cells names itself, :mod:`lowmodel.screw.b2b_rolling`)

    Raises ValueError for bad input (naming it), ConvergenceError (with its residual) if Newton fails or the
    power balance misses POWER_BALANCE_TOLERANCE.
    """
    check_solver_options(tolerance, max_iterations)
    if not isinstance(module, screw_contacts.ScrewModule):
        raise ValueError(f"module must be a ball.ScrewModule (ball.screw_module), got {type(module)!r}")
    eps = float(regularisation)
    if not math.isfinite(eps) or not 0.0 < eps <= 1e-6:
        raise ValueError(f"regularisation must lie in (0, 1e-6], got {regularisation!r}")
    radius = module.ball_radius
    balls = [[_check_screw_patch(patch, i, radius) for i, patch in enumerate(patches)] for patches in balls]
    n = len(balls)
    if n < 1 or min(len(p) for p in balls) < 1:
        raise ValueError("balls must hold n >= 1 balls with >= 1 patch each")
    if not any(patch.top for patch in balls[0]) or not all(any(p.top for p in patches) for patches in balls):
        raise ValueError("balls: every ball needs a loaded nut patch (top=True): the nut drives the balls")
    gaps = b2b.check_gaps(gaps, n - 1)
    touching = np.flatnonzero(gaps <= 1e-12) if with_b2b else np.zeros(0, dtype=int)
    reference_force = max(p.normal_force for patches in balls for p in patches)  # F_ref [N]
    samples = _Samples(balls, module, reference_force, eps)
    guess = _initial_guess(samples, n)

    states, lam, iterations, residual_norm = solve_chain(
        samples, guess, touching, lambda layout: pair_function(module, layout, reference_force),
        complementarity="fischer-burmeister", tolerance=tolerance, max_iterations=max_iterations,
        what_ball=f"{name} screw ball", what_chain=f"{name} {n}-ball screw B2B contact")
    forces = lam * module.friction_coefficient * reference_force
    return _state(samples, states, forces, balls, module, reference_force, iterations, residual_norm)


def _initial_guess(samples: _Samples, n: int) -> np.ndarray:
    """Least-squares zero slip at the force-weighted centre of every patch (free rolling)."""
    guess = np.zeros((n, N_UNKNOWNS))
    for b in range(n):
        rows, rhs = [], []
        on_ball = samples.ball == b
        for p in np.unique(samples.patch[on_ball]):
            mask = samples.patch == p
            weight = samples.load[mask] / samples.load[mask].sum()
            rows.append(np.einsum("k,kij->ij", weight, samples.D[mask]))
            rhs.append(weight @ samples.groove_slip[mask])
        guess[b] = np.linalg.lstsq(np.vstack(rows), np.concatenate(rhs), rcond=None)[0]
    return guess


def pair_function(module: screw_contacts.ScrewModule, layout: ChainLayout, reference_force: float):
    """The B2B loads of the chain's pairs (eqs 56-59) as generalised forces of the 4 unknowns per ball (units
    ``mu F_ref``; force slots in units ``mu F_ref``): :class:`lowmodel.b2b_chain.PairBlocks`."""
    k = N_UNKNOWNS
    pair = b2b.pair_geometry(module)
    rows = _b2b_rows(module)
    radius, mu = module.ball_radius, module.friction_coefficient
    spin_unit = abs(module.nut_speed) * module.helix_radius / radius  # rad/s per unit of the spin unknowns
    force_unit = mu * reference_force                                # N per unit of the force slot
    pairs = layout.pairs

    def function(balls, forces):
        loads, d_spin, d_force, slip = b2b.b2b_loads(balls[:, 1:] * spin_unit, forces * force_unit, pair, radius, mu,
                                                     pairs, abs(module.nut_speed))
        d_balls = np.zeros((len(pairs), 2, 2, k, k))
        d_balls[..., 1:] = np.einsum("ra,psqac->psqrc", rows, d_spin) * (spin_unit / force_unit)
        return PairBlocks(loads @ rows.T / force_unit, d_balls, d_force @ rows.T, slip)

    return function


def _patch_sum(samples: _Samples, values: np.ndarray, n: int) -> np.ndarray:
    p = samples.n_patches
    return np.bincount(samples.patch, values, minlength=n * p).reshape(n, p)


def _state(samples: _Samples, states, forces, balls, module, reference_force, iterations,
           residual_norm) -> ScrewTractionState:
    n, p = samples.n_balls, samples.n_patches
    speed = abs(module.nut_speed) * module.helix_radius  # m/s per unit slip
    force_unit = module.friction_coefficient * reference_force
    _, _, slip, force = samples.evaluate(states, jacobian=False)
    force_n = force * force_unit  # N
    friction_force = np.stack([_patch_sum(samples, force_n[:, c], n) for c in range(3)], axis=-1)
    moment_k = np.cross(samples.r, force_n)
    friction_moment = np.stack([_patch_sum(samples, moment_k[:, c], n) for c in range(3)], axis=-1)
    loss = _patch_sum(samples, -np.einsum("ki,ki->k", force, slip) * force_unit * speed, n)
    input_power = float(np.einsum("ki,ki->k", force, samples.groove_slip).sum() * force_unit * speed)
    spin_unit = speed / module.ball_radius
    pair = b2b.pair_geometry(module)
    b2b_slip = np.zeros(n - 1)
    if n > 1:
        b2b_slip = b2b.b2b_loads(states[:, 1:] * spin_unit, forces, pair, module.ball_radius,
                                       module.friction_coefficient)[3]
    b2b_loss = module.friction_coefficient * forces * b2b_slip  # lin2019 eq 58
    losses = float(loss.sum() + b2b_loss.sum())
    balance = abs(input_power - losses) / max(abs(input_power), 1e-300)
    if not balance <= POWER_BALANCE_TOLERANCE:
        raise ConvergenceError("FE-informed screw B2B: power balance missed", residual=balance,
                               iterations=iterations, tolerance=POWER_BALANCE_TOLERANCE,
                               reason="power balance missed")
    s, c = math.sin(module.lead_angle), math.cos(module.lead_angle)
    z_hat = np.array([0.0, s, c])
    normal_force = np.zeros((n, p))
    angle = np.zeros((n, p))
    names = []
    axial = np.zeros(n)
    for b, patches in enumerate(balls):
        names.append(tuple(patch.name for patch in patches) + ("",) * (p - len(patches)))
        for i, patch in enumerate(patches):
            normal_force[b, i] = patch.normal_force
            x, _, z = patch.centre
            angle[b, i] = math.atan2(abs(z), abs(x))  # lin2019 eq 37
            if not patch.top:
                axial[b] += float(-(patch.forces @ patch.normals) @ z_hat + friction_force[b, i] @ z_hat)
    omega = states[:, 1:] * spin_unit
    return ScrewTractionState(states[:, 0] * abs(module.nut_speed), omega, tuple(names), normal_force, angle,
                              friction_force, friction_moment, axial, balance, friction_loss=loss,
                              input_power=input_power, b2b_force=forces, b2b_friction_loss=b2b_loss,
                              b2b_slip=b2b_slip, iterations=iterations, residual=residual_norm)


@dataclass(frozen=True)
class ModuleB2B:
    """Two (or more) touching balls and the same balls apart (:func:`module_b2b`).

    touching, free : ScrewTractionState with and without B2B contact
    b2b_force : (n-1,) N;  friction_increase : % (total loss touching / free - 1, lin2019 Sec 3.3)
    power_balance : the larger relative power error of the two solves
    """

    touching: ScrewTractionState
    free: ScrewTractionState
    b2b_force: np.ndarray
    friction_increase: float
    power_balance: float


def module_b2b(balls, module: screw_contacts.ScrewModule, *, free_balls=None, **options) -> ModuleB2B:
    """lin2019 Sec 3.3's two-ball module with sampled contacts: F_B2B, friction increase, power balance.

    ``balls``: per ball (ball 0 behind, lin2019's ball 1) its :class:`TractionPatch` sequence (e.g. the FE
    module's contacts of ball 1 at theta = 0 and of ball 2 at the case's theta, each from its own solve;
    points relative to that ball's centre in its CS3); ``free_balls`` the patches of the balls apart (default
    the same: normal loads decoupled from the B2B force).  ``options`` go to :func:`solve`.
    """
    touching = solve(balls, module, **options)
    free = solve(balls if free_balls is None else free_balls, module, with_b2b=False, **options)
    increase = 100.0 * friction_increase(touching, free)
    return ModuleB2B(touching, free, touching.b2b_force, increase, max(touching.power_balance, free.power_balance))
