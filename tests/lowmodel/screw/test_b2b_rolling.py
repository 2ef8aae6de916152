"""lin2019's ball-screw B2B solve with stick/slip ball-to-groove contacts (lowmodel.screw.b2b_rolling;
docs/b2b_rolling.md)."""
from __future__ import annotations

import math

import pytest

from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import b2b_rolling as screw_rolling
from ballbench.lowmodel.screw import contacts as screw_contacts

CELLS = (8, 32)


def test_screw_theta_zero_gives_no_b2b_and_the_table5_case_balances_power():
    module = screw_contacts.screw_module(oversize=1.6848e-6)
    for theta, expect_force in ((0.0, False), (math.radians(2.0), True)):
        contacts = screw_contacts.ball_contacts(module, [0.0, theta], reading="tilted")
        low = screw_b2b.solve(contacts, 50.0)
        balls = [screw_rolling.hertz_contacts(low, contacts, j, cells=CELLS) for j in range(2)]
        result = screw_rolling.module_b2b(balls, module)
        assert result.power_balance < 1e-6
        if expect_force:
            assert result.b2b_force[0] == pytest.approx(low.b2b_force[0], rel=0.01)
            assert result.b2b_force[0] == pytest.approx(result.full_slip.b2b_force[0], rel=0.01)
        else:
            assert result.b2b_force[0] < 1e-9 * low.normal_force.max()
            assert result.touching.orbit_speed[0] == pytest.approx(result.touching.orbit_speed[1], rel=1e-9)
