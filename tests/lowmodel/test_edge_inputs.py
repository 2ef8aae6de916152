"""Edge inputs of issue 10 (item 6): each case failed (NaN, IndexError, silent wrong answer) before its fix."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.lowmodel.linear_bearing import b2b_analytical as analytical
from ballbench.lowmodel.screw import kinematics as screw

RADIUS = 5e-3  # lin2019 Table 1
COMMON = dict(normal_load=100.0, friction_coefficient=0.1, ball_radius=RADIUS,
              psi=hertz.psi_constant(hertz.ball_in_groove(RADIUS, 0.56), RADIUS))


pytestmark = pytest.mark.filterwarnings("error")  # every warning fails the test


# --- analytical model (lin2019 eqs 22, 30) ---------------------------------------------------------
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
    numerical = b2b.solve(b2b.module_contacts(theta, -0.5, groove_velocity=-0.01))
    assert float(numerical.b2b_force[0]) == 0.0
    # the approach rate (epsilon_1 - epsilon_2) v/2 decides, also in contact_force
    forces = analytical.diagonal_forces(100.0, -50.0), analytical.diagonal_forces(100.0, 50.0)
    args = dict(k_f=1.38, friction_coefficient=0.1, psi=COMMON["psi"], ball_radius=RADIUS)
    assert float(analytical.contact_force(0.0, 0.01, *forces, groove_velocity=-1.0, **args)) > 0.0
    assert float(analytical.contact_force(0.01, 0.0, *forces, groove_velocity=-1.0, **args)) == 0.0
    assert float(analytical.contact_force(0.01, 0.0, *forces, groove_velocity=0.0, **args)) == 0.0


@pytest.mark.parametrize("theta_deg, rho", [(20.0, -0.5), (20.0, 0.5), (13.0, 0.8), (46.0, 0.0)])
def test_analytical_keeps_the_eq37_range(theta_deg, rho):
    """theta = 20 deg, rho = 0.5: beta_BL = 25 deg, tan 25 deg = 0.466 < 0.5, no four-point contact (was 31-37 N)."""
    with pytest.raises(ValueError, match="rho|contact angles"):
        analytical.two_ball_case(math.radians(theta_deg), rho, groove_velocity=0.01, **COMMON)


def test_analytical_rejects_contact_angles_outside_0_90():
    with pytest.raises(ValueError, match="contact angles"):
        analytical.velocity_deviation([-1.0, 0.0, 0.0, 0.0], 10.0, 10.0)  # beta_BL = 45 - 57 deg < 0
    with pytest.raises(ValueError, match="contact angles"):
        analytical.two_ball_case(0.0, 0.0, groove_velocity=0.01, delta_beta_top=(1.0, 0.0), **COMMON)
    with pytest.raises(ValueError, match="delta_beta_top"):
        analytical.two_ball_case(0.0, 0.0, groove_velocity=0.01, delta_beta_top=(0.0,), **COMMON)


def test_analytical_common_velocity_is_finite_when_the_balls_separate():
    separating = analytical.two_ball_case(math.radians(0.1), 0.5, groove_velocity=0.01, **COMMON)
    assert float(separating.b2b_force) == 0.0
    assert np.isfinite(separating.common_velocity)  # was NaN
    assert float(separating.final_velocity_1) == float(separating.ball_velocity_1)  # free velocities
    assert float(separating.final_velocity_2) == float(separating.ball_velocity_2)
    pressed = analytical.two_ball_case(math.radians(0.1), -0.5, groove_velocity=0.01, **COMMON)
    assert float(pressed.final_velocity_1) == float(pressed.final_velocity_2) == float(pressed.common_velocity)


# --- Hertz ------------------------------------------------------------------------------------------
def test_hertz_flags_semi_axes_beyond_its_validity():
    contact = hertz.solve_load(hertz.ball_on_flat(1e-3), [1.0, 1e9])
    assert contact.a[1] > 1e-3  # a semi-axis larger than the ball: returned, but flagged
    np.testing.assert_array_equal(contact.within_validity, [True, False])
    geometry = hertz.ball_in_groove(RADIUS, 0.56)
    assert geometry.reference_radius == RADIUS
    limit = (hertz.VALIDITY_RATIO * RADIUS / hertz.solve_load(geometry, 1.0).a) ** 3  # a ~ F^(1/3)
    flags = hertz.solve_load(geometry, [0.99 * limit, 1.01 * limit]).within_validity
    np.testing.assert_array_equal(flags, [True, False])


def test_conformity_near_one_half_names_conformity():
    """Conformity 0.5005 is valid Hertz input, but b/a = 0.0147 is below the friction map's 0.02: the error
    named an internal ``b_over_a`` before."""
    assert hertz.ball_in_groove(RADIUS, 0.5005).axis_ratio < ef.B_OVER_A_RANGE[0]
    with pytest.raises(ValueError, match="conformity") as error:
        bearing_contacts.ball_contacts(np.full(4, math.pi / 4), 0.0, 100.0, ball_radius=RADIUS, conformity=0.5005,
                                   friction_coefficient=0.1, groove_velocity=0.01)
    assert "b_over_a must" not in str(error.value)
    limit = bearing_contacts.minimum_conformity()
    assert 0.5005 < limit < 0.501
    assert hertz.ball_in_groove(RADIUS, limit).axis_ratio == pytest.approx(ef.B_OVER_A_RANGE[0], rel=1e-9)
    bearing_contacts.ball_contacts(np.full(4, math.pi / 4), 0.0, 100.0, ball_radius=RADIUS, conformity=limit + 1e-9,
                               friction_coefficient=0.1, groove_velocity=0.01)


# --- ellipse friction -------------------------------------------------------------------------------
@pytest.mark.parametrize("c_over_a", [1e300, -1e300, 1e200, 1e8, 300.0, -250.0])
def test_friction_exact_far_velocity_centre(c_over_a):
    """c/a = 1e300 gave NaN (overflow); far out the identity moment = loss + (c/a) force cancels."""
    beta = 0.3
    result = ef.friction_exact(c_over_a, beta)
    for name in ("force", "moment", "loss", "dforce_dc", "dmoment_dc", "dloss_dc"):
        assert np.isfinite(getattr(result, name)), name
    assert float(result.force) == pytest.approx(-math.copysign(1.0, c_over_a), rel=1e-6)
    assert float(result.moment) == pytest.approx(beta**2 / (5 * abs(c_over_a)), rel=1e-4)  # leading term
    assert float(result.loss) >= abs(c_over_a)


def test_friction_exact_series_meets_quadrature():
    """Both sides of the switch at |c/a| = 200 (quadrature below, series above) against the two leading
    terms of the far field, ``force = -1 + (b/a)^2 / (10 (c/a)^2)``, ``loss = c/a + (b/a)^2 / (10 c/a)``."""
    beta = np.array([0.02, 0.3, 1.0])[:, None]
    kappa = np.array([150.0, 199.0, 201.0, 250.0])[None, :]
    exact = ef.friction_exact(kappa, beta)
    np.testing.assert_allclose(exact.force, -1.0 + beta**2 / (10 * kappa**2), rtol=0, atol=5e-11)  # next: 0.011/k^4
    np.testing.assert_allclose(exact.loss, kappa + beta**2 / (10 * kappa), rtol=1e-15, atol=5e-9)  # next: 0.004/k^3
    np.testing.assert_allclose(-exact.dforce_dc, beta**2 / (5 * kappa**3), rtol=2e-4)


def test_cubic_coefficient_at_zero_ratio():
    """b/a = 0 is inside the documented range; NaN before (0 * inf), the limit is E(1)/2 = 1/2."""
    values = ef.cubic_coefficient([0.0, 1e-8, 1e-4])
    assert np.all(np.isfinite(values))
    np.testing.assert_allclose(values, 0.5, rtol=1e-6)


def test_friction_velocity_at_huge_velocities():
    result = ef.friction_velocity(1e300, 3e300, 0.5)
    reference = ef.friction_velocity(1.0, 3.0, 0.5)
    assert float(result.force) == pytest.approx(float(reference.force), rel=1e-12)
    assert float(result.loss) == pytest.approx(1e300 * float(reference.loss), rel=1e-12)


# --- kinematics -------------------------------------------------------------------------------------
def test_kinematics_at_huge_speed():
    """1e300 rad/s gave NaN (overflowing squares); every velocity is linear in the speed, S is not."""
    args = (16.5e-3, 2.778e-3, 20e-3)
    huge = screw.kinematics(*args, 1e300, math.radians(45))
    unit = screw.kinematics(*args, 1.0, math.radians(45))
    for name in huge.__dataclass_fields__:
        assert np.all(np.isfinite(getattr(huge, name))), name
    assert float(huge.slide_roll_nut) == pytest.approx(float(unit.slide_roll_nut), rel=1e-12)
    assert float(huge.entrainment_screw) == pytest.approx(1e300 * float(unit.entrainment_screw), rel=1e-12)
    with pytest.raises(ValueError, match="screw_speed"):
        screw.kinematics(*args, 1.7e308, math.radians(45))


# --- numerical B2B ----------------------------------------------------------------------------------
@pytest.mark.parametrize("top", [(0.0,), (0.0, 0.0, 1.0), ()])
def test_top_deviations_must_be_a_pair(top):
    """(0.0,) ended in IndexError, a 3-tuple was silently truncated."""
    with pytest.raises(ValueError, match="top_deviations"):
        b2b.module_contacts(0.01, 0.5, top_deviations=top)


@pytest.mark.parametrize("count", [True, False, 2.0, 0])
def test_ball_count_is_an_integer(count):
    with pytest.raises(ValueError, match="n_balls"):
        b2b.module_contacts(0.01, 0.5, n_balls=count)


@pytest.mark.parametrize("tolerance", [float("nan"), -1e-9, float("inf")])
def test_gap_tolerance_is_checked(tolerance):
    """A NaN gap_tolerance switched B2B contact off silently (every gap <= NaN is False)."""
    contacts = b2b.module_contacts(math.radians(0.1), -0.5)
    with pytest.raises(ValueError, match="gap_tolerance"):
        b2b.solve(contacts, gap_tolerance=tolerance)
