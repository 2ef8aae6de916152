"""Shared styles and the one save of the figures (matplotlib object API)."""
from __future__ import annotations

import math
from pathlib import Path

HERTZ_STYLE = {"color": "#D55E00", "ls": "-", "lw": 2.2}   # Okabe-Ito vermillion, solid
FE_STYLE = {"color": "#56B4E9", "ls": "--", "lw": 2.2}      # Okabe-Ito sky blue, dashed


def figure(**kwargs):
    """A new :class:`matplotlib.figure.Figure` (``figsize``, ``layout``, ...), outside pyplot."""
    from matplotlib.figure import Figure

    return Figure(**kwargs)


def save(fig, path, *, dpi: int = 110, tight: bool = False) -> Path:
    """Write ``fig`` to the PNG ``path`` and return the path (``tight``: crop to the drawn area)."""
    path = Path(path)
    fig.savefig(path, dpi=dpi, **({"bbox_inches": "tight"} if tight else {}))
    return path


def against(value: float, reference: float) -> str:
    """``"+0.010 %"``: the signed relative difference of ``value`` from ``reference`` for a figure label."""
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0.0:
        return "n/a"
    return f"{100.0 * (value / reference - 1.0):+.3f} %"
