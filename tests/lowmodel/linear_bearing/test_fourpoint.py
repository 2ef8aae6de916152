"""lowmodel.linear_bearing.fourpoint: rigid four-point rolling/sliding (lin2017).  Default-run budget 20 s.

The closed forms of the paper (eqs 11, 13, 20, 23, 36, 39-41) appear here only as references.
"""
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.optimize import linprog

from ballbench.lowmodel.linear_bearing import fourpoint
from tests.property_support import SETTINGS, angle, call, real

R_B = 5e-3
MU = 0.1
V = 0.01
N_Y = 100.0
DEG = math.pi / 180


def case1(theta):
    theta = np.asarray(theta, dtype=float)
    return math.pi / 4 + np.stack([0 * theta, 0 * theta, theta, -theta], axis=-1)


def case2(alpha):
    alpha = np.asarray(alpha, dtype=float)
    return math.pi / 4 + np.stack([0 * alpha, 0 * alpha, alpha, 0 * alpha], axis=-1)


def solve(angles, rho, *, mu=MU, v=V, vertical=N_Y, radius=R_B):
    return fourpoint.solve(angles, np.asarray(rho) * vertical, vertical, ball_radius=radius,
                           friction_coefficient=mu, groove_velocity=v)


def positions(angles, radius=R_B):
    """Contact points q_i (lin2017 eq 1 and Fig 2), (..., 4, 3)."""
    bl, br, tr, tl = np.moveaxis(np.asarray(angles), -1, 0)
    zero = np.zeros_like(bl)
    return radius * np.stack([np.stack([-np.sin(bl), -np.cos(bl), zero], -1),
                              np.stack([np.sin(br), -np.cos(br), zero], -1),
                              np.stack([np.sin(tr), np.cos(tr), zero], -1),
                              np.stack([-np.sin(tl), np.cos(tl), zero], -1)], axis=-2)


def denominators(angles):
    """Denominators of lin2017 eq 23 (reference)."""
    bl, br, tr, tl = np.moveaxis(np.asarray(angles), -1, 0)
    return np.stack([np.sin(br + tr) + np.sin(tr + tl) + np.sin(tl - br),
                     np.sin(bl + tl) + np.sin(tr + tl) + np.sin(tr - bl),
                     np.sin(bl + br) + np.sin(bl + tl) + np.sin(br - tl),
                     np.sin(bl + br) + np.sin(br + tr) + np.sin(bl - tr)], axis=-1)


def random_cases(n, seed=0, spread=20 * DEG):
    rng = np.random.default_rng(seed)
    angles = rng.uniform(45 * DEG - spread, 45 * DEG + spread, (n, 4))
    lower, upper = fourpoint.contact_limits(angles)
    rho = lower + (upper - lower) * rng.uniform(0.02, 0.98, n)
    return angles, rho


# --- normal forces (eqs 35-37) ------------------------------------------------------------------
def test_normal_forces_satisfy_eq35():
    angles, rho = random_cases(200)
    side = rho * N_Y
    forces = fourpoint.normal_forces(side, N_Y, angles)
    bl, br, tr, tl = angles.T
    a_n = np.stack([np.stack([np.sin(bl), -np.sin(br), -np.sin(tr), np.sin(tl)], -1),
                    np.stack([np.cos(bl), np.cos(br), -np.cos(tr), -np.cos(tl)], -1),
                    np.stack([0 * bl, 0 * bl, -np.sin(tr), np.sin(tl)], -1),
                    np.stack([0 * bl, 0 * bl, -np.cos(tr), -np.cos(tl)], -1)], axis=-2)   # lin2017 eq 35
    rhs = np.stack([0 * side, 0 * side, side, -N_Y + 0 * side], -1)
    np.testing.assert_allclose(np.einsum("nij,nj->ni", a_n, forces), rhs, atol=1e-12 * N_Y)
    assert np.all(forces > 0)


@pytest.mark.parametrize("end", ["lower", "upper"])
def test_loss_of_four_point_contact_at_eq37(end):
    angles = np.radians([40.0, 47.0, 52.0, 38.0])
    lower, upper = fourpoint.contact_limits(angles)
    limit = float(lower if end == "lower" else upper)
    inside = limit * (1 - 1e-9)
    assert np.all(fourpoint.normal_forces(inside * N_Y, N_Y, angles) > 0)
    with pytest.raises(ValueError, match=r"side_force.*eq 37.*must lie in \(-0\.839\d*, 0\.781\d*\)"):
        fourpoint.normal_forces(limit * (1 + 1e-9) * N_Y, N_Y, angles)
    with pytest.raises(ValueError, match="side_force"):
        solve(angles, limit * (1 + 1e-9))
    # eq 37 in closed form: -min(tan BL, tan TR) < rho < min(tan BR, tan TL)
    assert float(lower) == pytest.approx(-min(math.tan(angles[0]), math.tan(angles[2])), rel=1e-15)
    assert float(upper) == pytest.approx(min(math.tan(angles[1]), math.tan(angles[3])), rel=1e-15)


GOOD = dict(contact_angles=case1(2 * DEG), side_force=10.0, vertical_force=N_Y, ball_radius=R_B,
            friction_coefficient=MU, groove_velocity=V)


@pytest.mark.parametrize("name, value, match", [
    ("vertical_force", 0.0, r"vertical_force.*> 0"),
    ("vertical_force", -5.0, r"vertical_force.*> 0"),
    ("vertical_force", math.nan, "vertical_force"),
    ("side_force", math.nan, "side_force.*finite"),
    ("side_force", math.inf, "side_force.*finite"),
    ("ball_radius", -1e-3, r"ball_radius.*> 0"),
    ("ball_radius", 0.0, r"ball_radius.*> 0"),
    ("ball_radius", math.nan, "ball_radius"),
    ("friction_coefficient", -0.1, r"friction_coefficient.*>= 0"),
    ("friction_coefficient", math.nan, "friction_coefficient.*finite"),
    ("groove_velocity", math.nan, "groove_velocity.*finite"),
    ("contact_angles", np.radians([0.0, 45, 45, 45]), r"contact_angles.*\(0, 90\) deg"),
    ("contact_angles", np.radians([45, 90.0, 45, 45]), r"contact_angles.*\(0, 90\) deg"),
    ("contact_angles", np.radians([45, 45, -10.0, 45]), r"contact_angles.*\(0, 90\) deg"),
    ("contact_angles", np.array([0.7, 0.7, math.nan, 0.7]), r"contact_angles.*\(0, 90\) deg"),
    ("contact_angles", np.radians([45, 45, 45]), "contact_angles.*trailing axis of 4"),
    ("side_force", 200.0, r"side_force.*loss of four-point contact.*must lie in"),
])
def test_bad_input_names_parameter_and_range(name, value, match):
    with pytest.raises(ValueError, match=match):
        fourpoint.solve(**{**GOOD, name: value})


def test_bad_input_normal_forces_and_solve_forces():
    with pytest.raises(ValueError, match=r"contact_angles.*\(0, 90\) deg"):
        fourpoint.normal_forces(0.0, N_Y, np.radians([45, 45, 45, 95.0]))
    with pytest.raises(ValueError, match=r"forces.*> 0"):
        fourpoint.solve_forces(case1(0.0), [10.0, -1.0, 10.0, 10.0], ball_radius=R_B, friction_coefficient=MU,
                               groove_velocity=V)
    with pytest.raises(ValueError, match="first and second"):
        fourpoint.two_point_sliding_ratio(case1(0.01), "TR", "XX")
    with pytest.raises(ValueError, match="tie_tolerance"):
        fourpoint.solve(**GOOD, tie_tolerance=-1.0)


# --- K, C_beta, pure rolling (eqs 9-13, 23, 38) ---------------------------------------------------------------
def test_characteristic_parameters_and_c_beta_match_eqs_13_23():
    angles, rho = random_cases(300, seed=1)
    forces = fourpoint.normal_forces(rho * N_Y, N_Y, angles)
    np.testing.assert_allclose(fourpoint.characteristic_parameters(angles, forces), forces / denominators(angles),
                               rtol=1e-13)
    bl, br, tr, tl = angles.T
    c_beta = np.sin(bl + tl) - np.sin(br + tr) - np.sin(bl - tr) + np.sin(br - tl)   # lin2017 eq 13
    np.testing.assert_allclose(fourpoint.rolling_condition(angles), c_beta, atol=1e-14)
    assert np.all(denominators(angles) > 0)   # Annex A1


def rolling_angles(bl, br, tl):
    """TR from eq 10 so that the pure-rolling condition holds."""
    slope = (math.cos(bl) - math.cos(br)) / (math.sin(bl) + math.sin(br))
    # -(cos tl - cos tr)/(sin tl + sin tr) = slope  <=>  cos(tr) - slope sin(tr) = cos(tl) + slope sin(tl)
    phase = math.atan(slope)
    tr = math.acos((math.cos(tl) + slope * math.sin(tl)) * math.cos(phase)) - phase
    return np.array([bl, br, tr, tl])


@pytest.mark.parametrize("bl, br, tl", [(45 * DEG, 45 * DEG, 45 * DEG), (40 * DEG, 50 * DEG, 35 * DEG),
                                        (60 * DEG, 30 * DEG, 44 * DEG)])
def test_pure_rolling_when_eq10_holds(bl, br, tl):
    angles = rolling_angles(bl, br, tl)
    bl_, br_, tr, tl_ = angles
    lhs = math.sin(bl + tl) + math.sin(br - tl)
    assert lhs == pytest.approx(math.sin(br + tr) + math.sin(bl - tr), abs=1e-14)   # eq 9
    state = solve(angles, 0.1)
    assert state.pure_rolling and not state.sliding.any()
    assert state.friction_loss == 0.0 and np.all(state.friction_forces == 0.0)
    denominator = math.sin(bl + br) + math.sin(bl + tl) + math.sin(br - tl)
    expected = V * np.array([math.sin(bl + br), (math.sin(bl) + math.sin(br)) / R_B,
                             (math.cos(bl) - math.cos(br)) / R_B]) / denominator   # eq 11 (times v)
    np.testing.assert_allclose([state.ball_velocity, *state.omega[:2]], expected, rtol=1e-12)
    assert state.omega[2] == 0.0


def test_theta_zero_is_pure_rolling_with_zero_loss():
    rho = np.linspace(-0.99, 0.99, 199)
    state = solve(case1(0.0), rho)
    assert np.all(state.pure_rolling) and not state.sliding.any()
    assert np.all(state.friction_loss == 0.0)
    np.testing.assert_allclose(state.ball_velocity, V / 2, rtol=1e-14)


# --- one-point sliding (eqs 12-24) ----------------------------------------------------------------
def test_one_point_tr_sliding_matches_eqs_12_to_24():
    angles = np.array([46.0, 43.0, 49.0, 41.0]) * DEG
    rho = 0.05
    state = solve(angles, rho)
    k = state.K
    assert np.argmin(k) == 2 and np.array_equal(state.sliding, [False, False, True, False])
    bl, br, tr, tl = angles
    den = math.sin(bl + br) + math.sin(bl + tl) + math.sin(br - tl)
    c_beta = math.sin(bl + tl) - math.sin(br + tr) - math.sin(bl - tr) + math.sin(br - tl)
    slip_tr = -c_beta * V / den                                                  # eq 13
    assert state.slip_velocity[2] == pytest.approx(slip_tr, rel=1e-12)
    f_tr = -MU * state.normal_forces[2] * math.copysign(1.0, slip_tr)            # eq 14
    d_beta = np.array([math.sin(br + tr) + math.sin(tl + tr) - math.sin(br - tl),
                       -math.sin(bl + tl) - math.sin(tl + tr) + math.sin(bl - tr),
                       -math.sin(bl + br) - math.sin(br + tr) - math.sin(bl - tr)])  # eq 20
    np.testing.assert_allclose(state.friction_forces[[0, 1, 3]], f_tr * d_beta / den, rtol=1e-12)
    assert state.friction_forces[2] == pytest.approx(f_tr, rel=1e-12)
    assert state.friction_loss == pytest.approx(k[2] * V * MU * abs(c_beta), rel=1e-12)     # eq 24
    # eq 12 (third row R_B sin beta_TL, papers/README.md): the three sticking contacts roll
    a_bar = np.array([[1, -R_B * math.cos(bl), R_B * math.sin(bl)], [1, -R_B * math.cos(br), -R_B * math.sin(br)],
                      [1, R_B * math.cos(tl), R_B * math.sin(tl)]])
    motion = np.array([state.ball_velocity, *state.omega[:2]])
    np.testing.assert_allclose(a_bar @ motion, [0, 0, V], atol=1e-15)


def test_eq41_and_eq39_over_theta():
    theta = np.linspace(0.0, 5 * DEG, 101)
    state = solve(case1(theta), 0.0)
    eq41 = V / (1 + np.cos(theta) + np.sin(theta))
    np.testing.assert_allclose(state.ball_velocity, eq41, rtol=1e-9)
    np.testing.assert_allclose(state.omega[:, 0], eq41 * math.sqrt(2) / R_B, rtol=1e-9)
    np.testing.assert_allclose(state.omega[:, 1:], 0.0, atol=1e-9 * V / R_B)
    assert np.all(state.sliding[1:] == [False, False, True, False])
    line = fourpoint.two_point_sliding_ratio(case1(theta), "TR", "BR")
    eq39 = -(1 + np.sin(theta) - np.cos(theta)) / (1 + np.sin(theta) + np.cos(theta))
    np.testing.assert_allclose(line, eq39, rtol=1e-9, atol=1e-15)
    on_line = solve(case1(theta[1:]), line[1:])
    assert np.all(on_line.sliding == [False, True, True, False]) and not np.any(on_line.motion_unique)


def test_eq40_loss_with_eq38():
    theta, rho = np.meshgrid(np.linspace(-5, 5, 21) * DEG, np.linspace(-0.9, 0.9, 37), indexing="ij")
    angles = case1(theta)
    lower, upper = fourpoint.contact_limits(angles)
    inside = (rho > lower) & (rho < upper)
    theta, rho, angles = theta[inside], rho[inside], angles[inside]
    state = solve(angles, rho)
    bl, br, tr, tl = np.moveaxis(angles, -1, 0)
    k38 = N_Y * np.stack([(np.sin(br) - rho * np.cos(br)) / np.sin(bl + br),
                          (np.sin(bl) + rho * np.cos(bl)) / np.sin(bl + br),
                          (np.sin(tl) - rho * np.cos(tl)) / np.sin(tl + tr),
                          (np.sin(tr) + rho * np.cos(tr)) / np.sin(tl + tr)], -1) / denominators(angles)  # eq 38
    np.testing.assert_allclose(state.K, k38, rtol=1e-12)
    eq40 = k38.min(-1) * 2 * V * MU * np.abs(np.sin(theta))
    np.testing.assert_allclose(state.friction_loss, eq40, rtol=1e-9, atol=1e-15)


# --- physics: equilibrium, Coulomb, power balance, dissipation minimum ---------------------------------------
def check_physics(state, angles, mu=MU, v=V):
    q = positions(angles)
    force = np.zeros(state.friction_forces.shape + (3,))
    force[..., 2] = state.friction_forces
    total = force.sum(-2)
    moment = np.cross(q, force).sum(-2)
    scale = mu * state.normal_forces.max(-1)
    np.testing.assert_allclose(total, 0.0, atol=1e-12 * scale.max())                 # eq 19
    np.testing.assert_allclose(moment, 0.0, atol=1e-12 * (scale * R_B).max())
    assert np.all(np.abs(state.friction_forces) <= mu * state.normal_forces * (1 + 1e-9))   # Coulomb bound
    sliding = state.sliding
    coulomb = -mu * state.normal_forces * np.sign(state.slip_velocity)
    np.testing.assert_allclose(state.friction_forces[sliding], coulomb[sliding], rtol=1e-9)  # eqs 14, 27
    # sticking contacts have zero slip, recomputed from the motion (eqs 4, 6)
    omega = state.omega
    ball = state.ball_velocity[..., None] + np.cross(omega[..., None, :], q)[..., 2]
    groove = np.array([0.0, 0.0, 1.0, 1.0]) * np.asarray(v)[..., None]
    slip = ball - groove
    np.testing.assert_allclose(slip[~sliding], 0.0, atol=1e-12 * abs(v))
    np.testing.assert_allclose(slip[sliding], state.slip_velocity[sliding], rtol=1e-9, atol=1e-15)
    # power balance: dissipation = work of the groove drive, v (f_TR + f_TL)
    drive = v * (state.friction_forces[..., 2] + state.friction_forces[..., 3])
    np.testing.assert_allclose(state.friction_loss, drive, rtol=1e-9, atol=1e-15 * np.max(scale) * abs(v))
    assert np.all(state.friction_loss >= 0.0)


def test_physics_random_cases():
    angles, rho = random_cases(2000, seed=3)
    state = solve(angles, rho)
    check_physics(state, angles)
    assert np.all(state.sliding.sum(-1) == 1) and np.all(state.motion_unique)   # no ties in random geometry
    motion = np.concatenate([state.ball_velocity[:, None], state.omega[:, :2]], axis=1)
    np.testing.assert_allclose(state.motion_range, np.stack([motion, motion], axis=1), rtol=1e-9, atol=1e-15)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(10, 80), min_size=4, max_size=4), st.floats(0.02, 0.98),
       st.floats(-1.0, 1.0, allow_subnormal=False))
def test_physics_property(angles_deg, fraction, velocity):
    angles = np.radians(angles_deg)
    lower, upper = fourpoint.contact_limits(angles)
    rho = float(lower + (upper - lower) * fraction)
    state = solve(angles, rho, v=velocity)
    check_physics(state, angles, v=velocity)


def test_state_is_the_minimum_of_dissipation_lp():
    """Weighted L1 fit min sum mu F_i |A u - b|_i (HiGHS LP): same loss, same motion where unique."""
    angles, rho = random_cases(25, seed=4, spread=30 * DEG)
    states = solve(angles, rho)
    for k in range(len(rho)):
        a = fourpoint._rows(angles[k])
        b = np.array([0, 0, V, V])
        weights = MU * states.normal_forces[k]
        # variables (u[3], t[4]): minimise w.t with -t <= A u - b <= t
        c = np.concatenate([np.zeros(3), weights])
        a_ub = np.block([[a, -np.eye(4)], [-a, -np.eye(4)]])
        result = linprog(c, A_ub=a_ub, b_ub=np.concatenate([b, -b]), bounds=[(None, None)] * 3 + [(0, None)] * 4,
                         method="highs", options={"primal_feasibility_tolerance": 1e-10,
                                                  "dual_feasibility_tolerance": 1e-10})
        assert result.status == 0
        assert states.friction_loss[k] == pytest.approx(result.fun, rel=1e-8)
        np.testing.assert_allclose(result.x[:3], [states.ball_velocity[k], *(R_B * states.omega[k, :2])],
                                   rtol=1e-7, atol=1e-12)


def test_spin_cannot_be_balanced():
    """omega_z != 0 slides every contact along local x with one sign: the moment about z cannot vanish."""
    angles, rho = random_cases(50, seed=5)
    state = solve(angles, rho)
    for spin in (1e-3, -1e-3):
        slip_x = spin * R_B * np.ones((50, 4))                   # eqs 4, 6: local x slip omega_z R_B
        slip_z = state.slip_velocity
        friction_x = -MU * state.normal_forces * slip_x / np.hypot(slip_x, slip_z)
        moment_z = R_B * friction_x.sum(-1)                      # eq 18: M_z = R_B f_x per contact
        assert np.all(np.sign(moment_z) == -np.sign(spin)) and np.all(np.abs(moment_z) > 0)


# --- ties (eqs 28-34) -------------------------------------------------------------------------------
def test_case2_two_point_bl_tr_and_three_point_line():
    alpha = 3 * DEG
    angles = case2(alpha)
    state = solve(angles, np.array([0.3, 0.6]))
    assert np.all(state.sliding == [True, False, True, False]) and not np.any(state.motion_unique)
    check_physics(state, angles)
    # admissible motions: hull of the one-point motions of BL and TR (v_B, R_B omega_x, R_B omega_y)
    vertices = []
    for j in (0, 2):
        rows = np.delete(np.arange(4), j)
        vertices.append(np.linalg.solve(fourpoint._rows(angles)[rows], np.array([0, 0, V, V])[rows]))
    vertices = np.array(vertices) / [1.0, R_B, R_B]
    for k in range(2):
        low, high = state.motion_range[k]
        np.testing.assert_allclose(low, vertices.min(0), rtol=1e-12, atol=1e-15)
        np.testing.assert_allclose(high, vertices.max(0), rtol=1e-12, atol=1e-15)
        motion = np.array([state.ball_velocity[k], *state.omega[k, :2]])
        np.testing.assert_allclose(motion, vertices.mean(0), rtol=1e-12, atol=1e-15)   # centroid
    assert vertices[0, 1] != pytest.approx(vertices[1, 1], rel=1e-3)   # the motion is not unique
    line = fourpoint.two_point_sliding_ratio(angles, "BL", "BR")
    on = solve(angles, line)
    assert np.array_equal(on.sliding, [True, True, True, False])
    check_physics(on, angles)
    below = solve(angles, line - 1e-6)
    assert np.array_equal(below.sliding, [False, True, False, False]) and below.motion_unique


def test_four_point_tie():
    """All K equal (eq 34): symmetric angles off the rolling condition, forces chosen so that K_i are equal."""
    angles = np.radians([40.0, 50.0, 47.0, 41.0])
    forces = 10.0 * np.abs(fourpoint._null_vector(angles))
    state = fourpoint.solve_forces(angles, forces, ball_radius=R_B, friction_coefficient=MU, groove_velocity=V)
    assert state.sliding.all() and state.n_sliding == 4
    check_physics(state, angles)
    assert state.friction_loss == pytest.approx(10.0 * MU * V * abs(float(state.C_beta)), rel=1e-12)   # eq 30


# --- symmetry, scaling, broadcasting ----------------------------------------------------------------
def test_mirror_symmetry_and_reversal():
    angles, rho = random_cases(100, seed=6)
    state = solve(angles, rho)
    mirror = solve(angles[:, [1, 0, 3, 2]], -rho)
    np.testing.assert_allclose(mirror.ball_velocity, state.ball_velocity, rtol=1e-12)
    np.testing.assert_allclose(mirror.omega[:, 0], state.omega[:, 0], rtol=1e-12)
    np.testing.assert_allclose(mirror.omega[:, 1], -state.omega[:, 1], rtol=1e-9, atol=1e-12)
    np.testing.assert_array_equal(mirror.sliding, state.sliding[:, [1, 0, 3, 2]])
    np.testing.assert_allclose(mirror.friction_loss, state.friction_loss, rtol=1e-12)
    back = solve(angles, rho, v=-V)
    np.testing.assert_allclose(back.ball_velocity, -state.ball_velocity, rtol=1e-14)
    np.testing.assert_allclose(back.friction_forces, -state.friction_forces, rtol=1e-14)
    np.testing.assert_allclose(back.friction_loss, state.friction_loss, rtol=1e-14)


def test_scaling_in_load_and_mu():
    angles, rho = random_cases(50, seed=7)
    state = solve(angles, rho)
    heavy = solve(angles, rho, vertical=3 * N_Y, mu=0.2)
    np.testing.assert_allclose(heavy.ball_velocity, state.ball_velocity, rtol=1e-14)
    np.testing.assert_allclose(heavy.friction_loss, 6 * state.friction_loss, rtol=1e-12)
    at_rest = solve(angles, rho, v=0.0)
    assert np.all(at_rest.pure_rolling) and not at_rest.sliding.any() and np.all(at_rest.friction_loss == 0.0)
    assert np.all(at_rest.ball_velocity == 0.0) and np.all(at_rest.omega == 0.0)
    zero = solve(angles, rho, mu=0.0)
    assert np.all(zero.friction_loss == 0.0) and np.all(zero.friction_forces == 0.0)


def test_broadcasting_shapes():
    angles = case1(np.radians(np.linspace(-3, 3, 6)).reshape(2, 3))
    state = fourpoint.solve(angles, np.array([0.0, 5.0, -5.0]), N_Y, ball_radius=R_B, friction_coefficient=MU,
                            groove_velocity=V)
    assert state.ball_velocity.shape == (2, 3) and state.omega.shape == (2, 3, 3)
    assert state.sliding.shape == (2, 3, 4) and state.motion_range.shape == (2, 3, 2, 3)
    single = fourpoint.solve(angles[1, 1], 5.0, N_Y, ball_radius=R_B, friction_coefficient=MU, groove_velocity=V)
    assert single.ball_velocity.shape == () and single.friction_forces.shape == (4,)
    np.testing.assert_allclose(single.friction_forces, state.friction_forces[1, 1], rtol=1e-15)
    assert fourpoint.normal_forces(np.zeros(5), N_Y, case1(0.0)).shape == (5, 4)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


angles4 = st.lists(angle, min_size=4, max_size=4)


@SETTINGS
@given(angles=angles4, side=real(-1e4, 1e4), vertical=real(-10.0, 1e4), mu=real(-0.1, 1.5),
       velocity=real(-1.0, 1.0))
def test_fourpoint(angles, side, vertical, mu, velocity):
    call(fourpoint.normal_forces, side, vertical, angles)
    call(fourpoint.contact_limits, angles)
    call(fourpoint.solve, angles, side, vertical, ball_radius=5e-3, friction_coefficient=mu,
         groove_velocity=velocity)
