"""Shared pieces of the property-based tests of lowmodel's public API (hypothesis).

``call(function, ...)``: finite result, or a ValueError / ConvergenceError whose message names a parameter
of the call; never NaN, never a warning.  Strategies ``real`` and ``positive`` draw finite floats.
``BALLBENCH_PROPERTY_SCALE=k`` (environment) multiplies the examples of every property test by k.
"""
from __future__ import annotations

import dataclasses
import inspect
import math
import os
import warnings

import numpy as np
from hypothesis import HealthCheck, settings
from hypothesis import strategies as st

from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["SETTINGS", "SLOW", "real", "positive", "call", "float_values", "angle", "EXTREME", "angle_limits", "mostly",
           "one_bad", "length", "speed", "force", "lead_angle", "contact_angle", "ball_fraction", "count"]

# BALLBENCH_PROPERTY_SCALE=k runs k times the examples (still derandomized: fixed seeds), for a long stress run
_SCALE = max(1, int(os.environ.get("BALLBENCH_PROPERTY_SCALE", "1")))
SETTINGS = settings(max_examples=40 * _SCALE, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.too_slow])
SLOW = settings(max_examples=12 * _SCALE, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])


def real(low, high):
    return st.floats(low, high, allow_nan=False, allow_infinity=False)


def positive(low=1e-6, high=1e6):
    return st.floats(low, high, allow_nan=False, allow_infinity=False, exclude_min=True)


def float_values(result):
    """Every float in a result (arrays, scalars, dataclasses, tuples), flattened."""
    if dataclasses.is_dataclass(result):
        return [v for field in dataclasses.fields(result) for v in float_values(getattr(result, field.name))]
    if isinstance(result, (tuple, list)):
        return [v for item in result for v in float_values(item)]
    if isinstance(result, (bool, str, type(None))):
        return []
    array = np.asarray(result)
    if array.dtype.kind in "fc":
        return [array]
    return []


CALLS = {"returned": 0, "ValueError": 0, "ConvergenceError": 0}  # outcomes of call(), for a stress run's report


def call(function, *args, allow_inf=(), **kwargs):
    """``function(*args, **kwargs)`` under the property: finite result, or an error naming a parameter."""
    names = set(inspect.signature(function).parameters)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        try:
            result = function(*args, **kwargs)
        except ValueError as error:
            CALLS["ValueError"] += 1
            assert any(name in str(error) for name in names), f"{function.__name__}: {error}"
            return None
        except ConvergenceError as error:
            CALLS["ConvergenceError"] += 1
            assert math.isfinite(error.residual) or error.residual == math.inf
            assert str(error) and error.reason, f"{function.__name__}: ConvergenceError without a reason: {error}"
            return None
    CALLS["returned"] += 1
    if dataclasses.is_dataclass(result):
        for field in dataclasses.fields(result):
            if field.name in allow_inf:
                continue
            for array in float_values(getattr(result, field.name)):
                assert np.all(np.isfinite(array)), f"{function.__name__}.{field.name} not finite"
    else:
        for array in float_values(result):
            assert np.all(np.isfinite(array)), f"{function.__name__} not finite"
    return result


# contact angles: the whole of (0, pi/2) rad, with the last 1e-3 rad at either end (where lin2017 eqs 23, 36 and
# lin2019 eqs 30, 32 divide by sin or cos of them) drawn as often as the rest, the extreme floats near 0 and pi/2,
# and outside (0, pi/2) for the errors
angle = st.one_of(real(1e-3, 0.5 * math.pi - 1e-3), real(0.0, 1e-3), real(0.5 * math.pi - 1e-3, 0.5 * math.pi),
                  st.sampled_from([5e-324, 2.2250738585072014e-308, 1e-200, 1e-16, math.nextafter(0.5 * math.pi, 0.0),
                                   0.5 * math.pi * (1.0 - 1e-12)]),
                  real(-0.2, 0.0), real(0.5 * math.pi, 1.8))

# the extreme floats, zero and negatives; angles at and beyond the ends of [0, pi/2]
EXTREME = [0.0, 5e-324, 2.2250738585072014e-308, 1e-300, 1e-16, 1e16, 1e300, 1.7976931348623157e308, -1e-3, -1.0]
angle_limits = (5e-324, 1e-16, math.nextafter(0.5 * math.pi, 0.0), 0.5 * math.pi, 0.0, -0.1, 2.0)


def mostly(valid, *invalid):
    """``valid`` draws with about one in eight from ``invalid`` (bad or extreme values): most calls get through
    the input checks to the computation, and every check still sees its bad inputs."""
    return st.integers(0, 7).flatmap(lambda i: st.sampled_from(invalid) if i == 7 else valid)


def one_bad(valid: dict, bad: dict):
    """Keyword dicts: every value drawn from ``valid`` (the documented ranges), and in half the cases one of them
    replaced by a draw from ``bad`` (zero, negative, huge, tiny, a bool count), so that the solves run often."""
    keys = sorted(bad)
    return st.fixed_dictionaries(valid).flatmap(lambda kw: st.sampled_from([None] * len(keys) + keys).flatmap(
        lambda key: st.just(kw) if key is None else bad[key].map(lambda value: {**kw, key: value})))


# draws of the screw-scale inputs shared by the geometry, contact and screw property tests: lengths [m] (real
# screws: mm), speeds [rad/s or m/s], forces [N] as physical draws with the extreme floats, zero and negatives
# among the rest; angles [rad] over [0, pi/2) and beyond; ball radius / pitch radius; counts with bools and floats
length = mostly(positive(1e-4, 0.1), *EXTREME)
speed = mostly(real(-1e3, 1e3), *EXTREME, -1e300)
force = mostly(real(0.0, 1e4), *EXTREME)
lead_angle = mostly(real(0.0, 1.4), *angle_limits)  # [0, pi/2)
contact_angle = st.one_of(mostly(real(0.2, 1.3), *angle_limits), angle)  # (0, pi/2)
ball_fraction = mostly(real(0.05, 0.3), 0.5, 1.0, 2.0, 1e300, 1e-300)
count = mostly(st.integers(1, 40), -1, 0, True, False, 2.0, 3.5)
