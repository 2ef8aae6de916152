"""``ballbench show SCENE``: pictures of an FE Hertz scene from the fields ``validate`` saved.

Reads ``<out>/<scene>/fields.vtu`` and ``fields.json`` (written by the FE
scenes, :func:`validation.scenes.fe_hertz.write_fields`); only when they are
missing does it solve the scene's checked level first
(:func:`validation.scenes.fe_hertz.compute_fields`).  Draws off-screen with
matplotlib (no window, no X server; pyvista cuts the mesh) and writes into the
scene's report folder the two figures below, then the 3D screenshots of
:func:`validation.figures.render3d.render` (``3d_*.png``, pyvista off-screen;
for the four-point modules ``fe-b2b-*`` only those, from their saved fields):

* ``pressure.png`` - the contact pressure [MPa] on the deformed contact
  surface of the ball (seen along the contact normal), the symmetry cut
  mirrored to the full contact, with the Hertz ellipse (solid) and the
  fitted FE ellipse (dashed); beside it the pressure along both axes against
  Hertz's ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``;
* ``stress.png`` - the von Mises stress [MPa] on the cut y = 0 through the
  contact centre (the plane of the major semi-axis a), both bodies, mirrored,
  with the Hertz subsurface maximum marked; beside it von Mises along the
  contact axis against Hertz (Boussinesq quadrature,
  validation.references.hertz.axis_stress).

The FE stresses are the element means of the P2 stress, averaged at the
nodes: they smooth peaks on coarse meshes, and the figure says so.
"""
from __future__ import annotations

import contextlib
import io
import json
import math
from pathlib import Path

import numpy as np

__all__ = ["show", "load_fields", "can_show", "against"]

HERTZ_STYLE = {"color": "#D55E00", "ls": "-", "lw": 2.2}   # Okabe-Ito vermillion, solid
FE_STYLE = {"color": "#56B4E9", "ls": "--", "lw": 2.2}      # Okabe-Ito sky blue, dashed


# scenes that save BEM / EHL fields on a surface grid (validation.figures.render3d.surface_artifacts)
SURFACE_SCENES = ("sun2021-dry-contact", "sun2021-ehl", "sun2021-fe-bem")


def can_show(scene_name: str) -> bool:
    """True for the scenes :func:`show` draws: the FE Hertz scenes (``validation.scenes.fe_hertz.FE_SCENES``),
    the two-ball modules ``fe-b2b-*`` and the scenes that save surface fields (SURFACE_SCENES)."""
    from ballbench.validation.scenes import fe_hertz

    return (scene_name.startswith("fe-b2b-") or scene_name in SURFACE_SCENES
            or any(entry.name == scene_name for entry in fe_hertz.FE_SCENES))


def load_fields(directory: Path) -> tuple[dict, dict]:
    """The saved fields of an FE scene: ``(mesh, meta)``; FileNotFoundError if missing.

    ``mesh``: ``points`` (n, 3) [m], ``tets`` (m, 10) quadratic tetrahedra (VTK node order) or (m, 4),
    ``body`` (m,) and the point fields by their names in ``meta["fields"]``.
    """
    import meshio

    directory = Path(directory)
    vtu, meta_path = directory / "fields.vtu", directory / "fields.json"
    if not (vtu.exists() and meta_path.exists()):
        raise FileNotFoundError(f"no saved fields in {directory} (fields.vtu, fields.json)")
    meta = json.loads(meta_path.read_text())
    messages = io.StringIO()
    try:  # meshio prints and calls sys.exit on a file it cannot read
        with contextlib.redirect_stdout(messages), contextlib.redirect_stderr(messages):
            mesh = meshio.read(vtu, file_format="vtu")
    except (SystemExit, Exception) as error:
        reason = " ".join(messages.getvalue().split()) or str(error)
        raise ValueError(f"cannot read {vtu}: {reason}") from None
    for key in ("fields", "hertz", "fe", "symmetry", "level"):
        if key not in meta:
            raise ValueError(f"{meta_path} lacks {key!r}")
    kind = "tetra10" if "tetra10" in mesh.cells_dict else "tetra"
    if kind not in mesh.cells_dict:
        raise ValueError(f"{vtu} holds no tetrahedra")
    data = {"points": np.asarray(mesh.points, dtype=float), "tets": np.asarray(mesh.cells_dict[kind]),
            "body": np.asarray(mesh.cell_data_dict["body"][kind])}
    data.update({name: np.asarray(values) for name, values in mesh.point_data.items()})
    return data, meta


def against(value: float, reference: float) -> str:
    """``"+0.010 %"``: the signed relative difference of ``value`` from ``reference`` for a figure label."""
    if not (math.isfinite(value) and math.isfinite(reference)) or reference == 0.0:
        return "n/a"
    return f"{100.0 * (value / reference - 1.0):+.3f} %"


def _mirror_points(xy: np.ndarray, values: np.ndarray, mirror_x: bool, mirror_y: bool):
    """Mirror a symmetry cut (x >= 0 and/or y >= 0) to the full picture."""
    xy, values = [xy], [values]
    if mirror_x:
        keep = np.abs(xy[0][:, 0]) > 1e-12
        xy.append(xy[0][keep] * [-1, 1])
        values.append(values[0][keep])
    if mirror_y:
        base = np.concatenate(xy)
        base_values = np.concatenate(values)
        keep = np.abs(base[:, 1]) > 1e-12
        xy.append(base[keep] * [1, -1])
        values.append(base_values[keep])
    return np.concatenate(xy), np.concatenate(values)


def _ellipse(a: float, b: float, count: int = 361) -> np.ndarray:
    t = np.linspace(0, 2 * np.pi, count)
    return np.column_stack([a * np.cos(t), b * np.sin(t)])


def _pressure_figure(data: dict, meta: dict, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri

    names = meta["fields"]
    hertz, fe = meta["hertz"], meta["fe"]
    mm = 1e3
    candidate = data["contact_candidate"] > 0.5
    deformed = data["points"] + data[names["displacement"]]
    xy = deformed[candidate][:, :2]
    pressure = data[names["pressure"]][candidate] / 1e6
    xy, pressure = _mirror_points(xy, pressure, meta["symmetry"]["x"], meta["symmetry"]["y"])
    a, b = hertz["a_m"], hertz["b_m"]
    zone = (np.abs(xy[:, 0]) <= 1.5 * a) & (np.abs(xy[:, 1]) <= 1.5 * b)
    xy, pressure = xy[zone], pressure[zone]
    triangulation = mtri.Triangulation(xy[:, 0] * mm, xy[:, 1] * mm)
    aspect = b / a
    figure, (left, right) = plt.subplots(1, 2, figsize=(13, max(4.8, 3.2 + 4.5 * aspect)), layout="constrained",
                                         gridspec_kw={"width_ratios": (1.5, 1.0)})
    from matplotlib.ticker import MaxNLocator

    levels = MaxNLocator(nbins=20).tick_values(0.0, max(float(pressure.max()), hertz["p0_Pa"] / 1e6))
    image = left.tricontourf(triangulation, pressure, levels=levels, cmap="viridis")
    left.plot(*(_ellipse(a, b) * mm).T, **HERTZ_STYLE, label=f"Hertz ellipse a = {a * 1e6:.1f} um, "
                                                             f"b = {b * 1e6:.1f} um")
    left.plot(*(_ellipse(fe["a_m"], fe["b_m"]) * mm).T, **FE_STYLE,
              label=f"fitted FE ellipse a = {fe['a_m'] * 1e6:.1f} um ({against(fe['a_m'], a)} against Hertz), "
                    f"b = {fe['b_m'] * 1e6:.1f} um ({against(fe['b_m'], b)})")
    left.set_aspect("equal")
    left.set_xlabel("x [mm] (major semi-axis a)")
    left.set_ylabel("y [mm] (minor semi-axis b)")
    left.set_xlim(-1.5 * a * mm, 1.5 * a * mm)
    left.set_ylim(-1.5 * b * mm, 1.5 * b * mm)
    figure.legend(*left.get_legend_handles_labels(), loc="outside lower left", fontsize=8, ncol=2, frameon=False)
    left.set_title("contact pressure on the deformed ball surface (seen along the normal)", fontsize=10)
    figure.colorbar(image, ax=left, label="contact pressure [MPa]", location="right", shrink=0.9)
    # profiles along both axes
    band_y = np.abs(xy[:, 1]) <= 0.12 * b
    band_x = np.abs(xy[:, 0]) <= 0.12 * a
    p0 = hertz["p0_Pa"] / 1e6
    s = np.linspace(-1.3, 1.3, 400)
    hertz_profile = p0 * np.sqrt(np.clip(1 - s**2, 0, None))
    right.plot(s, hertz_profile, **HERTZ_STYLE, label=f"Hertz, p0 = {p0:.0f} MPa")
    right.plot(xy[band_y, 0] / a, pressure[band_y], "o", ms=3.5, color="#0072B2",
               label="FE nodes near the x axis (x / a)")
    right.plot(xy[band_x, 1] / b, pressure[band_x], "^", ms=3.5, color="#E69F00",
               label="FE nodes near the y axis (y / b)")
    right.axhline(fe["p0_Pa"] / 1e6, **FE_STYLE, label=f"fitted FE p0 = {fe['p0_Pa'] / 1e6:.0f} MPa "
                                                      f"({against(fe['p0_Pa'], hertz['p0_Pa'])})")
    right.set_xlabel("x / a or y / b [-]")
    right.set_ylabel("contact pressure [MPa]")
    right.set_ylim(bottom=0)
    right.grid(True, alpha=0.3)
    right.legend(fontsize=8, loc="lower center")
    right.set_title("pressure along the axes against Hertz", fontsize=10)
    level = meta["level"]
    figure.suptitle(f"{meta['scene']}: {meta['force_N']:.0f} N, {meta['fidelity']} level (n = b/h {level['n']:g}, "
                    f"growth {level['growth']:g}); coordinates in mm", fontsize=11)
    figure.savefig(path, dpi=100, bbox_inches="tight")
    plt.close(figure)
    return path


def _cut(data: dict, meta: dict, field: str, span: float):
    """Triangles of the cut y = 0 (inside a y-symmetry cut: just inside it) through the contact region."""
    import pyvista as pv
    from vtkmodules.vtkCommonCore import vtkObject

    vtkObject.GlobalWarningDisplayOff()
    y_cut = 1e-6 * span if meta["symmetry"]["y"] else 0.0
    # the elements near the contact that the plane crosses, selected in numpy (cheaper than a VTK clip)
    tets, points = data["tets"], data["points"]
    corners = points[tets[:, :4]]                                    # (m, 4, 3)
    near = np.all(np.abs(corners[:, :, [0, 2]]).min(axis=1) <= span, axis=1)
    crosses = (corners[:, :, 1].min(axis=1) <= y_cut) & (corners[:, :, 1].max(axis=1) >= y_cut)
    chosen = tets[near & crosses]
    used, local = np.unique(chosen, return_inverse=True)
    cell_type = pv.CellType.QUADRATIC_TETRA if tets.shape[1] == 10 else pv.CellType.TETRA
    grid = pv.UnstructuredGrid({cell_type: local.reshape(chosen.shape)}, points[used])
    grid.point_data["value"] = data[field][used]
    cut = grid.slice(normal=(0, 1, 0), origin=(0, y_cut, 0)).triangulate()
    faces = cut.faces.reshape(-1, 4)[:, 1:]
    return np.asarray(cut.points)[:, [0, 2]], faces, np.asarray(cut.point_data["value"])


def _stress_figure(data: dict, meta: dict, path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import matplotlib.tri as mtri

    from ballbench.validation.references.hertz import axis_stress, axis_von_mises_maximum

    hertz = meta["hertz"]
    a, b, p0 = hertz["a_m"], hertz["b_m"], hertz["p0_Pa"]
    nu = meta["poisson_ratio"]
    mm = 1e3
    span = 3.0 * max(a, b)
    xz, faces, von_mises = _cut(data, meta, meta["fields"]["von_mises"], span)
    if meta["symmetry"]["x"]:
        count = len(xz)
        xz = np.concatenate([xz, xz * [-1, 1]])
        faces = np.concatenate([faces, faces + count])
        von_mises = np.concatenate([von_mises, von_mises])
    depth_max, value_max = axis_von_mises_maximum(a, b, p0, nu)
    figure, (left, right) = plt.subplots(1, 2, figsize=(13, 5.6), layout="constrained",
                                         gridspec_kw={"width_ratios": (1.5, 1.0)})
    triangulation = mtri.Triangulation(xz[:, 0] * mm, xz[:, 1] * mm, faces)
    top = max(float(von_mises.max()), value_max) / 1e6
    image = left.tripcolor(triangulation, von_mises / 1e6, shading="gouraud", cmap="magma", vmin=0, vmax=top)
    figure.colorbar(image, ax=left, label="von Mises stress [MPa]", location="right", shrink=0.9)
    left.plot([0, 0], [depth_max * mm, -depth_max * mm], marker="x", ms=11, mew=2.5, color="#56B4E9", ls="none",
              label=f"Hertz subsurface maximum {value_max / 1e6:.0f} MPa at depth {depth_max * 1e6:.1f} um")
    left.axhline(0.0, color="0.7", lw=0.6, ls=":")
    left.set_aspect("equal")
    left.set_xlim(-span * mm, span * mm)
    left.set_ylim(-span * mm, span * mm)
    left.set_xlabel("x [mm] (major semi-axis a)")
    left.set_ylabel("z [mm] (contact normal: ball above, counter body below)")
    left.legend(loc="upper left", fontsize=8)
    left.set_title("von Mises stress on the cut y = 0 through the contact centre", fontsize=10)
    # along the axis
    axis_span = min(span, 6.0 * depth_max)
    depth = np.linspace(0.005, 1.0, 150) * axis_span
    sx, sy, sz = axis_stress(a, b, p0, nu, depth)
    reference = np.sqrt(0.5 * ((sx - sy) ** 2 + (sy - sz) ** 2 + (sz - sx) ** 2))
    right.plot(reference / 1e6, depth * 1e6, **HERTZ_STYLE, label="Hertz (Boussinesq quadrature)")
    right.plot(reference / 1e6, -depth * 1e6, **HERTZ_STYLE)
    near_axis = (np.abs(xz[:, 0]) <= 0.08 * a) & (np.abs(xz[:, 1]) <= axis_span)
    right.plot(von_mises[near_axis] / 1e6, xz[near_axis, 1] * 1e6, "o", ms=3.5, color="#0072B2",
               label="FE nodes near the axis (nodal average of element means)")
    right.plot([value_max / 1e6] * 2, [depth_max * 1e6, -depth_max * 1e6], "x", ms=10, mew=2.5, color="#56B4E9",
               ls="none", label=f"Hertz maximum {value_max / p0:.3f} p0")
    right.set_ylim(-axis_span * 1e6, axis_span * 1e6)
    right.set_xlabel("von Mises stress [MPa]")
    right.set_ylabel("z [um] on the contact axis")
    right.grid(True, alpha=0.3)
    right.legend(fontsize=8, loc="lower right")
    right.set_title("along the contact axis against Hertz", fontsize=10)
    level = meta["level"]
    figure.suptitle(f"{meta['scene']}: {meta['force_N']:.0f} N, {meta['fidelity']} level (n = b/h {level['n']:g}, "
                    f"growth {level['growth']:g}); FE stress: element means of the P2 stress averaged at the "
                    "nodes (smooths peaks on coarse meshes)", fontsize=10)
    figure.savefig(path, dpi=100)
    plt.close(figure)
    return path


def show(scene_name: str, out_dir: Path, fidelity: str = "default", *, show_progress: bool = False) -> list[Path]:
    """Draw FE scene ``scene_name`` from its saved fields in ``<out_dir>/<scene>/``; returns the PNG paths.

    Solves the scene's checked level at ``fidelity`` first only when no fields are saved there.
    """
    import sys

    from ballbench.validation.figures import render3d
    from ballbench.validation.scenes import fe_hertz

    if scene_name in SURFACE_SCENES:  # their BEM / EHL fields, saved by validate (3D screenshots only)
        if not render3d.has_fields(Path(out_dir) / scene_name):
            raise FileNotFoundError(f"no saved surface fields in {Path(out_dir) / scene_name}: run 'ballbench "
                                    f"validate {scene_name} --out {out_dir}' first")
        return render3d.render(Path(out_dir) / scene_name)
    if scene_name.startswith("fe-b2b-") and render3d.has_fields(Path(out_dir) / scene_name):
        return render3d.render(Path(out_dir) / scene_name)  # the modules' saved fields: 3D screenshots, no solve
    if scene_name.startswith("fe-b2b-screw-"):  # the ball-screw modules (validation/scenes/fe_b2b_screw.py)
        from ballbench.validation.scenes import fe_b2b_screw

        return fe_b2b_screw.show(scene_name, out_dir, fidelity)
    if scene_name.startswith("fe-b2b-"):  # the four-point modules (validation/scenes/fe_b2b.py)
        from ballbench.validation.scenes import fe_b2b

        return fe_b2b.show(scene_name, out_dir, fidelity)
    entry = fe_hertz.fe_scene(scene_name)  # ValueError naming the FE scenes
    if fidelity not in entry.levels:
        raise ValueError(f"fidelity must be one of {tuple(entry.levels)}, got {fidelity!r}")
    directory = Path(out_dir) / scene_name
    try:
        data, meta = load_fields(directory)
    except FileNotFoundError:
        hint = ""
        results = Path(out_dir) / "results.json"
        if fidelity != "quick" and results.is_file():
            try:
                if json.loads(results.read_text()).get("fidelity") == "quick":
                    hint = (f"; the report there is a --quick run, which saves no fields ('ballbench show "
                            f"{scene_name} --quick' draws the quick level)")
            except (OSError, ValueError):
                pass
        print(f"ballbench: no saved fields in {directory}; solving the {fidelity} level of {scene_name} first "
              f"(about {entry.cost_s:.0f} s){hint}", file=sys.stderr, flush=True)
        fe_hertz.compute_fields(scene_name, fidelity, directory, show_progress=show_progress)
        data, meta = load_fields(directory)
    if not math.isfinite(meta["hertz"]["a_m"]):
        raise ValueError(f"{directory / 'fields.json'}: no Hertz reference")
    return [_pressure_figure(data, meta, directory / "pressure.png"),
            _stress_figure(data, meta, directory / "stress.png")] + render3d.render(directory)
