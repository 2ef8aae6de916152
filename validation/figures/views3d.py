"""Building blocks of the 3D screenshots (:mod:`validation.figures.render3d`): a deterministic off-screen plotter,
parallel cameras, cuts with the mesh edges of a zone, curves on a surface, arrows, frames, markers, colour bars,
the pressure surface, the stress window with its FE and Hertz maxima.

Lengths in mm, stresses in MPa (the pictures' units).  pyvista is imported inside the functions; on Linux without
``DISPLAY`` VTK is pointed at its EGL render window (``VTK_DEFAULT_OPENGL_WINDOW``) before pyvista loads, so that
it does not first try an X server and print a warning.
"""
from __future__ import annotations

import math
import os
import sys
from functools import lru_cache
from pathlib import Path

import numpy as np
from scipy.spatial import cKDTree

from ballbench.validation.references.hertz import axis_von_mises_maximum

# Okabe-Ito (colour-blind safe)
ORANGE, SKY_BLUE, GREEN, YELLOW, BLUE, VERMILLION, PURPLE = ("#E69F00", "#56B4E9", "#009E73", "#F0E442", "#0072B2",
                                                             "#D55E00", "#CC79A7")
BALL_COLOUR, FIXED_COLOUR, LOADED_COLOUR = "#DDDDDD", "#9CC9E6", "#F2C879"  # ball, clamped body, loaded body
ZERO_PRESSURE_COLOUR = "#C8C8C8"  # the ball outside the contact patches
AXIS_COLOURS = (VERMILLION, GREEN, BLUE)  # x, y, z (and e1, e2, e3)
EDGE_COLOUR = "#303030"
PRESSURE_CMAP = "viridis"  # perceptually uniform, colour-blind safe
STRESS_CMAP = "YlOrRd"  # ColorBrewer sequential, colour-blind safe
HERTZ_COLOUR, FE_COLOUR = "white", ORANGE  # the Hertz and the FE moment ellipse
FE_MAX_COLOUR, HERTZ_MAX_COLOUR = GREEN, SKY_BLUE  # the FE and the Hertz stress maximum
FONT = 10  # points, the viewport titles (text actors of a fixed size)
MM, MPA = 1e3, 1e-6


def pyvista():
    """pyvista, with VTK pointed at EGL on a Linux machine without an X server (module docstring)."""
    if sys.platform.startswith("linux") and not os.environ.get("DISPLAY"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import pyvista as pv

    return pv


HEADING_PX = 50  # the heading row: two lines of the picture's title


def plotter(shape, size, heading: str, *, caption: int = 0, column_weights=None):
    """An off-screen plotter with a heading row (``heading``, two lines at most) above ``shape`` (rows, columns)
    viewports of ``size`` (width, height) pixels in all, and with ``caption`` > 0 a caption row of that many
    pixels below them (:func:`caption`); select a viewport with :func:`subplot`.  The fixed settings of every
    picture: no anti-aliasing, white background, the default light kit."""
    pv = pyvista()
    theme = pv.themes.DocumentTheme()
    theme.anti_aliasing = None
    theme.multi_samples = 0
    theme.font.family = "arial"
    theme.font.color = "black"
    theme.background = "white"
    theme.show_scalar_bar = False
    rows, columns = shape
    width, height = size
    weights = [HEADING_PX] + [height / rows] * rows + ([caption] if caption else [])
    groups = [(0, np.s_[:])] + ([(rows + 1, np.s_[:])] if caption else [])
    out = pv.Plotter(off_screen=True, window_size=[width, int(height + HEADING_PX + caption)],
                     shape=(len(weights), columns), theme=theme, border=False, row_weights=weights, groups=groups,
                     col_weights=column_weights)
    out.disable_anti_aliasing(all_renderers=True)
    out.subplot(0, 0)
    _text_at_top(out, heading, 12)
    return out


def transparency(plot, peels: int = 2) -> None:
    """Depth peeling in the current viewport for a transparent body, with ``peels`` layers (a transparent body
    seen through is two: its front and back faces; 2 peels differ from pyvista's default 4 in 0.1 % of the pixels
    of the module pictures at 60-70 % of the rendering time).  Set on the renderer directly: pyvista's
    ``enable_depth_peeling`` first renders a probe window to ask whether peeling works (VTK falls back to plain
    blending where it does not)."""
    renderer = plot.renderer
    renderer.SetUseDepthPeeling(True)
    renderer.SetMaximumNumberOfPeels(peels)
    renderer.SetOcclusionRatio(0.0)
    renderer.Modified()


def subplot(plot, row: int, column: int) -> None:
    """Select the viewport (``row``, ``column``) of a :func:`plotter` (below its heading row)."""
    plot.subplot(row + 1, column)


def caption(plot, words: str, size: int = FONT, *, bar=None) -> None:
    """``words`` in the caption row of a plotter made with ``caption`` > 0; with ``bar`` ``(actor, label,
    n_labels[, below])`` a horizontal colour bar of that actor's colour map at the right of the row (``below``
    names the colour below its range)."""
    plot.subplot(plot.shape[0] - 1, 0)
    _text_at_top(plot, words, size)
    if bar is not None:
        actor, label, n_labels = bar[:3]
        scale = plot.add_scalar_bar(title=label, mapper=actor.mapper, n_labels=n_labels, fmt="%.0f",
                                    title_font_size=14, label_font_size=13, color="black", vertical=False,
                                    position_x=0.64, position_y=0.04, width=0.33, height=0.92,
                                    below_label=bar[3] if len(bar) > 3 else None)
        scale.SetTextPositionToPrecedeScalarBar()  # the labels below the bar, the title above it


def save(plot, path: Path) -> Path:
    """Write the screenshot of ``plot`` to the PNG ``path`` (zlib level 4: a third of the default's encoding time
    for 5-10 % more bytes), close it and return ``path``."""
    from PIL import Image

    image = plot.screenshot(return_img=True)
    plot.close()
    Image.fromarray(image).save(path, compress_level=4)
    return Path(path)


def view(plot, focal, direction, up, half_height: float, *, perspective: float | None = None) -> None:
    """Camera at ``focal`` [mm] looking along ``direction`` with ``up`` up: parallel projection of ``half_height``
    [mm], or with ``perspective`` [deg] a perspective of that view angle from the distance that shows
    ``half_height`` at the focal point."""
    direction = np.asarray(direction, dtype=float)
    direction = direction / np.linalg.norm(direction)
    focal = np.asarray(focal, dtype=float)
    camera = plot.camera
    if perspective is None:
        distance = 50.0 * max(half_height, 1e-3)
        camera.parallel_projection = True
        camera.parallel_scale = half_height
    else:
        distance = half_height / math.tan(math.radians(0.5 * perspective))
        camera.parallel_projection = False
        camera.view_angle = perspective
    camera.focal_point = tuple(focal)
    camera.position = tuple(focal - distance * direction)
    camera.up = tuple(np.asarray(up, dtype=float))
    camera.clipping_range = (1e-3 * distance, 3.0 * distance)


def _text_at_top(plot, words: str, size: int) -> None:
    """``words`` at the top left of the current viewport in ``size`` points (a fixed size: corner annotations would
    shrink long texts to the viewport's width)."""
    xmin, ymin, xmax, ymax = plot.renderer.GetViewport()
    height = (ymax - ymin) * plot.window_size[1]
    actor = plot.add_text(words, position=(6, int(height) - 4), font_size=size, color="black")
    prop = actor.GetTextProperty()
    prop.SetVerticalJustificationToTop()
    prop.SetBackgroundColor(1.0, 1.0, 1.0)  # legible over the picture
    prop.SetBackgroundOpacity(0.75)


def look_from(plot, position, focal, up, angle: float = 40.0) -> None:
    """Perspective camera at ``position`` [mm] looking at ``focal`` with ``up`` up and the view angle ``angle``
    [deg]."""
    camera = plot.camera
    camera.parallel_projection = False
    camera.view_angle = angle
    camera.position = tuple(np.asarray(position, dtype=float))
    camera.focal_point = tuple(np.asarray(focal, dtype=float))
    camera.up = tuple(np.asarray(up, dtype=float))
    distance = float(np.linalg.norm(np.asarray(position, dtype=float) - np.asarray(focal, dtype=float)))
    camera.clipping_range = (1e-3 * distance, 20.0 * distance)


def title(plot, text: str, size: int = FONT) -> None:
    """``text`` at the top left of the current viewport."""
    _text_at_top(plot, text, size)


def colour_scale(top: float) -> tuple[float, int]:
    """``(top', n_labels)``: ``top`` rounded up to a multiple of a 1-2-5 step that gives 4-8 intervals, and the
    number of labels from 0 to it (round tick values on a colour bar)."""
    if not (math.isfinite(top) and top > 0.0):
        return 1.0, 2
    for step in (nice(top / 4.0) * f for f in (1.0, 2.0, 2.5, 5.0)):
        intervals = math.ceil(top / step - 1e-9)
        if 4 <= intervals <= 8:
            return intervals * step, intervals + 1
    step = nice(top / 5.0)
    intervals = math.ceil(top / step - 1e-9)
    return intervals * step, intervals + 1


def scalar_bar(plot, label: str, n_labels: int, *, position=(0.88, 0.1), height: float = 0.7,
               below: str | None = None) -> None:
    """A vertical colour bar for the last scalar mesh of the current viewport, titled ``label`` (with its unit);
    ``below`` names the colour below the range."""
    plot.add_scalar_bar(title=label, n_labels=n_labels, fmt="%.0f", title_font_size=15, label_font_size=14,
                        color="black", vertical=True, position_x=position[0], position_y=position[1], width=0.05,
                        height=height, below_label=below)


def nice(value: float) -> float:
    """The 1-2-5 number at or below ``value`` > 0."""
    exponent = math.floor(math.log10(value))
    mantissa = value / 10**exponent
    return float((5 if mantissa >= 5 else 2 if mantissa >= 2 else 1) * 10**exponent)


# ----------------------------------------------------------------------------------------------- grids
def tets(grid) -> np.ndarray:
    """(m, 4) corner nodes of the tetrahedra of a linear grid."""
    return np.asarray(grid.cells_dict[pyvista().CellType.TETRA])


def read_linear(path: Path, point_names=(), cell_names=(), *, displacement: str | None = None):
    """The VTU at ``path`` as a grid of linear tetrahedra (the corner nodes of quadratic ones), lengths in mm, with
    the point arrays ``point_names`` and cell arrays ``cell_names`` (``(source, target, factor)`` triples:
    ``target = factor * source``), ``body`` and, with ``displacement`` (a point array [m]), ``u_mm``."""
    pv = pyvista()
    source = pv.read(str(path))
    cells = source.cells_dict
    if pv.CellType.QUADRATIC_TETRA in cells:
        corners = np.asarray(cells[pv.CellType.QUADRATIC_TETRA])[:, :4]
    elif pv.CellType.TETRA in cells:
        corners = np.asarray(cells[pv.CellType.TETRA])
    else:
        raise ValueError(f"{path} holds no tetrahedra")
    used, local = np.unique(corners, return_inverse=True)
    grid = pv.UnstructuredGrid({pv.CellType.TETRA: local.reshape(corners.shape)}, np.asarray(source.points)[used] * MM)
    for name, target, factor in point_names:
        grid.point_data[target] = factor * np.asarray(source.point_data[name])[used]
    if displacement is not None:
        grid.point_data["u_mm"] = MM * np.asarray(source.point_data[displacement])[used]
    grid.cell_data["body"] = np.asarray(source.cell_data["body"])
    for name, target, factor in cell_names:
        grid.cell_data[target] = factor * np.asarray(source.cell_data[name])
    return grid


def within(grid, box):
    """The tetrahedra of ``grid`` whose corners all lie in ``box`` (xmin, xmax, ymin, ymax, zmin, zmax) [mm],
    uncut (a linear grid of tetrahedra again, with its data)."""
    pv = pyvista()
    corners_of = tets(grid)
    corners = np.asarray(grid.points)[corners_of]
    lower, upper = np.asarray(box[0::2]), np.asarray(box[1::2])
    keep = np.all((corners >= lower) & (corners <= upper), axis=(1, 2))
    used, local = np.unique(corners_of[keep], return_inverse=True)
    out = pv.UnstructuredGrid({pv.CellType.TETRA: local.reshape(-1, 4)}, np.asarray(grid.points)[used])
    for name in grid.point_data.keys():
        out.point_data[name] = np.asarray(grid.point_data[name])[used]
    for name in grid.cell_data.keys():
        out.cell_data[name] = np.asarray(grid.cell_data[name])[keep]
    return out


def mirror(grid, axis: int):
    """``grid`` and its mirror image in the plane ``x_axis = 0`` as one grid: the nodes on the plane shared, the
    vector data mirrored too."""
    pv = pyvista()
    points = np.asarray(grid.points)
    on_plane = np.abs(points[:, axis]) <= 1e-9 * float(np.ptp(points, axis=0).max())
    copies = np.flatnonzero(~on_plane)
    index = np.arange(len(points))
    index[copies] = len(points) + np.arange(len(copies))  # mirrored node of each node (itself on the plane)
    mirrored = points[copies].copy()
    mirrored[:, axis] *= -1.0
    corners = tets(grid)
    both = pv.UnstructuredGrid({pv.CellType.TETRA: np.vstack([corners, index[corners][:, [0, 2, 1, 3]]])},
                               np.vstack([points, mirrored]))
    for name in grid.point_data.keys():
        values = np.asarray(grid.point_data[name])
        flipped = values[copies].copy()
        if values.ndim == 2 and values.shape[1] == 3:
            flipped[:, axis] *= -1.0
        both.point_data[name] = np.concatenate([values, flipped])
    for name in grid.cell_data.keys():
        values = np.asarray(grid.cell_data[name])
        both.cell_data[name] = np.concatenate([values, values])
    return both


def moved(grid, rotation, translation):
    """A copy of ``grid`` turned by ``rotation`` (3, 3) and moved by ``translation`` (3,) [mm] (``u_mm`` turned)."""
    rotation = np.asarray(rotation, dtype=float)
    out = grid.copy()
    out.points = np.asarray(grid.points) @ rotation.T + np.asarray(translation, dtype=float)
    if "u_mm" in grid.point_data.keys():
        out.point_data["u_mm"] = np.asarray(grid.point_data["u_mm"]) @ rotation.T
    return out


def surface(grid, body: int | None = None):
    """The outer surface of ``grid`` (or of its body ``body``) as PolyData with the point and cell data."""
    if body is not None:
        grid = grid.extract_cells(np.flatnonzero(np.asarray(grid.cell_data["body"]) == body))
    return grid.extract_surface(algorithm="dataset_surface")


def clipped(grid, halfspaces, *, crinkle: bool = False):
    """``grid`` cut to the half-spaces ``[(point, normal), ...]`` [mm] (each keeps the side ``normal`` points to);
    ``crinkle``: whole cells (those the plane crosses kept), so that a cut shows the elements themselves."""
    for point, normal in halfspaces:
        grid = grid.clip(normal=tuple(np.asarray(normal, dtype=float)), origin=tuple(np.asarray(point, dtype=float)),
                         invert=False, crinkle=crinkle)
    return grid


def body_colours(count: int, loaded: int | None = None) -> list:
    """Colours of the bodies 0 (the ball), 1, ...: the ball grey, the loaded body orange, the others blue."""
    return [BALL_COLOUR if k == 0 else LOADED_COLOUR if k == loaded else FIXED_COLOUR for k in range(count)]


def bodies(plot, grid, colours, *, zones=(), opacity=None, smooth: bool = False, lighting: bool = True) -> None:
    """The surfaces of the bodies of ``grid`` in ``colours``, the faces within the spheres ``zones``
    ``[(centre, radius), ...]`` [mm] (the refined zones) with their mesh edges.  ``opacity``: per body (default
    opaque); ``smooth``: smooth shading of the ball (body 0, a coarse sphere away from the contacts);
    ``lighting`` off for a cut seen face on."""
    outer = surface(grid)
    body = np.asarray(outer.cell_data["body"])
    edged = np.zeros(outer.n_cells, dtype=bool)
    if zones:
        centres = np.asarray(outer.cell_centers().points)
        for centre, radius in zones:
            edged |= np.linalg.norm(centres - np.asarray(centre, dtype=float), axis=1) <= radius
    for k, colour in enumerate(colours):
        for edges in (False, True):
            cells = np.flatnonzero((body == k) & (edged == edges))
            if cells.size:
                plot.add_mesh(outer.extract_cells(cells), color=colour, show_edges=edges, edge_color=EDGE_COLOUR,
                              line_width=1, opacity=1.0 if opacity is None else opacity[k],
                              smooth_shading=smooth and k == 0 and not edges, lighting=lighting)


def cut(grid, origin, normal, right, up, half_width: float, half_height: float):
    """The cut of ``grid`` by the plane through ``origin`` [mm] with ``normal``, trimmed to the rectangle
    ``|(x - origin) . right| <= half_width``, ``|(x - origin) . up| <= half_height`` (PolyData with the data)."""
    origin = np.asarray(origin, dtype=float)
    reach = 1.8 * math.hypot(half_width, half_height)  # whole cells about the window's corners
    box = np.column_stack([origin - reach, origin + reach]).ravel()
    local = within(grid, box)
    face = local.slice(normal=tuple(np.asarray(normal, dtype=float)), origin=tuple(origin))
    for axis, half in ((np.asarray(right, dtype=float), half_width), (np.asarray(up, dtype=float), half_height)):
        axis = axis / np.linalg.norm(axis)
        face = face.clip(normal=tuple(axis), origin=tuple(origin - half * axis), invert=False)
        face = face.clip(normal=tuple(-axis), origin=tuple(origin + half * axis), invert=False)
    return face


def maximum(face, name: str, body: int | None = None):
    """Location (3,) [mm] and value of the largest ``name`` on ``face`` (point or cell data; of body ``body``);
    ``(None, nan)`` when there is none."""
    cells = np.arange(face.n_cells)
    if body is not None:
        cells = np.flatnonzero(np.asarray(face.cell_data["body"]) == body)
    if cells.size == 0:
        return None, float("nan")
    if name in face.cell_data.keys():
        values = np.asarray(face.cell_data[name])[cells]
        k = int(np.argmax(values))
        return np.asarray(face.extract_cells(cells[k:k + 1]).center), float(values[k])
    part = face.extract_cells(cells)
    values = np.asarray(part.point_data[name])
    k = int(np.argmax(values))
    return np.asarray(part.points)[k], float(values[k])


# ----------------------------------------------------------------------------------------------- marks
def ellipse(centre, e1, e2, a: float, b: float, count: int = 181) -> np.ndarray:
    """(count, 3) points of the ellipse of semi-axes ``a`` along ``e1`` and ``b`` along ``e2`` about ``centre``."""
    t = np.linspace(0.0, 2.0 * math.pi, count)
    return (np.asarray(centre, dtype=float)[None, :] + (a * np.cos(t))[:, None] * np.asarray(e1)[None, :]
            + (b * np.sin(t))[:, None] * np.asarray(e2)[None, :])


def on_surface(outer, curve_plane, origin, frame, lift: float, scale: float) -> np.ndarray:
    """Points of a curve given in a tangent plane (``curve_plane`` (k, 2) along ``frame[0], frame[1]`` about
    ``origin``) moved along ``frame[2]`` onto the surface ``outer`` near the contact, displaced by ``scale`` times
    its ``u_mm`` there and lifted by ``lift`` against ``frame[2]``.  Height and displacement are the
    inverse-distance means of the 4 nearest surface points in the tangent plane (the refined mesh makes that
    exact to a small fraction of an element)."""
    frame = np.asarray(frame, dtype=float)
    local = (np.asarray(outer.points) - np.asarray(origin, dtype=float)[None, :]) @ frame.T
    reach = 1.6 * float(np.max(np.linalg.norm(curve_plane, axis=1)))
    near = (np.linalg.norm(local[:, :2], axis=1) <= reach) & (np.abs(local[:, 2]) <= 0.5 * reach)
    if np.count_nonzero(near) < 4:
        raise ValueError("too few surface points under the curve")
    values = np.column_stack([local[near, 2], np.asarray(outer.point_data["u_mm"])[near]])
    distance, nearest = cKDTree(local[near, :2]).query(curve_plane, k=4)
    weight = 1.0 / np.maximum(distance, 1e-12 * reach)
    sampled = np.einsum("kj,kjc->kc", weight, values[nearest]) / weight.sum(axis=1)[:, None]
    return (np.asarray(origin, dtype=float)[None, :] + curve_plane[:, :1] * frame[0]
            + curve_plane[:, 1:2] * frame[1] + sampled[:, :1] * frame[2] + scale * sampled[:, 1:]
            - lift * frame[2])


def polyline(points):
    return pyvista().lines_from_points(np.asarray(points, dtype=float), close=False)


def arrow(plot, start, vector, length: float, colour: str, label: str | None = None, font: int = 13) -> None:
    """An arrow of ``length`` [mm] from ``start`` along ``vector``, labelled at its tail."""
    pv = pyvista()
    direction = np.asarray(vector, dtype=float)
    direction = direction / np.linalg.norm(direction)
    plot.add_mesh(pv.Arrow(start=tuple(np.asarray(start, dtype=float)), direction=tuple(direction), scale=length,
                           tip_length=0.25, tip_radius=0.08, shaft_radius=0.03), color=colour, lighting=False)
    if label:
        text(plot, start, label, font=font)


def triad(plot, origin, frame, length: float, names=("x", "y", "z"), font: int = 12) -> None:
    """Three arrows along the rows of ``frame`` from ``origin`` [mm], labelled ``names`` at their tips."""
    pv = pyvista()
    origin = np.asarray(origin, dtype=float)
    tips = []
    for axis, colour in zip(np.asarray(frame, dtype=float), AXIS_COLOURS):
        plot.add_mesh(pv.Arrow(start=tuple(origin), direction=tuple(axis), scale=length, tip_length=0.25,
                               tip_radius=0.07, shaft_radius=0.025), color=colour, lighting=False)
        tips.append(origin + 1.15 * length * axis)
    plot.add_point_labels(tips, list(names), font_size=font, text_color="black", shape=None, point_size=1,
                          always_visible=True, show_points=False)


def frame_axes(plot) -> None:
    """The coordinate frame (x, y, z) as a small orientation marker in the lower left of the current viewport."""
    plot.add_axes(interactive=False, line_width=3, x_color=AXIS_COLOURS[0], y_color=AXIS_COLOURS[1],
                  z_color=AXIS_COLOURS[2], viewport=(0.0, 0.0, 0.16, 0.24))


def text(plot, point, words: str, font: int = 12, colour: str = "black") -> None:
    """``words`` in a white box at ``point`` [mm], always visible."""
    plot.add_point_labels([np.asarray(point, dtype=float)], [words], font_size=font, text_color=colour,
                          shape_color="white", shape_opacity=0.85, point_size=1, always_visible=True,
                          show_points=False, margin=2)


def dot(plot, point, colour: str, radius: float, toward=None, ring: bool = False) -> None:
    """A flat dot (or with ``ring`` a ring) of ``radius`` [mm] at ``point`` facing the direction ``toward``."""
    pv = pyvista()
    normal = (0.0, 0.0, 1.0) if toward is None else tuple(np.asarray(toward, dtype=float))
    shape = pv.Disc(center=tuple(np.asarray(point, dtype=float)), inner=0.55 * radius if ring else 0.0, outer=radius,
                    normal=normal, c_res=32)
    plot.add_mesh(shape, color=colour, lighting=False)


def legend(plot, entries, *, size=(0.62, 0.09), loc: str = "lower left") -> None:
    """A legend box of ``entries`` ``[(words, colour), ...]`` (circle symbols)."""
    plot.add_legend([[words, colour, "circle"] for words, colour in entries], bcolor="white", border=True,
                    size=size, loc=loc, font_family="arial")


def scale_bar(plot, start, right, length: float, *, font: int = 12) -> None:
    """A scale bar of ``length`` [mm] from ``start`` along ``right``, labelled in um or mm."""
    start = np.asarray(start, dtype=float)
    right = np.asarray(right, dtype=float) / np.linalg.norm(right)
    plot.add_mesh(polyline([start, start + length * right]), color="black", line_width=4)
    words = f"{length * 1e3:g} um" if length < 1.0 else f"{length:g} mm"
    plot.add_point_labels([start + 0.5 * length * right], [words], font_size=font, text_color="black", shape=None,
                          point_size=1, always_visible=True, show_points=False)


# ----------------------------------------------------------------------------------------------- fields
def hertz_maximum(a_m: float, b_m: float, p0_Pa: float, poisson_ratio: float) -> tuple[float, float]:
    """Depth [mm] and value [MPa] of Hertz's largest von Mises stress on the contact axis
    (``validation.references.hertz.axis_von_mises_maximum``), from the unit contact of the same ``a / b`` (the
    Boussinesq integral is homogeneous: depths scale with b, stresses with p0), ``a / b`` to 5 digits."""
    depth, value = _unit_maximum(float(f"{a_m / b_m:.5g}"), float(poisson_ratio))
    return depth * b_m * MM, value * p0_Pa * MPA


@lru_cache(maxsize=64)
def _unit_maximum(ratio: float, poisson_ratio: float) -> tuple[float, float]:
    return axis_von_mises_maximum(ratio, 1.0, 1.0, poisson_ratio)


def pressure_surface(plot, outer, top: float, n_labels: int, *, bar: bool = False, smooth: bool = False):
    """``outer`` coloured by ``p_MPa`` on the scale 0 - ``top``; below 1e-4 ``top`` (no contact) grey: the colour
    changes along that iso-line of the piecewise-linear FE pressure.  Returns the actor."""
    actor = plot.add_mesh(outer, scalars="p_MPa", cmap=PRESSURE_CMAP, clim=(1e-4 * top, top),
                          below_color=ZERO_PRESSURE_COLOUR, show_scalar_bar=False, interpolate_before_map=True,
                          smooth_shading=smooth, ambient=0.35, diffuse=0.7)  # colours readable on a shaded ball
    if bar:
        scalar_bar(plot, "p [MPa]", n_labels, below="p = 0")
    return actor


def warped(outer, scale: float):
    out = outer.copy()
    out.points = np.asarray(outer.points) + scale * np.asarray(outer.point_data["u_mm"])
    return out


def ellipse_curves(plot, outer, origin, frame, ellipses, lift: float, scale: float) -> None:
    """The ellipses ``[(a, b, x0, y0, colour, width), ...]`` [mm] of the tangent plane ``frame`` at ``origin`` as
    curves on ``outer`` (displaced by ``scale`` u_mm), the widest first and lowest (each next one lifted more)."""
    for k, (a, b, x0, y0, colour, width) in enumerate(sorted(ellipses, key=lambda e: -e[5])):
        plane = ellipse((x0, y0, 0.0), (1, 0, 0), (0, 1, 0), a, b)[:, :2]
        plot.add_mesh(polyline(on_surface(outer, plane, origin, frame, (1 + 2 * k) * lift, scale)),
                      color=colour, line_width=width)


def displacement_scale(outer, reference_mm: float, share: float = 0.03) -> float:
    """A 1-2-5 scale that makes the largest displacement of ``outer`` about ``share`` of ``reference_mm``."""
    largest = float(np.max(np.linalg.norm(np.asarray(outer.point_data["u_mm"]), axis=1)))
    return nice(share * reference_mm / largest) if largest > 0.0 else 1.0


def stress_window(plot, grid, centre, normal, right, up, half_width, half_height, top, n_labels, marks, *,
                 bar: bool, face=None) -> list:
    """Von Mises stress (``vm_MPa``) on the cut of ``grid`` through ``centre`` with ``normal``, trimmed to the
    window (``right``, ``up``, half sizes [mm]), seen along ``normal``; the largest value of each body in the window
    (green dots) and the Hertz maxima ``marks`` ``[(point, ...)]`` (blue rings).  Returns ``([(body, value, point),
    ...] of the FE maxima, the actor)``; ``face``: that cut, if already made."""
    face = cut(grid, centre, normal, right, up, half_width, half_height) if face is None else face
    actor = plot.add_mesh(face, scalars="vm_MPa", cmap=STRESS_CMAP, clim=(0.0, top), show_scalar_bar=False,
                          lighting=False)
    if bar:
        scalar_bar(plot, "von Mises [MPa]", n_labels)
    towards = -np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    radius = 0.035 * half_height
    found = []
    for body in np.unique(np.asarray(face.cell_data["body"])):
        where, value = maximum(face, "vm_MPa", int(body))
        if where is not None:
            dot(plot, where + 0.06 * half_height * towards, FE_MAX_COLOUR, radius, towards)
            found.append((int(body), value, where))
    for point in marks:
        dot(plot, np.asarray(point) + 0.04 * half_height * towards, HERTZ_MAX_COLOUR, 1.6 * radius, towards,
              ring=True)
    view_half = 1.45 * half_height  # the window in the lower part, the titles above it
    view(plot, np.asarray(centre) + 0.4 * half_height * np.asarray(up), -towards, up, view_half)
    return found, actor
