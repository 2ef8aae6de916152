"""Shared fixtures of the test suite."""
from __future__ import annotations

import pytest

from tests.scene_support import SceneRun


@pytest.fixture(scope="session")
def quick_scene(tmp_path_factory):
    """``quick_scene(name)`` runs the registered scene ``name`` at the quick fidelity once per test session (outputs
    under a session temporary folder) and returns its :class:`~tests.scene_support.SceneRun`.

    tests/validation/test_scenes.py asserts that every scene passes; a scene's own test file asserts what the scene
    shows beyond pass/fail on the same run."""
    runs: dict[str, SceneRun] = {}

    def run(name: str) -> SceneRun:
        if name not in runs:
            from ballbench.validation.runner import run_scene
            from ballbench.validation.scene import registry

            from ballbench.validation.studies.calibration.command import CALIBRATION_ENV

            folder = tmp_path_factory.mktemp("quick")
            with pytest.MonkeyPatch.context() as patch:  # the scene's own constants, not a calibration file's
                patch.delenv(CALIBRATION_ENV, raising=False)
                result = run_scene(registry()[name], "quick", folder, show_progress=False)
            runs[name] = SceneRun(result, folder / name)
        return runs[name]

    return run
