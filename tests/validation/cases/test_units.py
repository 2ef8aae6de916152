"""The one units parser (validation/cases/units.py) and the plausibility ranges (lowmodel.checks.PLAUSIBLE) that catch
mm-for-m and deg-for-rad at the models' entry points."""
import math

import pytest

from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.linear_bearing import b2b
from ballbench.validation.cases import units


def test_decimal_units_are_exact():
    # '40 um' is the float 4e-05 (a float multiplication 40 * 1e-6 gives 4.0000000000000003e-05)
    assert units.quantity("40 um", "length", "x") == 4e-05
    assert units.quantity("3.175 mm", "length", "x") == 3.175e-3
    assert units.quantity({"value": 3.175, "unit": "mm"}, "length", "x") == 3.175e-3
    assert units.quantity("2 deg", "angle", "x") == pytest.approx(math.radians(2.0), rel=1e-15)
    assert units.quantity("500 N", "force", "x") == 500.0


def test_wrong_dimension_and_unknown_unit_name_the_key():
    with pytest.raises(units.UnitError, match="ball_radius"):
        units.quantity("3 N", "length", "ball_radius")
    with pytest.raises(units.UnitError, match="ball_radius"):
        units.quantity("3 furlongs", "length", "ball_radius")


@pytest.mark.parametrize("call, name", [
    (lambda: hertz.ball_in_groove(3.175, 0.52), "ball_radius"),        # mm meant
    (lambda: b2b.module_contacts(0.0, 0.0, ball_radius=3.175), "ball_radius"),
    (lambda: b2b.module_contacts(2.0, 0.0), "theta"),                    # deg meant
])
def test_unit_mistakes_in_the_python_api_name_the_parameter_and_si_unit(call, name):
    with pytest.raises(ValueError, match=name) as error:
        call()
    assert "(metres" in str(error.value) or "rad" in str(error.value)
