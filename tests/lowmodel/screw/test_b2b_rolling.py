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


def test_the_rolling_start_reaches_the_state_of_the_full_slip_start():
    """lin2019 Table 5 case (a): the stick/slip screw solve from the rolling start reaches the state it reaches from
    full slip on the same cells (touching and free): the start does not choose the answer."""
    module = screw_contacts.screw_module(oversize=1.6848e-6)
    contacts = screw_contacts.ball_contacts(module, [0.0, math.radians(2.0)], reading="tilted")
    low = screw_b2b.solve(contacts, 50.0)
    balls = [screw_rolling.hertz_contacts(low, contacts, j, cells=CELLS) for j in range(2)]
    for with_b2b in (True, False):
        reference = screw_rolling.solve(balls, module, with_b2b=with_b2b)
        state = screw_rolling.solve(balls, module, with_b2b=with_b2b, start="rolling", max_iterations=160)
        assert state.b2b_force == pytest.approx(reference.b2b_force, rel=1e-6, abs=1e-9)
        assert state.orbit_speed == pytest.approx(reference.orbit_speed, rel=1e-9)
        assert state.input_power == pytest.approx(reference.input_power, rel=1e-8)


def test_past_the_preload_loss_the_balls_run_on_the_stick_slip_law_at_the_frictionless_two_point_loads():
    """A screw of 3/16-inch balls (R_B 2.381 mm, R_P 12.5 mm, lead 5 mm, f 0.54, oversize 1.5 um, mu 0.05) at 300 N,
    past its preload loss (111 N): lin2019's four-point model finds no state (its load ramp stops), the friction
    comes from the stick/slip law on the frictionless statics' loads, where contacts carry nothing (two-point
    contact); power balances, the normal loads carry the axial load, unloaded contacts are left out."""
    from ballbench.lowmodel import bearing_results
    from ballbench.lowmodel.bearing import BallScrew, Material, ScrewLoadCase
    from ballbench.lowmodel.errors import ConvergenceError

    screw = BallScrew(ball_radius=2.381e-3, pitch_radius=12.5e-3, lead=5e-3, nominal_angle=math.pi / 4,
                      conformity=0.54, material=Material(210e9, 0.3), friction_coefficient=0.05,
                      nut_speed=2 * math.pi, oversize=1.5e-6)
    case = ScrewLoadCase(screw, axial_load=300.0, deviations=(0.0, math.radians(2.0)), reading="tilted")
    with pytest.raises(ConvergenceError, match="load ramp stopped"):
        bearing_results.screw_states(case)
    states = bearing_results.screw_law_states(case, cells=(12, 48))
    assert states.law == bearing_results.STICK_SLIP and "load ramp stopped" in states.reason
    loads = states.loads
    assert (loads.normal_force == 0.0).sum() >= 2  # two-point contact: the open contacts carry nothing
    for state in (states.touching, states.free):
        assert state.power_balance < 1e-6 and state.input_power > 0.0
        assert [len(row) for row in state.contacts] == [int(n) for n in (loads.normal_force > 0).sum(axis=1)]
    contacts = screw_b2b.contacts(case)
    normal = bearing_results.axial_shares(contacts, bearing_results.stick_slip_forces(loads, states.touching, False))
    assert normal.sum() == pytest.approx(300.0, rel=1e-9)
    result = bearing_results.screw_result(case, contacts=contacts, states=states)
    assert result.law == bearing_results.STICK_SLIP
    assert result.friction_torque > result.friction_torque_free > 0.0 and result.b2b_forces[0] > 0.0


def test_the_linear_bearing_s_start_from_the_balls_alone_is_refused():
    module = screw_contacts.screw_module(oversize=1.6848e-6)
    contacts = screw_contacts.ball_contacts(module, [0.0, math.radians(2.0)], reading="tilted")
    low = screw_b2b.solve(contacts, 50.0)
    balls = [screw_rolling.hertz_contacts(low, contacts, j, cells=CELLS) for j in range(2)]
    with pytest.raises(ValueError, match="alone"):
        screw_rolling.solve(balls, module, start="alone")
