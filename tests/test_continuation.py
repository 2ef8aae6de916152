"""Globalised solves (issue 10 item 1): continuation where Newton from the cheap start fails.

Each case below raised ConvergenceError before (the issue's reproducer, light loads,
theta close to the eq 37 limit, random 2 N chains) although a state exists
(spin-capacity ratio 11 to 30 000); where no state exists the error says why and
where the path stopped.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel import b2b_relaxation

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.solvers import continuation


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
    and the solver says so (issue 10: the single-ball ratio is no existence bound for touching balls)."""
    theta = math.radians(3.0)
    below = b2b.solve(b2b.module_contacts(theta, -0.7, n_balls=2, friction_coefficient=0.467), [0.0])
    slip = np.hypot(below.slide, below.spin * b2b.module_contacts(theta, -0.7, n_balls=2).semi_major) / 0.01
    assert np.min(slip) < 1e-3 < np.median(slip)  # one contact nearly stuck, the others slide
    with pytest.raises(ConvergenceError) as error:
        b2b.solve(b2b.module_contacts(theta, -0.7, n_balls=2, friction_coefficient=0.5), [0.0])
    # the reason is the relaxation in time's (lowmodel.b2b_relaxation): a ball stalls at a contact
    assert error.value.reason == b2b_relaxation.STALL_REASON
    assert str(error.value).count(bearing_ball.STICK_REASON) == 1  # what the continuation met stays in the message
    name, last = error.value.last_converged
    assert name == "s (mu)" and 0.46 < 0.5 * b2b.MU_PATH_START ** (last - 1.0) < 0.4676  # the mu reached
    assert error.value.min_slip_speed < 1e-2
