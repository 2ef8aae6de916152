"""Every registered scene at its quick fidelity: it runs without an error and passes (known gaps allowed, an
unexpected pass of a known gap fails), and each of its checks names its model family.

Slow (``-m slow``): FE scenes and scenes that cost more than 20 s (tests/scene_support.py).  What a scene shows
beyond pass/fail is tested in tests/validation/scenes/, on the same run.
"""
from __future__ import annotations

import pytest

from ballbench.validation.scene import FAMILIES, registry
from tests.scene_support import scene_param

SCENES = sorted(registry())


@pytest.mark.parametrize("name", [scene_param(name) for name in SCENES])
def test_scene_passes_at_the_quick_level(name, quick_scene):
    result = quick_scene(name).result
    assert not result.error, result.error
    failed = [(o.quantity, o.status, o.rel_error, o.tolerance) for o in result.outputs
              if o.status in ("fail", "unexpected pass")]
    assert result.status() in ("pass", "known gap"), failed
    assert all(o.family in FAMILIES for o in result.outputs if o.kind == "accuracy")

