"""The half-space and sun2021 dry-contact scenes pass at the quick fidelity (every check, no error)."""
import pytest

from ballbench.validation.runner import run_scene
from ballbench.validation.scene import registry
from ballbench.validation.scenes import load_all


@pytest.mark.parametrize("name", ["halfspace-hertz", "sun2021-dry-contact"])
def test_scene_passes_quick(name, tmp_path):
    load_all()
    result = run_scene(registry()[name], "quick", tmp_path, show_progress=False)
    failed = [o.quantity for o in result.outputs if not o.passed]
    assert result.error in (None, ""), result.error
    assert result.passed, failed
