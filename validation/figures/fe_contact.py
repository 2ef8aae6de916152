"""Pictures of an FE contact pair (studies.fe_contact): mesh convergence, and the saved fields of the checked
level against Hertz.

* :func:`pressure_figure`: the contact pressure [MPa] on the deformed contact surface of the ball (seen along
  the contact normal), the symmetry cut mirrored to the full contact, with the Hertz ellipse (solid) and the
  fitted FE ellipse (dashed); beside it the pressure along both axes against Hertz's
  ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``;
* :func:`stress_figure`: the von Mises stress [MPa] on the cut y = 0 through the contact centre (the plane of
  the major semi-axis a), both bodies, mirrored, with the Hertz subsurface maximum marked; beside it von Mises
  along the contact axis against Hertz (Boussinesq quadrature, validation.references.hertz.axis_stress).

The FE stresses are the element means of the P2 stress, averaged at the nodes: they smooth peaks on coarse
meshes, and the figure says so.  Off-screen: matplotlib draws, pyvista only cuts the mesh (no VTK rendering).
"""
from __future__ import annotations

import numpy as np

from ballbench.validation.figures.style import FE_STYLE, HERTZ_STYLE, against, figure
from ballbench.validation.figures.views3d import MM, MPA, hertz_maximum
from ballbench.validation.references.hertz import axis_stress

QUANTITIES = ("a", "b", "p0", "delta")


def convergence_figure(scene_name: str, rows: list[dict]):
    """|error| against Hertz [%] of a, b, p0, delta over the mesh levels ``rows`` (``h_contact`` [m],
    ``wall_s`` [s], ``err_<quantity>``): against the element size at the contact and against wall time."""
    fig = figure(figsize=(10, 4))
    axes = fig.subplots(1, 2)
    h = np.array([r["h_contact"] for r in rows]) * 1e6
    t = np.array([r["wall_s"] for r in rows])
    for quantity in QUANTITIES:
        err = np.abs([r[f"err_{quantity}"] for r in rows]) * 100
        axes[0].loglog(h, err, "o-", label=quantity)
        axes[1].loglog(t, err, "o-", label=quantity)
    axes[0].set_xlabel("h at the contact [um]")
    axes[1].set_xlabel("wall time [s]")
    for ax in axes:
        ax.set_ylabel("|error| vs Hertz [%]")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend()
    fig.suptitle(f"{scene_name}: mesh convergence")
    return fig


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


def pressure_figure(data: dict, meta: dict):
    """The contact pressure of the saved fields ``(data, meta)`` (studies.fe_contact.load_fields)."""
    import matplotlib.tri as mtri
    from matplotlib.ticker import MaxNLocator

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
    fig = figure(figsize=(13, max(4.8, 3.2 + 4.5 * aspect)), layout="constrained")
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": (1.5, 1.0)})
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
    fig.legend(*left.get_legend_handles_labels(), loc="outside lower left", fontsize=8, ncol=2, frameon=False)
    left.set_title("contact pressure on the deformed ball surface (seen along the normal)", fontsize=10)
    fig.colorbar(image, ax=left, label="contact pressure [MPa]", location="right", shrink=0.9)
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
    fig.suptitle(f"{meta['scene']}: {meta['force_N']:.0f} N, {meta['fidelity']} level (n = b/h {level['n']:g}, "
                 f"growth {level['growth']:g}); coordinates in mm", fontsize=11)
    return fig


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


def stress_figure(data: dict, meta: dict):
    """The von Mises stress of the saved fields ``(data, meta)`` on the cut y = 0 and along the contact axis."""
    import matplotlib.tri as mtri

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
    depth_max, value_max = hertz_maximum(a, b, p0, nu)  # the 3D stress picture's maximum, computed once
    depth_max, value_max = depth_max / MM, value_max / MPA
    fig = figure(figsize=(13, 5.6), layout="constrained")
    left, right = fig.subplots(1, 2, gridspec_kw={"width_ratios": (1.5, 1.0)})
    triangulation = mtri.Triangulation(xz[:, 0] * mm, xz[:, 1] * mm, faces)
    top = max(float(von_mises.max()), value_max) / 1e6
    image = left.tripcolor(triangulation, von_mises / 1e6, shading="gouraud", cmap="magma", vmin=0, vmax=top)
    fig.colorbar(image, ax=left, label="von Mises stress [MPa]", location="right", shrink=0.9)
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
    fig.suptitle(f"{meta['scene']}: {meta['force_N']:.0f} N, {meta['fidelity']} level (n = b/h {level['n']:g}, "
                 f"growth {level['growth']:g}); FE stress: element means of the P2 stress averaged at the "
                 "nodes (smooths peaks on coarse meshes)", fontsize=10)
    return fig
