"""Scene modules.  Every module in this package registers its scenes on import.

One module per model family (``hertz.py``, ``fourpoint.py``, ...); add a
module and its scenes appear in ``ballbench scenes`` without touching this file.

:data:`SHOWN_IN` names the module of each scene with a ``show`` hook, so that ``ballbench show SCENE`` imports
that one module rather than all of them (docs/render3d.md, "Cost"); a test keeps it equal to what the full
registry says.
"""
from __future__ import annotations

import importlib
import pkgutil

SHOWN_IN = {
    "fe-b2b-linear-a": "fe_b2b",
    "fe-b2b-linear-b": "fe_b2b",
    "fe-b2b-screw-a": "fe_b2b_screw",
    "fe-b2b-screw-b": "fe_b2b_screw",
    "fe-hertz-ball-ball": "fe_hertz",
    "fe-hertz-flat": "fe_hertz",
    "fe-hertz-groove-052": "fe_hertz",
    "fe-hertz-groove-056": "fe_hertz",
    "fe-hertz-groove-060": "fe_hertz",
    "fe-hertz-nut": "fe_hertz",
    "fe-hertz-screw": "fe_hertz",
    "rolling-b2b-linear-a": "rolling_b2b",
    "rolling-b2b-linear-b": "rolling_b2b",
    "rolling-b2b-screw-a": "rolling_b2b",
    "rolling-b2b-screw-b": "rolling_b2b",
    "rolling-cattaneo": "rolling",
    "rolling-fe-compliance": "rolling",
    "rolling-lin2019-contacts": "rolling",
    "rolling-tractcurv": "rolling",
    "sun2021-dry-contact": "sun2021",
    "sun2021-ehl": "sun2021",
    "sun2021-fe-bem": "sun2021_fe",
}


def load_all() -> None:
    for info in pkgutil.iter_modules(__path__):
        if not info.name.startswith("_"):
            importlib.import_module(f"{__name__}.{info.name}")


def load_shown(scene_name: str) -> bool:
    """Import the module that registers the drawable scene ``scene_name``; False for a name not in
    :data:`SHOWN_IN` (the caller then looks in the full registry)."""
    module = SHOWN_IN.get(scene_name)
    if module is None:
        return False
    importlib.import_module(f"{__name__}.{module}")
    return True
