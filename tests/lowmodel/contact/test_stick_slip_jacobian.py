"""The stick/slip law's analytic Jacobian (lowmodel.contact.rolling_friction.StickSlipFriction, the rolling solve's
sensitivity and ``dw/dx = (T D - w dV/dx) / V``) against central differences of the same law's forces.

The reference perturbs the ball's unknowns by 1e-7 either way and solves every contact again (``evaluate`` without
a Jacobian, which never calls the sensitivity code; the law's own forward differences of 1e-6 are 1e-3 off here,
where cells switch between stick and slip within the step): a ball of lin2019 Table 1's guide where full sliding
has no state (theta 1.5 deg, rho -0.9, 300 N, mu 0.2: two contacts stick over 30-49 % of their area), off its
equilibrium, with the top groove moving either way (Kalker's rolling direction turned by pi on every contact).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.bearing import GuideLoadCase, LinearGuide, Material
from ballbench.lowmodel.contact import rolling_friction as rf
from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling, b2b_traction

pytestmark = pytest.mark.filterwarnings("error")

R_B, MU = 5e-3, 0.2


@pytest.mark.parametrize("velocity", [0.01, -0.01])
def test_the_analytic_jacobian_equals_forward_differences(velocity):
    guide = LinearGuide(ball_radius=R_B, conformity=0.56, nominal_angle=math.pi / 4, material=Material(210e9, 0.28),
                        friction_coefficient=MU, groove_velocity=velocity)
    case = GuideLoadCase(guide, vertical_force=300.0, side_force_ratio=-0.9,
                         deviations=(-math.radians(1.5), math.radians(1.5), 0.0, 0.0))
    balls = [b2b_rolling.hertz_contacts(b2b.contacts(case), 0, cells=(12, 48), guide=guide)]
    state = b2b_rolling.solve(balls, ball_radius=R_B, friction_coefficient=MU, groove_velocity=velocity, start="auto")
    speed = abs(velocity)
    x = np.column_stack([state.ball_velocity / speed, state.omega * R_B / speed])
    x = x + 1e-4 * np.array([[0.3, -0.2, 0.5]])  # off the equilibrium
    reference = max(c.normal_force for c in balls[0])
    friction = rf.StickSlipFriction(balls, lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, reference,
                                    math.copysign(1.0, velocity), speed)
    analytic = friction.evaluate(x)[1][0]
    stick = [c.stick_fraction for c in friction.summaries(x)[0]]
    assert 0.2 < max(stick) < 0.9 and min(stick) == 0.0  # both branches of the law in play
    step, central = 1e-7, np.zeros((3, 3))
    for j in range(3):
        shift = np.zeros_like(x)
        shift[0, j] = step
        central[:, j] = (friction.evaluate(x + shift, jacobian=False)[0][0]
                         - friction.evaluate(x - shift, jacobian=False)[0][0]) / (2.0 * step)
    # 6e-9 of the largest entry measured (the rolling solves' tolerance 1e-12 over the step)
    assert np.max(np.abs(analytic - central)) < 1e-6 * np.max(np.abs(central))


def test_the_deferred_jacobian_equals_the_jacobian_evaluated_with_the_residual():
    # evaluate(lazy=True): the residual of the plain evaluation, the Jacobian when called (the same contacts solved
    # again with their sensitivity, from the residual's tractions): both within the rolling solves' tolerance
    guide = LinearGuide(ball_radius=R_B, conformity=0.56, nominal_angle=math.pi / 4, material=Material(210e9, 0.28),
                        friction_coefficient=MU, groove_velocity=0.01)
    case = GuideLoadCase(guide, vertical_force=300.0, side_force_ratio=-0.9,
                         deviations=(-math.radians(1.5), math.radians(1.5), 0.0, 0.0))
    balls = [b2b_rolling.hertz_contacts(b2b.contacts(case), 0, cells=(12, 48), guide=guide)]
    state = b2b_rolling.solve(balls, ball_radius=R_B, friction_coefficient=MU, groove_velocity=0.01, start="auto")
    x = np.column_stack([state.ball_velocity / 0.01, state.omega * R_B / 0.01]) + 1e-4 * np.array([[0.3, -0.2, 0.5]])
    reference = max(c.normal_force for c in balls[0])

    def law():
        return rf.StickSlipFriction(balls, lambda p, m: b2b_traction.slip_field(p, R_B, m), MU, reference, 1.0, 0.01)

    plain = law().evaluate(x)
    residual, deferred = law().evaluate(x, lazy=True)[:2]
    assert callable(deferred)
    assert np.max(np.abs(residual - plain[0])) < 1e-9 * np.max(np.abs(plain[0]))
    assert np.max(np.abs(deferred() - plain[1])) < 1e-6 * np.max(np.abs(plain[1]))
