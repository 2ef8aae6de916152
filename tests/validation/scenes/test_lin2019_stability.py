"""The lin2019-stability sweep at the quick level: 100 % convergence of free balls with spin-capacity ratio >= 1.05
(pass/fail and a reason for every failure: tests/validation/test_scenes.py)."""
from __future__ import annotations

import pytest

from tests.scene_support import scene_param


@pytest.mark.parametrize("name", [scene_param("lin2019-stability")])
def test_stability_sweep_converges_for_every_free_ball(name, quick_scene):
    converged = [o for o in quick_scene(name).result.outputs
                 if o.quantity.startswith("converged fraction of free balls")]
    assert converged and converged[0].value == 1.0
