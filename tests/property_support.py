"""Shared pieces of the property-based tests of lowmodel's public API (issue 10 item 8, hypothesis).

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

__all__ = ["SETTINGS", "SLOW", "real", "positive", "call", "float_values"]

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
