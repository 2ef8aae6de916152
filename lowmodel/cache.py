"""On-disk cache for tabulated maps and meshes (stdlib only).

Location: ``$BALLBENCH_CACHE`` if set, else ``~/.cache/ballbench``.  Entries are
keyed by a hash of their parameters, so a change of any input gives a new entry.
"""
from __future__ import annotations

import hashlib
import json
import os
from pathlib import Path
from typing import Any


def cache_dir(kind: str) -> Path:
    """Directory ``<cache>/<kind>``, created if missing."""
    root = Path(os.environ.get("BALLBENCH_CACHE", Path.home() / ".cache" / "ballbench"))
    directory = root / kind
    directory.mkdir(parents=True, exist_ok=True)
    return directory


def parameter_hash(parameters: dict[str, Any], version: str = "1") -> str:
    """Stable 16-hex-digit hash of JSON-serialisable ``parameters`` and a format ``version``."""
    text = json.dumps({"version": version, **parameters}, sort_keys=True, default=repr)
    return hashlib.sha256(text.encode()).hexdigest()[:16]
