"""lowmodel.linear_bearing.contacts: the four contacts of a ball in a linear guide, bad input."""
import math

import numpy as np
import pytest
from ballbench.lowmodel.contact import ellipse_friction as ef
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import contacts as bearing_contacts

# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


RADIUS = 5e-3  # lin2019 Table 1


@pytest.mark.filterwarnings("error")
def test_conformity_near_one_half_names_conformity():
    """Conformity 0.5005 is valid Hertz input, but b/a = 0.0147 is below the friction map's 0.02: the error
    named an internal ``b_over_a`` before."""
    assert hertz.ball_in_groove(RADIUS, 0.5005).axis_ratio < ef.B_OVER_A_RANGE[0]
    with pytest.raises(ValueError, match="conformity") as error:
        bearing_contacts.ball_contacts(np.full(4, math.pi / 4), 0.0, 100.0, ball_radius=RADIUS, conformity=0.5005,
                                   friction_coefficient=0.1, groove_velocity=0.01)
    assert "b_over_a must" not in str(error.value)
    limit = bearing_contacts.minimum_conformity()
    assert 0.5005 < limit < 0.501
    assert hertz.ball_in_groove(RADIUS, limit).axis_ratio == pytest.approx(ef.B_OVER_A_RANGE[0], rel=1e-9)
    bearing_contacts.ball_contacts(np.full(4, math.pi / 4), 0.0, 100.0, ball_radius=RADIUS, conformity=limit + 1e-9,
                               friction_coefficient=0.1, groove_velocity=0.01)
