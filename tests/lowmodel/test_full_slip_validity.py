"""Where full slip holds: stick/slip against full slip per case, the rung a case needs (lowmodel.full_slip_validity)."""
from __future__ import annotations

import dataclasses
import math

import pytest

from ballbench.lowmodel import full_slip_validity as fsv


@pytest.fixture(scope="module")
def table1_point():
    return fsv.linear_point(math.radians(2.0), cells=(8, 32))


def test_linear_point_of_table1_is_near_full_slip(table1_point):
    point = table1_point
    assert not point.error
    assert 40.0 < point.spin_parameter < 90.0
    assert abs(point.b2b_difference) < 0.01 and point.friction_difference < 0.01
    assert point.b2b_force == pytest.approx(4.05, rel=0.01)
    assert fsv.required_rung(point) == "full slip"
    # a tolerance below the difference asks for the stick/slip rung
    assert fsv.required_rung(point, tolerance=0.1 * point.worst) == "stick/slip on a half-space"


def test_high_friction_and_an_open_groove_are_farther_from_full_slip(table1_point):
    rough = fsv.linear_point(math.radians(2.0), friction_coefficient=0.5, conformity=0.6, cells=(8, 32))
    assert rough.spin_parameter < 0.25 * table1_point.spin_parameter  # Lambda ~ 1 / mu, and lower in open grooves
    assert rough.friction_difference > 5 * table1_point.friction_difference


def test_required_rung_refuses_a_point_without_a_state(table1_point):
    failed = dataclasses.replace(table1_point, error="Newton did not converge")
    with pytest.raises(ValueError, match="no state"):
        fsv.required_rung(failed)
    with pytest.raises(ValueError, match="tolerance"):
        fsv.required_rung(table1_point, tolerance=-0.01)
    with pytest.raises(ValueError, match="product"):
        fsv.validity_map("bearing", [0.1], [0.56], [0.03], [100.0])


# --------------------------------------------------------------------------
# the grid error of the comparison (docs/b2b_rolling.md, 'Grid error of the comparison')
# --------------------------------------------------------------------------
# a random case of the stress run's kind: nearly full slip (Lambda 87, stick fraction <= 0.1 %), a B2B force of
# 2.3 N under 124 N per ball: 8 x 32 cells put full slip 1.2 % off stick/slip, finer cells 0.0-0.1 %
STRESS = dict(theta=math.radians(0.99), side_force_ratio=-0.86, friction_coefficient=0.057, conformity=0.579,
              vertical_force=124.1)


def test_the_rung_a_case_needs_does_not_depend_on_the_cells():
    point = fsv.linear_point(**STRESS)  # the default cells: GRID_LEVELS, refined while the verdict could flip
    assert fsv.required_rung(point) == "full slip"
    assert point.worst < 0.5 * fsv.TOLERANCE and point.grid_error < 0.25 * fsv.TOLERANCE
    assert point.cells in fsv.GRID_LEVELS[1:] and point.grid_cells in fsv.GRID_LEVELS
    assert 80.0 < point.spin_parameter < 95.0 and point.stick_fraction < 0.002


def test_no_verdict_on_cells_whose_grid_error_could_flip_it():
    coarse = fsv.linear_point(cells=(8, 32), **STRESS)
    assert not coarse.error and coarse.cells == (8, 32) and coarse.grid_cells == fsv.finer_cells((8, 32))
    assert abs(coarse.b2b_difference) > fsv.TOLERANCE  # the grid's difference, not the law's
    assert coarse.grid_error > abs(coarse.worst - fsv.TOLERANCE)
    with pytest.raises(ValueError, match="grid error .* could flip the verdict"):
        fsv.required_rung(coarse)


def test_finer_cells_and_a_verdict_without_a_grid_error(table1_point):
    assert fsv.finer_cells((8, 32)) == (12, 48) and fsv.finer_cells((16, 64)) == (24, 96)
    with pytest.raises(ValueError, match="cells"):
        fsv.finer_cells((1, 32))
    with pytest.raises(ValueError, match="grid error"):
        fsv.required_rung(dataclasses.replace(table1_point, b2b_grid_error=math.nan))
    # one difference beyond the tolerance by more than its grid error decides, whatever the other's grid error
    rough = dataclasses.replace(table1_point, friction_difference=0.02, friction_grid_error=0.001, b2b_difference=0.01,
                                b2b_grid_error=0.05)
    assert rough.verdict(0.01) is False and fsv.required_rung(rough) == "stick/slip on a half-space"
    assert dataclasses.replace(rough, friction_difference=0.005).verdict(0.01) is None


# lin2019's module at theta 3 deg, mu 0.5, 10 N per ball (the validity map's grid): the low-order model has a state
# (F_B2B 7.42 N); the full-slip chain on the cells does not converge from the free balls, only from that state
ROUGH_LIGHT = dict(theta=math.radians(3.0), friction_coefficient=0.5, conformity=0.56, vertical_force=10.0)


def test_a_failure_names_the_model_that_failed():
    from ballbench.lowmodel.contact import rolling_friction
    from ballbench.lowmodel.errors import ConvergenceError
    from ballbench.lowmodel.linear_bearing import b2b, b2b_rolling

    contacts = b2b.module_contacts(ROUGH_LIGHT["theta"], -0.6, vertical_force=10.0, conformity=0.56,
                                   friction_coefficient=0.5)
    balls = [b2b_rolling.hertz_contacts(contacts, j, cells=(6, 24), conformity=0.56) for j in range(2)]
    with pytest.raises(ConvergenceError, match="full slip on the stick/slip cells") as failure:
        b2b_rolling.module_b2b(balls, ball_radius=5e-3, friction_coefficient=0.5, groove_velocity=0.01)
    assert "FE-informed" not in str(failure.value) and rolling_friction.FULL_SLIP_NAME in str(failure.value)
    # in the f = 0.53 groove the second start (the low-order state, which exists there) does not help either:
    # the message says both were tried
    contacts = b2b.module_contacts(ROUGH_LIGHT["theta"], -0.6, vertical_force=10.0, conformity=0.53,
                                   friction_coefficient=0.5)
    balls = [b2b_rolling.hertz_contacts(contacts, j, cells=(6, 24), conformity=0.53) for j in range(2)]
    with pytest.raises(ConvergenceError, match="converged neither from the free balls .* nor from the low-order"):
        b2b_rolling.module_b2b(balls, ball_radius=5e-3, friction_coefficient=0.5, groove_velocity=0.01,
                               low_order=lambda gaps: b2b.solve(contacts, gaps))


def test_a_case_where_the_low_order_model_has_a_state_has_a_point():
    from ballbench.lowmodel.linear_bearing import b2b

    low = b2b.solve(b2b.module_contacts(ROUGH_LIGHT["theta"], -0.6, vertical_force=10.0, conformity=0.56,
                                        friction_coefficient=0.5))
    point = fsv.linear_point(cells=(6, 24), **ROUGH_LIGHT)  # coarse cells: the start is the point here
    assert not point.error, point.error
    assert point.b2b_force_full_slip == pytest.approx(float(low.b2b_force[0]), rel=0.01)
    assert fsv.required_rung(point) in fsv.RUNGS
