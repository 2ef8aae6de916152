"""3D screenshots of fields on a surface grid (the BEM and EHL solutions of ``lowmodel.contact``) saved by
:func:`ballbench.fem.fields.write_surface_fields`: each field a surface raised by its value (docs/render3d.md)."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ballbench.validation.figures import views3d as v

__all__ = ["surface_picture"]

MM, MPA = v.MM, v.MPA
_UNITS = {"_Pa": ("MPa", MPA), "_m": ("um", 1e6)}  # field-name suffix -> picture unit


def _surface_unit(name: str, values: np.ndarray) -> tuple[str, float, str]:
    """``(unit, factor, quantity)`` of a field from its name's unit suffix; lengths below 1 um in nm."""
    for suffix, (unit, factor) in _UNITS.items():
        if name.endswith(suffix):
            quantity = name[: -len(suffix)].replace("_", " ")
            if unit == "um" and float(np.percentile(np.abs(values), 30)) < 1e-6:
                return "nm", 1e9, quantity
            return unit, factor, quantity
    return "", 1.0, name.replace("_", " ")


def surface_picture(meta_path) -> Path:
    """``3d_<name>.png`` of the fields of ``surface_<name>.json`` (:func:`ballbench.fem.fields.write_surface_fields`):
    each field a surface over the grid, raised by its value (the height scale stated) and coloured by it.  A length
    field (a film, a separation) is capped at the 30th percentile of its positive values, about where it leaves
    the contact, and says so."""
    pv = v.pyvista()
    meta_path = Path(meta_path)
    meta = json.loads(meta_path.read_text())
    source = pv.read(str(meta_path.parent / meta["file"]))
    points = np.asarray(source.points) * MM
    width = float(np.ptp(points[:, 0])), float(np.ptp(points[:, 1]))
    names = meta["fields"]
    plot = v.plotter((1, len(names)), (max(900 * len(names), 1300), 720),
                     f"{meta['scene']}: {meta['title']}, {meta['fidelity']} level\nthe fields on the contact plane "
                     f"(x: {meta['axes'][0]}, y: {meta['axes'][1]}), each raised by its value")
    for column, name in enumerate(names):
        v.subplot(plot, 0, column)
        values = np.asarray(source.point_data[name], dtype=float)
        unit, factor, quantity = _surface_unit(name, values)
        shown = values * factor
        note = ""
        if unit in ("um", "nm") and np.any(shown > 0.0):
            cap = float(np.percentile(shown[shown > 0.0], 30))
            note = f", capped at {cap:.3g} {unit}" if float(shown.max()) > cap else ""
            shown = np.minimum(shown, cap)
        top, n_labels = v.colour_scale(float(shown.max()))
        height = 0.35 * max(width) / top
        mesh = pv.PolyData(points.copy(), source.cells)
        mesh.points[:, 2] = shown * height
        mesh.point_data[quantity] = shown
        plot.add_mesh(mesh, scalars=quantity, cmap=v.PRESSURE_CMAP if unit == "MPa" else "cividis", clim=(0.0, top),
                      show_scalar_bar=False)
        fmt = "%.0f" if top >= 10 else "%.2f"
        plot.add_scalar_bar(title=f"{quantity} [{unit}]", n_labels=n_labels, fmt=fmt, title_font_size=15,
                            label_font_size=14, color="black", vertical=True, position_x=0.87, position_y=0.12,
                            width=0.05, height=0.7)
        v.title(plot, f"{quantity} [{unit}]{note}; height: 1 {unit} = {height * 1e3:.3g} um")
        v.scale_bar(plot, (points[:, 0].min(), points[:, 1].min() - 0.08 * width[1], 0.0), (1, 0, 0),
                    v.nice(0.4 * width[0]))
        v.frame_axes(plot)
        centre = points.mean(axis=0) + [0.0, 0.0, 0.3 * top * height]
        v.view(plot, centre, (0.45, 0.65, -0.75), (0, 0, 1), 0.42 * max(width))
    return v.save(plot, meta_path.parent / f"3d_{meta_path.stem.removeprefix('surface_')}.png")
