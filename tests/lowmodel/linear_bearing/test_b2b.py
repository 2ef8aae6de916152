"""Ball-to-ball contact of 2..N balls (lin2019 eqs 5-10): physics, complementarity, stability, errors."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.linear_bearing import b2b, ball as bb, contacts as bearing_contacts
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError

from tests.lowmodel.linear_bearing.test_ball import (GEOMETRY, MU, RADIUS, SPEED, VERTICAL, case_angles, eq36,
                                                     power_error)
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from hypothesis import given, strategies as st
from tests.property_support import SLOW, call, real


def module(theta_deg, rho, *, top=(0.0, 0.0), n_balls=2, sides=None, mu=MU, approximate=False):
    """lin2019 Fig 7 module: ball j carries N_x = +-rho N_y (alternating) unless ``sides`` given."""
    angles = np.tile(case_angles(theta_deg, top), (n_balls, 1))
    if sides is None:
        sides = np.where(np.arange(n_balls) % 2 == 0, 1.0, -1.0) * rho * VERTICAL
    if approximate:  # lin2019 Sec 2.4.1: F_BL = F_TR = sqrt2/2 (N_y - N_x), F_BR = F_TL = sqrt2/2 (N_y + N_x)
        up = math.sqrt(0.5) * (VERTICAL - np.asarray(sides))
        down = math.sqrt(0.5) * (VERTICAL + np.asarray(sides))
        forces = np.stack([up, down, up, down], axis=-1)
    else:
        forces = eq36(np.asarray(sides, dtype=float), VERTICAL, angles)
    contact = hertz.solve_load(GEOMETRY, forces)
    return bearing_contacts.contacts_from_forces(angles, forces, contact.a, contact.b / contact.a, ball_radius=RADIUS,
                                   friction_coefficient=mu, groove_velocity=SPEED)


def check_complementarity(state, gaps, tol=1e-10):
    separation = np.diff(state.ball_velocity) / SPEED
    touching = np.asarray(gaps) <= 1e-9 * RADIUS
    force = state.b2b_force / (MU * VERTICAL)
    assert np.all(force >= 0.0)
    assert np.all(force[~touching] == 0.0)
    assert np.all(separation[touching] >= -tol)
    assert np.all(np.abs(force[touching] * separation[touching]) <= tol)


def test_case_a_contact_force_and_power_balance():
    contacts = module(2.0, -0.6)
    free = bb.solve(contacts)
    assert free.velocity_deviation[0] > free.velocity_deviation[1]  # ball 1 (behind) is faster
    state = b2b.solve(contacts, [0.0])
    assert state.b2b_force[0] > 0.0
    assert state.ball_velocity[0] == pytest.approx(state.ball_velocity[1], rel=1e-12)
    assert power_error(state) < 1e-8
    assert state.b2b_friction_loss[0] == pytest.approx(MU * state.b2b_force[0] * state.b2b_slip[0])
    check_complementarity(state, [0.0])
    # the common velocity lies between the free velocities
    assert free.ball_velocity[1] < state.ball_velocity[0] < free.ball_velocity[0]


def test_case_b_mitigation_gives_no_contact_force():
    state = b2b.solve(module(2.0, -0.6, top=(-2.0, 2.0)), [0.0])
    assert abs(state.b2b_force[0]) <= 1e-11 * MU * VERTICAL  # zero to the solver tolerance
    assert np.allclose(state.velocity_deviation, 0.0, atol=1e-12)
    assert power_error(state) < 1e-8


@pytest.mark.parametrize("rho", [-0.6, 0.0, 0.7])
def test_theta_zero_no_contact(rho):
    state = b2b.solve(module(0.0, rho), [0.0])
    assert abs(state.b2b_force[0]) <= 1e-11 * MU * VERTICAL
    np.testing.assert_allclose(state.ball_velocity, SPEED / 2, rtol=1e-12)


def test_separating_balls_and_open_gap_have_zero_force():
    contacts = module(2.0, 0.6)  # ball 1 slower: the balls separate
    state = b2b.solve(contacts, [0.0])
    assert abs(state.b2b_force[0]) <= 1e-11 * MU * VERTICAL and state.ball_velocity[1] > state.ball_velocity[0]
    approaching = module(2.0, -0.6)
    open_state = b2b.solve(approaching, [1e-4])
    free = bb.solve(approaching)
    assert open_state.b2b_force[0] == 0.0
    np.testing.assert_allclose(open_state.ball_velocity, free.ball_velocity, rtol=1e-12)


def test_mirror_symmetry_two_balls():
    """Mirror x -> -x of the whole module: same F_B2B and velocities, omega_y flips."""
    angles = np.radians([[43.0, 46.5, 44.2, 45.7], [44.0, 45.5, 45.2, 44.7]])
    sides = np.array([-50.0, 40.0])
    def build(a, s):
        forces = eq36(s, VERTICAL, a)
        c = hertz.solve_load(GEOMETRY, forces)
        return bearing_contacts.contacts_from_forces(a, forces, c.a, c.b / c.a, ball_radius=RADIUS,
                                                     friction_coefficient=MU, groove_velocity=SPEED)
    state = b2b.solve(build(angles, sides), [0.0])
    mirrored = b2b.solve(build(angles[:, [1, 0, 3, 2]], -sides), [0.0])
    assert state.b2b_force[0] > 0.0
    assert mirrored.b2b_force[0] == pytest.approx(state.b2b_force[0], rel=1e-9)
    np.testing.assert_allclose(mirrored.ball_velocity, state.ball_velocity, rtol=1e-10)
    np.testing.assert_allclose(mirrored.omega[:, 1], -state.omega[:, 1], rtol=1e-7, atol=1e-9)


def test_flipped_b2b_moment_breaks_power_balance():
    """The pitfall of lin2019 Sec 2.2: on ball 2 the contact point is -R_B z, so the B2B friction moment
    keeps its sign. Flipping it (naive 'opposite direction') violates the power balance."""
    contacts = module(2.0, -0.6)
    state = b2b.solve(contacts, [0.0])
    omega = state.omega
    f_dir = -np.array([omega[0, 1] + omega[1, 1], -(omega[0, 0] + omega[1, 0])])
    f_dir /= np.linalg.norm(f_dir)
    friction = MU * state.b2b_force[0] * f_dir
    moment = RADIUS * np.array([-friction[1], friction[0]])  # (R z) x f, the same on both balls
    power_ok = moment @ omega[0] + moment @ omega[1]
    power_flipped = moment @ omega[0] - moment @ omega[1]
    assert power_ok == pytest.approx(-state.b2b_friction_loss[0], rel=1e-9)
    assert abs(power_flipped + state.b2b_friction_loss[0]) > 0.5 * state.b2b_friction_loss[0]


def test_first_order_agreement_with_analytical_epsilon():
    """theta -> 0 with the forces of Sec 2.4.1: eps_num/theta converges and matches eq 33 to 1 %.

    The residual 0.7 % is the linearisation of the friction law (k_f, extreme moment) at the
    theta = 0 velocity centres, |c/a| ~ 0.1 (docs/b2b_bearing.md)."""
    rho = -0.6
    ratio = (1 + rho) / (1 - rho)
    slope_analytical = (1 - ratio ** (2 / 3)) / (1 + ratio ** (2 / 3)) / 2  # lin2019 eq 33 / theta
    slopes = []
    for theta_deg in (0.1, 0.05, 0.025):
        state = bb.solve(module(theta_deg, rho, approximate=True))
        slopes.append(state.velocity_deviation / math.radians(theta_deg))
    slopes = np.array(slopes)
    np.testing.assert_allclose(slopes[:, 0], -slopes[:, 1], rtol=1e-9)  # central symmetry of the loads
    assert abs(slopes[2, 0] - slopes[1, 0]) < 0.5 * abs(slopes[1, 0] - slopes[0, 0]) + 1e-9
    assert slopes[-1, 0] / slope_analytical == pytest.approx(1.0, abs=0.01)


def random_chain(rng, n_balls, theta_max_deg=3.0, rho_max=0.6):
    theta = rng.uniform(-theta_max_deg, theta_max_deg, size=(n_balls, 4)) * np.array([1, 1, 0.3, 0.3])
    angles = math.pi / 4 + np.radians(theta) * np.array([-1, 1, 1, 1])
    sides = rng.uniform(-rho_max, rho_max, size=n_balls) * VERTICAL
    forces = eq36(sides, VERTICAL, angles)
    contact = hertz.solve_load(GEOMETRY, forces)
    mu = float(rng.uniform(0.01, 0.3))
    contacts = bearing_contacts.contacts_from_forces(angles, forces, contact.a, contact.b / contact.a,
                                                     ball_radius=RADIUS, friction_coefficient=mu,
                                                     groove_velocity=SPEED)
    gaps = np.where(rng.random(n_balls - 1) < 0.6, 0.0, rng.uniform(0.0, 0.1 * RADIUS, n_balls - 1))
    return contacts, gaps


@pytest.mark.parametrize("n_balls, seed", [(3, 0), (5, 1), (10, 2), (20, 3), (50, 4)])
def test_random_chains_are_consistent(n_balls, seed):
    rng = np.random.default_rng(seed)
    contacts, gaps = random_chain(rng, n_balls)
    state = b2b.solve(contacts, gaps)
    assert np.all(np.isfinite(state.ball_velocity)) and np.all(np.isfinite(state.b2b_force))
    assert state.residual <= 1e-12 and state.iterations >= 0
    assert power_error(state) < 1e-8
    separation = np.diff(state.ball_velocity) / SPEED
    touching = gaps <= 1e-9 * RADIUS
    force = state.b2b_force / (contacts.friction_coefficient * contacts.normal_forces.max())
    assert np.all(force >= 0.0) and np.all(force[~touching] == 0.0)
    assert np.all(separation[touching] >= -1e-10)
    assert np.all(np.abs(force[touching] * separation[touching]) <= 1e-10)


def test_gap_history_two_balls():
    contacts = module(2.0, -0.6)
    free = bb.solve(contacts)
    gap0 = 0.1 * RADIUS
    closing = free.ball_velocity[0] - free.ball_velocity[1]
    history = b2b.simulate_gaps(contacts, [gap0], 2.0 * gap0 / closing)
    assert history.times[1] == pytest.approx(gap0 / closing, rel=1e-12)  # contact event
    assert history.gaps[1, 0] == 0.0 and history.gaps[-1, 0] == 0.0
    assert history.b2b_force[0, 0] == 0.0 and history.b2b_force[1, 0] > 0.0
    constant = b2b.simulate_gaps(module(2.0, -0.6, top=(-2.0, 2.0)), [gap0], 10.0)
    np.testing.assert_allclose(constant.gaps[:, 0], gap0, rtol=1e-9)


def test_gap_history_chain_never_overlaps():
    rng = np.random.default_rng(7)
    contacts, _ = random_chain(rng, 6)
    gaps = rng.uniform(0.0, 0.05 * RADIUS, 5)
    history = b2b.simulate_gaps(contacts, gaps, 50.0)
    assert np.all(history.gaps >= 0.0) and history.times[-1] == pytest.approx(50.0)
    assert np.all(np.diff(history.times) >= 0.0)


@pytest.mark.parametrize("gaps, match", [([0.0, 0.0], "gaps"), ([-1e-4], "gaps"), ([float("nan")], "gaps")])
def test_bad_gaps(gaps, match):
    with pytest.raises(ValueError, match=match):
        b2b.solve(module(2.0, -0.6), gaps)


def test_bad_simulation_inputs():
    with pytest.raises(ValueError, match="t_end"):
        b2b.simulate_gaps(module(2.0, -0.6), [0.0], 0.0)
    with pytest.raises(ValueError, match="n >= 2"):
        b2b.simulate_gaps(module(2.0, -0.6, n_balls=1), [], 1.0)


def test_convergence_error_carries_residual():
    with pytest.raises(ConvergenceError) as info:
        b2b.solve(module(2.0, -0.6), [0.0], max_iterations=1, tolerance=1e-16)
    assert info.value.residual > 0.0


def test_breakdown_near_four_point_limit_is_diagnosed():
    """Inside the four-point range but past the spin-capacity bound: ConvergenceError naming it."""
    theta = math.radians(3.0)
    limit = math.tan(math.pi / 4 - theta)
    ok = module(3.0, -(limit - 0.05), n_balls=1)
    assert bearing_contacts.spin_capacity_ratio(ok)[0] > 1.0
    bb.solve(ok)
    past = module(3.0, -(limit - 1e-3), n_balls=1)
    assert bearing_contacts.spin_capacity_ratio(past)[0] < 1.0
    with pytest.raises(ConvergenceError, match="spin-capacity ratio 0\\.[0-9]+ < 1") as info:
        bb.solve(past)
    assert info.value.residual > 1e-6


def test_module_contacts_error_exactly_at_loss_of_contact():
    theta = math.radians(3.0)
    limit = math.tan(math.pi / 4 - theta)  # lin2017 eq 37 for ball 1
    contacts = b2b.module_contacts(theta, -limit * (1 - 1e-12))
    assert np.all(contacts.normal_forces > 0.0)
    with pytest.raises(ValueError, match="four-point|contact"):
        b2b.module_contacts(theta, -limit * (1 + 1e-12))
    with pytest.raises(ValueError, match="n_balls"):
        b2b.module_contacts(theta, 0.1, n_balls=0)
    with pytest.raises(ValueError, match="theta"):
        b2b.module_contacts(float("nan"), 0.1)


def test_module_contacts_reproduce_table3():
    state = b2b.solve(b2b.module_contacts(math.radians(2.0), -0.6), [0.0])
    assert state.b2b_force[0] == pytest.approx(4.01, rel=0.03)  # lin2019 Table 3 case (a), numerical


@pytest.mark.parametrize("kwargs, name", [(dict(tolerance=0.0), "tolerance"),
                                          (dict(tolerance=float("nan")), "tolerance"),
                                          (dict(max_iterations=0), "max_iterations"),
                                          (dict(max_iterations=2.5), "max_iterations")])
def test_bad_solver_options(kwargs, name):
    with pytest.raises(ValueError, match=name):
        b2b.solve(module(2.0, -0.6), [0.0], **kwargs)
    with pytest.raises(ValueError, match=name):
        bb.solve(module(2.0, -0.6), **kwargs)


def test_gap_history_separation():
    """Touching balls whose complementarity solution separates them: the gap opens linearly."""
    contacts = module(2.0, 0.6)  # ball 1 (behind) slower
    free = bb.solve(contacts)
    history = b2b.simulate_gaps(contacts, [0.0], 10.0)
    assert np.all(history.b2b_force == 0.0)
    assert history.gaps[-1, 0] == pytest.approx(10.0 * (free.ball_velocity[1] - free.ball_velocity[0]), rel=1e-9)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("top", [(0.0,), (0.0, 0.0, 1.0), ()])
def test_top_deviations_must_be_a_pair(top):
    """(0.0,) ended in IndexError, a 3-tuple was silently truncated."""
    with pytest.raises(ValueError, match="top_deviations"):
        b2b.module_contacts(0.01, 0.5, top_deviations=top)


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("count", [True, False, 2.0, 0])
def test_ball_count_is_an_integer(count):
    with pytest.raises(ValueError, match="n_balls"):
        b2b.module_contacts(0.01, 0.5, n_balls=count)


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("tolerance", [float("nan"), -1e-9, float("inf")])
def test_gap_tolerance_is_checked(tolerance):
    """A NaN gap_tolerance switched B2B contact off silently (every gap <= NaN is False)."""
    contacts = b2b.module_contacts(math.radians(0.1), -0.5)
    with pytest.raises(ValueError, match="gap_tolerance"):
        b2b.solve(contacts, gap_tolerance=tolerance)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SLOW
@given(theta=real(-0.3, 0.3), rho=real(-1.0, 1.0), load=real(1e-3, 1e5), mu=real(1e-6, 1.0),
       velocity=st.sampled_from([-0.5, 0.01, 2.0]), conformity=real(0.5005, 0.7), n_balls=st.integers(1, 4),
       gap=real(0.0, 1e-4))
def test_numerical_b2b(theta, rho, load, mu, velocity, conformity, n_balls, gap):
    contacts = call(b2b.module_contacts, theta, rho, n_balls=n_balls, vertical_force=load, friction_coefficient=mu,
                    groove_velocity=velocity, conformity=conformity)
    if contacts is None:
        return
    state = call(bearing_ball.solve, contacts, allow_inf=("c_over_a",))
    if state is not None:
        assert abs(state.input_power - state.total_loss) <= 1e-8 * abs(state.input_power)
    gaps = np.where(np.arange(n_balls - 1) % 2 == 0, 0.0, gap)
    state = call(b2b.solve, contacts, gaps, allow_inf=("c_over_a",))
    if state is not None:
        assert abs(state.input_power - state.total_loss) <= 1e-8 * abs(state.input_power)
