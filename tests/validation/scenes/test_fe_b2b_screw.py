"""The fe-b2b-screw-* scenes at the quick level (two FE modules, 224k P2 DOFs in all, + FE-informed B2B): the B2B force,
the power balance and the friction increase are checked; pass/fail: tests/validation/test_scenes.py."""
from __future__ import annotations

import pytest

from tests.scene_support import scene_param


@pytest.mark.parametrize("name", [scene_param("fe-b2b-screw-a"), scene_param("fe-b2b-screw-b")])
def test_fe_b2b_screw_scene_checks(name, quick_scene):
    assert {"F_B2B", "power balance (input - losses)/input", "friction increase by B2B"} <= {
        o.quantity for o in quick_scene(name).result.outputs}
