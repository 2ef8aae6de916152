"""A guide's friction wherever its balls run (lowmodel.bearing_results.guide_states): lin2019's full sliding where it
has a state, the stick/slip law on a half-space elsewhere (docs/b2b_rolling.md, "Where full sliding has no state")."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from ballbench.lowmodel import bearing_results as br
from ballbench.lowmodel.bearing import GuideLoadCase, LinearGuide, Material
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b

STEEL = Material(youngs_modulus=210e9, poisson_ratio=0.28)
GUIDE = LinearGuide(ball_radius=5e-3, conformity=0.56, nominal_angle=math.pi / 4, material=STEEL,
                    friction_coefficient=0.1, groove_velocity=0.01)  # lin2019 Table 1
CELLS = (12, 48)  # the grid check's cells (validation.ladder.balls.GRID_CHECK_CELLS): within 0.2 % at the limit


def _case(theta_deg, rho, vertical, mu):
    theta = math.radians(theta_deg)
    return GuideLoadCase(dataclasses.replace(GUIDE, friction_coefficient=mu), vertical_force=vertical,
                         side_force_ratio=rho, deviations=(-theta, theta, 0.0, 0.0))


def _judge(states, case):
    """The defining conditions of a state, whichever law gave it: positive finite friction, the power balance."""
    for state in (states.touching, states.free):
        assert state.power_balance < 1e-6 if states.law == br.STICK_SLIP else True
        assert math.isfinite(state.input_power) and state.input_power > 0.0
        assert state.total_loss == pytest.approx(state.input_power, rel=1e-6)
    assert np.all(np.isfinite(states.touching.b2b_force)) and np.all(states.touching.b2b_force >= 0.0)


@pytest.mark.parametrize("theta, rho, vertical, mu, words", [
    (1.5, -0.9, 300.0, 0.2, "spin-capacity ratio 0.738 < 1"),
    (2.87, -0.83, 128.0, 0.604, "a contact stops sliding"),
    (0.94, -0.88, 12.0, 0.348, "converged only to slip directions against the slip")])
def test_guides_without_a_full_sliding_state_run_on_the_stick_slip_law(theta, rho, vertical, mu, words):
    """Guides of lin2019 Table 1 where full sliding has no state (the third: its continuation stops without a named
    cause, and full slip on the cells has none either, so the state comes from the rolling start): the stick/slip
    law gives their friction, with the full-sliding solve's words kept; the heavy contacts stick in part."""
    case = _case(theta, rho, vertical, mu)
    with pytest.raises(ConvergenceError):
        b2b.solve(b2b.contacts(case), [0.0])
    states = br.guide_states(case, cells=CELLS)
    assert states.law == br.STICK_SLIP and words in states.reason
    _judge(states, case)
    stick = max(c.stick_fraction for row in states.touching.contacts for c in row)
    assert stick > 0.3
    result = br.guide_result(case, contacts=b2b.contacts(case), states=states)
    assert result.law == br.STICK_SLIP and result.friction_force > result.friction_force_free > 0.0


def test_every_guide_over_the_four_point_range_has_a_state_or_a_named_physical_reason():
    """Random guides of lin2019 Table 1's geometry over the four-point range (theta 0-3.5 deg, rho up to the
    geometric limit, N_y 1e-3..1e5 N, mu 1e-3..1): each has a friction state (full sliding or stick/slip) or the
    balls leave four-point contact (ValueError naming side_force_ratio), none a solver failure."""
    rng = np.random.default_rng(20261207)
    laws = []
    for _ in range(24):
        theta, rho = rng.uniform(0.0, 3.5), -rng.uniform(0.0, 1.0)
        vertical, mu = 10 ** rng.uniform(-3, 5), 10 ** rng.uniform(-3, 0)
        case = _case(theta, rho, vertical, mu)
        try:
            contacts = b2b.contacts(case)
        except ValueError as error:
            assert "side_force_ratio" in str(error) and "loss of four-point contact" in str(error)
            laws.append("geometric limit")
            continue
        states = br.guide_states(case, contacts, cells=CELLS)
        _judge(states, case)
        laws.append(states.law)
    assert laws.count(br.FULL_SLIDING) >= 10 and "geometric limit" in laws and br.STICK_SLIP in laws, laws
