"""Contact angles within 1e-3 rad of 0 or 90 deg (docs/b2b_bearing.md): finite results, or a ValueError naming the
parameter.

lin2017 eqs 23, 36 and lin2019 eqs 30, 32 divide by sines and cosines of the contact angles.  The null vector
of lin2017 eq 19 (the denominators of eq 23) is written as products of half-angle sines (no cancellation when a
contact pair nearly coincides); where a pair degenerates so far that the forces are not representable, or a
loss of four-point contact is hidden behind an overflow, the models raise ValueError.
"""
from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from ballbench.lowmodel.linear_bearing import fourpoint
from ballbench.lowmodel.linear_bearing import b2b_analytical as analytical

PAPER = dict(ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.01)


@pytest.fixture(autouse=True)
def _warnings_are_errors():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        yield


@pytest.mark.parametrize("eps", [1e-3, 1e-8, 1e-12, 1e-100, 1e-300])
def test_null_vector_when_the_bottom_contacts_nearly_coincide(eps):
    """beta_BL = beta_BR = eps: by row reduction (BR - BL = (0, 0, -2 sin eps) exactly) the minor without TL is
    ``2 sin(eps) (cos beta_TR + cos eps)`` and the one without TR ``2 sin(eps) (cos beta_TL + cos eps)``; the
    determinant form loses these to cancellation, the product form keeps them to round-off."""
    tr, tl = 0.7, 0.9
    angles = np.array([eps, eps, tr, tl])
    n = fourpoint._null_vector(angles)
    assert n[3] == pytest.approx(-2.0 * math.sin(eps) * (math.cos(tr) + math.cos(eps)), rel=1e-14)
    assert n[2] == pytest.approx(2.0 * math.sin(eps) * (math.cos(tl) + math.cos(eps)), rel=1e-14)
    rows = fourpoint._rows(angles)
    assert np.max(np.abs(rows.T @ n)) <= 1e-15 * np.max(np.abs(n))  # lin2017 eq 19: A^T n = 0


@pytest.mark.parametrize("eps", [1e-3, 1e-8, 1e-12])
def test_solve_near_zero_and_ninety_degrees(eps):
    """Single angles near the ends of (0, pi/2): finite state, power balance, Coulomb bound (lin2017 eqs 20-24)."""
    for angles in ([eps, 0.8, 0.75, 0.7], [0.7, math.pi / 2 - eps, 0.75, 0.7], [0.7, 0.8, math.pi / 2 - eps, eps]):
        lower, upper = fourpoint.contact_limits(angles)
        side = 0.5 * (lower + upper) * 100.0
        state = fourpoint.solve(angles, side, 100.0, **PAPER)
        for value in (state.K, state.friction_forces, state.slip_velocity, state.friction_loss, state.ball_velocity):
            assert np.all(np.isfinite(value))
        assert np.all(np.abs(state.friction_forces) <= 0.1 * state.normal_forces * (1 + 1e-12))
        power = PAPER["groove_velocity"] * float(np.sum(state.friction_forces[2:]))  # top groove's work
        assert abs(power) == pytest.approx(float(state.friction_loss), rel=1e-9, abs=1e-18)


def test_degenerate_pair_raises_naming_contact_angles():
    """Both bottom (or top) angles at the last float below 90 deg: the pair faces itself, eq 36 ~ N / sin(sum)
    overflows under a huge load; both near 0: the pair coincides, any side force loses contact (eq 37 range
    +-1e-310), and K of eq 23 overflows at the top contacts (|n_TR|, |n_TL| ~ sin(beta_BL + beta_BR))."""
    near = math.nextafter(0.5 * math.pi, 0.0)
    for angles in ([near, near, 0.7, 0.7], [0.7, 0.7, near, near]):
        with pytest.raises(ValueError, match="contact_angles: a contact pair degenerates"):
            fourpoint.normal_forces(0.0, 1e300, angles)
        with pytest.raises(ValueError, match="contact_angles"):
            fourpoint.solve(angles, 0.0, 1e300, **PAPER)
    for angles in ([1e-310, 1e-310, 0.7, 0.7], [0.7, 0.7, 5e-324, 5e-324]):
        with pytest.raises(ValueError, match="side_force: loss of four-point contact"):
            fourpoint.normal_forces(1e-3, 1.0, angles)
        with pytest.raises(ValueError, match="contact_angles: a contact pair degenerates"):
            fourpoint.solve(angles, 0.0, 1.0, **PAPER)  # forces finite (1/2 each), |n_i| ~ 1e-310: K overflows
    with pytest.raises(ValueError, match="contact_angles: a contact pair degenerates"):  # K of eq 23 overflows
        fourpoint.characteristic_parameters([1e-200, 1e-200, 0.7, 0.7], [1.0, 1.0, 1e200, 1e200])


def test_loss_of_contact_message_with_a_tiny_vertical_force():
    """N_x / N_y overflows in the message only; the error names side_force (it used to warn 'overflow')."""
    with pytest.raises(ValueError, match="side_force: loss of four-point contact"):
        fourpoint.normal_forces(4.0, 2.2250738585072014e-308, [1e-3, 7e-4, 4e-4, 2e-5])


def test_analytical_near_the_ends():
    # beta_0 -> 0: |N_x| < N_y tan(beta_0) is tested without dividing by sin(beta_0)
    with pytest.raises(ValueError, match="loss of four-point contact"):
        analytical.diagonal_forces(1.0, 1.0, 5e-324)
    up, down = analytical.diagonal_forces(1.0, 0.0, 5e-324)
    assert up == down == 0.5
    # beta_0 -> 90 deg: N_y / (2 cos beta_0) overflows for a huge load
    with pytest.raises(ValueError, match="nominal_contact_angle"):
        analytical.diagonal_forces(1e300, 0.0, math.nextafter(0.5 * math.pi, 0.0))
    with pytest.raises(ValueError, match="nominal_contact_angle"):  # eq 32: 1 / cos(beta_0)
        analytical.friction_loss(1e300, 1.0, 1.0, math.nextafter(0.5 * math.pi, 0.0))
    with pytest.raises(ValueError, match="nominal_contact_angle"):  # eq 30: (eps_1 - eps_2) / (1 - cos 2 beta_0)
        analytical.contact_force(1.0, 0.0, (1.0, 1.0), (1.0, 1.0), k_f=0.7, friction_coefficient=0.1, psi=5.3e-4,
                                 ball_radius=5e-3, nominal_contact_angle=1e-160, groove_velocity=0.01)
    # inside the range close to the ends: finite and equal to eq 30 written with the weighted deviations
    case = analytical.two_ball_case(1e-4, 0.0, normal_load=100.0, groove_velocity=0.01, friction_coefficient=0.1,
                                    psi=5.3e-4, ball_radius=5e-3, nominal_contact_angle=math.pi / 2 - 1e-3)
    assert np.isfinite(case.b2b_force) and np.isfinite(case.b2b_friction_loss)
