"""Which registered scenes the default test run leaves out, from the scene's own kind and cost.

A scene runs in the default ``pytest`` (slow ones with ``-m slow``) at its quick fidelity.  Slow: every FE scene
(meshing and a contact solve of 10^5 DOFs or more, GBs of memory) and every scene whose declared cost
(``Scene.cost_s``, the wall time at the default fidelity on an idle machine, an upper bound of the quick one) is
above :data:`SLOW_COST_S`, so that the default run stays under 15 minutes on 2 shared cores (docs/developing.md).
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import pytest

SLOW_COST_S = 20.0


@dataclass(frozen=True)
class SceneRun:
    """A scene's result at the quick fidelity and the folder of its files."""
    result: object
    folder: Path


def is_slow(scene) -> bool:
    return scene.kind == "FE" or scene.cost_s > SLOW_COST_S


def scene_param(name: str):
    """``name`` as a pytest parameter, marked slow when the scene is."""
    from ballbench.validation.scene import registry

    return pytest.param(name, marks=(pytest.mark.slow,) if is_slow(registry()[name]) else ())
