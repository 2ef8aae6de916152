"""validation.studies.fe_b2b_linear.analytical: lin2019's analytical two-ball model of a linear-guide case."""
from __future__ import annotations

import dataclasses
import math

import pytest

from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b_analytical
from ballbench.validation.cases import lin2019
from ballbench.validation.studies import fe_b2b_linear


def test_the_analytical_rung_takes_the_case_whole():
    case = lin2019.TABLE3_A
    guide = case.guide
    # Psi of eq 15 from the exact Hertz contact of the case's groove, written out here
    psi = hertz.psi_constant(hertz.ball_in_groove(guide.ball_radius, guide.conformity, youngs_modulus=2.1e11,
                                                  poisson_ratio=0.28), guide.ball_radius)
    expected = b2b_analytical.two_ball_case(math.radians(2.0), -0.6, normal_load=100.0, groove_velocity=10e-3,
                                            friction_coefficient=0.1, psi=psi, ball_radius=5e-3)
    assert float(fe_b2b_linear.analytical(case).b2b_force) == float(expected.b2b_force)
    # a guide of another nominal contact angle is the analytical model at that angle, not at lin2019's 45 deg
    steeper = dataclasses.replace(case, guide=dataclasses.replace(guide, nominal_angle=math.radians(40.0)))
    at_40 = b2b_analytical.two_ball_case(math.radians(2.0), -0.6, normal_load=100.0, groove_velocity=10e-3,
                                         friction_coefficient=0.1, psi=psi, ball_radius=5e-3,
                                         nominal_contact_angle=math.radians(40.0))
    assert float(fe_b2b_linear.analytical(steeper).b2b_force) == pytest.approx(float(at_40.b2b_force), rel=1e-14)
    assert float(at_40.b2b_force) != pytest.approx(float(expected.b2b_force), rel=1e-3)
