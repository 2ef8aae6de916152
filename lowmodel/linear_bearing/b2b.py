"""Ball-to-ball (B2B) contact of 2 to N balls in a four-point-contact linear ball bearing.

lin2019 Sec 2.2, eqs 5-10 (low-order numerical model), built on the single-ball
equilibrium of :mod:`lowmodel.linear_bearing.ball` (eq 4).

Balls ``j = 0 .. n-1`` are ordered along +z (ball 0 is "ball 1, behind" of
lin2019 Fig 1).  Pair ``j`` is (ball j, ball j+1); ``gap_j = d_{j,j+1} - 2 R_B``.
Ball j touches ball j+1 at ``+R_B z`` of ball j and at ``-R_B z`` of ball j+1.

Slip at the B2B contact, measured on ball j relative to ball j+1 (eq 5; the
z part vanishes while the balls touch and move together)::

    dv = R_B (omega_y,j + omega_y,j+1,  -(omega_x,j + omega_x,j+1))

Friction on ball j (eq 6): ``f = -mu F_B2B dv/|dv|``; on ball j+1: ``-f``.
Loads on the balls (eq 8 for ball j; "ball 2" of the paper for ball j+1)::

    ball j   : force -F_B2B z,   moment (+R_B z) x f
    ball j+1 : force +F_B2B z,   moment (-R_B z) x (-f) = (+R_B z) x f

i.e. the B2B friction *moment* has the same sign on both balls (the force and
the arm both flip); the power balance of :func:`solve` checks this
(``v sum_top f_i = sum P_i + sum mu F_B2B |dv|``, lin2019 eq 7).

Contact complementarity (eqs 9-10), for a pair that touches (gap <= 0)::

    F_B2B >= 0,   v_B,j+1 - v_B,j >= 0,   F_B2B (v_B,j+1 - v_B,j) = 0

and ``F_B2B = 0`` for an open pair.  Solved as one nonlinear complementarity
problem by a semismooth Newton method on ``min(F_B2B/(mu F_ref),
gamma (v_B,j+1 - v_B,j)/|v|) = 0`` with the equilibrium of all balls: the chain
of :mod:`lowmodel.b2b_chain` (shared with the ball screw and the FE-informed
models), with the B2B loads of :func:`b2b_terms`.  Ball-to-groove normal forces
are not changed by the B2B forces (lin2019 Sec 2.2, "decoupled").

One concept in one file (about 630 lines): the lin2019 B2B model of the linear bearing, its solve and the
fallbacks that establish why a solve fails (the continuation, the walks of
:mod:`lowmodel.linear_bearing.branch_end`, the relaxation in time of :func:`relax_state`, which shares the model's
friction terms, and the Newton closures of :func:`solve`); split, they would cross private names or import each
other.

Time evolution (:func:`simulate_gaps`, lin2019 Fig 10): between events the
quasi-static velocities are constant, so gaps move linearly; events are a
gap closing (exact time) or a pair separating (read from the complementarity
solution at each event).
"""
from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.bearing import GuideLoadCase, LinearGuide, Material
from ballbench.lowmodel.b2b_chain import COMPLEMENTARITY_SCALE, BallBlocks, ChainLayout, PairBlocks, chain_forces, \
    chain_system
from ballbench.lowmodel.b2b_relaxation import Relaxation, relax
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES
from ballbench.lowmodel.linear_bearing import ball as single
from ballbench.lowmodel.linear_bearing import branch_end
from ballbench.lowmodel.linear_bearing import ball_fast
from ballbench.lowmodel.linear_bearing.contacts import BallContacts, ball_contacts
from ballbench.lowmodel.linear_bearing.ball import (
    N_UNKNOWNS,
    SPIN_CAPACITY_REASON,
    STICK_REASON,
    BallState,
    ContinuationPath,
    ball_state,
    ball_terms,
    initial_guess,
    slip_speeds,
    with_slip_angles,
    solve_branch,
    solve_free,
    solve_with_continuation,
    case_state,
)
from ballbench.lowmodel.solvers import ContinuationStep, check_solver_options

__all__ = ["solve", "no_full_sliding_state", "solve_cases", "relax_state", "RELAXATION_FAILED", "simulate_gaps",
           "GapHistory", "contacts",
           "module_contacts",
           "b2b_terms", "coupled_system", "pair_function", "touching_pairs", "MU_PATH_START"]

MU_PATH_START = 100.0  # the mu continuation path of solve() starts at mu / MU_PATH_START
_REGULARISATION = 1e-14  # |dv| floor (units |v|) in dv/|dv|; B2B slip is O(1) in four-point contact
_IDENTITY_2 = np.eye(2)


def contacts(case) -> BallContacts:
    """The contacts of the balls of a :class:`lowmodel.bearing.GuideLoadCase`: its contact angles
    ``beta_0 + deviations`` (BL, BR, TR, TL) for every ball, ``N_y`` on every ball and ``N_x = +-rho N_y``
    alternating (ball 0, "ball 1" behind, ``+rho N_y``; lin2019 Sec 2.4, Fig 7); normal forces from lin2017 eq 36
    (not the sqrt(2)/2 approximation of Sec 2.4.1, which only the analytical model uses), Hertz ellipses of the
    guide's groove (:func:`lowmodel.linear_bearing.contacts.ball_contacts`)."""
    angles = np.tile(case.contact_angles, (case.n_balls, 1))
    try:
        return ball_contacts(angles, case.side_forces, case.vertical_force, **case.guide.keywords)
    except ValueError as error:
        if "side_force" in str(error) and "side_force_ratio" not in str(error):  # name the case's field
            raise ValueError(f"side_force_ratio (N_x = side_force_ratio * vertical_force): {error}") from None
        raise


def module_contacts(theta: float, side_force_ratio: float, *, top_deviations=(0.0, 0.0), n_balls: int = 2,
                    nominal_angle: float = math.pi / 4, vertical_force: float = 100.0, ball_radius: float = 5e-3,
                    conformity: float = 0.56, friction_coefficient: float = 0.1, groove_velocity: float = 0.01,
                    youngs_modulus: float = 2.1e11, poisson_ratio: float = 0.28) -> BallContacts:
    """:func:`contacts` of the lin2019 case study (Sec 2.4, Fig 7; defaults: Table 1) by keywords, for the paper
    figures that sweep one parameter: bottom groove ``(-theta, +theta)``, top groove ``top_deviations``
    ``(Delta beta_TR, Delta beta_TL)`` (Table 2 case (b): ``(-theta, +theta)``); all angles in rad.  Builds the
    :class:`lowmodel.bearing.GuideLoadCase` (its checks) and its contacts."""
    n_balls = checks.count("n_balls", n_balls, 1)
    nominal_angle = checks.contact_angle("nominal_angle", nominal_angle)
    limit = min(nominal_angle, 0.5 * math.pi - nominal_angle)  # beta_0 -+ theta inside (0, 90) deg
    theta = checks.bounded("theta", theta, -limit, limit, "rad",
                           note=f"|theta| below {math.degrees(limit):.4g} deg keeps beta_0 -+ theta in (0, 90) deg; "
                                "radians: 2 deg is 0.0349 rad")
    side_force_ratio = checks.finite("side_force_ratio", side_force_ratio)
    top = checks.finite("top_deviations", top_deviations, "rad")
    if np.shape(top) != (2,):
        raise ValueError("top_deviations must be a pair (Delta beta_TR, Delta beta_TL) [rad], got shape "
                         f"{np.shape(top)}")
    checks.plausible("ball_radius", ball_radius)
    # the keyword entry point's range: theta up to the four-point geometry's limit (checked above), past the 20 deg
    # of a real bearing's deviation (lowmodel.checks.PLAUSIBLE), which the paper figures' sweeps reach
    with checks.beyond_plausible():
        guide = LinearGuide(ball_radius, conformity, nominal_angle, Material(youngs_modulus, poisson_ratio),
                            friction_coefficient, groove_velocity)
        case = GuideLoadCase(guide, vertical_force, side_force_ratio, (-theta, theta, float(top[0]), float(top[1])),
                             n_balls)
    return contacts(case)


def _check_gaps(gaps, n_balls: int, radius: float) -> np.ndarray:
    if gaps is None:
        return np.zeros(n_balls - 1)
    if (type(gaps) is np.ndarray and gaps.dtype == np.float64 and gaps.shape == (n_balls - 1,)
            and (gaps.size == 0 or (gaps.min() >= -1e-9 * radius and gaps.max() < math.inf))):
        return gaps  # the common case, without the checks' array passes (NaN fails the min comparison)
    gaps = checks.real("gaps", gaps).reshape(-1)
    if gaps.shape != (n_balls - 1,):
        raise ValueError(f"gaps must have shape ({n_balls - 1},) (one per neighbouring pair), got {gaps.shape}")
    checks.bounded("gaps", gaps, -1e-9 * radius, math.inf, "m", lower_closed=True,
                   note="rigid balls cannot overlap; -1e-9 R_B allows round-off")
    return gaps


def touching_pairs(gaps, n_balls: int, ball_radius: float, gap_tolerance: float | None = None) -> np.ndarray:
    """Indices of the pairs ``(j, j+1)`` whose gap [m] (shape (n-1,), default all 0) is at most
    ``gap_tolerance`` (default ``1e-9 R_B``); ValueError for a wrong shape, NaN or an overlap."""
    gaps = _check_gaps(gaps, n_balls, ball_radius)
    if gap_tolerance is None:
        gap_tolerance = 1e-9 * ball_radius
    else:  # a NaN tolerance would silently switch B2B contact off
        gap_tolerance = checks.non_negative("gap_tolerance", gap_tolerance, "m")
    return np.flatnonzero(gaps <= gap_tolerance)


def _slip_squared(scaled: np.ndarray):
    """lin2019 eq 5: ``dv = (u_y, -u_x) |v|`` with ``u = (omega_x,j + omega_x,j+1, omega_y,j + omega_y,j+1) R_B/|v|``
    for the ball unknowns ``scaled`` (n, 3); returns ``u`` (n-1, 2) and ``|dv|^2`` (n-1,) in units ``|v|^2``."""
    u = scaled[:-1, 1:3] + scaled[1:, 1:3]
    return u, np.einsum("pi,pi->p", u, u)


def b2b_terms(scaled: np.ndarray, forces: np.ndarray, mu: float):
    """B2B loads on the balls (eqs 5-8) for pairs with normal forces ``forces``.

    scaled (n, 3) ball unknowns; forces (n-1,) in units of mu F_ref.
    Returns (load (n, 3) added to the ball residuals, ``block`` (n-1, 2, 2): d (rows 1, 2 of the
    load on ball j and on ball j+1, the same) / d (x_1, x_2 of ball j and of ball j+1, the same),
    ``d_force`` (n-1, 3, 2): d (rows 0, 1, 2 of the load) / d F_j on ball j ([:, :, 0]) and j+1
    ([:, :, 1]), slip |dv| (n-1,) in units |v|).
    """
    u, squared = _slip_squared(scaled)
    norm = np.sqrt(squared + _REGULARISATION**2)
    unit = u / norm[:, None]  # (-e_y, e_x) with e = dv/|dv|
    scale = -mu * forces
    # eq 6: f = -mu F e on ball j; its moment (+R_B z) x f = (-f_y, f_x) R_B = -mu F unit, the same on ball j+1 (eq 8)
    moment = scale[:, None] * unit
    load = np.zeros((scaled.shape[0], 3))
    load[:-1, 0] = -forces  # ball j (behind): eq 8
    load[1:, 0] += forces  # ball j+1 (in front): force flips, moment does not (arm flips too)
    load[:-1, 1:] += moment
    load[1:, 1:] += moment
    # d moment / d u = -mu F (I - unit unit^T)/|dv|, and u depends on (x_1, x_2) of both balls alike
    block = unit[:, :, None] * unit[:, None, :]
    block -= _IDENTITY_2
    block *= (-scale / norm)[:, None, None]
    d_force = np.empty((u.shape[0], 3, 2))
    d_force[:, 0] = (-1.0, 1.0)
    d_force[:, 1:] = (-mu * unit)[:, :, None]
    return load, block, d_force, np.sqrt(squared)


def no_full_sliding_state(error: ConvergenceError) -> bool:
    """Whether a ConvergenceError of :func:`solve` says lin2019's full-sliding model has no state (a free ball's
    spin-capacity ratio below 1, or the full-sliding branch ending where a contact stops sliding; docs/b2b_bearing.md)
    rather than a solver fault: there the stick/slip law is the model of record (docs/b2b_rolling.md, "Where full
    sliding has no state")."""
    reason = getattr(error, "reason", "") or ""
    return reason == SPIN_CAPACITY_REASON or reason.startswith(STICK_REASON)


def solve(contacts: BallContacts, gaps=None, *, tolerance: float = 1e-12, max_iterations: int = 100,  # noqa: C901 - one solve: direct, free balls, continuation, the walks, the relaxation
          gap_tolerance: float | None = None) -> BallState:
    """Quasi-static motion of ``n >= 1`` balls with ball-to-ball contact (lin2019 eqs 4-10).

    Parameters
    ----------
    contacts : BallContacts of the ``n`` balls, ordered along +z (ball 0 behind)
    gaps : (n-1,) m, ``d_{j,j+1} - 2 R_B`` (default: all touching, 0)
    tolerance : max residual (eq 4/8 in units of ``mu max F``; complementarity)
    gap_tolerance : m, a pair with gap <= this touches (default 1e-9 R_B)

    Returns
    -------
    BallState with ``b2b_force`` (n-1,) [N], ``b2b_friction_loss`` [W],
    ``b2b_slip`` [m/s]; ``iterations`` of the coupled semismooth Newton.
    Raises ConvergenceError with its residual if the solve fails, or if the
    converged point violates complementarity.
    """
    check_solver_options(tolerance, max_iterations)
    n = contacts.n_balls
    touching = touching_pairs(gaps, n, contacts.ball_radius, gap_tolerance)
    if n == 1 or touching.size == 0:
        return single.solve(contacts, tolerance=tolerance, max_iterations=max_iterations)
    mu = contacts.friction_coefficient
    reference_force = float(contacts.normal_forces.max())
    speed = abs(contacts.groove_velocity)
    k = N_UNKNOWNS
    what = f"{n}-ball B2B contact"
    layout = ChainLayout(n, k, touching)
    fast = _solve_compiled(contacts, layout, reference_force, tolerance, max_iterations)
    if fast is not None:
        return fast
    at = {}  # the contacts the coupled system is evaluated for (one system, built once per solve)

    def ball_function(balls, _extra=None):
        terms = ball_terms(balls, at["contacts"], reference_force)
        at["last"] = (balls, at["contacts"], terms)  # the converged point's terms are the last ones evaluated
        return BallBlocks(terms.residual, terms.jacobian)

    systems = {mu: coupled_system(ball_function, layout, mu)}  # one system per friction coefficient (mu path)

    def balls_of(z):
        return layout.unpack(z)[0]

    def with_balls(z, balls):
        z = z.copy()
        z[:n * (k + 1)].reshape(n, k + 1)[:, :k] = balls
        return z

    def pack(balls):
        return layout.pack(balls)

    def solve_at(contacts_s, z0, label=what):
        at["contacts"] = contacts_s
        mu_s = contacts_s.friction_coefficient
        if mu_s not in systems:
            systems[mu_s] = coupled_system(ball_function, layout, mu_s)
        return solve_branch(systems[mu_s], z0, balls_of, contacts_s, tolerance=tolerance,
                            max_iterations=max_iterations, what=label, with_balls=with_balls)

    def mu_at(s):  # the friction coefficient from mu / MU_PATH_START to mu, geometrically (B2B friction grows)
        return dataclasses.replace(contacts, friction_coefficient=mu * MU_PATH_START ** (s - 1.0))

    def start_guess(contacts_s):
        return pack(initial_guess(contacts_s))

    def free_start(contacts_s):  # path starts: every ball solved on its own (light loads need it per ball)
        try:
            return pack(solve_free(contacts_s, reference_force, tolerance, max_iterations)[0])
        except ConvergenceError:
            return start_guess(contacts_s)

    paths = []
    try:  # from rolling at v/2 (cheap) ...
        z, residual, iterations = solve_at(contacts, start_guess(contacts))
    except ConvergenceError as first_error:  # ... else from the solution of every ball on its own ...
        try:
            guess, free_iterations, _ = solve_free(contacts, reference_force, tolerance, max_iterations, paths)
            z, residual, iterations = solve_at(contacts, pack(guess))
            iterations += free_iterations
        except ConvergenceError as error:  # ... else by continuation of the coupled problem
            paths = []
            try:
                (z, residual, iterations), taken = solve_with_continuation(
                    contacts, solve_at, free_start, error if error.iterations else first_error, what=what,
                    balls_of=balls_of, extra_paths=(("mu", MU_PATH_START, mu_at),))
            except ConvergenceError as failure:  # ... else the evidence decides (end of a branch, a gap, or the
                judged = failure  # solver; not where the spin-capacity bound already says why), then the relaxation
                if not failure.reason.startswith(SPIN_CAPACITY_REASON):
                    try:
                        (z, residual, iterations), start_mu = _judged(failure, contacts, solve_at, start_guess, pack,
                                                                      balls_of, reference_force, tolerance,
                                                                      max_iterations)
                        taken, judged = ContinuationPath((), "mu from a probe", start_mu / mu, ()), None
                    except ConvergenceError as error:
                        judged = error
                if judged is not None:
                    (z, residual, iterations), taken = _from_relaxation(contacts, layout, gaps, gap_tolerance,
                                                                        judged, solve_at, what)
            paths.append(dataclasses.replace(taken, balls=tuple(range(n))))
    balls, forces, _ = chain_forces(z, layout, rate_index=0, rate_scale=COMPLEMENTARITY_SCALE, tolerance=tolerance,
                                    iterations=iterations, what=what)
    last_balls, last_contacts, terms = at["last"]
    if last_contacts is not contacts or not np.array_equal(last_balls, balls):
        terms = ball_terms(balls, contacts, reference_force)
    slip = np.sqrt(_slip_squared(balls[:, :3])[1])
    state = ball_state(balls, terms, contacts, reference_force, b2b_force=forces * mu * reference_force,
                       b2b_slip=slip * speed, iterations=iterations, residual=float(np.max(np.abs(residual))))
    return dataclasses.replace(state, continuation=tuple(paths)) if paths else state


def _judged(failure, contacts, solve_at, start_guess, pack, balls_of, reference_force, tolerance, max_iterations):
    """:func:`branch_end.judge` for the coupled solve of :func:`solve` (its closures passed in)."""
    target = contacts.friction_coefficient
    last_contacts = getattr(failure, "last_contacts", None)
    on_mu_path = (last_contacts is not None and failure.last_converged is not None
                  and failure.last_converged[0] == "s (mu)")
    failure.last_mu = float(last_contacts.friction_coefficient) if on_mu_path else None

    def at(mu_p):
        return dataclasses.replace(contacts, friction_coefficient=mu_p)

    def solve_from(mu_p, z0):
        return solve_at(at(mu_p), z0)

    def probe(mu_p):
        try:
            return solve_at(at(mu_p), start_guess(at(mu_p)))
        except ConvergenceError:
            return solve_at(at(mu_p), pack(solve_free(at(mu_p), reference_force, tolerance, max_iterations)[0]))

    def slip_at(z, mu_p):  # the smallest contact slip speed and its contact, the evidence of a walk's stop
        slips = slip_speeds(balls_of(z), at(mu_p))
        ball, contact = np.unravel_index(int(np.argmin(slips)), slips.shape)
        return float(slips[ball, contact]), f"{CONTACT_NAMES[contact]} of ball {ball}"

    return branch_end.judge(failure, target, solve_from, probe, slip_at, stick_reason=STICK_REASON)


RELAXATION_FAILED = "the relaxation settled, but Newton from its state did not converge"
STEEL_DENSITY = 7850.0  # kg/m^3: the ball mass of the relaxation's time scale (lin2019 Table 1: steel)


def _free_start(contacts: BallContacts):
    """The relaxation's second start: every ball solved on its own (lin2019 eq 4), ``v_B`` their mean (touching
    balls move together); None where a ball alone has no state."""
    try:
        free = single.solve(contacts)
    except ConvergenceError:
        return None
    speed = contacts.groove_velocity
    start = np.column_stack([free.ball_velocity / speed, free.omega * contacts.ball_radius / speed])
    start[:, 0] = start[:, 0].mean()
    return start


def relax_state(contacts: BallContacts, gaps=None, *, gap_tolerance: float | None = None, start=None,
                density: float = STEEL_DENSITY, **options) -> Relaxation:
    """Relax the balls of ``contacts`` in time under the friction laws of :func:`solve` (the existence oracle,
    :mod:`lowmodel.b2b_relaxation`): lin2019 eq 4 with the friction map's loads at the current slip directions,
    the B2B loads of eqs 5-8 on touching pairs, their complementarity (eqs 9-10) at every time step.

    ``start`` (n, 3): the velocities ``(v_B, omega_x R_B, omega_y R_B) / |v|`` at ``t = 0``; default: rolling at
    v/2 (the start of :func:`solve`) and, where that does not settle, every ball's own state (lin2019 eq 4 alone,
    ``v_B`` their mean): the first that settles, else the account of the first with the second's appended (a
    verdict is about the transients from these starts: a full-sliding state with a contact slipping far slower
    than the transient's chatter may still exist, docs/b2b_bearing.md); ``gaps`` as :func:`solve` (an open gap
    closing ends the run: a third contact); ``density`` [kg/m^3] of the balls gives the time unit
    ``tau = m |v| / (mu F_ref)``.  ``options`` go to :func:`lowmodel.b2b_relaxation.relax`.  Loads in units
    ``mu F_ref`` (``F_ref`` the largest normal force).
    """
    n = contacts.n_balls
    touching = touching_pairs(gaps, n, contacts.ball_radius, gap_tolerance)
    live = np.zeros(n - 1, dtype=bool)
    live[touching] = True
    reference_force = float(contacts.normal_forces.max())
    mu = contacts.friction_coefficient
    _, _, _, dslide, dspin, _ = contacts.kinematics

    def ball_loads(x):
        unknowns = np.zeros((n, N_UNKNOWNS))
        unknowns[:, :3] = x
        unknowns = with_slip_angles(unknowns, contacts)  # friction along the current slip directions
        terms = ball_terms(unknowns, contacts, reference_force)
        squared = terms.slide ** 2 + terms.spin_velocity ** 2
        safe = np.where(squared > 0.0, squared, 1.0)
        d_phi = (terms.spin_velocity[..., None] * dslide - terms.slide[..., None] * dspin) / safe[..., None]
        jacobian = np.matmul(terms.jacobian[:, :3, 3:], d_phi)  # d load / d phi . d phi / d x
        return terms.residual[:, :3], jacobian, np.stack([terms.slide, terms.spin_velocity], axis=-1)

    def pair_loads(x):  # eqs 5-8 per unit force (b2b_terms): the loads on the balls behind and ahead, and their
        _, turn, d_force, _ = b2b_terms(x, np.ones(n - 1), mu)  # turning with the B2B slip, the same on both balls
        derivative = np.zeros((n - 1, 2, 3, 2, 3))
        derivative[:, :, 1:, :, 1:] = turn[:, None, :, None, :]
        return d_force.transpose(0, 2, 1), derivative

    mass = density * 4.0 / 3.0 * math.pi * contacts.ball_radius ** 3
    speed = abs(contacts.groove_velocity)
    tau = mass * speed / (mu * reference_force)
    open_gaps = None if gaps is None else _check_gaps(gaps, n, contacts.ball_radius)
    options.setdefault("contact_names", CONTACT_NAMES)
    if start is not None:
        return relax(ball_loads, pair_loads, start, touching=live, gaps=open_gaps, gap_scale=speed * tau, **options)
    first = relax(ball_loads, pair_loads, initial_guess(contacts)[:, :3], touching=live, gaps=open_gaps,
                  gap_scale=speed * tau, **options)
    free = None if first.settled else _free_start(contacts)
    if free is None:
        return first
    second = relax(ball_loads, pair_loads, free, touching=live, gaps=open_gaps, gap_scale=speed * tau, **options)
    if second.settled:
        return second
    return dataclasses.replace(first, reason=f"{first.reason} (from rolling at v/2; from every ball's own state: "
                                             f"{second.reason})")


def _from_relaxation(contacts: BallContacts, layout: ChainLayout, gaps, gap_tolerance, failure: ConvergenceError,
                     solve_at, what: str):
    """After the continuation and the walks of :func:`_judged` failed with ``failure``: relax in time
    (:func:`relax_state`); a settled state is the Newton start (``solve_at``), which must converge; else (not at a
    spin-capacity ratio < 1, which holds for any mu) relaxed states beside the target and walks in mu from them
    (:func:`lowmodel.linear_bearing.branch_end.relaxed_beside`, their stops the evidence of a gap:
    :func:`lowmodel.linear_bearing.branch_end.with_gap`); otherwise ConvergenceError
    with the reason the walks established (a branch's end or a gap, :data:`STICK_REASON`) or else the relaxation's
    (attribute ``relaxation``: the :class:`lowmodel.b2b_relaxation.Relaxation`)."""
    relaxation = relax_state(contacts, gaps, gap_tolerance=gap_tolerance)
    base = str(failure).split(" (residual")[0]

    def relaxed_start(relaxed, contacts_r):
        balls = np.zeros((layout.n_balls, N_UNKNOWNS))
        balls[:, :3] = relaxed.velocities
        return layout.pack(with_slip_angles(balls, contacts_r), relaxed.forces)

    searched = (failure.reason.startswith(SPIN_CAPACITY_REASON)  # the bound holds for any mu
                or "full-sliding states again beyond" in failure.reason  # a gap, its ends established by the walks
                or "full-sliding states exist beyond" in failure.reason)
    if not relaxation.settled and not searched:
        def at(mu_p):
            return dataclasses.replace(contacts, friction_coefficient=mu_p)

        def relax_from(mu_p):  # a relaxed state's Newton start at mu_p (from rolling at v/2), None if unsettled
            relaxed = relax_state(at(mu_p), gaps, gap_tolerance=gap_tolerance, start=initial_guess(at(mu_p))[:, :3])
            return relaxed_start(relaxed, at(mu_p)) if relaxed.settled else None

        def slip_at(z, mu_p):
            slips = slip_speeds(layout.unpack(z)[0], at(mu_p))
            ball, contact = np.unravel_index(int(np.argmin(slips)), slips.shape)
            return float(slips[ball, contact]), f"{CONTACT_NAMES[contact]} of ball {ball}"

        result, factor, stops = branch_end.relaxed_beside(
            contacts.friction_coefficient, relax_from, lambda mu_p, z: solve_at(at(mu_p), z), slip_at)
        if result is not None:
            return result, ContinuationPath((), "relaxation beside, mu", factor, (ContinuationStep(1.0,
                                                                                                    int(result[2])),))
        failure = branch_end.with_gap(failure, stops, stick_reason=STICK_REASON)
        base = str(failure).split(" (residual")[0]
    if relaxation.settled:
        start = relaxed_start(relaxation, contacts)
        try:
            z, residual, iterations = solve_at(contacts, start, f"{what}, from the relaxed state")
        except ConvergenceError as error:
            stopped = ConvergenceError(f"{base}; {RELAXATION_FAILED} ({error})", residual=error.residual,
                                       iterations=error.iterations, tolerance=error.tolerance,
                                       reason=RELAXATION_FAILED, last_converged=failure.last_converged)
            stopped.relaxation = relaxation
            stopped.min_slip_speed = getattr(failure, "min_slip_speed", math.nan)
            raise stopped from None
        step = ContinuationStep(1.0, int(iterations))
        return (z, residual, iterations), ContinuationPath((), "relaxation", 1.0, (step,))
    met = f" (continuation: {failure.reason})" if failure.reason else ""
    # the reason: the branch's end or gap where the walks established it (lowmodel.linear_bearing.branch_end),
    # else the relaxation's verdict; both accounts stay in the message
    reason = failure.reason if failure.reason.startswith((STICK_REASON, SPIN_CAPACITY_REASON)) else relaxation.kind
    stopped = ConvergenceError(f"{base}{met}; {relaxation.reason}", residual=failure.residual,
                               iterations=failure.iterations, tolerance=failure.tolerance, reason=reason,
                               last_converged=failure.last_converged)
    stopped.relaxation = relaxation
    stopped.min_slip_speed = getattr(failure, "min_slip_speed", math.nan)
    raise stopped from None


def solve_cases(contacts: BallContacts, balls_per_case: int, gaps=None, *, tolerance: float = 1e-12,
                max_iterations: int = 100, gap_tolerance: float | None = None):
    """Many independent B2B cases at once: balls ``c b .. c b + b - 1`` of ``contacts`` (ordered along +z) are case
    ``c`` (``b = balls_per_case``), every case with the same ``gaps`` (b-1,) m (default all touching).

    Returns :class:`lowmodel.linear_bearing.ball_fast.CaseStates` (``pair``: F_B2B, slip, loss), case ``c``
    equal to :func:`solve` of its contacts (:func:`lowmodel.linear_bearing.ball_fast.case_contacts`) to the last
    bit: the compiled kernels solve the batch (one Newton per case, one batched call), and the cases they
    cannot solve (all cases without kernels) are solved by :func:`solve` one by one, with its continuation.
    Raises what :func:`solve` raises for the first case without a state.
    """
    check_solver_options(tolerance, max_iterations)
    reference = ball_fast.case_reference_forces(contacts, balls_per_case)
    touching = touching_pairs(gaps, balls_per_case, contacts.ball_radius, gap_tolerance)
    if balls_per_case == 1 or touching.size == 0:
        return single.solve_cases(contacts, balls_per_case, tolerance=tolerance, max_iterations=max_iterations)
    layout = ChainLayout(balls_per_case, N_UNKNOWNS, touching)
    states = ball_fast.solve_chains(contacts, balls_per_case, layout.live, reference, tolerance=tolerance,
                                    max_iterations=max_iterations)
    if states is None:
        states = ball_fast.empty_states(reference.size, balls_per_case)
        states.status[:] = -1
    for case in np.flatnonzero(states.status):
        state = solve(ball_fast.case_contacts(contacts, balls_per_case, case), gaps, tolerance=tolerance,
                      max_iterations=max_iterations, gap_tolerance=gap_tolerance)
        ball_fast.store_state(states, case, state)
    return states


def _solve_compiled(contacts: BallContacts, layout: ChainLayout, reference_force: float, tolerance: float,
                    max_iterations: int):
    """:func:`solve`'s first two attempts (the coupled Newton from rolling at v/2, then from every ball solved on
    its own) and its complementarity check by the compiled kernels (:mod:`lowmodel.linear_bearing.ball_fast`);
    None where the kernels are off or the attempts fail (then :func:`solve` runs its numpy path, with the
    continuation, and names the failure)."""
    states = ball_fast.solve_chains(contacts, layout.n_balls, layout.live, reference_force, tolerance=tolerance,
                                    max_iterations=max_iterations)
    if states is None or states.status[0]:
        return None
    return case_state(states, 0)


def coupled_system(ball_function, layout: ChainLayout, mu: float):
    """Residual and Jacobian ``function(z)`` of the balls of ``layout`` with B2B contact (lin2019 eqs 4-10).

    ``ball_function(balls, extra)`` -> :class:`lowmodel.b2b_chain.BallBlocks` of every ball on its own, with
    ``balls`` (n, k) the per-ball unknowns: the first three are ``(v_B, omega_x R_B, omega_y R_B)/|v|``, the
    first three residual rows eq 4 (z force, x and y moments / R_B) in units of ``mu F_ref``; the other
    ``k - 3`` unknowns and rows are the model's own (slip angles of the low-order model; none for
    :mod:`lowmodel.linear_bearing.b2b_traction`).  The B2B loads of eqs 5-8 (:func:`b2b_terms`) are added to
    the eq 4 rows and the complementarity of eqs 9-10 is ``min(F_B2B/(mu F_ref), gamma (v_B,j+1 - v_B,j)/|v|)
    = 0``: the chain of :func:`lowmodel.b2b_chain.chain_system` (force slots in units of ``mu F_ref``).
    """
    return chain_system(ball_function, pair_function(layout, mu), layout, rate_index=0,
                        rate_scale=COMPLEMENTARITY_SCALE)


def pair_function(layout: ChainLayout, mu: float):
    """The B2B loads of eqs 5-8 (:func:`b2b_terms`, looked up at call time) as the pair blocks of the chain
    :class:`lowmodel.b2b_chain.PairBlocks`: on rows 0-2 (eq 4) of balls with ``layout.n_unknowns`` unknowns each."""
    k = layout.n_unknowns

    def function(balls, forces):
        load, block, d_force, slip = b2b_terms(balls[:, :3], forces, mu)
        d_balls = np.zeros((len(forces), 2, 2, k, k))
        d_balls[:, :, :, 1:3, 1:3] = block[:, None, None]  # the B2B moment: rows and columns 1, 2 of both balls
        d_load_d_force = np.zeros((len(forces), 2, k))
        d_load_d_force[:, :, :3] = d_force.transpose(0, 2, 1)
        return PairBlocks(load, d_balls, d_load_d_force, slip)

    return function


@dataclass(frozen=True)
class GapHistory:
    """Piecewise-linear gap history (lin2019 Fig 10).

    times : (k,) s, event times from 0 to ``t_end``
    gaps : (k, n-1) m, gaps at those times (linear in between)
    ball_velocity : (k-1, n) m/s, velocities on each interval
    b2b_force : (k-1, n-1) N, B2B forces on each interval
    iterations : (k-1,) Newton iterations of each quasi-static solve
    """

    times: np.ndarray
    gaps: np.ndarray
    ball_velocity: np.ndarray
    b2b_force: np.ndarray
    iterations: np.ndarray

    def gaps_at(self, time) -> np.ndarray:
        """Gaps [m] at ``time`` [s] (scalar or (k,)), shape (..., n-1)."""
        time = np.asarray(time, dtype=float)
        return np.stack([np.interp(time, self.times, self.gaps[:, j]) for j in range(self.gaps.shape[1])],
                        axis=-1)


def simulate_gaps(contacts: BallContacts, initial_gaps, t_end: float, *, max_events: int = 10000,
                  tolerance: float = 1e-12) -> GapHistory:
    """Gaps between neighbouring balls over time from the quasi-static velocities.

    Parameters
    ----------
    contacts : BallContacts of ``n >= 2`` balls (ordered along +z)
    initial_gaps : (n-1,) m (lin2019 Fig 10: 0.1 R_B)
    t_end : s, end time (> 0)

    Between events every ball moves at its quasi-static velocity (the transient
    of the contact is ignored, lin2019 Sec 2.2), so gaps are linear in time;
    a gap that reaches zero closes exactly at its event time, and a touching
    pair whose complementarity solution separates opens.
    """
    n = contacts.n_balls
    if n < 2:
        raise ValueError(f"simulate_gaps needs n >= 2 balls, got {n}")
    t_end = checks.positive("t_end", t_end, "s")
    gaps = _check_gaps(initial_gaps, n, contacts.ball_radius).copy()
    gap_tolerance = 1e-9 * contacts.ball_radius
    time = 0.0
    times, history, velocities, forces, counts = [0.0], [gaps.copy()], [], [], []
    for _ in range(max_events):
        state = solve(contacts, gaps, tolerance=tolerance, gap_tolerance=gap_tolerance)
        rate = np.diff(state.ball_velocity)  # d gap_j / dt = v_{j+1} - v_j
        touching = gaps <= gap_tolerance
        closing = (~touching) & (rate < 0.0)
        dt = t_end - time
        hit = -1
        if np.any(closing):
            when = np.where(closing, gaps / np.where(closing, -rate, 1.0), np.inf)
            hit = int(np.argmin(when))
            if when[hit] < dt:
                dt = float(when[hit])
            else:
                hit = -1
        gaps = gaps + rate * dt
        gaps[touching & (state.b2b_force > 0.0)] = 0.0  # pairs that stay pressed together
        if hit >= 0:
            gaps[hit] = 0.0
        gaps = np.maximum(gaps, 0.0)
        time += dt
        times.append(time)
        history.append(gaps.copy())
        velocities.append(state.ball_velocity)
        forces.append(state.b2b_force)
        counts.append(state.iterations)
        if time >= t_end:
            break
    else:
        raise ConvergenceError("simulate_gaps: too many contact events", residual=t_end - time,
                               iterations=max_events, tolerance=0.0, reason="too many contact events")
    return GapHistory(np.array(times), np.array(history), np.array(velocities), np.array(forces),
                      np.array(counts))
