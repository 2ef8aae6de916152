"""Ball-to-ball (B2B) contact of 2 to N balls in a ball screw (lin2019 Sec 3.2, eqs 56-61).

Built on the single-ball equilibrium of :mod:`lowmodel.screw.ball` (eq 54).
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
the equilibrium of all balls and the axial balance by the semismooth Newton method of
:mod:`lowmodel.b2b_chain` (one implementation with the linear bearing and the
FE-informed models) on the Fischer-Burmeister function of ``F / (mu F_ref)`` and
``gamma (omega_B,j+1 - omega_B,j)/|omega_N|`` (``a + b - sqrt(a^2 + b^2) = 0``; with the
``min`` function of the linear bearing Levenberg-Marquardt stalls on chains of 100 balls).
A pair with a positive gap carries no force.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np

from ballbench.lowmodel import checks, kernels
from ballbench.lowmodel.b2b_chain import (COMPLEMENTARITY_SCALE, SPARSE_BALLS, BallBlocks, ChainLayout, PairBlocks,
                                          chain_forces, chain_system)
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.screw import ball as sb
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw.convergence import row_tolerances, row_weights, sliding_ratio
from ballbench.lowmodel.solvers import check_solver_options, newton

__all__ = ["contacts", "PairGeometry", "pair_geometry", "b2b_angle_eq56", "b2b_loads", "b2b_slip", "solve",
           "LOAD_RAMP_START", "FULL_SLIDING_LIMIT", "RAMP_STOP", "ramp_stop_cause", "saturation", "check_gaps",
           "warm_up_kernel", "warm_up_ring_kernel", "RING_KERNELS"]

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
def pair_geometry(module: screw_contacts.ScrewModule) -> PairGeometry:
    """Exact helix chord of two touching balls (geometry core: :func:`helix.ball_centre_azimuths`); cached."""
    step = helix.ball_centre_azimuths(module.pitch_radius, module.lead, 2.0 * module.ball_radius)
    frame_0 = helix.cs3_frame(0.0, module.lead_angle)
    frame_1 = helix.cs3_frame(step, module.lead_angle)
    chord = frame_0.T @ (helix.ball_centre(step, module.pitch_radius, module.lead)
                         - helix.ball_centre(0.0, module.pitch_radius, module.lead))
    chord = chord / np.linalg.norm(chord)
    return PairGeometry(float(step), chord, frame_0.T @ frame_1, float(math.asin(-chord[0])))


def b2b_angle_eq56(module: screw_contacts.ScrewModule) -> float:
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
    Returns ``(load (n, 6) [force N, moment N m] on every ball in its CS3, d_spin (p, 2, 2, 6, 3) =
    d (load on the ball behind, ahead) / d (spin behind, ahead) of each pair, d_force (p, 2, 6) =
    d (load on the ball behind, ahead) / d F, slip speeds (p,) m/s)``.
    """
    n = spins.shape[0]
    if pairs is None:
        pairs = np.stack([np.arange(n - 1), np.arange(1, n)], axis=1)
    pairs = np.asarray(pairs, dtype=int).reshape(-1, 2)
    count = len(pairs)
    load = np.zeros((n, 6))
    d_spin = np.zeros((count, 2, 2, 6, 3))
    d_force = np.zeros((count, 2, 6))
    if count == 0:
        return load, d_spin, d_force, np.zeros(0)
    forces = np.asarray(forces, dtype=float)
    a_mat = -radius * _skew(pair.chord)          # s = A (omega_j + R omega_k)
    b_mat = radius * _skew(pair.chord)           # moment = B f
    rot = pair.rotation
    behind, ahead = pairs[:, 0], pairs[:, 1]
    slip, speeds = b2b_slip(spins, pair, radius, pairs)
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
    for side, d_fric in enumerate((d_behind, d_behind @ rot)):                # columns: spin behind, spin ahead
        d_spin[:, 0, side, :3] = d_fric
        d_spin[:, 0, side, 3:] = b_mat @ d_fric
        d_spin[:, 1, side, :3] = -rot.T @ d_fric
        d_spin[:, 1, side, 3:] = rot.T @ b_mat @ d_fric
    dfric_dforce = -mu * direction                                            # (p, 3)
    d_force[:, 0, :3] = -pair.chord + dfric_dforce
    d_force[:, 0, 3:] = dfric_dforce @ b_mat.T
    d_force[:, 1, :3] = (pair.chord - dfric_dforce) @ rot
    d_force[:, 1, 3:] = dfric_dforce @ b_mat.T @ rot
    return load, d_spin, d_force, speeds


def b2b_slip(spins: np.ndarray, pair: PairGeometry, radius: float, pairs: np.ndarray):
    """Slip of every pair (eq 57), ball behind relative to ball ahead: ``(s (p, 3) [m/s] in the CS3 of the ball
    behind, |s| (p,) [m/s])`` of spins (n, 3) [rad/s] and ``pairs`` (p, 2) int indices (behind, ahead) (the
    arithmetic of :func:`b2b_loads`)."""
    behind, ahead = pairs[:, 0], pairs[:, 1]
    slip = (spins[behind] + spins[ahead] @ pair.rotation.T) @ (-radius * _skew(pair.chord)).T
    return slip, np.sqrt(np.einsum("pi,pi->p", slip, slip))


@dataclass(frozen=True)
class _ChainSetup:
    """What a solve of :func:`_solve_attempt` needs besides its start, for one load, gap pattern and tolerance on
    one set of contacts (remembered in :attr:`BallContacts.solver_memo`): the reference force's scales, the chain's
    layout, the scaled axial targets, the complementarity rate's scale, the per-row tolerances and step weights
    (docs/ball_screw.md, small mu) and the compiled solver's constant arrays; the free-rolling start (n, 4) in scaled
    unknowns at the first cold start (:meth:`rolling_start`): a warm-started solve on new contacts (each step of the
    whole screw after the first) would pay its least squares for nothing."""

    scales: sb.Scales
    layout: ChainLayout
    targets: np.ndarray
    rate_scale: float
    rows: np.ndarray
    weights: np.ndarray
    kernel_constants: tuple
    _lazy: dict = field(default_factory=dict, compare=False, repr=False)

    def rolling_start(self, contacts: screw_contacts.BallContacts) -> np.ndarray:
        """The free-rolling start of a cold start on ``contacts`` (those of this setup; :func:`_rolling_start`),
        computed at its first use, then remembered (read-only)."""
        if "rolling_start" not in self._lazy:
            start = _rolling_start(contacts, self.scales)
            start.setflags(write=False)
            self._lazy["rolling_start"] = start
        return self._lazy["rolling_start"]


def _chain_setup(contacts: screw_contacts.BallContacts, loads: np.ndarray, per_ball: bool, touching: np.ndarray,
                 ring: bool, tolerance: float) -> _ChainSetup:
    """The :class:`_ChainSetup` of a solve (computed at the first solve with these inputs, then remembered)."""
    key = (loads.tobytes(), per_ball, touching.tobytes(), bool(ring), float(tolerance))
    setups = contacts.solver_memo.setdefault("chain", {})
    if key not in setups:
        if len(setups) >= sb.MEMO_SIZE:
            setups.clear()
        setups[key] = _new_chain_setup(contacts, loads, per_ball, touching, ring, tolerance)
    return setups[key]


def _new_chain_setup(contacts, loads, per_ball, touching, ring, tolerance) -> _ChainSetup:
    n = contacts.n_balls
    module = contacts.module
    total = float(loads.sum())
    reference = sb.reference_force(contacts, float(np.max(np.abs(loads))) if per_ball else total / n)
    scales = sb.scales_for(contacts, reference)
    k = sb.N_UNKNOWNS + (1 if per_ball else 0)   # per-ball loads: the ball's own nut shift is its 7th unknown
    layout, live = _chain_layout(n, k, np.asarray(touching, dtype=np.intp).tobytes(), bool(ring) and n > 1,
                                 0 if per_ball else 1)
    rate_scale = COMPLEMENTARITY_SCALE * scales.orbit / abs(module.nut_speed)   # rate in units |omega_N| / gamma
    # per-row tolerances and step weights (docs/ball_screw.md, small mu) in the chain's order: every ball's block
    # (six eq 54 rows, its axial row when the nut shift is per ball, its pair's slot), then the global axial row
    rows = np.tile(row_tolerances(tolerance, friction_coefficient=module.friction_coefficient,
                                  groove_radius=module.groove_radius, ball_radius=module.ball_radius,
                                  approach=scales.length, balls=1, axial=1 if per_ball else 0, extra=1), n)
    if layout.n_global:
        rows = np.concatenate([rows, row_tolerances(tolerance, friction_coefficient=module.friction_coefficient,
                                                    groove_radius=module.groove_radius,
                                                    ball_radius=module.ball_radius, approach=scales.length, balls=0,
                                                    axial=layout.n_global)])
    weights = _chain_weights(module.friction_coefficient, n, per_ball, layout.n_global)
    pair_scalars = np.array([module.ball_radius, module.friction_coefficient, abs(module.nut_speed), rate_scale])
    constants = (np.array(sb.kernel_scalars(scales, module, None)), live, pair_scalars)
    targets = loads / scales.force
    for array in (rows, targets, constants[0], pair_scalars):
        array.setflags(write=False)
    return _ChainSetup(scales, layout, targets, rate_scale, rows, weights, constants)


@lru_cache(maxsize=256)
def _chain_layout(n: int, k: int, touching: bytes, ring: bool, n_global: int) -> tuple[ChainLayout, np.ndarray]:
    """The :class:`ChainLayout` of ``n`` balls of ``k`` unknowns with the touching pairs ``touching`` (the bytes of an
    intp array) and its ``live`` slots (contiguous), read-only, cached: one object for every solve with this pattern
    (the steps of the whole screw while no pair opens or closes keep its cached pairs)."""
    layout = ChainLayout(n, k, np.frombuffer(touching, dtype=np.intp), ring=ring, n_global=n_global)
    return layout, checks.read_only(np.ascontiguousarray(layout.live))


@lru_cache(maxsize=64)
def _chain_weights(friction_coefficient: float, n: int, per_ball: bool, n_global: int) -> np.ndarray:
    """The step weights (read-only, cached) of a chain of ``n`` balls in :func:`_new_chain_setup`'s row order:
    :func:`convergence.row_weights` of every ball's block, then of the ``n_global`` global axial rows."""
    weights = np.tile(row_weights(friction_coefficient=friction_coefficient, balls=1, axial=1 if per_ball else 0,
                                  extra=1), n)
    if n_global:
        weights = np.concatenate([weights, row_weights(friction_coefficient=friction_coefficient, balls=0,
                                                       axial=n_global)])
    return checks.read_only(weights)


def _rolling_start(contacts: screw_contacts.BallContacts, scales: sb.Scales) -> np.ndarray:
    """The cold start of a solve: the free-rolling orbit and spins (:func:`ball.free_rolling_guess`, remembered per
    contacts) in scaled unknowns, (n, 4)."""
    rates = sb.free_rolling_guess(contacts)
    start = np.empty((contacts.n_balls, 4))
    start[:, 0] = rates[:, 0] / scales.orbit
    start[:, 1:] = rates[:, 1:] / scales.spin
    return start


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
# ConvergenceError.reason when the load ramp stops past a converged state whose contacts slide near their limit
# mu F: the declared limit of lin2019's full-sliding model under heavy load (docs/ball_screw.md, "Preload loss")
FULL_SLIDING_LIMIT = "load ramp stopped: contacts near full sliding"
RAMP_STOP = "load ramp stopped ({})"  # a ramp without a converged step: the reason of the step that failed


def ramp_stop_cause(reason: str) -> str:
    """The reason of the failed step inside a :data:`RAMP_STOP` reason (the ramp found no state even at its first
    load), else ``reason`` itself."""
    head, tail = RAMP_STOP.split("{}")
    return reason[len(head):-len(tail)] if reason.startswith(head) and reason.endswith(tail) else reason


def contacts(case, *, oversize: float | None = None, reading: str | None = None,
             contact_law: screw_contacts.GrooveContactLaws | None = None) -> screw_contacts.BallContacts:
    """The contacts of the balls of a :class:`lowmodel.bearing.ScrewLoadCase` (each ball's screw-side deviation
    theta, read as the case's ``reading``): :func:`lowmodel.screw.contacts.ball_contacts` on the screw's module
    (:func:`lowmodel.screw.contacts.module`).  ``oversize`` [m] and ``reading``: other than the case's (a fit of the
    preload, the other reading of lin2019 Fig 17); ``contact_law``: calibrated laws of the grooves, None: Hertz
    (lin2019 eq 53)."""
    return screw_contacts.ball_contacts(screw_contacts.module(case.screw, oversize), np.array(case.deviations),
                                        reading=case.reading if reading is None else reading,
                                        contact_law=contact_law)


def solve(contacts: screw_contacts.BallContacts, axial_load, gaps=None, *, ring: bool = False, tolerance: float = 1e-10,
          max_iterations: int = 80, with_b2b: bool = True, initial: sb.ScrewBallState | None = None,
          ramp_steps: int = 8) -> sb.ScrewBallState:
    """:func:`_solve_attempt` with fallbacks: a second start from the balls solved without B2B contact; and for
    heavy loads, if that fails too with more than ``LOAD_RAMP_START``
    per ball, the load is ramped up geometrically from there in ``ramp_steps`` warm-started solves
    (continuation in the load; the preload continuation alone stalls where contacts open under kN loads).
    Parameters as :func:`_solve_attempt`."""
    try:
        try:
            return _solve_attempt(contacts, axial_load, gaps, ring=ring, tolerance=tolerance,
                            max_iterations=max_iterations, with_b2b=with_b2b, initial=initial)
        except ConvergenceError:
            if not with_b2b or contacts.n_balls < 2:
                raise
            # second start: the balls without B2B contact, then the contact problem from there
            free = _solve_attempt(contacts, axial_load, gaps, ring=ring, tolerance=tolerance,
                            max_iterations=max_iterations, with_b2b=False)
            return _solve_attempt(contacts, axial_load, gaps, ring=ring, tolerance=tolerance,
                            max_iterations=max_iterations, with_b2b=True, initial=free)
    except ConvergenceError as error:
        loads = np.asarray(axial_load, dtype=float)
        per_ball = float(np.max(np.abs(loads))) / (1 if loads.ndim else contacts.n_balls)
        if per_ball <= LOAD_RAMP_START:
            raise
        state, reached = None, 0.0
        for factor in np.geomspace(LOAD_RAMP_START / per_ball, 1.0, ramp_steps):
            try:
                state = _solve_attempt(contacts, loads * factor, gaps, ring=ring, tolerance=tolerance,
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
                                       reason=FULL_SLIDING_LIMIT if reason else RAMP_STOP.format(ramp_error.reason),
                                       last_converged=("load fraction", float(reached)) if state is not None
                                       else None) from error
        return state


def saturation(state: sb.ScrewBallState) -> float:
    """Largest ``|c/a| = |slip_minor| / |spin a|`` over the loaded contacts (inf at pure sliding; 0 if none)."""
    return sliding_ratio(state.normal_force, state.slip_minor, state.spin, state.semi_major)


def _solve_attempt(contacts: screw_contacts.BallContacts, axial_load, gaps=None, *, ring: bool = False,
                   tolerance: float = 1e-10, max_iterations: int = 80, with_b2b: bool = True,
                   initial: sb.ScrewBallState | None = None
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

    The balls, their nut shifts and the B2B forces form the chain of :mod:`lowmodel.b2b_chain`: per ball
    the 6 unknowns of eq 55 (and its own nut shift with the axial balance as its 7th row, for per-ball
    loads), the force slot ``F / (mu F_ref)``; one global nut shift with the total axial balance otherwise.
    Returns ScrewBallState with ``b2b_force`` (pairs,) [N], ``b2b_friction_loss`` [W] and ``b2b_slip`` [m/s].
    Raises ConvergenceError with its residual if the solve fails or complementarity is violated.
    """
    check_solver_options(tolerance, max_iterations)
    n = contacts.n_balls
    loads = np.atleast_1d(np.asarray(checks.finite("axial_load", axial_load, "N"), dtype=float))
    per_ball = loads.size > 1 or (n == 1 and np.ndim(axial_load) == 1)
    if per_ball and loads.shape != (n,):
        raise ValueError(f"axial_load must be a scalar (total) or have shape ({n},) (per ball), got {loads.shape}")
    n_pairs = (n - 1) + (1 if ring and n > 1 else 0)
    gaps = check_gaps(gaps, n_pairs)
    touching = np.flatnonzero(gaps <= 1e-12) if with_b2b else np.zeros(0, dtype=int)
    module = contacts.module
    total = float(loads.sum())
    setup = _chain_setup(contacts, loads, per_ball, touching, ring, tolerance)
    scales, layout, rows, weights, targets = setup.scales, setup.layout, setup.rows, setup.weights, setup.targets
    pair = pair_geometry(module)
    k = layout.n_unknowns
    pairs = layout.pairs
    rate_scale = setup.rate_scale
    spin_factor = scales.spin / scales.force
    last = {}

    def pair_function(balls, forces):   # eqs 57-59 in the scaled unknowns (spins: columns 3-5; moments / R_B)
        load, d_spin, d_force, slip = b2b_loads(balls[:, 3:6] * scales.spin, forces * scales.force, pair,
                                                module.ball_radius, module.friction_coefficient, pairs,
                                                abs(module.nut_speed))
        for array in (load[:, 3:], d_spin[..., 3:, :], d_force[..., 3:]):
            array /= module.ball_radius
        d_balls = np.zeros((len(pairs), 2, 2, k, k))
        d_balls[..., :6, 3:6] = d_spin * spin_factor
        d_load_d_force = np.zeros((len(pairs), 2, k))
        d_load_d_force[..., :6] = d_force
        return PairBlocks(load / scales.force, d_balls, d_load_d_force, slip)

    def make_function(oversize):
        def ball_function(balls, extra):
            shift = balls[:, sb.N_UNKNOWNS] if per_ball else extra[0]
            terms = sb.ball_terms(balls[:, :sb.N_UNKNOWNS], shift, contacts, scales, oversize=oversize)
            last.update(terms=terms, oversize=oversize, balls=balls, extra=extra)
            if per_ball:   # eq 54 and the ball's axial balance
                residual = np.concatenate([terms.residual, (terms.axial - targets)[:, None]], axis=1)
                jacobian = np.concatenate([terms.jacobian, terms.axial_gradient[:, None, :]], axis=1)
                return BallBlocks(residual, jacobian)
            m = sb.N_UNKNOWNS   # one common nut shift: the global unknown, the total axial balance its row
            return BallBlocks(terms.residual, terms.jacobian[:, :, :m], terms.jacobian[:, :, m:],
                              np.array([terms.axial.sum() - targets[0]]), terms.axial_gradient[None, :, :m],
                              np.array([[terms.axial_gradient[:, m].sum()]]))

        function = chain_system(ball_function, pair_function, layout, rate_index=2, rate_scale=rate_scale,
                                complementarity="fischer-burmeister")
        function.oversize = oversize   # what the compiled solver (_compiled_solver) needs to solve the same system
        return function

    what = f"{n}-ball screw module"
    solver = _compiled_solver(contacts, layout, per_ball, targets, scales, pair, rate_scale, last=last,
                              constants=setup.kernel_constants)
    warm_newton = newton if solver is None else solver
    guess = np.zeros((n, k))
    extra = np.zeros(layout.n_global)
    forces = None
    if initial is not None and initial.orbit_speed.shape == (n,):
        guess[:, :2] = initial.centre / scales.length
        guess[:, 2] = initial.orbit_speed / scales.orbit
        guess[:, 3:6] = initial.omega / scales.spin
        shifts = np.broadcast_to(np.asarray(initial.nut_shift, dtype=float), (n,)) / scales.length
        if per_ball:
            guess[:, sb.N_UNKNOWNS] = shifts
        else:
            extra[:] = shifts.mean()
        previous = np.asarray(initial.b2b_force, dtype=float)
        if previous.shape == (n_pairs,):
            forces = previous / scales.force
        z, residual, iterations = warm_newton(make_function(module.oversize), layout.pack(guess, forces, extra),
                                              tolerance=tolerance, max_iterations=max_iterations,
                                              what=f"{what} (warm start)", row_tolerance=rows, row_weight=weights)
    else:
        guess[:, 2:6] = setup.rolling_start(contacts)

        def contacts_at(z, oversize):  # the contacts of a converged point, for a stall's reason
            balls_z, _, extra_z = layout.unpack(z)
            shift_z = balls_z[:, sb.N_UNKNOWNS] if per_ball else extra_z[0]
            return sb.ball_terms(balls_z[:, :sb.N_UNKNOWNS], shift_z, contacts, scales, oversize=oversize)

        z, residual, iterations = sb.solve_preloaded(make_function, layout.pack(guess, None, extra), contacts,
                                                     float(np.max(np.abs(loads))) if per_ball else total / n,
                                                     tolerance=tolerance, max_iterations=max_iterations, what=what,
                                                     row_tolerance=rows, row_weight=weights, contacts_at=contacts_at,
                                                     solver=solver)
    balls, forces, extra = chain_forces(z, layout, rate_index=2, rate_scale=rate_scale, tolerance=tolerance,
                                        iterations=iterations, what=what)
    shift = balls[:, sb.N_UNKNOWNS] * 1.0 if per_ball else extra[0]
    balls = balls[:, :sb.N_UNKNOWNS]
    if (last.get("oversize") == module.oversize and np.array_equal(last["balls"][:, :sb.N_UNKNOWNS], balls)
            and np.array_equal(last["extra"], extra)):   # the last evaluation was at the solution
        terms = last["terms"]
    else:
        terms = sb.ball_terms(balls, shift, contacts, scales)
    forces = forces * scales.force
    speeds = b2b_slip(balls[:, 3:6] * scales.spin, pair, module.ball_radius, pairs)[1]
    b2b_loss = module.friction_coefficient * forces * speeds          # lin2019 eq 58: mu F |s|
    return sb.state_from(balls, shift, terms, scales, axial_load=total, b2b_force=forces, b2b_loss=b2b_loss,
                         b2b_slip=speeds, iterations=iterations, residual=float(np.max(np.abs(residual))))


def _compiled_solver(contacts: screw_contacts.BallContacts, layout: ChainLayout, per_ball: bool, targets, scales,
                     pair: PairGeometry, rate_scale: float, compiled=None, last=None, constants=None):
    """A solver with the signature of :func:`lowmodel.solvers.newton` that runs the same Levenberg-Marquardt
    iterations on the same chain compiled (docs/speed.md): in :mod:`lowmodel.screw.ball_kernels` for the dense chains
    (fewer than :data:`lowmodel.b2b_chain.SPARSE_BALLS` balls), in :mod:`lowmodel.screw.ring_kernels` for longer
    chains and rings with one nut shift per ball (the whole screw), of Hertz contacts; None where it does not apply
    (a long chain with a common nut shift, a calibrated contact law) or the kernels are off.  It solves the system of
    ``function.oversize``; where the kernel hands an evaluation back (a contact at rest), the numpy ``newton`` runs
    ``function`` itself.  ``last`` (a dict): a converged solve leaves there the ball terms at its solution, as the
    numpy ``function`` does (``terms``, ``oversize``, ``balls``, ``extra``).  Failures raise the ConvergenceError of
    :func:`lowmodel.solvers.newton` (same message, reason, residual and iterations).  ``constants``: the kernel's
    ``(scalars, live, pair scalars)`` of these arguments if already at hand (:class:`_ChainSetup`)."""
    if contacts.bulk_compliance is not None:
        return None
    long_chain = layout.n_balls >= SPARSE_BALLS
    if long_chain and not per_ball:
        return None   # a long chain with one common nut shift (a global unknown) keeps the numpy Newton
    compiled = compiled or kernels.load(RING_KERNELS if long_chain else sb.KERNELS)
    if compiled is None:
        return None
    module = contacts.module
    if constants is None:   # read-only as _new_chain_setup's: the types numba compiles for (warm_up_kernel)
        constants = (np.array(sb.kernel_scalars(scales, module, None)),
                     checks.read_only(np.ascontiguousarray(layout.live)),
                     checks.read_only(np.array([module.ball_radius, module.friction_coefficient, abs(module.nut_speed),
                                                rate_scale])))
    base, live, pair_scalars = constants
    targets = np.ascontiguousarray(targets, dtype=float)
    failures = {compiled.NOT_CONVERGED: ("Newton did not converge", "iteration limit"),
                compiled.NON_FINITE: ("Newton did not converge", "non-finite residual"),
                compiled.STATIONARY: ("stationary point of |residual|", "stationary point of |residual|"),
                compiled.NO_DESCENT: ("no descent step (damping diverged)", "no descent step")}

    def solver(function, x0, *, tolerance, max_iterations, what, row_tolerance=None, row_weight=None):
        scalars = base.copy()
        scalars[9] = function.oversize
        size = layout.size
        rows = np.full(size, float(tolerance)) if row_tolerance is None else np.asarray(row_tolerance, dtype=float)
        weights = np.ones(size) if row_weight is None else np.asarray(row_weight, dtype=float)
        z, result = np.empty(size), np.empty(size)
        outputs = sb.kernel_outputs(layout.n_balls)
        chain = (layout.n_balls, layout.ring) if long_chain else (layout.n_balls, per_ball, layout.ring)
        status, iterations, norm = compiled.newton(
            np.asarray(x0, dtype=float), *chain, live, targets, contacts.kernel_geometry, scalars,
            sb.kernel_tables(), pair.chord, pair.rotation, pair_scalars, int(max_iterations), rows, weights, z,
            result, outputs)
        if status == compiled.CONVERGED:
            if last is not None:
                balls, _, extra = layout.unpack(z)
                last.update(terms=sb.terms_of_kernel(outputs), oversize=function.oversize, balls=balls, extra=extra)
            return z, result, int(iterations)
        if status == compiled.FALLBACK:
            return newton(function, x0, tolerance=tolerance, max_iterations=max_iterations, what=what,
                          row_tolerance=row_tolerance, row_weight=row_weight)
        message, reason = failures[status]
        raise ConvergenceError(f"{what}: {message}", residual=float(norm), iterations=int(iterations),
                               tolerance=tolerance, reason=reason)

    return solver


RING_KERNELS = "screw.ring_kernels"  # the compiled Newton of long chains with per-ball loads (lowmodel.kernels.load)


def warm_up_ring_kernel(compiled) -> None:
    """Compile (or load from the cache) :mod:`lowmodel.screw.ring_kernels` for the argument types of :func:`solve`
    (a ring of ``SPARSE_BALLS`` balls of lin2019 Table 4 with per-ball loads, one Newton iteration; the read-only
    arrays of a solve's :class:`_ChainSetup` read-only here too: numba compiles a read-only array type apart)."""
    n = SPARSE_BALLS
    contacts = screw_contacts.ball_contacts(screw_contacts.screw_module(), np.zeros(n))
    scales = sb.scales_for(contacts, 100.0)
    layout = ChainLayout(n, sb.N_UNKNOWNS + 1, np.arange(n), ring=True)
    solver = _compiled_solver(contacts, layout, True, checks.read_only(np.ones(n)), scales,
                              pair_geometry(contacts.module), 1.0, compiled)

    def function(_z):   # not called: the kernel converges or stops at the iteration limit
        raise AssertionError("warm-up")

    function.oversize = 0.0
    guess = np.zeros((n, sb.N_UNKNOWNS + 1))
    guess[:, 2] = 0.45
    try:
        solver(function, layout.pack(guess), tolerance=1e-10, max_iterations=1, what="warm-up",
               row_tolerance=checks.read_only(np.full(layout.size, 1e-10)),
               row_weight=checks.read_only(np.ones(layout.size)))
    except (ConvergenceError, AssertionError):   # compiled either way
        pass


def warm_up_kernel(compiled) -> None:
    """Compile (or load from the cache) the chain solver of :mod:`lowmodel.screw.ball_kernels` for the argument
    types of :func:`solve` (two balls of lin2019 Table 4, one Newton iteration)."""
    contacts = screw_contacts.ball_contacts(screw_contacts.screw_module(), np.zeros(2))
    scales = sb.scales_for(contacts, 100.0)
    layout = ChainLayout(2, sb.N_UNKNOWNS, np.array([0]), n_global=1)
    solver = _compiled_solver(contacts, layout, False, checks.read_only(np.array([1.0])), scales,
                              pair_geometry(contacts.module), 1.0, compiled)

    def function(_z):   # not called: the kernel converges or stops at the iteration limit
        raise AssertionError("warm-up")

    function.oversize = 0.0
    try:
        solver(function, layout.pack(np.zeros((2, sb.N_UNKNOWNS))), tolerance=1e-10, max_iterations=1, what="warm-up",
               row_tolerance=checks.read_only(np.full(layout.size, 1e-10)),
               row_weight=checks.read_only(np.ones(layout.size)))
    except (ConvergenceError, AssertionError):   # compiled either way
        pass
