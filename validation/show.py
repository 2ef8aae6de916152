"""``ballbench show SCENE``: the pictures of a scene, drawn by the scene's own ``show`` hook.

A scene that has pictures declares ``@scene(..., show=hook)`` with ``hook(scene_dir, fidelity, solve=False) ->
list[Path]``: it draws into ``<out>/<scene>/`` from what the scene saved there (fields.vtu, fields.json); where
nothing is saved it raises FileNotFoundError, or with ``solve`` solves the scene's checked level at ``fidelity``
first (validation.studies; ``ballbench show --solve``).  This
module knows no scene: it looks the scene up in the registry and calls its hook.  A drawable scene is found
through ``validation.scenes.SHOWN_IN``, which imports only the module that registers it (docs/render3d.md,
"Cost"); any other name is looked up in the full registry.
"""
from __future__ import annotations

from pathlib import Path

from ballbench.validation import scenes
from ballbench.validation.scene import FIDELITIES, REGISTRY, Scene, registry

__all__ = ["show", "can_show", "drawable"]


def drawable() -> list[str]:
    """Names of the registered scenes with a ``show`` hook, sorted."""
    return sorted(name for name, entry in registry().items() if entry.show is not None)


def _entry(scene_name: str) -> Scene | None:
    if scenes.load_shown(scene_name) and scene_name in REGISTRY:
        return REGISTRY[scene_name]
    return registry().get(scene_name)


def can_show(scene_name: str) -> bool:
    """True for a registered scene with a ``show`` hook (the FE scenes that save fields or solve their modules)."""
    entry = _entry(scene_name)
    return entry is not None and entry.show is not None


def show(scene_name: str, out_dir: Path, fidelity: str = "default", solve: bool = False) -> list[Path]:
    """Draw scene ``scene_name`` into ``<out_dir>/<scene>/`` with its hook; returns the PNG paths.

    FileNotFoundError where the scene saved nothing there (with ``solve``: its checked level at ``fidelity`` is
    solved first instead); ValueError for a scene without pictures (naming the FE scenes that have them) or an
    unknown fidelity.
    """
    if not can_show(scene_name):
        raise ValueError(f"show draws the FE scenes with pictures ({', '.join(drawable())}), got {scene_name!r}")
    if fidelity not in FIDELITIES:
        raise ValueError(f"fidelity must be one of {FIDELITIES}, got {fidelity!r}")
    return _entry(scene_name).show(Path(out_dir) / scene_name, fidelity, solve)
