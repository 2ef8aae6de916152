"""studies.bearing_results: the engineer's results of a case (friction force / torque, per-ball loads)."""
import dataclasses

import numpy as np
import pytest

from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts
from ballbench.validation.cases import case_file
from ballbench.validation.studies import bearing_results
from tests import paths

GUIDE = paths.ROOT / "examples" / "compact_linear_guide.toml"


def test_module_contacts_and_the_general_ball_contacts_agree_on_the_papers_deviations():
    case = case_file.load(GUIDE)
    guide = case.guide
    general = bearing_contacts.ball_contacts(
        np.tile(case.contact_angles, (case.n_balls, 1)), [case.side_force(j) for j in range(case.n_balls)],
        case.vertical_force, ball_radius=guide.ball_radius, conformity=guide.conformity,
        friction_coefficient=guide.friction_coefficient, groove_velocity=guide.groove_velocity,
        **guide.material.keywords)
    module = bearing_results.guide_contacts(case)
    np.testing.assert_allclose(module.normal_forces, general.normal_forces, rtol=1e-13)


def test_any_four_deviations_give_a_result():
    # bottom deviations that are not (-theta, +theta) used to raise in case.theta
    case = dataclasses.replace(case_file.load(GUIDE), deviations=(-0.02, 0.01, 0.0, 0.005))
    result = bearing_results.guide_result(case)
    assert result.friction_force == pytest.approx(result.power / case.guide.groove_velocity, rel=1e-12)
    assert result.friction_force > 0 and len(result.contacts) == 4 * case.n_balls
