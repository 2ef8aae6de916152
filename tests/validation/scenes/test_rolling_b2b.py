"""The stick/slip B2B scenes and the full-slip validity scene at the quick level (validation/scenes/rolling_b2b.py;
docs/b2b_rolling.md)."""
from __future__ import annotations

import pytest


@pytest.mark.slow
def test_full_slip_validity_scene_quick(quick_scene):
    result = quick_scene("full-slip-validity").result
    assert all(o.family for o in result.outputs if o.kind == "accuracy")


@pytest.mark.slow
@pytest.mark.parametrize("name", ["rolling-b2b-linear-a", "rolling-b2b-linear-b"])
def test_rolling_b2b_scene_quick(quick_scene, name):
    result = quick_scene(name).result
    families = {o.family for o in result.outputs if o.kind == "accuracy"}
    assert {"BEM", "FE-informed", "low-order numerical"} <= families
