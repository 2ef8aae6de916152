"""The half-space and sun2021 dry-contact scenes pass at the quick fidelity (every check, no error)."""
import pytest


@pytest.mark.parametrize("name", ["halfspace-hertz", "sun2021-dry-contact"])
def test_scene_passes_quick(name, quick_scene):
    quick_scene(name)
