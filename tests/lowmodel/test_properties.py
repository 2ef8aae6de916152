"""Property-based test of the public API of lowmodel (issue 10 item 8, hypothesis).

Random finite inputs in the documented ranges (and a little beyond) give finite
outputs, or a ValueError / ConvergenceError whose message names a parameter of
the call; never NaN, never a warning.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from ballbench.lowmodel.linear_bearing import fourpoint
from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from ballbench.lowmodel.linear_bearing import b2b_analytical as analytical
from ballbench.lowmodel.ball_bearing import harris
from ballbench.lowmodel.screw import kinematics as screw
from tests.property_support import SETTINGS, SLOW, call, positive, real


# --- contact ------------------------------------------------------------------------------------------
@SETTINGS
@given(radius=positive(1e-5, 1.0), conformity=real(0.45, 1.05), force=real(-1.0, 1e7),
       modulus=positive(1e6, 1e13), poisson=real(-1.2, 0.6))
def test_hertz(radius, conformity, force, modulus, poisson):
    geometry = call(hertz.ball_in_groove, radius, conformity, youngs_modulus=modulus, poisson_ratio=poisson)
    if geometry is not None:
        call(hertz.solve_load, geometry, force)
        call(hertz.psi_constant, geometry, radius)
        call(hertz.hertz_constant, geometry)
    for build in (hertz.ball_on_flat, hertz.ball_on_ball):
        geometry = call(build, radius, youngs_modulus=modulus, poisson_ratio=poisson)
        if geometry is not None:
            call(hertz.solve_approach, geometry, abs(force) * 1e-12)


@SETTINGS
@given(kappa=real(-1e300, 1e300), small=real(-3.0, 3.0), beta=real(-0.1, 1.2))
def test_ellipse_friction(kappa, small, beta):
    for c_over_a in (kappa, small):
        call(ef.friction, c_over_a, beta, allow_inf=("loss",))
        call(ef.friction_exact, c_over_a, beta, allow_inf=("loss",))
        call(ef.friction_angle, c_over_a, beta)
        call(ef.friction_inside, c_over_a, beta)
    call(ef.friction_velocity, small, kappa, beta)
    call(ef.k_f_exact, beta)
    call(ef.cubic_coefficient, beta)
    call(ef.spin_moment, beta)


@SLOW
@given(beta=real(0.0, 1.0), c_max=real(-0.5, 3.0))
def test_k_f_least_squares(beta, c_max):
    call(ef.k_f_least_squares, beta, c_max)


# --- four-point contact, analytical and numerical B2B -----------------------------------------------
# contact angles: the whole of (0, pi/2) rad, with the last 1e-3 rad at either end (where lin2017 eqs 23, 36 and
# lin2019 eqs 30, 32 divide by sin or cos of them) drawn as often as the rest, the extreme floats near 0 and pi/2,
# and outside (0, pi/2) for the errors
angle = st.one_of(real(1e-3, 0.5 * math.pi - 1e-3), real(0.0, 1e-3), real(0.5 * math.pi - 1e-3, 0.5 * math.pi),
                  st.sampled_from([5e-324, 2.2250738585072014e-308, 1e-200, 1e-16, math.nextafter(0.5 * math.pi, 0.0),
                                   0.5 * math.pi * (1.0 - 1e-12)]),
                  real(-0.2, 0.0), real(0.5 * math.pi, 1.8))
angles4 = st.lists(angle, min_size=4, max_size=4)


@SETTINGS
@given(angles=angles4, side=real(-1e4, 1e4), vertical=real(-10.0, 1e4), mu=real(-0.1, 1.5),
       velocity=real(-1.0, 1.0))
def test_fourpoint(angles, side, vertical, mu, velocity):
    call(fourpoint.normal_forces, side, vertical, angles)
    call(fourpoint.contact_limits, angles)
    call(fourpoint.solve, angles, side, vertical, ball_radius=5e-3, friction_coefficient=mu,
         groove_velocity=velocity)


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


# --- screw kinematics ----------------------------------------------------------------------------------
@SETTINGS
@given(pitch=positive(1e-4, 10.0), ball=positive(1e-5, 1.0), lead=real(-0.01, 1.0), speed=real(-1e300, 1e300),
       alpha=angle, alpha_i=angle)
def test_screw_kinematics(pitch, ball, lead, speed, alpha, alpha_i):
    call(screw.kinematics, pitch, ball, lead, speed, alpha, alpha_i)
    call(screw.wei_ball_centre_kinematics, pitch, ball, lead, speed, alpha, alpha_i)
    call(harris.kinematics, pitch, ball, speed, alpha)


def test_property_helper_sees_nan():
    """The helper itself fails on a NaN result (a test that cannot fail proves nothing)."""
    with pytest.raises(AssertionError):
        call(lambda x: np.array([x, math.nan]), 1.0)
    with pytest.raises(AssertionError):
        call(lambda x: (_ for _ in ()).throw(ValueError("something else went wrong")), 1.0)
