"""Scene modules.  Every module in this package registers its scenes on import.

One module per model family (``hertz.py``, ``fourpoint.py``, ...); add a
module and its scenes appear in ``ballbench scenes`` without touching this file.
"""
from __future__ import annotations

import importlib
import pkgutil


def load_all() -> None:
    for info in pkgutil.iter_modules(__path__):
        if not info.name.startswith("_"):
            importlib.import_module(f"{__name__}.{info.name}")
