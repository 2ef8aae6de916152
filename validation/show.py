"""``ballbench show SCENE``: off-screen pyvista screenshots of an FE Hertz scene.

Two PNGs in ``<out>/<scene>/``:

* ``pressure.png`` - nodal contact pressure [MPa] on the ball's contact surface
  (seen along -z, through the counter body), with the Hertz ellipse outline
  (lowmodel.contact.hertz, semi-axes a along x, b along y) drawn over it and the
  fitted FE ellipse dashed;
* ``displacement.png`` - displacement magnitude [um] on the cut y = 0 through
  the contact (both bodies), zoomed on the contact.

Coordinates are shown in mm.  The mesh level is the scene's level for the
fidelity (``default``; ``quick`` the coarse CI level).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["show"]


def _ellipse(a: float, b: float, z: float, quarter: bool, half: bool, count: int = 200) -> np.ndarray:
    start = 0.0
    stop = np.pi / 2 if quarter else (np.pi if half else 2 * np.pi)
    t = np.linspace(start, stop, count)
    return np.column_stack([a * np.cos(t), b * np.sin(t), np.full_like(t, z)])


def show(scene_name: str, out_dir: Path, fidelity: str = "default") -> list[Path]:
    """Solve the scene's FE case at ``fidelity`` and write its screenshots; returns the PNG paths."""
    import pyvista as pv

    from ballbench.fem.contact import full_displacement
    from ballbench.validation.scenes import fe_hertz

    entry = fe_hertz.fe_scene(scene_name)  # ValueError naming the FE scenes
    if fidelity not in entry.levels:
        raise ValueError(f"fidelity must be one of {tuple(entry.levels)}, got {fidelity!r}")
    pv.OFF_SCREEN = True
    case = fe_hertz.pair_case(scene_name)
    n, growth = case.level_list(fidelity)[-1]
    result, ref = fe_hertz.solve_level(case, n, growth)
    model, state = result.model, result.state
    pair = model.pair
    target = Path(out_dir) / scene_name
    target.mkdir(parents=True, exist_ok=True)
    mm = 1e3
    quarter = "symmetry_x" in pair.surfaces
    half = "symmetry_y" in pair.surfaces
    paths = []

    # --- contact pressure on the ball's contact surface
    pressure = np.zeros(len(pair.points))
    pressure[model.candidates] = state.pressure / 1e6
    zone = np.zeros(len(pair.points), bool)
    zone[model.candidates] = True
    tris = pair.surfaces["ball_contact"]
    tris = tris[zone[tris].all(axis=1)]
    used = np.unique(tris)
    remap = -np.ones(len(pair.points), dtype=np.int64)
    remap[used] = np.arange(used.size)
    points = pair.points[used] * mm
    points[:, 2] = 0.0  # the projection on the contact plane
    faces = np.hstack([np.full((len(tris), 1), 3), remap[tris]]).ravel()
    surface = pv.PolyData(points, faces)
    surface.point_data["contact pressure [MPa]"] = pressure[used]
    plotter = pv.Plotter(off_screen=True, window_size=(1200, 900))
    plotter.add_mesh(surface, scalars="contact pressure [MPa]", cmap="viridis", show_edges=True, edge_color="grey",
                     line_width=0.3, scalar_bar_args={"title": "contact pressure [MPa]", "vertical": False,
                                                      "position_x": 0.25, "position_y": 0.06, "width": 0.5,
                                                      "fmt": "%.0f"})
    hertz_line = pv.lines_from_points(_ellipse(ref.a * mm, ref.b * mm, 1e-4, quarter, half))
    plotter.add_mesh(hertz_line, color="red", line_width=4, label=f"Hertz ellipse a = {ref.a * 1e3:.4f} mm, "
                                                                  f"b = {ref.b * 1e3:.4f} mm")
    fit_line = pv.lines_from_points(_ellipse(result.a * mm, result.b * mm, 2e-4, quarter, half))
    plotter.add_mesh(fit_line, color="white", line_width=2, label=f"FE fit a = {result.a * 1e3:.4f} mm, "
                                                                  f"b = {result.b * 1e3:.4f} mm")
    plotter.add_legend(bcolor="black", size=(0.45, 0.1), loc="upper left")
    plotter.add_text(f"{scene_name}: p0 FE {result.p0 / 1e6:.0f} MPa, Hertz {float(ref.p0) / 1e6:.0f} MPa "
                     f"(coordinates in mm)", position="upper_right", font_size=10)
    plotter.view_xy()
    plotter.show_bounds(xtitle="x [mm]", ytitle="y [mm]", ztitle="", font_size=10, fmt="%.3f")
    path = target / "pressure.png"
    plotter.screenshot(str(path))
    plotter.close()
    paths.append(path)

    # --- displacement magnitude on the cut y = 0 (or y = eps inside a cut model)
    u = full_displacement(model, state)
    grid = pv.UnstructuredGrid({pv.CellType.TETRA: pair.tets}, pair.points * mm)
    grid.point_data["|u| [um]"] = np.linalg.norm(u, axis=1) * 1e6
    span = 4.0 * max(result.a, result.b) * mm
    clipped = grid.clip_box([-span, span, -span, span, -span, span], invert=False)
    y_cut = 1e-6 * span if half else 0.0
    cut = clipped.slice(normal=(0, 1, 0), origin=(0, y_cut, 0))
    plotter = pv.Plotter(off_screen=True, window_size=(1200, 900))
    plotter.add_mesh(cut, scalars="|u| [um]", cmap="plasma", show_edges=True, edge_color="grey", line_width=0.2,
                     scalar_bar_args={"title": "displacement magnitude [um]", "vertical": False, "position_x": 0.25,
                                      "position_y": 0.06, "width": 0.5, "fmt": "%.2f"})
    plotter.add_text(f"{scene_name}: cut y = 0 through the contact, approach {result.approach * 1e6:.3f} um "
                     f"(coordinates in mm)", position="upper_left", font_size=10)
    plotter.view_xz()
    plotter.show_bounds(xtitle="x [mm]", ytitle="", ztitle="z [mm]", font_size=10, fmt="%.2f")
    path = target / "displacement.png"
    plotter.screenshot(str(path))
    plotter.close()
    paths.append(path)
    return paths
