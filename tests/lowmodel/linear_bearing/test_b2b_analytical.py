"""Analytical B2B model (lin2019 eqs 16-33): derivations re-done numerically, published numbers, limits."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.linear_bearing import b2b_analytical as b2b
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b as numerical_b2b, b2b_analytical as analytical
from hypothesis import given, strategies as st
from tests.property_support import SETTINGS, angle, call, real

BALL_RADIUS = 5e-3  # lin2019 Table 1
MU = 0.1
V = 0.01
N_Y = 100.0


def _psi() -> float:
    geometry = hertz.ball_in_groove(ball_radius=BALL_RADIUS, conformity=0.56, youngs_modulus=2.1e11,
                                    poisson_ratio=0.28)
    return hertz.psi_constant(geometry, BALL_RADIUS)


def _matrices(beta0: float):
    c, s = math.cos(beta0), math.sin(beta0)
    force_rows = np.array([[1, 1, 1, 1], [-c, -c, c, c], [s, -s, -s, s]])   # lin2019 eq 4 with beta_i = beta_0
    moment_rows = np.array([[0, 0, 0, 0], [s, -s, -s, s], [c, c, -c, -c]])
    return force_rows, moment_rows


def _linear_gains(forces, k_f, psi):
    # columns of eq 16: +-(k_f/Psi) mu (R_B F_i)^(2/3) for (BL, BR, TR, TL)
    return k_f / psi * MU * (BALL_RADIUS * forces) ** (2 / 3) * np.array([1, 1, -1, -1])


@pytest.mark.parametrize("beta0_deg", [45.0, 40.0])
def test_eq22_from_eqs_16_19_21(beta0_deg):
    """Solve the linear system of eqs 16 and 19 (matrices at beta_0, diagonal forces equal) and
    evaluate eq 21: the result must be eq 22 (the spin-moment terms cancel)."""
    beta0 = math.radians(beta0_deg)
    rng = np.random.default_rng(2)
    psi, k_f, ellip = _psi(), 1.38, 1.2
    force_rows, moment_rows = _matrices(beta0)
    for _ in range(5):
        f_up, f_down = rng.uniform(20.0, 150.0, 2)
        forces = np.array([f_up, f_down, f_up, f_down])
        delta_beta = rng.uniform(-0.05, 0.05, 4)
        moments = 3 / 8 * psi * ellip * MU * BALL_RADIUS ** (-2 / 3) * forces ** (4 / 3) * np.array([-1, 1, 1, -1])
        system = np.vstack([force_rows * _linear_gains(forces, k_f, psi), [1, -1, -1, 1]])
        rhs = np.concatenate([-moment_rows @ moments,
                              [-(delta_beta[0] + delta_beta[3] - delta_beta[1] - delta_beta[2])]])  # eq 19
        delta_eta = np.linalg.solve(system, rhs)
        epsilon = (1 - math.cos(2 * beta0)) * (-delta_beta[1] - delta_eta[1] + delta_beta[3] + delta_eta[3]) / 2
        assert b2b.velocity_deviation(delta_beta, f_up, f_down, beta0) == pytest.approx(epsilon, rel=1e-10, abs=1e-15)


def _delta_epsilon(forces, load, k_f, psi, beta0=math.pi / 4):
    """Additional deviation of one ball pushed by ``load`` along z: solve eqs 25 and 27, evaluate eq 28."""
    force_rows, _ = _matrices(beta0)
    f = np.array([forces[0], forces[1], forces[0], forces[1]])
    system = np.vstack([force_rows * _linear_gains(f, k_f, psi), [1, -1, -1, 1]])  # eq 25, eq 27
    zeta = np.linalg.solve(system, np.array([load, 0.0, 0.0, 0.0]))
    return (1 - math.cos(2 * beta0)) * (-zeta[1] + zeta[3]) / 2                     # eq 28


def test_eq30_from_eqs_25_27_28_29():
    """Solve eqs 25 and 27 for each ball under +-F_B2B, take eq 28 and impose eq 29: F_B2B must be eq 30."""
    psi, k_f = _psi(), 1.38
    forces_1 = b2b.diagonal_forces(N_Y, -0.6 * N_Y)
    forces_2 = b2b.diagonal_forces(N_Y, 0.6 * N_Y)
    eps_1, eps_2 = 0.0123, -0.004
    # eq 29 is linear in F_B2B: ball 1 gets +F on the rhs of eq 24, ball 2 -F
    per_newton = _delta_epsilon(forces_1, 1.0, k_f, psi) - _delta_epsilon(forces_2, -1.0, k_f, psi)
    force = (eps_2 - eps_1) / per_newton
    expected = b2b.contact_force(eps_1, eps_2, forces_1, forces_2, k_f=k_f, friction_coefficient=MU, psi=psi,
                                 ball_radius=BALL_RADIUS)
    assert force == pytest.approx(float(expected), rel=1e-12)
    assert per_newton < 0.0  # the B2B force slows ball 1 and speeds up ball 2


def test_common_velocity_from_eq28():
    psi, k_f = _psi(), 1.38
    case = b2b.two_ball_case(math.radians(2.0), -0.45, normal_load=N_Y, groove_velocity=V, friction_coefficient=MU,
                             psi=psi, ball_radius=BALL_RADIUS, k_f=k_f)
    force = float(case.b2b_force)
    forces_1 = b2b.diagonal_forces(N_Y, -0.45 * N_Y)
    forces_2 = b2b.diagonal_forces(N_Y, 0.45 * N_Y)
    v_1 = (1 + float(case.epsilon_1) + _delta_epsilon(forces_1, force, k_f, psi)) * V / 2
    v_2 = (1 + float(case.epsilon_2) + _delta_epsilon(forces_2, -force, k_f, psi)) * V / 2
    assert v_1 == pytest.approx(v_2, rel=1e-12)                               # eq 29 holds
    assert float(case.common_velocity) == pytest.approx(v_1, rel=1e-12)


def test_eq33_is_eq22_with_the_case_study_forces():
    theta = np.radians(np.linspace(-3, 3, 13))[:, None]
    rho = np.linspace(-0.9, 0.9, 19)[None, :]
    forces = b2b.diagonal_forces(N_Y, rho * N_Y)
    np.testing.assert_allclose(forces[0], math.sqrt(2) / 2 * (N_Y - rho * N_Y), rtol=1e-14)
    deviations = np.stack(np.broadcast_arrays(-theta, theta, 0 * theta, 0 * theta), axis=-1)
    np.testing.assert_allclose(b2b.side_force_deviation(theta, rho),
                               b2b.velocity_deviation(deviations, *forces), atol=1e-15)


def test_table2_case_a_analytical():
    """lin2019 Table 2 analytical column (see papers/README.md): epsilon_1 = -epsilon_2 = 0.75 %."""
    case = b2b.two_ball_case(math.radians(2.0), -0.6, normal_load=N_Y, groove_velocity=V, friction_coefficient=MU,
                             psi=_psi(), ball_radius=BALL_RADIUS)
    assert abs(100 * float(case.epsilon_1) - 0.75) <= 0.005  # published to two decimals
    assert float(case.epsilon_2) == pytest.approx(-float(case.epsilon_1), rel=1e-14)
    assert b2b.side_force_deviation(math.radians(2.0), -0.6) == pytest.approx(float(case.epsilon_1), rel=1e-14)


def test_table3_case_a_analytical_force():
    """lin2019 Table 3: analytical F_B2B = 3.74 N (k_f = 1.38, Psi recomputed from Hertz theory)."""
    case = b2b.two_ball_case(math.radians(2.0), -0.6, normal_load=N_Y, groove_velocity=V, friction_coefficient=MU,
                             psi=_psi(), ball_radius=BALL_RADIUS, k_f=b2b.K_F_PAPER)
    assert float(case.b2b_force) == pytest.approx(3.74, rel=0.005)
    assert float(case.b2b_friction_loss) == pytest.approx(MU * float(case.b2b_force) * V / math.cos(math.pi / 4),
                                                         rel=1e-14)
    # the contact velocity: both balls move at the S-weighted mean, between the free velocities
    assert float(case.ball_velocity_2) < float(case.common_velocity) < float(case.ball_velocity_1)


def test_table2_3_case_b_mitigation():
    theta = np.radians(np.linspace(-3, 3, 7))[:, None]
    rho = np.linspace(-0.9, 0.9, 7)[None, :]
    top = b2b.mitigating_top_deviations(-theta, theta)
    case = b2b.two_ball_case(theta, rho, normal_load=N_Y, groove_velocity=V, friction_coefficient=MU, psi=_psi(),
                             ball_radius=BALL_RADIUS, delta_beta_top=top)
    np.testing.assert_array_equal(case.epsilon_1, 0.0)
    np.testing.assert_array_equal(case.epsilon_2, 0.0)
    np.testing.assert_array_equal(case.b2b_force, 0.0)
    np.testing.assert_array_equal(case.b2b_friction_loss, 0.0)
    # any load, any bottom deviations
    rng = np.random.default_rng(4)
    bottom = rng.uniform(-0.05, 0.05, (50, 2))
    tr, tl = b2b.mitigating_top_deviations(bottom[:, 0], bottom[:, 1])
    deviations = np.stack([bottom[:, 0], bottom[:, 1], tr, tl], axis=-1)
    np.testing.assert_array_equal(b2b.velocity_deviation(deviations, rng.uniform(1, 200, 50),
                                                         rng.uniform(1, 200, 50)), 0.0)


def test_limits_and_symmetry():
    common = dict(normal_load=N_Y, groove_velocity=V, friction_coefficient=MU, psi=_psi(), ball_radius=BALL_RADIUS)
    rho = np.linspace(-0.9, 0.9, 19)
    at_zero_theta = b2b.two_ball_case(0.0, rho, **common)  # no deviation: v_B = v/2, no contact
    np.testing.assert_array_equal(at_zero_theta.epsilon_1, 0.0)
    np.testing.assert_array_equal(at_zero_theta.ball_velocity_1, V / 2)
    np.testing.assert_array_equal(at_zero_theta.b2b_force, 0.0)
    at_zero_rho = b2b.two_ball_case(np.radians(2.5), 0.0, **common)  # symmetric load: equal velocities
    assert float(at_zero_rho.b2b_force) == 0.0
    # mirror: rho -> -rho swaps the balls; only one sign of (epsilon_1 - epsilon_2) gives contact
    theta = math.radians(2.0)
    plus, minus = b2b.two_ball_case(theta, rho, **common), b2b.two_ball_case(theta, -rho, **common)
    np.testing.assert_allclose(plus.epsilon_1, minus.epsilon_2, atol=1e-16)
    np.testing.assert_allclose(plus.epsilon_1, -plus.epsilon_2, atol=1e-16)
    assert np.all((plus.b2b_force > 0) == (plus.epsilon_1 > plus.epsilon_2))
    assert np.all(((plus.b2b_force > 0) != (minus.b2b_force > 0))[rho != 0])
    # mu -> 0: no friction, no B2B force
    assert float(b2b.two_ball_case(theta, -0.6, **{**common, "friction_coefficient": 0.0}).b2b_force) == 0.0
    # F_B2B is linear in (epsilon_1 - epsilon_2), zero when the balls do not touch
    forces = b2b.diagonal_forces(N_Y, -60.0), b2b.diagonal_forces(N_Y, 60.0)
    args = dict(k_f=1.38, friction_coefficient=MU, psi=_psi(), ball_radius=BALL_RADIUS)
    one = b2b.contact_force(0.01, 0.0, *forces, **args)
    two = b2b.contact_force(0.02, 0.0, *forces, **args)
    assert float(two) == pytest.approx(2 * float(one), rel=1e-14)
    assert float(b2b.contact_force(0.01, 0.0, *forces, touching=False, **args)) == 0.0
    assert float(b2b.contact_force(0.0, 0.01, *forces, **args)) == 0.0


def test_first_order_in_theta():
    """epsilon is linear in the deviations (eq 22): doubling theta doubles epsilon and F_B2B."""
    common = dict(normal_load=N_Y, groove_velocity=V, friction_coefficient=MU, psi=_psi(), ball_radius=BALL_RADIUS)
    one = b2b.two_ball_case(math.radians(1.0), -0.4, **common)
    two = b2b.two_ball_case(math.radians(2.0), -0.4, **common)
    assert float(two.epsilon_1) == pytest.approx(2 * float(one.epsilon_1), rel=1e-14)
    assert float(two.b2b_force) == pytest.approx(2 * float(one.b2b_force), rel=1e-14)


def test_vectorised_shapes():
    theta = np.radians(np.linspace(0, 3, 4))[:, None]
    rho = np.linspace(-0.8, 0.8, 5)[None, :]
    case = b2b.two_ball_case(theta, rho, normal_load=N_Y, groove_velocity=V, friction_coefficient=MU, psi=_psi(),
                             ball_radius=BALL_RADIUS)
    assert case.b2b_force.shape == (4, 5)
    assert np.all(np.isfinite(case.b2b_force)) and np.all(case.b2b_force >= 0.0)


@pytest.mark.parametrize("call, match", [
    (lambda: b2b.side_force_deviation(0.03, 1.0), "rho"),
    (lambda: b2b.side_force_deviation(float("nan"), 0.2), "theta"),
    (lambda: b2b.diagonal_forces(100.0, 100.0), "four-point"),
    (lambda: b2b.diagonal_forces(-1.0, 0.0), "normal_load"),
    (lambda: b2b.diagonal_forces(100.0, 0.0, math.radians(95.0)), "nominal_contact_angle"),
    (lambda: b2b.velocity_deviation([0.0, 0.0, 0.0], 1.0, 1.0), "delta_beta"),
    (lambda: b2b.velocity_deviation([0.0] * 4, 0.0, 1.0), "force_up"),
    (lambda: b2b.contact_force(0.01, 0.0, (1.0, 1.0), (1.0, 1.0), k_f=1.38, friction_coefficient=-0.1,
                               psi=5e-4, ball_radius=5e-3), "friction_coefficient"),
    (lambda: b2b.contact_force(0.01, 0.0, (1.0, 1.0), (1.0, 1.0), k_f=1.38, friction_coefficient=0.1,
                               psi=0.0, ball_radius=5e-3), "psi"),
    (lambda: b2b.contact_force(0.01, 0.0, (1.0, 1.0), (1.0, 1.0), k_f=1.38, friction_coefficient=0.1,
                               psi=5e-4, ball_radius=-5e-3), "ball_radius"),
    (lambda: b2b.contact_force(0.01, 0.0, (1.0, 1.0), (1.0, 1.0), k_f=0.0, friction_coefficient=0.1,
                               psi=5e-4, ball_radius=5e-3), "k_f"),
    (lambda: b2b.friction_loss(-1.0, 0.1, 0.01), "b2b_force"),
    (lambda: b2b.two_ball_case(0.03, 0.99, normal_load=N_Y, groove_velocity=V, friction_coefficient=MU, psi=5e-4,
                               ball_radius=BALL_RADIUS, nominal_contact_angle=math.radians(40.0)), "four-point"),
])
def test_bad_input(call, match):
    with pytest.raises(ValueError, match=match):
        call()


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


RADIUS = 5e-3  # lin2019 Table 1


COMMON = dict(normal_load=100.0, friction_coefficient=0.1, ball_radius=RADIUS,
              psi=hertz.psi_constant(hertz.ball_in_groove(RADIUS, 0.56), RADIUS))


@pytest.mark.filterwarnings("error")
def test_analytical_honours_the_direction_of_motion():
    """Groove moving along -z: ball 2 is behind; the pair that approached now separates and vice versa.

    Mirror image z -> -z: (v, rho) and (-v, -rho) give the same force; the numerical model agrees."""
    theta = math.radians(0.1)
    forward = analytical.two_ball_case(theta, -0.5, groove_velocity=0.01, **COMMON)
    backward = analytical.two_ball_case(theta, -0.5, groove_velocity=-0.01, **COMMON)
    mirrored = analytical.two_ball_case(theta, 0.5, groove_velocity=-0.01, **COMMON)
    assert float(forward.b2b_force) > 0.0
    assert float(backward.b2b_force) == 0.0  # was 0.154 N: the balls move apart
    assert float(mirrored.b2b_force) == pytest.approx(float(forward.b2b_force), rel=1e-14)
    numerical = numerical_b2b.solve(numerical_b2b.module_contacts(theta, -0.5, groove_velocity=-0.01))
    assert float(numerical.b2b_force[0]) == 0.0
    # the approach rate (epsilon_1 - epsilon_2) v/2 decides, also in contact_force
    forces = analytical.diagonal_forces(100.0, -50.0), analytical.diagonal_forces(100.0, 50.0)
    args = dict(k_f=1.38, friction_coefficient=0.1, psi=COMMON["psi"], ball_radius=RADIUS)
    assert float(analytical.contact_force(0.0, 0.01, *forces, groove_velocity=-1.0, **args)) > 0.0
    assert float(analytical.contact_force(0.01, 0.0, *forces, groove_velocity=-1.0, **args)) == 0.0
    assert float(analytical.contact_force(0.01, 0.0, *forces, groove_velocity=0.0, **args)) == 0.0


@pytest.mark.filterwarnings("error")
@pytest.mark.parametrize("theta_deg, rho", [(20.0, -0.5), (20.0, 0.5), (13.0, 0.8), (46.0, 0.0)])
def test_analytical_keeps_the_eq37_range(theta_deg, rho):
    """theta = 20 deg, rho = 0.5: beta_BL = 25 deg, tan 25 deg = 0.466 < 0.5, no four-point contact (was 31-37 N)."""
    with pytest.raises(ValueError, match="rho|contact angles"):
        analytical.two_ball_case(math.radians(theta_deg), rho, groove_velocity=0.01, **COMMON)


@pytest.mark.filterwarnings("error")
def test_analytical_rejects_contact_angles_outside_0_90():
    with pytest.raises(ValueError, match="contact angles"):
        analytical.velocity_deviation([-1.0, 0.0, 0.0, 0.0], 10.0, 10.0)  # beta_BL = 45 - 57 deg < 0
    with pytest.raises(ValueError, match="contact angles"):
        analytical.two_ball_case(0.0, 0.0, groove_velocity=0.01, delta_beta_top=(1.0, 0.0), **COMMON)
    with pytest.raises(ValueError, match="delta_beta_top"):
        analytical.two_ball_case(0.0, 0.0, groove_velocity=0.01, delta_beta_top=(0.0,), **COMMON)


@pytest.mark.filterwarnings("error")
def test_analytical_common_velocity_is_finite_when_the_balls_separate():
    separating = analytical.two_ball_case(math.radians(0.1), 0.5, groove_velocity=0.01, **COMMON)
    assert float(separating.b2b_force) == 0.0
    assert np.isfinite(separating.common_velocity)  # was NaN
    assert float(separating.final_velocity_1) == float(separating.ball_velocity_1)  # free velocities
    assert float(separating.final_velocity_2) == float(separating.ball_velocity_2)
    pressed = analytical.two_ball_case(math.radians(0.1), -0.5, groove_velocity=0.01, **COMMON)
    assert float(pressed.final_velocity_1) == float(pressed.final_velocity_2) == float(pressed.common_velocity)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SETTINGS
@given(theta=real(-0.8, 0.8), rho=real(-1.2, 1.2), load=real(-1.0, 1e5), velocity=real(-1.0, 1.0),
       mu=real(-0.1, 1.5), top=st.tuples(real(-0.2, 0.2), real(-0.2, 0.2)), beta0=angle,
       k_f=real(-0.5, 2.0))
def test_analytical(theta, rho, load, velocity, mu, top, beta0, k_f):
    psi = 5.3e-4
    call(analytical.two_ball_case, theta, rho, normal_load=load, groove_velocity=velocity, friction_coefficient=mu,
         psi=psi, ball_radius=5e-3, k_f=k_f, delta_beta_top=top, nominal_contact_angle=beta0)
    call(analytical.side_force_deviation, theta, rho)
    call(analytical.diagonal_forces, load, rho * load, beta0)
    call(analytical.velocity_deviation, [-theta, theta, top[0], top[1]], abs(load) + 1.0, abs(load) + 2.0, beta0)
    call(analytical.contact_force, theta, -theta, (load, load + 1.0), (load + 2.0, load), k_f=k_f,
         friction_coefficient=mu, psi=psi, ball_radius=5e-3, nominal_contact_angle=beta0, groove_velocity=velocity)
    call(analytical.friction_loss, load, mu, velocity, beta0)
