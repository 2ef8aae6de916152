"""tests/property_support.py: the property helper ``call`` itself rejects a NaN result."""
import math

import numpy as np
import pytest

from tests.property_support import call


def test_property_helper_sees_nan():
    """The helper itself fails on a NaN result (a test that cannot fail proves nothing)."""
    with pytest.raises(AssertionError):
        call(lambda x: np.array([x, math.nan]), 1.0)
    with pytest.raises(AssertionError):
        call(lambda x: (_ for _ in ()).throw(ValueError("something else went wrong")), 1.0)
