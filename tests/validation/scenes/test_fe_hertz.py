"""The FE Hertz scenes (validation/scenes/fe_hertz.py) at the quick level: every contact quantity is checked, the wall
time is a budget (reported, decides pass/fail only with ``--strict-time``, so these tests do not depend on the
machine's load), every check names its FE level, and the convergence table has its columns.

Pass/fail of every scene (the screw and nut pairs included): tests/validation/test_scenes.py.
"""
from __future__ import annotations

import pytest

from ballbench.validation.cases import ContactCase
from ballbench.validation.scene import registry
from tests.scene_support import scene_param

FAST = sorted(name for name, entry in registry().items()
              if isinstance(entry.case, ContactCase) and entry.case.pair not in ("screw", "nut"))


@pytest.mark.parametrize("name", [scene_param(name) for name in FAST])
def test_fe_scene_quick_level_checks(name, quick_scene):
    run = quick_scene(name)
    result = run.result
    assert {o.quantity for o in result.outputs} >= {"a", "b", "p0", "delta", "force_sum", "wall_time"}
    budget = next(o for o in result.outputs if o.quantity == "wall_time")
    assert budget.kind == "budget" and budget.reference == 60.0  # docs/fem.md: 60 s at the quick level
    assert budget.family == "FE" and all(o.family == "FE" and o.level for o in result.outputs)
    header = (run.folder / "convergence.csv").read_text().splitlines()[0].split(",")
    assert "mesh_s" in header and not any(column.endswith("_s_s") for column in header)
