"""Globalised solves (docs/b2b_bearing.md, 'Solver'): continuation where Newton from the cheap start fails.

Each case below raised ConvergenceError before (the issue's reproducer, light loads,
theta close to the eq 37 limit, random 2 N chains) although a state exists
(spin-capacity ratio 11 to 30 000); where no state exists the error says why and
where the path stopped.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b, ball as bearing_ball, contacts as bearing_contacts
from ballbench.lowmodel.solvers import continuation
from ballbench.lowmodel import b2b_relaxation, solvers
from hypothesis import given, strategies as st
from tests.property_support import SETTINGS, positive, real


def _power_error(state) -> float:
    return abs(state.input_power - state.total_loss) / abs(state.input_power)


def test_issue_reproducer_converges_by_continuation():
    contacts = b2b.module_contacts(math.radians(2), -0.6, vertical_force=4.6)
    assert np.min(bearing_contacts.spin_capacity_ratio(contacts)) > 10.0
    state = bearing_ball.solve(contacts)
    assert state.continuation, "the direct solve used to fail here: a path must be reported"
    path = state.continuation[0]
    assert path.steps[0].parameter == 0.0 and path.steps[-1].parameter == 1.0
    assert state.residual <= 1e-12
    assert _power_error(state) < 1e-8
    # the same ball a little heavier converges directly and is close (continuity in the load)
    nearby = bearing_ball.solve(b2b.module_contacts(math.radians(2), -0.6, vertical_force=4.7))
    np.testing.assert_allclose(state.velocity_deviation, nearby.velocity_deviation, atol=5e-4)


@pytest.mark.parametrize("vertical_force", [5e-3, 0.05, 1.0, 2.0, 4.6, 7.5])
def test_light_loads_converge(vertical_force):
    """Light loads: the state tends to the rigid lin2017 one (a/R_B -> 0); two touching balls."""
    state = b2b.solve(b2b.module_contacts(math.radians(2), -0.6, vertical_force=vertical_force), [0.0])
    assert np.all(np.isfinite(state.ball_velocity))
    assert state.residual <= 1e-12
    assert _power_error(state) < 1e-8


def test_light_load_tends_to_the_rigid_lin2017_state():
    """As N_y -> 0 the contact ellipses shrink and eq 4 tends to lin2017's rigid point contacts:
    epsilon of ball 1 tends to the rigid value of lin2017 (fourpoint.solve)."""
    from ballbench.lowmodel.linear_bearing import fourpoint

    gaps = []
    for load in (1e-1, 1e-3, 1e-5):
        contacts = b2b.module_contacts(math.radians(2), -0.6, vertical_force=load, n_balls=1)
        state = bearing_ball.solve(contacts)
        rigid = fourpoint.solve(contacts.contact_angles[0], -0.6 * load, load, ball_radius=5e-3,
                                friction_coefficient=0.1, groove_velocity=0.01)
        gaps.append(abs(float(state.velocity_deviation[0]) - (2 * float(rigid.ball_velocity) / 0.01 - 1)))
    assert gaps[0] > gaps[1] > gaps[2]  # approaches the rigid state (1.6856 %) as the load falls
    assert gaps[2] < 1e-4


@pytest.mark.parametrize("theta_deg", [13.75, 14.0])
def test_theta_near_the_four_point_limit(theta_deg):
    """rho = 0.6: four-point contact up to theta = 14.04 deg (lin2017 eq 37); spin-capacity ratio ~11."""
    contacts = b2b.module_contacts(math.radians(theta_deg), 0.6, n_balls=1)
    state = bearing_ball.solve(contacts)
    assert state.residual <= 1e-12 and _power_error(state) < 1e-8


def test_random_light_chains():
    """2 N chains of 2-7 balls, random angles and side loads, all touching (11 of 20 failed before)."""
    rng = np.random.default_rng(0)
    for _ in range(8):
        n = int(rng.integers(2, 8))
        theta = np.radians(rng.uniform(-3, 3, (n, 2)))
        angles = math.pi / 4 + np.column_stack([-theta[:, 0], theta[:, 0], 0.3 * theta[:, 1], -0.3 * theta[:, 1]])
        contacts = bearing_contacts.ball_contacts(angles, rng.uniform(-0.6, 0.6, n) * 2.0, 2.0, ball_radius=5e-3,
                                              conformity=0.56, friction_coefficient=0.1, groove_velocity=0.01)
        state = b2b.solve(contacts, np.zeros(n - 1))
        assert state.residual <= 1e-12
        assert _power_error(state) < 1e-8


def test_no_state_names_reason_and_last_converged_parameter():
    """Near the rho limit (spin-capacity ratio < 1) no full-sliding state exists: the error says so."""
    theta = math.radians(3.0)
    low = -math.tan(math.pi / 4 - theta)
    contacts = b2b.module_contacts(theta, low + 1e-6, n_balls=1)
    assert np.min(bearing_contacts.spin_capacity_ratio(contacts)) < 1.0
    with pytest.raises(ConvergenceError, match="spin-capacity ratio") as error:
        bearing_ball.solve(contacts)
    assert error.value.reason == "spin-capacity ratio < 1"
    assert error.value.residual > 0.0


def test_continuation_stops_at_a_fold():
    """x^2 = 1 - 2 s has solutions only up to s = 1/2 (a fold): the path stops there and says so."""
    def solve_at(s, x0):
        x = float(x0[0])
        for iteration in range(1, 40):
            value = x * x - (1.0 - 2.0 * s)
            if abs(value) < 1e-12:
                return np.array([x]), np.array([value]), iteration
            x = x - value / (2.0 * x)
            if not math.isfinite(x) or abs(x) > 1e6:
                break
        raise ConvergenceError("toy", residual=abs(value), iterations=iteration, tolerance=1e-12)

    with pytest.raises(ConvergenceError, match="stopped at") as error:
        continuation(solve_at, np.array([1.0]), what="toy", name="s")
    name, last = error.value.last_converged
    assert name == "s" and 0.45 < last <= 0.5
    assert "fold" in error.value.reason
    x, _, path = continuation(lambda s, x0: solve_at(0.4 * s, x0), np.array([1.0]), what="toy")
    assert path[-1].parameter == 1.0 and float(x[0]) == pytest.approx(math.sqrt(0.2), rel=1e-10)


def test_touching_pair_ends_where_a_contact_stops_sliding():
    """Two touching balls at theta = 3 deg, rho = -0.7 (spin-capacity ratio 4.2): the B2B force grows with mu until
    the BL contact of ball 0 stops sliding near mu = 0.4675; beyond, the continued branch slips against its friction
    and the solver says so (docs/b2b_bearing.md, 'validity': the single-ball ratio is no existence bound for touching
    balls)."""
    theta = math.radians(3.0)
    below = b2b.solve(b2b.module_contacts(theta, -0.7, n_balls=2, friction_coefficient=0.467), [0.0])
    slip = np.hypot(below.slide, below.spin * b2b.module_contacts(theta, -0.7, n_balls=2).semi_major) / 0.01
    assert np.min(slip) < 1e-3 < np.median(slip)  # one contact nearly stuck, the others slide
    with pytest.raises(ConvergenceError) as error:
        b2b.solve(b2b.module_contacts(theta, -0.7, n_balls=2, friction_coefficient=0.5), [0.0])
    # the reason is the branch's end established by the walks (lowmodel.linear_bearing.branch_end); the relaxation
    # in time (lowmodel.b2b_relaxation) agrees: a ball stalls at a contact
    assert error.value.reason.startswith(bearing_ball.STICK_REASON)
    assert error.value.relaxation.kind == b2b_relaxation.STALL_REASON
    assert bearing_ball.STICK_REASON in str(error.value)  # what the continuation met stays in the message
    assert b2b_relaxation.STALL_REASON in str(error.value)  # and the relaxation's account
    name, last = error.value.last_converged
    assert name == "s (mu)" and 0.46 < 0.5 * b2b.MU_PATH_START ** (last - 1.0) < 0.4676  # the mu reached
    assert error.value.min_slip_speed < 1e-2


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


def _square(c):
    return lambda x: (x * x - c, np.diag(2.0 * x))


@pytest.mark.filterwarnings("error")
def test_newton_refuses_an_infinite_tolerance_and_bool_iterations():
    with pytest.raises(ValueError, match="tolerance"):  # returned the start x0 = 1 of x^2 = 4 as converged
        solvers.newton(_square(4.0), np.array([1.0]), tolerance=math.inf, max_iterations=20, what="x^2 = 4")
    with pytest.raises(ValueError, match="max_iterations"):
        solvers.newton(_square(4.0), np.array([1.0]), tolerance=1e-12, max_iterations=True, what="x^2 = 4")


@pytest.mark.filterwarnings("error")
def test_continuation_options_and_max_steps():
    def solve_at(s, x0):
        return solvers.newton(_square(1.0 + s), x0, tolerance=1e-12, max_iterations=30, what="x^2 = 1 + s")

    with pytest.raises(ValueError, match="max_steps"):  # was ConvergenceError with an infinite residual
        solvers.continuation(solve_at, np.array([1.0]), what="path", max_steps=0)
    with pytest.raises(ValueError, match="initial_step"):
        solvers.continuation(solve_at, np.array([1.0]), what="path", initial_step=math.nan)
    with pytest.raises(ConvergenceError) as stopped:  # a path with no fold that runs out of steps
        solvers.continuation(solve_at, np.array([1.0]), what="path", max_steps=1)
    assert stopped.value.reason == "max_steps reached"  # was "continuation stopped (fold or no state beyond)"
    assert math.isfinite(stopped.value.residual) and stopped.value.last_converged == ("s", 0.25)
    x, _, _ = solvers.continuation(solve_at, np.array([1.0]), what="path")
    assert x[0] == pytest.approx(math.sqrt(2.0), rel=1e-12)


@pytest.mark.filterwarnings("error")
def test_solve_with_restarts_needs_an_attempt():
    with pytest.raises(ValueError, match="attempts"):  # was ConvergenceError with an infinite residual
        solvers.solve_with_restarts(_square(4.0), np.array([1.0]), lambda x: None, tolerance=1e-12,
                                    max_iterations=20, what="x^2 = 4", attempts=0)


@pytest.mark.filterwarnings("error")
def test_newton_huge_trial_step_is_rejected_without_a_warning():
    """x^2 = 2 from x0 = -2.7e-112: the first Levenberg-Marquardt trial step is ~1e111 and its merit |r|^2
    overflows (it was a RuntimeWarning).  newton rejects it and raises damping; x0 is a stationary point of |r|^2
    to double precision (predicted decrease 1e-111 against a merit of 16), so it ends in a ConvergenceError
    naming that, with no warning on the way."""
    import warnings

    import numpy as np

    from ballbench.lowmodel import solvers

    def quadratic(x):
        return x * x - 2.0, np.diag(2.0 * x)

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(ConvergenceError, match="no descent step"):
            solvers.newton(quadratic, np.full(4, -2.7e-112), tolerance=1e-12, max_iterations=200, what="x^2 = 2")


@pytest.mark.filterwarnings("error")
def test_restarts_that_use_up_the_iteration_budget_end_in_a_convergence_error():
    """solve_with_restarts shares max_iterations among its runs; when a restart came after the budget was used
    up it called newton(max_iterations=0), which the input check refuses with a ValueError (the default
    lin2019-stability run errored on it).  Now: ConvergenceError, or the restart point if it already solves."""
    import numpy as np

    from ballbench.lowmodel import solvers

    def quadratic(x):
        return x * x - 4.0, np.diag(2.0 * x)

    _, _, needed = solvers.newton(quadratic, np.array([3.0]), tolerance=1e-12, max_iterations=50, what="x^2 = 4")

    def away(x):  # reject the root +2 and restart from 3 (converges again, needing the same iterations)
        return None if x[0] < 0 else (np.array([3.0]), 1.0)

    with pytest.raises(ConvergenceError, match="did not converge"):
        solvers.solve_with_restarts(quadratic, np.array([3.0]), away, tolerance=1e-12, max_iterations=needed,
                                    what="x^2 = 4")

    def to_the_other_root(x):  # reject +2 and restart at the root -2 itself: accepted with no further step
        return None if x[0] < 0 else (np.array([-2.0]), 1.0)

    x, _, total = solvers.solve_with_restarts(quadratic, np.array([3.0]), to_the_other_root, tolerance=1e-12,
                                              max_iterations=needed, what="x^2 = 4")
    assert x[0] == -2.0 and total == needed


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


def _quadratic(c):
    """x^2 = c: a root for c >= 0, none (a minimum of |r| at x = 0) for c < 0."""
    return lambda x: (x * x - c, np.diag(2.0 * x))


@SETTINGS
@given(c=real(-10.0, 10.0), x0=real(-100.0, 100.0), size=st.integers(1, 4),
       tolerance=st.one_of(positive(1e-14, 1e-2), st.sampled_from([0.0, -1.0, math.nan, math.inf])),
       iterations=st.one_of(st.integers(0, 80), st.sampled_from([True, 2.5])))
def test_newton(c, x0, size, tolerance, iterations):
    try:
        x, residual, count = solvers.newton(_quadratic(c), np.full(size, x0), tolerance=tolerance,
                                            max_iterations=iterations, what="x^2 = c")
    except ValueError as error:
        assert "tolerance" in str(error) or "max_iterations" in str(error), error
        return
    except ConvergenceError as error:
        assert math.isfinite(error.residual) and "x^2 = c" in str(error)
        return
    # never an unconverged point, never an accepted nonsense option
    assert 0.0 < tolerance < math.inf and iterations is not True and isinstance(iterations, int)
    assert np.max(np.abs(x * x - c)) <= tolerance and count <= iterations  # (c < -tolerance: never here)
    assert np.all(np.isfinite(residual))


@SETTINGS
@given(fold=real(0.05, 2.0), initial=st.one_of(positive(1e-3, 1.0), st.sampled_from([0.0, -0.25, math.nan])),
       min_step=st.one_of(positive(1e-6, 0.5), st.sampled_from([0.0, -1.0])),
       max_steps=st.one_of(st.integers(0, 50), st.just(True)))
def test_continuation(fold, initial, min_step, max_steps):
    """Root of x^2 = 1 - s / fold from x = 1 at s = 0: exists up to s = fold (a fold there)."""
    def solve_at(s, x0):
        return solvers.newton(_quadratic(1.0 - s / fold), x0, tolerance=1e-12, max_iterations=30, what="fold")

    try:
        x, residual, path = solvers.continuation(solve_at, np.array([1.0]), what="fold", initial_step=initial,
                                                 min_step=min_step, max_steps=max_steps)
    except ValueError as error:
        assert any(name in str(error) for name in ("initial_step", "min_step", "max_steps")), error
        return
    except ConvergenceError as error:
        assert math.isfinite(error.residual) and error.last_converged is not None
        assert error.last_converged[1] <= fold + 1e-12  # never beyond the fold
        return
    assert fold >= 1.0 and path[-1].parameter == 1.0 and abs(x[0] ** 2 - (1.0 - 1.0 / fold)) <= 1e-12


@SETTINGS
@given(c=real(0.0, 10.0), attempts=st.one_of(st.integers(-1, 4), st.just(True)))
def test_solve_with_restarts(c, attempts):
    """The positive root of x^2 = c: a converged negative root is rejected and restarted from -x."""
    def restart(x):
        return None if x[0] >= 0.0 else (-x, float(-x[0]))

    try:
        x, _, _ = solvers.solve_with_restarts(_quadratic(c), np.array([-3.0]), restart, tolerance=1e-12,
                                              max_iterations=60, what="root", attempts=attempts)
    except ValueError as error:
        assert "attempts" in str(error), error
        return
    except ConvergenceError as error:
        assert math.isfinite(error.residual)
        return
    assert x[0] >= 0.0 and abs(x[0] ** 2 - c) <= 1e-12


@pytest.mark.parametrize("weighted", [False, True])
def test_a_deferred_jacobian_is_called_once_per_step_and_gives_the_same_steps(weighted):
    # the function returns its Jacobian as a function of no arguments: newton calls it only where it takes a step
    # (not at rejected trials nor at the converged point), and the iterates equal those of the Jacobian given
    def function(x):
        return np.array([np.arctan(x[0]) - 0.3, x[1] ** 3 + x[0] - 1.0]), np.array([[1.0 / (1.0 + x[0] ** 2), 0.0],
                                                                                       [1.0, 3.0 * x[1] ** 2]])
    calls, points = [], []

    def deferred(x):
        residual, jacobian = function(x)
        points.append(x.copy())
        return residual, lambda: calls.append(1) or jacobian

    options = dict(tolerance=1e-12, max_iterations=80, what="arctan", row_weight=np.array([1.0, 3.0]) if weighted
                   else None)
    x0 = np.array([10.0, 1.0])  # far: the first steps of Levenberg-Marquardt are rejected
    plain = solvers.newton(function, x0, **options)
    lazy = solvers.newton(deferred, x0, **options)
    assert np.array_equal(plain[0], lazy[0]) and plain[2] == lazy[2]
    assert len(calls) == lazy[2] and len(points) > lazy[2] + 1  # one per step; trials rejected on the way


def test_a_deferred_ball_jacobian_defers_the_chains():
    from ballbench.lowmodel.b2b_chain import BallBlocks, ChainLayout, PairBlocks, chain_system

    layout = ChainLayout(2, 1, np.array([0]))

    def balls(states, _extra=None):
        return BallBlocks(states ** 3 - 1.0, 3.0 * states[:, :, None] ** 2)

    def lazy(states, _extra=None):
        blocks = balls(states)
        return BallBlocks(blocks.residual, lambda: blocks.jacobian)

    def pair(states, forces):
        load = np.zeros((2, 1))
        load[0, 0], load[1, 0] = forces[0], -forces[0]
        d_balls = np.zeros((1, 2, 2, 1, 1))
        d_force = np.array([[[1.0], [-1.0]]])
        return PairBlocks(load, d_balls, d_force, np.zeros(1))

    z = np.array([1.2, 0.1, 0.7, 0.0])
    plain = chain_system(balls, pair, layout, rate_index=0, rate_scale=1.0)(z)
    deferred = chain_system(lazy, pair, layout, rate_index=0, rate_scale=1.0)(z)
    assert np.array_equal(plain[0], deferred[0]) and callable(deferred[1])
    assert np.array_equal(plain[1], deferred[1]())
