"""Single-ball quasi-static solver (lin2019 eqs 1-4): physics checks and errors."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from ballbench.lowmodel.linear_bearing import ball as bb
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.errors import ConvergenceError

RADIUS = 5e-3  # lin2019 Table 1
CONFORMITY = 0.56
MU = 0.1
SPEED = 0.01
VERTICAL = 100.0
GEOMETRY = hertz.ball_in_groove(RADIUS, CONFORMITY, youngs_modulus=2.1e11, poisson_ratio=0.28)


def eq36(side, vertical, angles):
    """lin2017 eq 36 (local reference for the tests; the library uses lowmodel.linear_bearing.fourpoint)."""
    bl, br, tr, tl = np.moveaxis(np.asarray(angles, dtype=float), -1, 0)
    return np.stack([-(side * np.cos(br) - vertical * np.sin(br)) / np.sin(bl + br),
                     (side * np.cos(bl) + vertical * np.sin(bl)) / np.sin(bl + br),
                     -(side * np.cos(tl) - vertical * np.sin(tl)) / np.sin(tl + tr),
                     (side * np.cos(tr) + vertical * np.sin(tr)) / np.sin(tl + tr)], axis=-1)


def make_contacts(angles, side, *, mu=MU, speed=SPEED, vertical=VERTICAL):
    angles = np.atleast_2d(np.asarray(angles, dtype=float))
    side = np.broadcast_to(np.asarray(side, dtype=float), angles.shape[:1])
    forces = eq36(side, vertical, angles)
    contact = hertz.solve_load(GEOMETRY, forces)
    return bearing_contacts.contacts_from_forces(angles, forces, contact.a, contact.b / contact.a, ball_radius=RADIUS,
                                   friction_coefficient=mu, groove_velocity=speed)


def case_angles(theta_deg, top=(0.0, 0.0)):
    th = math.radians(theta_deg)
    return math.pi / 4 + np.array([-th, th, math.radians(top[0]), math.radians(top[1])])


def power_error(state):
    return abs(state.input_power - state.total_loss) / abs(state.input_power)


@pytest.mark.parametrize("rho", [-0.8, -0.3, 0.0, 0.5, 0.9])
def test_theta_zero_rolls_at_half_speed(rho):
    state = bb.solve(make_contacts(case_angles(0.0), rho * VERTICAL))
    assert state.ball_velocity[0] == pytest.approx(SPEED / 2, rel=1e-12)
    assert power_error(state) < 1e-8


@pytest.mark.parametrize("theta, rho, top", [(2.0, -0.6, (0, 0)), (3.0, 0.85, (0, 0)), (-2.5, 0.4, (1.0, -0.5)),
                                             (1.0, -0.9, (0, 0)), (0.3, 0.0, (-0.3, 0.3))])
def test_power_balance_and_loss_identity(theta, rho, top):
    state = bb.solve(make_contacts(case_angles(theta, top), rho * VERTICAL))
    assert state.residual <= 1e-12
    assert power_error(state) < 1e-8
    # the loss from the traction power equals the tabulated eq A6 to the map's accuracy
    np.testing.assert_allclose(state.friction_loss, state.friction_loss_table, rtol=1e-5,
                               atol=1e-7 * state.friction_loss.max())
    assert np.all(state.friction_loss >= 0.0)


def test_table2_mitigation_gives_zero_deviation():
    """lin2019 eq 22 insight: Delta beta_TR = Delta beta_BL, Delta beta_TL = Delta beta_BR -> v_B = v/2."""
    for rho in (-0.6, 0.3):
        state = bb.solve(make_contacts(case_angles(2.0, top=(-2.0, 2.0)), rho * VERTICAL))
        assert state.velocity_deviation[0] == pytest.approx(0.0, abs=1e-12)


def test_mirror_symmetry():
    """Mirror x -> -x: BL <-> BR, TR <-> TL, N_x -> -N_x; then v_B, omega_x stay and omega_y flips."""
    angles = np.radians([43.0, 46.5, 44.2, 45.7])
    state = bb.solve(make_contacts(angles, -35.0))
    mirrored = bb.solve(make_contacts(angles[[1, 0, 3, 2]], 35.0))
    assert mirrored.ball_velocity[0] == pytest.approx(state.ball_velocity[0], rel=1e-10)
    assert mirrored.omega[0, 0] == pytest.approx(state.omega[0, 0], rel=1e-10)
    assert mirrored.omega[0, 1] == pytest.approx(-state.omega[0, 1], rel=1e-8, abs=1e-10)
    np.testing.assert_allclose(mirrored.friction_loss[0], state.friction_loss[0, [1, 0, 3, 2]], rtol=1e-9)


def test_reversed_groove_velocity_reverses_motion():
    contacts = make_contacts(case_angles(2.0), -60.0)
    forward = bb.solve(contacts)
    backward = bb.solve(make_contacts(case_angles(2.0), -60.0, speed=-SPEED))
    assert backward.ball_velocity[0] == pytest.approx(-forward.ball_velocity[0], rel=1e-10)
    np.testing.assert_allclose(backward.friction_loss, forward.friction_loss, rtol=1e-9)


def test_jacobian_matches_finite_differences():
    contacts = make_contacts(case_angles(2.0), -60.0)
    reference = float(contacts.normal_forces.max())
    z = np.array([[0.503, 0.71, 0.02, 0.1, 2.0, -3.0, 1.2]])
    terms = bb.ball_terms(z, contacts, reference)
    step = 1e-7
    for k in range(bb.N_UNKNOWNS):
        dz = np.zeros_like(z)
        dz[0, k] = step
        numeric = (bb.ball_terms(z + dz, contacts, reference).residual
                   - bb.ball_terms(z - dz, contacts, reference).residual)[0] / (2 * step)
        np.testing.assert_allclose(terms.jacobian[0, :, k], numeric, rtol=1e-5, atol=1e-7)


def test_finite_at_zero_spin():
    """omega_BL = 0 (c_BL -> inf, pure sliding): residual and Jacobian finite, |f| = mu F against the slip."""
    contacts = make_contacts(case_angles(2.0), -60.0)
    beta = contacts.contact_angles[0, 0]
    omega_x = 0.7
    omega_y = -omega_x * math.tan(beta)  # omega_BL = omega_x sin + omega_y cos = 0
    z = np.array([[0.5, omega_x, omega_y, 0.0, 0.0, 0.0, 0.0]])
    z = bb.with_slip_angles(z, contacts)
    terms = bb.ball_terms(z, contacts, 100.0)
    assert terms.spin_velocity[0, 0] == pytest.approx(0.0, abs=1e-15)
    assert abs(z[0, 3]) == pytest.approx(math.pi / 2)
    assert np.all(np.isfinite(terms.residual)) and np.all(np.isfinite(terms.jacobian))
    np.testing.assert_allclose(terms.residual[0, 3:], 0.0, atol=1e-15)
    assert abs(terms.force[0, 0]) == pytest.approx(contacts.normal_forces[0, 0] / 100.0, rel=1e-6)
    assert np.sign(terms.force[0, 0]) == -np.sign(terms.slide[0, 0])
    assert np.linalg.cond(terms.jacobian[0]) < 1e8


def test_approaching_four_point_limit_solves_or_fails_loudly():
    """rho towards lin2017 eq 37 from inside: converged states balance power; past the last
    full-sliding state the solver raises ConvergenceError (never NaN, never a wrong answer)."""
    theta = math.radians(3.0)
    limit = math.tan(math.pi / 4 - theta)  # -min(tan beta_BL, tan beta_TR)
    solved = []
    for margin in (0.2, 0.1, 0.05, 0.03, 0.01, 1e-3, 1e-6):
        contacts = make_contacts(case_angles(3.0), -(limit - margin) * VERTICAL)
        try:
            state = bb.solve(contacts)
        except ConvergenceError as error:
            assert error.residual > 0.0 and "ball 0" in str(error)
            continue
        solved.append(margin)
        assert np.all(np.isfinite(state.ball_velocity)) and np.all(np.isfinite(state.omega))
        assert state.residual <= 1e-12 and power_error(state) < 1e-8
    assert {0.2, 0.1, 0.05, 0.03} <= set(solved)


def test_iterations_are_few():
    state = bb.solve(make_contacts(case_angles(2.0), -60.0))
    assert 1 <= state.iterations <= 8


def test_convergence_error_reports_residual():
    with pytest.raises(ConvergenceError) as info:
        bb.solve(make_contacts(case_angles(2.0), -60.0), max_iterations=1, tolerance=1e-15)
    assert info.value.residual > 0.0 and info.value.iterations == 1


GOOD = dict(ball_radius=RADIUS, friction_coefficient=MU, groove_velocity=SPEED)


@pytest.mark.parametrize("override, name", [
    (dict(ball_radius=-1e-3), "ball_radius"),
    (dict(ball_radius=float("nan")), "ball_radius"),
    (dict(friction_coefficient=0.0), "friction_coefficient"),
    (dict(groove_velocity=0.0), "groove_velocity"),
    (dict(groove_velocity=float("inf")), "groove_velocity"),
])
def test_bad_scalar_inputs(override, name):
    kwargs = {**GOOD, **override}
    with pytest.raises(ValueError, match=name):
        bearing_contacts.contacts_from_forces(case_angles(1.0), 50.0, 1e-4, 0.2, **kwargs)


@pytest.mark.parametrize("angles", [[0.0, 0.7, 0.7, 0.7], [0.7, 1.6, 0.7, 0.7], [0.7, float("nan"), 0.7, 0.7]])
def test_bad_contact_angles(angles):
    with pytest.raises(ValueError, match="contact_angles"):
        bearing_contacts.contacts_from_forces(angles, 50.0, 1e-4, 0.2, **GOOD)


def test_loss_of_contact_is_an_error():
    with pytest.raises(ValueError, match="normal_forces.*four-point"):
        bearing_contacts.contacts_from_forces(case_angles(1.0), [50.0, 0.0, 50.0, 50.0], 1e-4, 0.2, **GOOD)
    with pytest.raises(ValueError, match="normal_forces"):
        bearing_contacts.contacts_from_forces(case_angles(1.0), [50.0, float("nan"), 50.0, 50.0], 1e-4, 0.2, **GOOD)


def test_solution_satisfies_eq4_with_exact_quadrature():
    """Independent of the tabulated map: eq 4 at the solution with lin2019 eqs A4-A5 by direct quadrature."""
    from ballbench.lowmodel.contact.ellipse_friction import friction_exact

    contacts = make_contacts(case_angles(2.0, (0.5, -0.3)), -60.0)
    state = bb.solve(contacts)
    exact = friction_exact(state.c_over_a[0], contacts.b_over_a[0])
    sign = np.sign(state.spin[0])
    mu_force = MU * contacts.normal_forces[0]
    force = sign * mu_force * exact.force  # f_{i,z}, eq A4
    moment = sign * mu_force * contacts.semi_major[0] * exact.moment  # M_{i,O}, eq A5
    np.testing.assert_allclose(force, state.friction_force[0], rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(moment, state.friction_moment[0], rtol=1e-6, atol=1e-12)
    beta = contacts.contact_angles[0]
    s, c = np.sin(beta), np.cos(beta)
    rows = np.array([[1, 1, 1, 1], [-c[0], -c[1], c[2], c[3]], [s[0], -s[1], -s[2], s[3]]])  # lin2019 eq 4
    moment_rows = np.array([[0, 0, 0, 0], [s[0], -s[1], -s[2], s[3]], [c[0], c[1], -c[2], -c[3]]])
    residual = rows @ force + moment_rows @ (-moment / RADIUS)
    assert np.max(np.abs(residual)) < 1e-6 * MU * contacts.normal_forces.max()


deviation = st.floats(min_value=-3.0, max_value=3.0)


@settings(max_examples=25, deadline=None)
@given(dbl=deviation, dbr=deviation, dtr=deviation, dtl=deviation, rho=st.floats(min_value=-0.5, max_value=0.5))
def test_random_balls_balance_power_and_mirror(dbl, dbr, dtr, dtl, rho):
    """Any deviations within +-3 deg and |rho| <= 0.5: converged, power balanced, mirror-symmetric."""
    angles = math.pi / 4 + np.radians([dbl, dbr, dtr, dtl])
    state = bb.solve(make_contacts(angles, rho * VERTICAL))
    assert state.residual <= 1e-12 and power_error(state) < 1e-8
    mirrored = bb.solve(make_contacts(angles[[1, 0, 3, 2]], -rho * VERTICAL))
    assert mirrored.ball_velocity[0] == pytest.approx(state.ball_velocity[0], rel=1e-9)
    assert mirrored.omega[0, 1] == pytest.approx(-state.omega[0, 1], rel=1e-6, abs=1e-9 * abs(state.omega[0, 0]))
