"""The reason of a failed solve of touching balls is established by evidence (lowmodel.linear_bearing.branch_end).

Two touching balls of a random case of an outside stress run (nominal angle 0.78476 rad, N_y 0.847 N, R_B
1.9917 mm, conformity 0.5422, theta 0.05157 rad, rho -0.70798) failed at mu = 0.26 with "a contact stops sliding"
although direct solves converge at 0.25 and 0.265: the reason came from the branch on which Newton stopped.
Measured here: the full-sliding branch from below ends at mu = 0.25225 (contact BL of ball 0 stops sliding) and
another begins at 0.26205; between them no full-sliding state exists (a gap, not the end of the model).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.lowmodel.linear_bearing.ball import STICK_REASON
STICK_SLIP = 1e-3  # |v|, as branch_end.STICK_SLIP


def _case(mu):
    return b2b.module_contacts(0.05157, -0.70798, nominal_angle=0.78476, vertical_force=0.847,
                               ball_radius=1.9917e-3, conformity=0.5422, friction_coefficient=mu)


def _smallest_slip(state, contacts):
    return float(np.min(np.hypot(state.slide, state.spin * contacts.semi_major))) / abs(contacts.groove_velocity)


def test_a_gap_between_full_sliding_branches_is_named_as_a_gap():
    with pytest.raises(ConvergenceError) as caught:
        b2b.solve(_case(0.26))
    reason = caught.value.reason
    assert reason.startswith(STICK_REASON) and "full-sliding states again beyond" in reason
    low, high = (float(v) for v in reason.split("between mu = ")[1].split(" (")[0].split(" and "))
    assert 0.25 < low < 0.26 < high < 0.265
    # the evidence names the contact whose slip falls to 0 where each walk stops, and its slip speed
    assert "stops at mu = %.6g with a slip speed of" % low in str(caught.value)
    assert "(contact BL of ball 0)" in str(caught.value)
    # the evidence, checked apart from the solver's verdict: just outside the gap the solves converge, and the
    # slip speed of a contact falls towards 0 as mu approaches either end of the gap
    slips = {}
    for mu in (0.24, 0.25, 0.265, 0.27):
        contacts = _case(mu)
        slips[mu] = _smallest_slip(b2b.solve(contacts), contacts)
    assert slips[0.25] < slips[0.24] and slips[0.265] < slips[0.27]  # falling towards the gap from both sides
    assert slips[0.265] < STICK_SLIP  # 1.8e-4 |v|, 0.003 above the gap's end


def test_the_end_of_the_branch_is_still_the_end():
    # theta = 3 deg, rho = -0.7, lin2019 Table 1 (lin2019-stability): the branch from below ends at mu = 0.4675;
    # at 0.5 no full-sliding state is found up to 1.1 mu, the reason says so and where
    # lin2019 Table 1 as printed: R_B 5 mm, conformity 0.56, N_y 100 N, v 10 mm/s, E 2.1e11 Pa, nu 0.28
    contacts = _table1(0.5)
    with pytest.raises(ConvergenceError) as caught:
        b2b.solve(contacts, [0.0])
    reason = caught.value.reason
    assert reason.startswith(STICK_REASON) and "no full-sliding state found beyond" in reason
    assert float(reason.split("at mu = ")[1].split(";")[0]) == pytest.approx(0.4675, abs=2e-4)


def _table1(mu):
    return b2b.module_contacts(math.radians(3.0), -0.7, n_balls=2, ball_radius=5e-3, conformity=0.56,
                               vertical_force=100.0, groove_velocity=10e-3, friction_coefficient=mu,
                               youngs_modulus=2.1e11, poisson_ratio=0.28)


def test_a_branch_beyond_the_end_is_found_and_the_gap_named():
    # the same balls at mu = 0.6: a full-sliding state exists (another branch, reached from a relaxed state;
    # main said "no full-sliding state found beyond, up to mu = 0.66"); at 0.55 the reason is the gap between the
    # branch that ends at 0.4675 and this one, with the contact whose slip falls to 0 at the gap's upper end
    contacts = _table1(0.6)
    state = b2b.solve(contacts, [0.0])
    assert state.residual <= 1e-12 and float(np.min(_slip(state, contacts))) > 0.0
    assert abs(state.input_power - state.friction_loss.sum() - state.b2b_friction_loss.sum()) <= (
        1e-9 * state.input_power)  # power balance, lin2019 eq 7
    with pytest.raises(ConvergenceError) as caught:
        b2b.solve(_table1(0.55), [0.0])
    reason = caught.value.reason
    assert reason.startswith(STICK_REASON) and "full-sliding states again beyond" in reason
    low, high = (float(v) for v in reason.split("between mu = ")[1].split(" (")[0].split(" and "))
    assert low == pytest.approx(0.4675, abs=5e-4) and 0.55 < high < 0.6  # the walk stops within 3e-4 of the end
    assert "(contact BL of ball 0) there" in reason
    # the evidence apart from the solver's verdict: on the upper branch the slip of that contact falls towards 0
    # as mu falls towards the gap's upper end
    slips = [float(_slip(b2b.solve(_table1(mu), [0.0]), _table1(mu))[0, 0]) for mu in (0.6, high + 0.005)]
    assert slips[1] < slips[0] and slips[1] < STICK_SLIP


def _slip(state, contacts):
    return np.hypot(state.slide, state.spin * contacts.semi_major) / abs(contacts.groove_velocity)


def test_the_relaxation_agrees_with_the_gaps_and_the_states_beside_them():
    # the independent oracle (lowmodel.b2b_relaxation) on the same balls: it settles on the state of b2b.solve
    # where that converges (main: a "stall" at 0.265, 0.28, 0.31 -- a contact slipping at 1e-4..3e-4 |v| chattered
    # at the step limit of 0.05 |v|), and does not settle inside the gaps (0.26, 0.30), where a contact stalls
    for mu in (0.25, 0.265, 0.28, 0.31):
        contacts = _case(mu)
        state = b2b.solve(contacts, [0.0])
        relaxed = b2b.relax_state(contacts, [0.0])
        assert relaxed.settled, (mu, relaxed.reason)
        reference = mu * float(contacts.normal_forces.max())
        np.testing.assert_allclose(relaxed.forces * reference, state.b2b_force, atol=1e-7 * reference)
    for mu in (0.26, 0.30):
        relaxed = b2b.relax_state(_case(mu), [0.0])
        assert not relaxed.settled and relaxed.reason.startswith("a contact stops sliding"), (mu, relaxed.reason)
