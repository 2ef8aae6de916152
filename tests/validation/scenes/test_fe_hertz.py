"""The coarse (quick) level of every FE Hertz scene, as CI runs it: every check passes.

The wall time of each scene is a budget (reported, decides pass/fail only with
``--strict-time``), so these tests do not depend on the machine's load.  The
screw pair (full helical model, ~340k P2 DOFs, ~7 GB) is marked slow.
"""
from __future__ import annotations

import pytest

from ballbench.validation.cases import ContactCase
from ballbench.validation.runner import run_scene
from ballbench.validation.scene import registry

FAST = sorted(name for name, entry in registry().items()
              if isinstance(entry.case, ContactCase) and entry.case.pair not in ("screw", "nut"))


@pytest.mark.parametrize("name", FAST)
def test_fe_scene_quick_level_passes(name, tmp_path):
    result = run_scene(registry()[name], "quick", tmp_path)
    assert not result.error, result.error
    failed = [(o.quantity, o.rel_error, o.tolerance) for o in result.outputs if o.status == "fail"]
    assert result.passed, failed
    assert {o.quantity for o in result.outputs} >= {"a", "b", "p0", "delta", "force_sum", "wall_time"}
    budget = next(o for o in result.outputs if o.quantity == "wall_time")
    assert budget.kind == "budget" and budget.reference == 60.0  # docs/fem.md: 60 s at the quick level
    assert budget.family == "FE" and all(o.family == "FE" and o.level for o in result.outputs)
    header = (tmp_path / name / "convergence.csv").read_text().splitlines()[0].split(",")
    assert "mesh_s" in header and not any(column.endswith("_s_s") for column in header)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["fe-hertz-screw", "fe-hertz-nut"])
def test_fe_screw_quick_level_passes(name, tmp_path):
    result = run_scene(registry()[name], "quick", tmp_path)
    assert not result.error, result.error
    assert result.passed, [(o.quantity, o.rel_error) for o in result.outputs if o.status == "fail"]


@pytest.mark.slow
@pytest.mark.parametrize("name", ["fe-b2b-linear-a", "fe-b2b-linear-b"])
def test_fe_b2b_scene_quick_level_passes(name, tmp_path):
    # FE four-point module (111k P2 DOFs) for both balls' loads + FE-informed B2B: ~30-40 s each
    result = run_scene(registry()[name], "quick", tmp_path, show_progress=False)
    assert result.passed, [o for o in result.outputs if not o.passed] or result.error
