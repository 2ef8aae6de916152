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
