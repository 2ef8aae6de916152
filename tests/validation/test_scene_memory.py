"""A scene's own peak memory (docs/validation.md, "Memory"): what the scene itself needed, not what the process
holds, and the flag of a scene above the memory it declares."""
from __future__ import annotations

import json
import os

import numpy as np
import pytest

from ballbench.validation import cli
from ballbench.validation import scene as scene_module
from ballbench.validation.runner import MemoryUse, SceneMemory, run_scene
from ballbench.validation.scene import Scene

pytestmark = pytest.mark.skipif(not os.path.exists("/proc/self/clear_refs"), reason="needs Linux /proc")

BLOCK = 25_000_000  # float64 values: 0.2 GB
HELD: list = []  # what a scene leaves loaded for the scenes after it (a cache, as a mesh cache does)


def _check(run, value):
    run.check(model="probe", family="analytical", quantity="sum", unit="1", value=value, reference=value,
              source="probe", tolerance=0.0, time_s=0.0)


def _allocating(run):
    block = np.ones(BLOCK)  # touched: resident
    _check(run, float(block.sum()))


def _leaving(run):
    HELD.append(np.ones(BLOCK))
    _check(run, float(HELD[-1].sum()))


def _trivial(run):
    _check(run, 1.0)


def _scene(name, function, memory_gb=None):
    return Scene(name, "probe", function, default=False, kind="low-order", cost_s=0.1, memory_gb=memory_gb)


def test_a_scene_of_200_mb_measures_about_200_mb(tmp_path):
    result = run_scene(_scene("zz-alloc", _allocating), "quick", tmp_path)
    assert result.status() == "pass"
    assert 0.17 < result.scene_peak_memory_gb < 0.3
    assert result.peak_memory_gb >= result.scene_peak_memory_gb  # the process's peak holds the interpreter too
    assert result.declared_memory_gb == 3.5  # low-order's default declaration (scene.DEFAULT_MEMORY_GB)


def test_a_trivial_scene_after_a_heavy_one_measures_near_zero(tmp_path):
    # the heavy scene leaves 0.2 GB loaded; the process's peak during the next scene holds it, the scene's own does not
    try:
        run_scene(_scene("zz-leave", _leaving), "quick", tmp_path)
        after = run_scene(_scene("zz-trivial", _trivial), "quick", tmp_path)
    finally:
        HELD.clear()
    assert 0.0 <= after.scene_peak_memory_gb < 0.05
    assert after.peak_memory_gb - after.scene_peak_memory_gb > 0.17


@pytest.fixture
def over_declared():
    scene_module.REGISTRY["zz-over"] = _scene("zz-over", _allocating, memory_gb=0.1)
    scene_module.REGISTRY["zz-within"] = _scene("zz-within", _allocating, memory_gb=1.0)
    yield
    for name in ("zz-over", "zz-within"):
        scene_module.REGISTRY.pop(name, None)


def test_a_scene_above_its_declared_memory_is_flagged_and_fails_only_strict_time(over_declared, tmp_path, capsys):
    out = tmp_path / "r"
    assert cli.main(["validate", "zz-over", "zz-within", "--out", str(out)]) == 0  # reported, not failed
    err = capsys.readouterr().err
    assert "zz-over" in err and "scene peak memory 0.2 GB over its declared 0.1 GB (reported; --strict-time" in err
    assert "over its declared 1.0 GB" not in err
    scenes = {s["name"]: s for s in json.loads((out / "results.json").read_text())["scenes"]}
    assert scenes["zz-over"]["over_memory"] and not scenes["zz-within"]["over_memory"]
    assert scenes["zz-over"]["declared_memory_gb"] == 0.1 and 0.17 < scenes["zz-over"]["scene_peak_memory_gb"] < 0.3
    report = (out / "report.md").read_text()
    assert "scene peak memory / declared" in report
    budgets = report[report.index("Budgets"):]
    assert "zz-over" in budgets and "zz-within" not in budgets.split("\n#")[0]
    assert cli.main(["validate", "zz-over", "--out", str(tmp_path / "s"), "--strict-time"]) == 1
    assert "over its declared 0.1 GB (--strict-time)" in capsys.readouterr().err


def test_scenes_overlapping_in_one_process_are_not_measured():
    # the peak resident memory is the process's: a scene beside another (a dask worker with several threads) has no
    # own peak to read, so neither says one
    first, second = SceneMemory(), SceneMemory()
    first.start()
    second.start()
    block = np.ones(BLOCK)
    assert second.stop() == MemoryUse() and first.stop() == MemoryUse()
    alone = SceneMemory()
    alone.start()
    block = np.ones(2 * BLOCK)
    used = alone.stop()
    del block
    assert 0.35 < used.scene_peak_gb < 0.5
