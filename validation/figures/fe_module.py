"""Pictures of the FE modules (one ball between its grooves; fem.fourpoint, fem.screw_module): the contact
pressure on each patch against the Hertz and FE moment ellipses, and the von Mises stress on a cut plane."""
from __future__ import annotations

import math

import numpy as np

from ballbench.validation.figures.style import figure

# panels whose own peak lies below this share of the shared colour scale say so in their title
FAINT_SHARE = 0.25
MOMENT_ELLIPSE_LABEL = "FE moment ellipse (force and second moments of the FE pressure)"


def contact_summary(result) -> str:
    """``"BL 42.90 deg 114.1 N, ..."``: loaded contact angle and normal force of each contact of a solved module."""
    return ", ".join(f"{c.name} {math.degrees(c.contact_angle):.2f} deg {c.normal_force:.1f} N"
                     for c in result.contacts)


def patch_figure(results, hertz_axes, *, ylabel: str = "e2 [mm]", xlim: float = 0.6, ylim: float = 0.25,
                 heading: str = "contact pressure", hertz_label: str = "Hertz ellipse"):
    """Figure: one row per solved module (``results``, :class:`fem.fourpoint.ModuleResult`), one panel per
    contact: nodal pressure [MPa] in the contact's tangent plane (e1 across the groove [mm], e2 along it) on one
    colour scale shared by all panels (0 to the largest FE pressure, one colour bar), the Hertz ellipse
    ``hertz_axes[row][i] = (a, b)`` [m] (white, legend ``hertz_label``) and the FE moment ellipse
    (``fem.postprocess.moment_ellipse``: the ellipse with the FE pressure's force and second moments; red dashed).
    ``heading`` starts the figure title.  Each panel's title gives its force, loaded angle and peak pressure, and
    says when that peak is below FAINT_SHARE of the shared scale."""
    from matplotlib.lines import Line2D
    from matplotlib.ticker import MaxNLocator

    pressures = [[np.clip(contact.nodal_pressure, 0.0, None) / 1e6 for contact in result.contacts]
                 for result in results]  # MPa
    top = max(float(p.max(initial=0.0)) for row in pressures for p in row)
    levels = np.linspace(0.0, top if top > 0.0 else 1.0, 15)
    n_contacts = len(results[0].contacts)
    fig = figure(figsize=(15, 1.0 + 1.9 * len(results)), layout="constrained")
    axes = fig.subplots(len(results), n_contacts, squeeze=False)
    t = np.linspace(0.0, 2 * math.pi, 200)
    image = None
    for ball, result in enumerate(results):
        for i, contact in enumerate(result.contacts):
            ax = axes[ball, i]
            xy = contact.local_nodes * 1e3
            image = ax.tricontourf(xy[:, 0], xy[:, 1], pressures[ball][i], levels=levels, cmap="viridis",
                                   vmin=levels[0], vmax=levels[-1])
            a_h, b_h = hertz_axes[ball][i]
            ax.plot(a_h * 1e3 * np.cos(t), b_h * 1e3 * np.sin(t), "w-", lw=1.2)
            if contact.ellipse is not None:
                e = contact.ellipse
                ax.plot((e.x0 + e.a * np.cos(t)) * 1e3, (e.y0 + e.b * np.sin(t)) * 1e3, "r--", lw=1.0)
            peak = float(pressures[ball][i].max(initial=0.0))
            faint = f" (< {FAINT_SHARE:.0%} of the scale)" if peak < FAINT_SHARE * top else ""
            ax.set_title(f"ball {ball + 1} {contact.name}: {contact.normal_force:.1f} N, "
                         f"{math.degrees(contact.contact_angle):.2f} deg\npeak {peak:.0f} MPa{faint}", fontsize=9)
            ax.set_aspect("equal")
            ax.set_xlim(-xlim, xlim)
            ax.set_ylim(-ylim, ylim)
            ax.set_xlabel("e1 [mm]")
            ax.set_ylabel(ylabel)
    bar = fig.colorbar(image, ax=axes, label="FE contact pressure p [MPa]", shrink=0.9, pad=0.01)
    ticks = MaxNLocator(nbins=8).tick_values(0.0, levels[-1])
    bar.set_ticks(ticks[ticks <= levels[-1]])  # round values, not the 15 contour levels
    handles = [Line2D([], [], color="w", lw=1.2), Line2D([], [], color="r", ls="--", lw=1.0)]
    legend = fig.legend(handles, [hertz_label, MOMENT_ELLIPSE_LABEL], loc="outside lower center", ncol=2,
                        fontsize=9, facecolor="0.35", labelcolor="w")
    legend.get_frame().set_edgecolor("0.35")
    fig.suptitle(f"{heading}: one colour scale 0 - {top:.0f} MPa (the largest FE pressure); white: {hertz_label}, "
                 "red dashed: FE moment ellipse", fontsize=11)
    return fig


def cut_figure(points, tets, stress, *, normal, origin, title: str, view_up=None, axis_names=("x", "y")):
    """Figure of the element values ``stress`` [MPa] of the linear tetrahedra ``tets`` (m, 4) on ``points``
    (n, 3) [m] on the plane through ``origin`` [m] with ``normal``, seen along the normal: the plane's
    coordinates [mm] from ``origin`` along ``up x normal`` (to the right) and ``up`` (``view_up`` made normal to
    ``normal``; default y), named ``axis_names``.  Each cut element keeps its own value, drawn flat in the colour
    map's own colours (pyvista only cuts, matplotlib draws: no lighting, no VTK render window), framed to the
    cut; the colour scale runs from 0 to the 99.9th percentile of ``stress`` (a few contact elements above it
    show as the top colour, the colour bar says so and gives the maximum)."""
    import pyvista as pv

    normal = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    up = np.array([0.0, 1.0, 0.0]) if view_up is None else np.asarray(view_up, dtype=float)
    up = up - (up @ normal) * normal
    up /= np.linalg.norm(up)
    right = np.cross(up, normal)  # pyvista's view_vector(normal, viewup=up): the same picture as before
    mm = 1e3
    stress = np.asarray(stress, dtype=float)
    grid = pv.UnstructuredGrid({pv.CellType.TETRA: np.asarray(tets)}, np.asarray(points, dtype=float) * mm)
    grid.cell_data["stress"] = stress
    origin_mm = np.asarray(origin, dtype=float) * mm
    cut = grid.slice(normal=tuple(normal), origin=tuple(origin_mm)).triangulate()
    if cut.n_cells == 0:
        raise ValueError(f"the plane through origin {tuple(origin)} m with normal {tuple(normal)} misses the mesh")
    relative = np.asarray(cut.points) - origin_mm
    u, v = relative @ right, relative @ up
    faces = cut.faces.reshape(-1, 4)[:, 1:]
    top = float(np.percentile(stress, 99.9))
    width, height = float(np.ptp(u)), float(np.ptp(v))
    fig = figure(figsize=(9.0, float(np.clip(9.0 * height / width, 3.5, 11.0)) + 1.6), layout="constrained")
    ax = fig.subplots()
    image = ax.tripcolor(u, v, faces, facecolors=np.asarray(cut.cell_data["stress"]), cmap="YlOrRd", vmin=0.0,
                         vmax=top, shading="flat")
    ax.set_facecolor("0.82")  # gaps between the bodies: grey, apart from the near-white low stress
    ax.set_aspect("equal")
    ax.set_xlim(u.min(), u.max())
    ax.set_ylim(v.min(), v.max())
    ax.set_xlabel(f"{axis_names[0]} [mm]")
    ax.set_ylabel(f"{axis_names[1]} [mm]")
    ax.set_title(title, fontsize=10)
    fig.colorbar(image, ax=ax, location="bottom", shrink=0.8, aspect=40, extend="max",
                 label=f"von Mises stress [MPa] (element means; scale 0 to the 99.9th percentile {top:.0f} MPa, "
                       f"maximum {stress.max():.0f} MPa)")
    return fig
