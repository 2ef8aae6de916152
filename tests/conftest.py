"""Shared fixtures of the test suite."""
import pytest


@pytest.fixture
def quick_scene(tmp_path):
    """``quick_scene(name)`` runs the registered scene ``name`` at the quick fidelity (outputs under
    ``tmp_path``), asserts that it ran without an error and passed every check, and returns its result."""
    def run(name: str):
        from ballbench.validation.runner import run_scene
        from ballbench.validation.scene import registry

        result = run_scene(registry()[name], "quick", tmp_path, show_progress=False)
        assert result.error in (None, ""), result.error
        assert result.passed, [o.quantity for o in result.outputs if not o.passed]
        return result

    return run
