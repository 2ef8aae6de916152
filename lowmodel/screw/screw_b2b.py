"""Ball-to-ball (B2B) contact of 2 to N balls in a ball screw (lin2019 Sec 3.2, eqs 56-61).

Built on the single-ball equilibrium of :mod:`lowmodel.screw.screw_ball` (eq 54).
Balls ``j = 0 .. n-1`` are ordered along the helix in the direction of their
orbit (``omega_B > 0``: increasing azimuth); ball 0 is lin2019's "ball 1"
(behind).  All balls share one nut and one screw: a common nut shift ``u`` and
the total axial load ``sum_balls sum_screw contacts (force on ball) . z_hat``.

Geometry of a touching pair (j, j+1): the centres lie on the nominal helix a
chord ``2 R_B`` apart, azimuth difference ``dphi`` from
:func:`lowmodel.geometry.helix.ball_centre_azimuths`; ``n`` is the unit chord
from ball j to ball j+1 in ball j's CS3, ``R`` the rotation from ball j+1's CS3
to ball j's (``T_CS-CS3(0)^T T_CS-CS3(dphi)``, eq 41).  ``n`` makes the angle
``beta_chord`` with ``y3`` towards ``-x3``; lin2019 eq 56 writes it as
``asin(2 pi R_B / L)`` (a circle of radius ``L / 2 pi`` in place of the helix;
docs/ball_screw.md gives both, 2 % apart for Table 4).  The exact chord is
used so that the contact points of the two balls coincide and the power
balance is exact.

Slip at the B2B contact, ball j relative to ball j+1 (eq 57): with both balls
at the same orbit speed the helical motions of the two centres cancel at the
contact point and

    s = (omega_j + R omega_{j+1}) x (R_B n)      (CS3 of ball j; tangent to the contact)

Friction on ball j ``f = -mu F s/|s|`` (eq 58) at ``+R_B n``; normal force
``-F n``.  Ball j+1 gets ``+F n`` and ``-f`` at ``-R_B n``, i.e. the same moment
``R_B n x f`` (eq 59 for ball 1, "opposite direction" for ball 2).  Loss
``mu F |s|`` (power balance in :func:`solve`).

Complementarity (eqs 60-61) for a touching pair: ``F >= 0``,
``omega_B,j+1 - omega_B,j >= 0``, ``F (omega_B,j+1 - omega_B,j) = 0``; solved with
the equilibrium of all balls and the axial balance by a semismooth Newton
method on the Fischer-Burmeister function of ``F / (mu F_ref)`` and
``gamma (omega_B,j+1 - omega_B,j)/|omega_N|`` (``a + b - sqrt(a^2 + b^2) = 0``; the ``min``
form of :mod:`lowmodel.linear_bearing.b2b` stalled Levenberg-Marquardt on chains of 100 balls).
A pair with a positive gap carries no force.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.screw import screw_ball as sb
from ballbench.lowmodel.screw.convergence import row_tolerances, row_weights, sliding_ratio

__all__ = ["PairGeometry", "pair_geometry", "b2b_angle_eq56", "b2b_loads", "solve", "solve_at", "COMPLEMENTARITY_SCALE",
           "LOAD_RAMP_START", "saturation", "fischer_burmeister", "check_gaps"]

COMPLEMENTARITY_SCALE = 10.0
_FB_SMOOTHING = 1e-14  # keeps the Fischer-Burmeister function differentiable at (0, 0)
_REGULARISATION = 1e-14  # |s| floor in units of R_B * spin scale


@dataclass(frozen=True)
class PairGeometry:
    """Geometry of two touching balls (CS3 of the ball behind).

    azimuth_step : rad, ``dphi`` between the two centres (chord 2 R_B)
    chord : (3,) unit vector from ball j to ball j+1
    rotation : (3, 3), CS3 of ball j+1 -> CS3 of ball j
    angle : rad, ``beta_chord``, the angle of ``chord`` from ``y3`` towards ``-x3`` (eq 56's beta_B2B)

    ``chord`` and ``rotation`` are read-only: :func:`pair_geometry` hands the same cached object to every
    caller with the same module (lowmodel.checks.freeze_arrays).
    """

    azimuth_step: float
    chord: np.ndarray
    rotation: np.ndarray
    angle: float

    def __post_init__(self):
        checks.freeze_arrays(self, "chord", "rotation")

    def __reduce__(self):
        return checks.rebuilt_through_init(self)


@lru_cache(maxsize=64)
def pair_geometry(module: sb.ScrewModule) -> PairGeometry:
    """Exact helix chord of two touching balls (geometry core: :func:`helix.ball_centre_azimuths`); cached."""
    step = helix.ball_centre_azimuths(module.pitch_radius, module.lead, 2.0 * module.ball_radius)
    frame_0 = helix.cs3_frame(0.0, module.lead_angle)
    frame_1 = helix.cs3_frame(step, module.lead_angle)
    chord = frame_0.T @ (helix.ball_centre(step, module.pitch_radius, module.lead)
                         - helix.ball_centre(0.0, module.pitch_radius, module.lead))
    chord = chord / np.linalg.norm(chord)
    return PairGeometry(float(step), chord, frame_0.T @ frame_1, float(math.asin(-chord[0])))


def b2b_angle_eq56(module: sb.ScrewModule) -> float:
    """lin2019 eq 56: ``beta_B2B = asin(2 pi R_B / L)`` [rad]."""
    big_l = 2.0 * math.pi * module.helix_radius
    return math.asin(2.0 * math.pi * module.ball_radius / big_l)


def _skew(v: np.ndarray) -> np.ndarray:
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def b2b_loads(spins: np.ndarray, forces: np.ndarray, pair: PairGeometry, radius: float, mu: float,
              pairs=None, speed: float = 1.0):
    """B2B loads of touching pairs (eqs 57-59).

    spins (n, 3) rad/s in each ball's CS3; forces (p,) N (0 for open pairs); ``pairs``
    (p, 2) indices (behind, ahead), default the chain ``(j, j+1)``; ``speed`` [rad/s] the motion's scale (e.g.
    ``|omega_N|``): the slip floor of the friction direction is ``1e-14 R_B speed`` (scale-free).
    Returns (load (n, 6) [force N, moment N m] in each ball's CS3, d load / d spins (n, 6, n, 3),
    d load / d forces (n, 6, p), slip speeds (p,) m/s).
    """
    n = spins.shape[0]
    if pairs is None:
        pairs = np.stack([np.arange(n - 1), np.arange(1, n)], axis=1)
    pairs = np.asarray(pairs, dtype=int).reshape(-1, 2)
    count = len(pairs)
    load = np.zeros((n, 6))
    d_spin = np.zeros((n, 6, n, 3))
    d_force = np.zeros((n, 6, count))
    if count == 0:
        return load, d_spin, d_force, np.zeros(0)
    forces = np.asarray(forces, dtype=float)
    a_mat = -radius * _skew(pair.chord)          # s = A (omega_j + R omega_k)
    b_mat = radius * _skew(pair.chord)           # moment = B f
    rot = pair.rotation
    behind, ahead = pairs[:, 0], pairs[:, 1]
    slip = (spins[behind] + spins[ahead] @ rot.T) @ a_mat.T                 # (p, 3)
    speeds = np.sqrt(np.einsum("pi,pi->p", slip, slip))
    norm = np.sqrt(speeds**2 + (_REGULARISATION * radius * speed) ** 2)
    direction = slip / norm[:, None]
    friction = -mu * forces[:, None] * direction                              # eq 58 on the ball behind
    force_behind = -forces[:, None] * pair.chord + friction
    moment = friction @ b_mat.T
    np.add.at(load, (behind, slice(0, 3)), force_behind)
    np.add.at(load, (behind, slice(3, 6)), moment)
    np.add.at(load, (ahead, slice(0, 3)), -force_behind @ rot)                # rot.T @ (-f) per pair
    np.add.at(load, (ahead, slice(3, 6)), moment @ rot)
    # d friction / d slip = -mu F (I - d d^T) / |s|
    projector = np.eye(3)[None] - direction[:, :, None] * direction[:, None, :]
    dfric_dslip = (-mu * forces / norm)[:, None, None] * projector            # (p, 3, 3)
    d_behind = dfric_dslip @ a_mat                                            # d friction / d omega_behind
    d_ahead = d_behind @ rot                                                  # d friction / d omega_ahead
    for ball_index, d_fric in ((behind, d_behind), (ahead, d_ahead)):
        np.add.at(d_spin, (behind, slice(0, 3), ball_index), d_fric)
        np.add.at(d_spin, (behind, slice(3, 6), ball_index), b_mat @ d_fric)
        np.add.at(d_spin, (ahead, slice(0, 3), ball_index), -rot.T @ d_fric)
        np.add.at(d_spin, (ahead, slice(3, 6), ball_index), rot.T @ b_mat @ d_fric)
    dfric_dforce = -mu * direction                                            # (p, 3)
    index = np.arange(count)
    d_force[behind, 0:3, index] = -pair.chord + dfric_dforce
    d_force[behind, 3:6, index] = dfric_dforce @ b_mat.T
    d_force[ahead, 0:3, index] = (pair.chord - dfric_dforce) @ rot
    d_force[ahead, 3:6, index] = dfric_dforce @ b_mat.T @ rot
    return load, d_spin, d_force, speeds


def fischer_burmeister(a, b):
    """Fischer-Burmeister function of the complementarity ``a >= 0, b >= 0, a b = 0`` (eqs 60-61).

    ``phi = a + b - sqrt(a^2 + b^2 + s^2)`` (``s`` a 1e-14 smoothing, differentiable at (0, 0));
    ``phi = 0`` is the complementarity.  Returns ``(phi, d phi / d a, d phi / d b)``, arrays like ``a``.
    """
    a = np.asarray(checks.finite("a", a), dtype=float)
    b = np.asarray(checks.finite("b", b), dtype=float)
    with np.errstate(over="ignore"):
        squared = a * a + b * b + _FB_SMOOTHING**2
    root = np.sqrt(squared)
    if not np.all(np.isfinite(root)):   # |a| or |b| beyond ~1e154: no overflow of the squares
        root = np.where(np.isfinite(root), root, np.hypot(np.hypot(a, b), _FB_SMOOTHING))
    return a + b - root, 1.0 - a / root, 1.0 - b / root


def check_gaps(gaps, count: int) -> np.ndarray:
    """Azimuth gaps (count,) [rad] >= 0 beyond touching; ``None`` is all touching (zeros); ``count`` >= 0 pairs."""
    count = checks.count("count", count, 0)
    if gaps is None:
        return np.zeros(count)
    gaps = np.asarray(checks.non_negative("gaps", gaps, "rad (azimuth gap between neighbouring balls)"),
                      dtype=float).reshape(-1)
    if gaps.shape != (count,):
        raise ValueError(f"gaps must have shape ({count},) (one per neighbouring pair), got {gaps.shape}")
    return gaps


LOAD_RAMP_START = 100.0  # N per ball: above it a failed solve is retried by a load ramp from here


def solve(contacts: sb.BallContacts, axial_load, gaps=None, *, ring: bool = False, tolerance: float = 1e-10,
          max_iterations: int = 80, with_b2b: bool = True, initial: sb.ScrewBallState | None = None,
          ramp_steps: int = 8) -> sb.ScrewBallState:
    """:func:`solve_at` with fallbacks: a second start from the balls solved without B2B contact; and for
    heavy loads, if that fails too with more than ``LOAD_RAMP_START``
    per ball, the load is ramped up geometrically from there in ``ramp_steps`` warm-started solves
    (continuation in the load; the preload continuation alone stalls where contacts open under kN loads).
    Parameters as :func:`solve_at`."""
    try:
        try:
            return solve_at(contacts, axial_load, gaps, ring=ring, tolerance=tolerance,
                            max_iterations=max_iterations, with_b2b=with_b2b, initial=initial)
        except ConvergenceError:
            if not with_b2b or contacts.n_balls < 2:
                raise
            # second start: the balls without B2B contact, then the contact problem from there
            free = solve_at(contacts, axial_load, gaps, ring=ring, tolerance=tolerance,
                            max_iterations=max_iterations, with_b2b=False)
            return solve_at(contacts, axial_load, gaps, ring=ring, tolerance=tolerance,
                            max_iterations=max_iterations, with_b2b=True, initial=free)
    except ConvergenceError as error:
        loads = np.asarray(axial_load, dtype=float)
        per_ball = float(np.max(np.abs(loads))) / (1 if loads.ndim else contacts.n_balls)
        if per_ball <= LOAD_RAMP_START:
            raise
        state, reached = None, 0.0
        for factor in np.geomspace(LOAD_RAMP_START / per_ball, 1.0, ramp_steps):
            try:
                state = solve_at(contacts, loads * factor, gaps, ring=ring, tolerance=tolerance,
                                 max_iterations=max_iterations, with_b2b=with_b2b, initial=state)
                reached = factor
            except ConvergenceError as ramp_error:
                reason = ""
                if state is not None:
                    sliding = saturation(state)
                    reason = (f"; at {100 * reached:.1f} % of the load the contacts slide with |c/a| up to "
                              f"{sliding:.1f} (friction near its sliding limit mu F): no full-sliding state of "
                              f"lin2019's model beyond, as the spin moments grow like F a and the friction of the "
                              f"light contacts only like F (docs/ball_screw.md)")
                raise ConvergenceError(f"no converged state: load ramp stopped at {100 * factor:.1f} % of the "
                                       f"load{reason}", residual=ramp_error.residual,
                                       iterations=ramp_error.iterations, tolerance=tolerance,
                                       reason="load ramp stopped" + (": contacts near full sliding" if reason
                                                                     else f" ({ramp_error.reason})")) from error
        return state


def saturation(state: sb.ScrewBallState) -> float:
    """Largest ``|c/a| = |slip_minor| / |spin a|`` over the loaded contacts (inf at pure sliding; 0 if none)."""
    return sliding_ratio(state.normal_force, state.slip_minor, state.spin, state.semi_major)


def solve_at(contacts: sb.BallContacts, axial_load, gaps=None, *, ring: bool = False, tolerance: float = 1e-10,
             max_iterations: int = 80, with_b2b: bool = True, initial: sb.ScrewBallState | None = None
             ) -> sb.ScrewBallState:
    """Quasi-static motion of ``n >= 1`` balls sharing nut and screw, with B2B contact (lin2019 eqs 54-61).

    Parameters
    ----------
    contacts : BallContacts of the ``n`` balls, ordered along the orbit (ball 0 behind)
    axial_load : N; a scalar is the total force of the screw on the balls along +z with one common
        nut shift; an array (n,) prescribes each ball's axial load (each ball its own nut shift:
        a load distribution computed elsewhere, :mod:`lowmodel.screw.load_distribution`)
    gaps : (pairs,) rad, azimuth gaps beyond touching (default: all touching, 0)
    ring : the balls form a closed chain (recirculation): pair (n-1, 0) as well
    with_b2b : False solves the same balls with B2B contact switched off (the "before contact" state)
    initial : a previous state of the same balls (warm start)

    Returns ScrewBallState with ``b2b_force`` (pairs,) [N] and ``b2b_friction_loss`` [W].
    Raises ConvergenceError with its residual if the solve fails or complementarity is violated.
    """
    from ballbench.lowmodel.solvers import check_solver_options

    check_solver_options(tolerance, max_iterations)
    n = contacts.n_balls
    loads = np.atleast_1d(np.asarray(checks.finite("axial_load", axial_load, "N"), dtype=float))
    per_ball = loads.size > 1 or (n == 1 and np.ndim(axial_load) == 1)
    if per_ball and loads.shape != (n,):
        raise ValueError(f"axial_load must be a scalar (total) or have shape ({n},) (per ball), got {loads.shape}")
    pairs = [(j, j + 1) for j in range(n - 1)] + ([(n - 1, 0)] if ring and n > 1 else [])
    pairs = np.array(pairs, dtype=int).reshape(-1, 2)
    gaps = check_gaps(gaps, len(pairs))
    touching = np.flatnonzero(gaps <= 1e-12) if with_b2b else np.zeros(0, dtype=int)
    module = contacts.module
    total = float(loads.sum())
    reference = sb.reference_force(contacts, float(np.max(np.abs(loads))) if per_ball else total / n)
    scales = sb.scales_for(contacts, reference)
    pair = pair_geometry(module)
    k = sb.N_UNKNOWNS
    m = touching.size
    n_shift = n if per_ball else 1
    base = k * n + n_shift
    size = base + m
    gamma = COMPLEMENTARITY_SCALE
    targets = loads / scales.force
    speed_factor = gamma * scales.orbit / abs(module.nut_speed)

    def unpack(z):
        balls = z[:k * n].reshape(n, k)
        forces = np.zeros(len(pairs))
        forces[touching] = z[base:] * scales.force
        return balls, z[k * n:base], forces

    last = {}

    def make_function(oversize):
        def function(z):
            balls, shift, forces = unpack(z)
            terms = sb.ball_terms(balls, shift if per_ball else shift[0], contacts, scales, oversize=oversize)
            last.update(z=z, terms=terms, oversize=oversize)
            residual = np.empty(size)
            jac = np.zeros((size, size))
            ball_residual = terms.residual.copy()
            if m:
                loads_b2b, d_spin, d_force, _ = b2b_loads(balls[:, 3:6] * scales.spin, forces, pair,
                                                          module.ball_radius, module.friction_coefficient, pairs,
                                                          abs(module.nut_speed))
                for array in (loads_b2b, d_spin, d_force):
                    array[:, 3:] /= module.ball_radius
                ball_residual += loads_b2b / scales.force
                block = d_spin * (scales.spin / scales.force)          # (n, 6, n, 3)
                view = jac[:k * n, :k * n].reshape(n, k, n, k)     # a view: the square block of ball unknowns
                view[:, :, :, 3:6] += block
                jac[:k * n, base:] = d_force[:, :, touching].reshape(k * n, m)
            residual[:k * n] = ball_residual.reshape(-1)
            for ball in range(n):
                rows = slice(k * ball, k * ball + k)
                jac[rows, rows] += terms.jacobian[ball][:, :k]
                jac[rows, k * n + (ball if per_ball else 0)] = terms.jacobian[ball][:, k]
            if per_ball:
                residual[k * n:base] = terms.axial - targets
                for ball in range(n):
                    jac[k * n + ball, k * ball:k * ball + k] = terms.axial_gradient[ball, :k]
                    jac[k * n + ball, k * n + ball] = terms.axial_gradient[ball, k]
            else:
                residual[k * n] = terms.axial.sum() - targets[0]
                jac[k * n, :k * n] = terms.axial_gradient[:, :k].reshape(-1)
                jac[k * n, k * n] = terms.axial_gradient[:, k].sum()
            if m:
                lam = z[base:]
                ahead, behind = pairs[touching, 1], pairs[touching, 0]
                separation = speed_factor * (balls[ahead, 2] - balls[behind, 2])
                rows = base + np.arange(m)
                residual[rows], d_lam, d_sep = fischer_burmeister(lam, separation)
                jac[rows, base + np.arange(m)] = d_lam
                np.add.at(jac, (rows, k * ahead + 2), d_sep * speed_factor)
                np.add.at(jac, (rows, k * behind + 2), -d_sep * speed_factor)
            return residual, jac
        return function

    rows = row_tolerances(tolerance, friction_coefficient=module.friction_coefficient,
                          groove_radius=module.groove_radius, ball_radius=module.ball_radius,
                          approach=scales.length, balls=n, axial=n_shift, extra=m)
    weights = row_weights(friction_coefficient=module.friction_coefficient, balls=n, axial=n_shift, extra=m)
    guess = np.zeros(size)
    if initial is not None and initial.orbit_speed.shape == (n,):
        balls0 = guess[:k * n].reshape(n, k)
        balls0[:, :2] = initial.centre / scales.length
        balls0[:, 2] = initial.orbit_speed / scales.orbit
        balls0[:, 3:6] = initial.omega / scales.spin
        shifts = np.broadcast_to(np.asarray(initial.nut_shift, dtype=float), (n,))
        guess[k * n:base] = (shifts if per_ball else shifts.mean(keepdims=True)) / scales.length
        previous = np.asarray(initial.b2b_force, dtype=float)
        if previous.shape == (len(pairs),):
            guess[base:] = previous[touching] / scales.force
        z, residual, iterations = _newton(make_function(module.oversize), guess, tolerance, max_iterations,
                                          f"{n}-ball screw module (warm start)", rows, weights)
    else:
        rates = sb.free_rolling_guess(contacts)
        guess[:k * n].reshape(n, k)[:, 2] = rates[:, 0] / scales.orbit
        guess[:k * n].reshape(n, k)[:, 3:6] = rates[:, 1:] / scales.spin
        def contacts_at(z, oversize):
            balls, shift, _ = unpack(z)
            return sb.ball_terms(balls, shift if per_ball else shift[0], contacts, scales, oversize=oversize)

        z, residual, iterations = sb.solve_preloaded(make_function, guess, contacts,
                                                     float(np.max(np.abs(loads))) if per_ball else total / n,
                                                     tolerance=tolerance, max_iterations=max_iterations,
                                                     what=f"{n}-ball screw module", row_tolerance=rows,
                                                     row_weight=weights, contacts_at=contacts_at)
    balls, shift, forces = unpack(z)
    if m:
        ahead, behind = pairs[touching, 1], pairs[touching, 0]
        separation = speed_factor * (balls[ahead, 2] - balls[behind, 2])
        lam = z[base:]
        violation = max(float(np.max(-lam, initial=0.0)), float(np.max(-separation, initial=0.0)))
        if violation > 10 * tolerance:
            raise ConvergenceError(f"{n}-ball screw module: complementarity violated", residual=violation,
                                   iterations=iterations, tolerance=tolerance, reason="complementarity violated")
        forces = np.maximum(forces, 0.0)
    if last.get("z") is z and last.get("oversize") == module.oversize:   # the last evaluation was at the solution
        terms = last["terms"]
    else:
        terms = sb.ball_terms(balls, shift if per_ball else shift[0], contacts, scales)
    speeds = np.zeros(len(pairs))
    if len(pairs):
        speeds = b2b_loads(balls[:, 3:6] * scales.spin, forces, pair, module.ball_radius,
                           module.friction_coefficient, pairs, abs(module.nut_speed))[3]
    b2b_loss = module.friction_coefficient * forces * speeds          # lin2019 eq 58: mu F |s|
    return sb.state_from(balls, shift * 1.0 if per_ball else shift[0], terms, scales, axial_load=total,
                         b2b_force=forces, b2b_loss=b2b_loss, iterations=iterations,
                         residual=float(np.max(np.abs(residual))))


def _newton(function, guess, tolerance, max_iterations, what, row_tolerance=None, row_weight=None):
    from ballbench.lowmodel.solvers import newton

    return newton(function, guess, tolerance=tolerance, max_iterations=max_iterations, what=what,
                  row_tolerance=row_tolerance, row_weight=row_weight)
