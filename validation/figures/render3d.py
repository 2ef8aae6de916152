"""3D screenshots of the fields the FE scenes saved: pyvista, off-screen, deterministic (docs/render3d.md).

:func:`render` reads a scene folder (``fields.json`` with ``fields.vtu`` of an FE Hertz pair,
``validation.scenes.fe_hertz.write_fields``, or with ``fields_ball<k>.vtu`` of the four-point modules,
:func:`ballbench.fem.fields.write_module_fields`) and writes PNG files beside them; it never solves.

Pictures (``3d_*.png``):

* ``3d_assembly.png`` - the bodies with the mesh edges of the refined zones on a cut that shows the contacts, the
  coordinate frame, the contact frames (modules) and the load arrows;
* ``3d_pressure.png`` (pairs), ``3d_pressure_overview.png`` and ``3d_pressure_contacts.png`` (modules) - the
  contact pressure on the deformed ball surface (the displacement scale is stated), every patch of a picture on
  one colour scale, the Hertz ellipse at the FE force (white, wide) and the FE moment ellipse (orange, narrow) as
  3D curves on it;
* ``3d_stress.png`` - von Mises stress on cuts through the contact normal (the plane of the major axis; for pairs
  also of the minor one), the largest FE value of each body on the cut marked (green dot) with its value, and the
  Hertz subsurface maximum (``validation.references.hertz.axis_von_mises_maximum``, blue ring) beside it;
* ``3d_helix.png`` (ball-screw modules) - the two-ball module seen along the helix;
* ``3d_<name>.png`` - fields on a surface grid (BEM, EHL; :mod:`validation.figures.surfaces3d`);
* ``3d_stickslip_<name>.png`` - the stick and slip areas of rolling contacts (:mod:`validation.figures.stickslip3d`).

Determinism (the image regression tests rely on it): fixed window sizes, anti-aliasing off, cameras computed
from the saved geometry, the default light kit, no time stamps.  Colour maps are perceptually uniform and
colour-blind safe (``viridis`` for pressure, ``YlOrRd`` for stress); bodies and marks use the Okabe-Ito palette
(:mod:`validation.figures.views3d`).  Lengths are drawn in mm, stresses in MPa.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ballbench.validation.figures import stickslip3d, surfaces3d
from ballbench.validation.figures import views3d as v

__all__ = ["render", "artifacts", "module_artifacts", "surface_artifacts", "has_fields",
           "pair_pictures", "module_pictures", "PRESSURE_CMAP", "STRESS_CMAP"]

PRESSURE_CMAP, STRESS_CMAP, HERTZ_COLOUR, FE_COLOUR = v.PRESSURE_CMAP, v.STRESS_CMAP, v.HERTZ_COLOUR, v.FE_COLOUR
ELLIPSE_NOTE = ("white (wide): the Hertz ellipse at the FE contact force, centred on the FE pressure;\n"
                "orange (narrow): the FE moment ellipse (the force and second moments of the FE pressure);\n"
                "grey: no contact pressure")
MM, MPA = v.MM, v.MPA


# ----------------------------------------------------------------------------------------------- entry points
def has_fields(scene_dir) -> bool:
    """True when ``scene_dir`` holds saved fields :func:`render` can draw (``fields.json``, ``surface_*.json`` or
    ``stickslip_*.json``)."""
    scene_dir = Path(scene_dir)
    return ((scene_dir / "fields.json").is_file() or any(scene_dir.glob("surface_*.json"))
            or any(scene_dir.glob("stickslip_*.json")))


def render(scene_dir) -> list[Path]:
    """Write the 3D screenshots of the fields saved in ``scene_dir``; returns the PNG paths.

    FileNotFoundError when no fields are saved there, ValueError for a meta file of an unknown kind."""
    scene_dir = Path(scene_dir)
    if not has_fields(scene_dir):
        raise FileNotFoundError(f"no saved fields in {scene_dir} (fields.json, surface_*.json or stickslip_*.json)")
    paths = []
    meta_path = scene_dir / "fields.json"
    if meta_path.is_file():
        meta = json.loads(meta_path.read_text())
        kind = meta.get("kind", "pair")
        if kind == "pair":
            paths += pair_pictures(scene_dir, meta)
        elif kind == "module":
            paths += module_pictures(scene_dir, meta)
        else:
            raise ValueError(f"{meta_path}: unknown kind of fields {kind!r} (pair or module)")
    for surface_meta in sorted(scene_dir.glob("surface_*.json")):
        paths.append(surfaces3d.surface_picture(surface_meta))
    for stickslip_meta in sorted(scene_dir.glob("stickslip_*.json")):
        paths.append(stickslip3d.picture(stickslip_meta))
    return paths


def show_saved(scene_dir, fidelity: str, solve: bool = False) -> list[Path]:
    """The ``show`` hook of a scene whose pictures are only the 3D screenshots of fields it saved during
    ``ballbench validate`` (the BEM / EHL surfaces, the stick/slip areas): :func:`render`, or FileNotFoundError
    saying to validate first.  ``fidelity`` and ``solve`` are not used: the saved fields are those of the run that
    wrote them, and this hook has nothing to solve."""
    del fidelity, solve  # the hook signature; the saved fields fix the level
    scene_dir = Path(scene_dir)
    if not has_fields(scene_dir):
        raise FileNotFoundError(f"no saved surface or stick/slip fields in {scene_dir}: run 'ballbench validate "
                                f"{scene_dir.name} --out {scene_dir.parent}' first")
    return render(scene_dir)


def artifacts(scene_dir, note) -> list[Path]:
    """:func:`render` for a scene run: the PNG paths, or none and a sentence through ``note`` (e.g. ``Run.note``)
    when the pictures cannot be drawn here (no OpenGL context, damaged fields), so that a validation run never
    fails on a picture."""
    try:
        return render(scene_dir)
    except Exception as error:  # the pictures are an extra; the checks stand without them
        note(f"3D screenshots not drawn: {type(error).__name__}: {error} (`ballbench show` draws them from the saved "
             "fields)")
        return []


def module_artifacts(run, models, results, *, materials, level: dict, case: str = "") -> None:
    """For a scene run (``validation.scene.Run``): write the solved modules' fields into its folder
    (:func:`ballbench.fem.fields.write_module_fields`), draw them (:func:`artifacts`) and register both as the run's
    artifacts.  ``level``: the mesh level (e.g. ``{"h_contact_m": 3e-5, "growth": 1.35}``), ``case`` in words."""
    from ballbench.fem.fields import write_module_fields

    directory = run.path("")
    for path in write_module_fields(directory, models, results, materials=materials, scene=run.scene.name,
                                    fidelity=run.fidelity, level=level, case=case):
        run.add_artifact(path)
    for path in artifacts(directory, run.note):
        run.add_artifact(path)


def surface_artifacts(run, name: str, x, y, fields: dict, *, title: str, axes=("x", "y")) -> None:
    """For a scene run: write fields on a surface grid (``x`` (nx,), ``y`` (ny,) [m], each field (nx, ny) named
    with its unit, ``pressure_Pa``, ``film_m``, ``separation_m``; :func:`ballbench.fem.fields.write_surface_fields`)
    as ``surface_<name>``, draw them (:func:`validation.figures.surfaces3d.surface_picture`) and register both as
    the run's artifacts.  ``title`` names the case, ``axes`` the directions of x and y in words."""
    from ballbench.fem.fields import write_surface_fields

    paths = write_surface_fields(run.path(""), name, x, y, fields, {
        "scene": run.scene.name, "fidelity": run.fidelity, "title": title, "axes": list(axes)})
    for path in paths:
        run.add_artifact(path)
    try:
        run.add_artifact(surfaces3d.surface_picture(paths[1]))
    except Exception as error:  # the picture is an extra; the checks stand without it
        run.note(f"3D screenshot of {paths[0].name} not drawn: {type(error).__name__}: {error}")


def _level_text(meta: dict) -> str:
    level = meta.get("level", {})
    if "n" in level:
        words = f"n = b/h {level['n']:g}, growth {level['growth']:g}"
    elif "h_contact_m" in level:
        where = ("the most loaded contact, each contact at its own b / h" if level.get("per_contact") else
                 "the contacts")
        words = f"h {level['h_contact_m'] * 1e6:.0f} um at {where}, growth {level['growth']:g}"
    else:
        words = ", ".join(f"{k} {value}" for k, value in level.items())
    return f"{meta.get('fidelity', '?')} level ({words})"


# ----------------------------------------------------------------------------------------------- pairs
def pair_pictures(scene_dir, meta: dict | None = None) -> list[Path]:
    """The three pictures of an FE Hertz pair (module docstring); returns the PNG paths."""
    scene_dir = Path(scene_dir)
    meta = json.loads((scene_dir / "fields.json").read_text()) if meta is None else meta
    names = meta["fields"]
    grid = v.read_linear(scene_dir / "fields.vtu", [(names["pressure"], "p_MPa", MPA),
                                                    (names["von_mises"], "vm_MPa", MPA)],
                         displacement=names["displacement"])
    symmetry = meta["symmetry"]
    half = v.mirror(grid, 0) if symmetry["x"] else grid  # y >= 0 (a symmetry cut) or the whole model
    heading = f"{meta['scene']}: F = {meta['force_N']:.0f} N, {_level_text(meta)}"
    return [_pair_assembly(half, meta, heading, scene_dir / "3d_assembly.png", cut=not symmetry["y"]),
            _pair_pressure(v.mirror(half, 1) if symmetry["y"] else half, meta, heading, scene_dir / "3d_pressure.png"),
            _pair_stress(grid, meta, heading, scene_dir / "3d_stress.png")]


def _mesh_cut(plot, grid, origin, normal, right, up, half_width, half_height, colours) -> None:
    """The cut of ``grid`` in the window (:func:`views3d.cut`) in the bodies' colours with its mesh edges (the
    traces of the elements on the plane)."""
    face = v.cut(grid, origin, normal, right, up, half_width, half_height)
    body = np.asarray(face.cell_data["body"])
    for k in np.unique(body):
        plot.add_mesh(face.extract_cells(np.flatnonzero(body == k)), color=colours[int(k)], show_edges=True,
                      edge_color=v.EDGE_COLOUR, line_width=1, lighting=False)


def _pair_assembly(half, meta, heading, path: Path, *, cut: bool) -> Path:
    hertz = meta["hertz"]
    a, b = hertz["a_m"] * MM, hertz["b_m"] * MM
    plane = ((0.0, 0.0, 0.0), (0.0, 1.0, 0.0))
    shown = v.clipped(half, [plane]) if cut else half
    xmin, xmax, ymin, ymax, zmin, zmax = shown.bounds
    size = max(xmax - xmin, zmax - zmin)
    colours = v.body_colours(2, loaded=0)
    plot = v.plotter((1, 2), (1800, 800), f"{heading}\nthe bodies cut at y = 0 (the plane of the major axis a"
                                          f"{'' if cut else ', a symmetry plane of the model'}); mesh edges about the "
                                          "contact")
    v.subplot(plot, 0, 0)
    v.bodies(plot, shown, colours, zones=[((0.0, 0.0, 0.0), 5.0 * max(a, b))])
    centre_y = 0.5 * (ymin + ymax)
    v.arrow(plot, (0.0, centre_y, zmax + 0.3 * size), (0.0, 0.0, -1.0), 0.28 * size, v.VERMILLION,
            f"F = {meta['force_N']:.0f} N (the ball_load face moved rigidly)")
    v.text(plot, (0.5 * (xmin + xmax), centre_y, zmin), "counter_support clamped")
    v.frame_axes(plot)
    v.view(plot, (0.5 * (xmin + xmax), centre_y, 0.5 * (zmin + zmax + 0.3 * size)), (0.5, 1.0, -0.4), (0, 0, 1),
           0.5 * max(xmax - xmin, zmax - zmin + 0.3 * size) + 0.15 * size)
    v.subplot(plot, 0, 1)
    half_width = 1.15 * a * 1800 / 800
    if cut:
        _mesh_cut(plot, half, (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0), 1.05 * half_width,
                  1.2 * a, colours)
    else:
        v.bodies(plot, shown, colours, zones=[((0.0, 0.0, 0.0), 1e9)], lighting=False)
    v.title(plot, f"the contact on the cut y = 0: Hertz a = {a * 1e3:.0f} um along x, b = {b * 1e3:.0f} um;\n"
                  f"h = b / {meta['level']['n']:g} = {b / meta['level']['n'] * 1e3:.1f} um at the contact")
    plot.add_mesh(v.polyline([[-a, -1e-3 * a, 0.0], [a, -1e-3 * a, 0.0]]), color=v.VERMILLION, line_width=5)
    v.text(plot, (0.0, 0.0, -0.25 * a), "Hertz contact width 2a", colour=v.VERMILLION)
    v.scale_bar(plot, (-1.0 * a, -1e-3 * a, -0.85 * a), (1, 0, 0), v.nice(0.5 * a))
    v.view(plot, (0.0, 0.0, 0.05 * a), (0.0, 1.0, 0.0), (0, 0, 1), 1.05 * a)
    return v.save(plot, path)


def _pair_pressure(full, meta, heading, path: Path) -> Path:
    hertz, fe = meta["hertz"], meta["fe"]
    a, b = hertz["a_m"] * MM, hertz["b_m"] * MM
    zone = 2.5 * a
    near = v.surface(v.within(full, (-zone, zone, -zone, zone, -1.0, zone)), 0)
    near = near.extract_cells(np.flatnonzero(np.asarray(near.cell_centers().points)[:, 2] < 0.4 * zone))
    ball = near.extract_surface(algorithm="dataset_surface")
    scale = v.displacement_scale(ball, zone)
    top, n_labels = v.colour_scale(max(float(np.max(ball.point_data["p_MPa"])), hertz["p0_Pa"] * MPA))
    ellipses = [(a, b, 0.0, 0.0, HERTZ_COLOUR, 6), (fe["a_m"] * MM, fe["b_m"] * MM, 0.0, 0.0, FE_COLOUR, 2.5)]
    plot = v.plotter((1, 2), (1800, 760), f"{heading}\ncontact pressure on the deformed ball surface", caption=62)
    for column, s in enumerate((scale, 1.0)):
        v.subplot(plot, 0, column)
        v.pressure_surface(plot, v.warped(ball, s), top, n_labels, bar=column == 1)
        v.ellipse_curves(plot, ball, (0, 0, 0), np.eye(3), ellipses, 0.02 * b, s)
    v.subplot(plot, 0, 0)
    v.title(plot, f"the ball's surface about the contact, seen from the counter body's side;\ndisplacements x "
                  f"{scale:g}")
    v.view(plot, (0.0, 0.0, 0.1 * zone), (0.45, 0.55, 0.7), (0, 0, 1), 0.55 * zone)
    v.subplot(plot, 0, 1)
    v.title(plot, f"seen along the contact normal, true displacements;\nHertz a = {a * 1e3:.1f} um, "
                  f"b = {b * 1e3:.1f} um, p0 = {hertz['p0_Pa'] * MPA:.0f} MPa;\nFE moment ellipse a = "
                  f"{fe['a_m'] * 1e6:.1f} um, b = {fe['b_m'] * 1e6:.1f} um, p0 = {fe['p0_Pa'] * MPA:.0f} MPa")
    half = max(1.35 * b, 0.62 * a)
    v.scale_bar(plot, (-1.05 * a, -0.85 * half, 0.0), (1, 0, 0), v.nice(0.5 * a))
    v.view(plot, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), (0, 1, 0), half)
    v.caption(plot, ELLIPSE_NOTE)
    return v.save(plot, path)


def _pair_stress(grid, meta, heading, path: Path) -> Path:
    hertz = meta["hertz"]
    a, b = hertz["a_m"] * MM, hertz["b_m"] * MM
    depth, value = v.hertz_maximum(hertz["a_m"], hertz["b_m"], hertz["p0_Pa"], meta["poisson_ratio"])
    symmetry = meta["symmetry"]
    views = (("y = 0, the plane of the major axis a", 1, a, symmetry["x"]),
             ("x = 0, the plane of the minor axis b", 0, b, symmetry["y"]))
    prepared = []
    for _, axis, semi, mirror in views:
        span = max(2.0 * semi, 4.0 * depth)
        local = v.within(grid, (-1.5 * span, 1.5 * span, -1.5 * span, 1.5 * span, -1.5 * span, 1.5 * span))
        prepared.append((v.mirror(local, 1 - axis) if mirror else local, span))
    top = max(max(float(np.max(local.point_data["vm_MPa"])) for local, _ in prepared), value)
    top, n_labels = v.colour_scale(top)
    marks = [(0.0, 0.0, depth), (0.0, 0.0, -depth)]
    plot = v.plotter((1, 2), (1800, 800), f"{heading}\nvon Mises stress on cuts through the contact normal, the ball "
                                          "above (nodal averages of the element means of the P2 stress)")
    for column, ((words, axis, _, _), (local, span)) in enumerate(zip(views, prepared)):
        v.subplot(plot, 0, column)
        right = np.eye(3)[1 - axis] * (1.0 if axis == 1 else -1.0)
        inside = 1e-6 * span * np.eye(3)[axis]  # a symmetry face is the cut itself: just inside it
        found, _ = v.stress_window(plot, local, inside, np.eye(3)[axis], right, (0, 0, 1), span, 0.62 * span, top,
                             n_labels, marks, bar=column == 1)
        entries = [(f"FE maximum in the {('ball', 'counter body')[body]}: {peak:.0f} MPa at depth "
                    f"{abs(where[2]) * 1e3:.0f} um", v.FE_MAX_COLOUR) for body, peak, where in found]
        entries.append((f"Hertz subsurface maximum: {value:.0f} MPa at depth {depth * 1e3:.0f} um",
                        v.HERTZ_MAX_COLOUR))
        v.legend(plot, entries, size=(0.6, 0.13), loc="upper left")
        v.title(plot, f"the cut {words}")
    return v.save(plot, path)


# ----------------------------------------------------------------------------------------------- modules
def _module_grid(scene_dir: Path, meta: dict, ball: dict):
    names = meta["fields"]
    return v.read_linear(scene_dir / ball["file"], [(names["pressure"], "p_MPa", MPA)],
                         [(names["von_mises"], "vm_MPa", MPA)], displacement=names["displacement"])


def _module_frame(ball: dict):
    """``(centre [mm], look, up, right)`` of one ball's module in its own frame: ``look`` normal to the plane
    through the ball centre that holds the contact normals (the smallest singular direction of the four ``e3``),
    ``up`` from the ball centre towards the loaded body's contacts (y of the rails, x3 of the screw), ``right =
    look x up`` (screen right), the sign of ``look`` chosen so that the first contact (BL, SL) lies on the left."""
    centre = np.asarray(ball["ball_centre_m"]) * MM
    normals = np.array([c["frame"][2] for c in ball["contacts"]])
    look = np.linalg.svd(normals)[2][-1]
    up = -np.sum([n for n, c in zip(normals, ball["contacts"]) if c["moving"]], axis=0)
    up -= (up @ look) * look
    up /= np.linalg.norm(up)
    first = np.asarray(ball["contacts"][0]["point_m"]) * MM - centre
    if np.cross(look, up) @ first > 0.0:
        look = -look
    return centre, look, up, np.cross(look, up)


def module_pictures(scene_dir, meta: dict | None = None) -> list[Path]:
    """The pictures of the four-point modules (module docstring); returns the PNG paths."""
    scene_dir = Path(scene_dir)
    meta = json.loads((scene_dir / "fields.json").read_text()) if meta is None else meta
    grids = [_module_grid(scene_dir, meta, ball) for ball in meta["balls"]]
    heading = f"{meta['scene']}: {meta['case']}, {_level_text(meta)}" if meta.get("case") else \
        f"{meta['scene']}: {_level_text(meta)}"
    paths = [_module_assembly(grids, meta, heading, scene_dir / "3d_assembly.png"),
             _module_pressure_overview(grids, meta, heading, scene_dir / "3d_pressure_overview.png"),
             _module_pressure_contacts(grids, meta, heading, scene_dir / "3d_pressure_contacts.png"),
             _module_stress(grids, meta, heading, scene_dir / "3d_stress.png")]
    if meta["module"] == "ball screw":
        paths.append(_module_helix(grids, meta, heading, scene_dir / "3d_helix.png"))
    return paths


def _placed(grids, meta):
    """Each ball's module moved to its place in the assembly and cut between the balls:
    ``[(grid, rotation, translation [mm]), ...]``."""
    out = []
    for grid, ball in zip(grids, meta["balls"]):
        place = ball["placement"]
        rotation = np.asarray(place["rotation"])
        translation = np.asarray(place["translation"]) * MM
        moved = v.moved(grid, rotation, translation)
        keeps = [(np.asarray(k["point_m"]) * MM, np.asarray(k["normal"])) for k in place["keep"]]
        out.append((v.clipped(moved, keeps) if keeps else moved, rotation, translation))
    return out


def _loaded_index(ball: dict) -> int:
    return ball["bodies"].index(ball["loaded_body"])


def _load_arrow(plot, ball, rotation, translation, length: float, label: str) -> None:
    load = np.asarray(ball["load_N"])
    direction = rotation @ (load / np.linalg.norm(load))
    tip = rotation @ (np.asarray(ball["load_point_m"]) * MM) + translation
    components = ", ".join(f"{x:.1f}" for x in load)
    v.arrow(plot, tip - 1.05 * length * direction, direction, length, v.VERMILLION,
            f"{label}: load on the {ball['loaded_body']} ({components}) N")


def _zones(ball):
    """The refined zones about the contacts: spheres of 2.5 times the Hertz semi-axis a [mm]."""
    return [(np.asarray(c["point_m"]) * MM, 2.5 * c["hertz"]["a_m"] * MM) for c in ball["contacts"]]


def _module_bodies(grids, meta, loaded_opacity: float):
    """The modules' balls, placement, ball radius [mm], body colours and opacities (the loaded body at
    ``loaded_opacity``) and placed ball centres [mm]: what the assembly and helix views share."""
    balls = meta["balls"]
    placed = _placed(grids, meta)
    loaded = _loaded_index(balls[0])
    colours = v.body_colours(len(balls[0]["bodies"]), loaded=loaded)
    opacity = [1.0] * len(colours)
    opacity[loaded] = loaded_opacity
    centres = [rotation @ (np.asarray(ball["ball_centre_m"]) * MM) + translation
               for ball, (_, rotation, translation) in zip(balls, placed)]
    return balls, placed, balls[0]["ball_radius_m"] * MM, colours, opacity, centres


def _module_assembly(grids, meta, heading, path: Path) -> Path:
    balls, placed, radius, colours, opacity, centres = _module_bodies(grids, meta, 0.35)
    middle = np.mean(centres, axis=0)
    _, look, up, right = _module_frame(balls[0])
    rotation0 = placed[0][1]
    look, up, right = rotation0 @ look, rotation0 @ up, rotation0 @ right
    plot = v.plotter((1, 3), (2300, 800), f"{heading}\n{meta['module']}: {len(balls)} ball(s), each solved as its own "
                                          "one-ball module, here placed and cut between the balls; the loads from the "
                                          "contact forces on the loaded bodies", column_weights=[1.25, 1.0, 1.0])
    v.subplot(plot, 0, 0)
    v.transparency(plot)
    for k, (grid, rotation, translation) in enumerate(placed):
        v.bodies(plot, grid, colours, opacity=opacity, smooth=True)
        _load_arrow(plot, balls[k], rotation, translation, 1.2 * radius, f"ball {k + 1}")
        v.text(plot, centres[k] + 0.2 * radius * up, f"ball {k + 1}")
    if len(centres) > 1:
        v.text(plot, 0.5 * (centres[0] + centres[1]) - 0.3 * radius * up, "B2B contact")
    v.title(plot, f"the {balls[0]['loaded_body'].replace('_', ' ')} transparent")
    v.frame_axes(plot)
    extent = max(float(np.ptp(np.asarray(grid.points) @ axis)) for grid, _, _ in placed for axis in (up, right))
    v.view(plot, middle + 0.35 * radius * up, 0.9 * look - 0.75 * right - 0.45 * up, up,
           max(2.4 * radius * max(1.0, 0.65 * len(balls)), 0.62 * extent))
    # ball 1's cross-section with the contact frames
    v.subplot(plot, 0, 1)
    c0, look0, up0, right0 = _module_frame(balls[0])
    section = v.clipped(grids[0], [(c0, look0)])
    v.bodies(plot, section, colours, lighting=False)
    for contact in balls[0]["contacts"]:
        point = np.asarray(contact["point_m"]) * MM
        frame = np.asarray(contact["frame"])
        v.triad(plot, point - 0.02 * radius * frame[2] - 0.05 * radius * look0, frame, 0.4 * radius,
                names=("e1", "e2", "e3"))
        v.text(plot, point - 0.62 * radius * frame[2] - 0.3 * radius * look0,
               f"{contact['name']}: {contact['normal_force_N']:.1f} N,\n"
               f"{math.degrees(contact['contact_angle_rad']):.2f} deg")
    v.title(plot, "ball 1: the cut through the ball centre and the four contacts;\ncontact frames e1 (major axis), "
                  "e2 (minor axis),\ne3 (normal into the ball); loaded contact angles")
    v.view(plot, c0 - 0.05 * radius * up0, look0, up0, 1.6 * radius)
    # the most loaded contact's refined zone on that cut
    v.subplot(plot, 0, 2)
    contact = max(balls[0]["contacts"], key=lambda c: c["normal_force_N"])
    frame = np.asarray(contact["frame"])
    a, b = contact["hertz"]["a_m"] * MM, contact["hertz"]["b_m"] * MM
    origin = np.asarray(contact["point_m"]) * MM
    across = np.cross(look0, frame[2])
    face = v.cut(grids[0], origin, look0, across, frame[2], 2.3 * a, 2.3 * a * 1.2)
    body = np.asarray(face.cell_data["body"])
    for k in np.unique(body):
        plot.add_mesh(face.extract_cells(np.flatnonzero(body == k)), color=colours[int(k)], show_edges=True,
                      edge_color=v.EDGE_COLOUR, line_width=1, lighting=False)
    towards = -look0 * 0.01 * a
    plot.add_mesh(v.polyline([origin - a * across + towards, origin + a * across + towards]), color=v.VERMILLION,
                  line_width=5)
    v.text(plot, origin - 0.3 * a * frame[2], "Hertz contact width 2a", colour=v.VERMILLION)
    v.scale_bar(plot, origin - 2.0 * a * across - 1.8 * a * frame[2] + towards, across, v.nice(0.5 * a))
    level = meta.get("level", {})
    h_words = f"h = {level['h_contact_m'] * 1e6:.0f} um at the contact; " if "h_contact_m" in level else ""
    v.title(plot, f"ball 1 {contact['name']}: the mesh on that cut (ball above);\n{h_words}Hertz a = "
                  f"{a * 1e3:.0f} um, b = {b * 1e3:.0f} um")
    v.view(plot, origin + 0.25 * a * frame[2], look0, frame[2], 1.9 * a)
    return v.save(plot, path)


def _pressure_top(grids, balls) -> tuple[float, int]:
    peak = max(float(np.max(grid.point_data["p_MPa"])) for grid in grids)
    hertz = max(c["hertz"]["p0_Pa"] for ball in balls for c in ball["contacts"]) * MPA
    return v.colour_scale(max(peak, hertz))


def _ellipses(contact, width_hertz=6.0, width_fe=2.5):
    hertz, fe = contact["hertz"], contact["fe_ellipse"]
    x0, y0 = (0.0, 0.0) if fe is None else (fe["x0_m"] * MM, fe["y0_m"] * MM)
    out = [(hertz["a_m"] * MM, hertz["b_m"] * MM, x0, y0, HERTZ_COLOUR, width_hertz)]
    if fe is not None:
        out.append((fe["a_m"] * MM, fe["b_m"] * MM, x0, y0, FE_COLOUR, width_fe))
    return out


def _module_pressure_overview(grids, meta, heading, path: Path) -> Path:
    balls = meta["balls"]
    top, n_labels = _pressure_top(grids, balls)
    rows = len(balls)
    plot = v.plotter((rows, 2), (1800, 480 * rows), f"{heading}\ncontact pressure on the deformed ball surfaces: "
                                                    "where the contacts sit; one colour scale",
                     caption=62)
    for row, (grid, ball) in enumerate(zip(grids, balls)):
        outer = v.surface(grid, 0)
        radius = ball["ball_radius_m"] * MM
        scale = v.displacement_scale(outer, radius, 0.12)  # the flattened contacts visible on the whole ball
        warped = v.warped(outer, scale)
        centre, look, up, right = _module_frame(ball)
        for column, moving in enumerate((False, True)):
            v.subplot(plot, row, column)
            actor = v.pressure_surface(plot, warped, top, n_labels, smooth=True)
            seen = [c for c in ball["contacts"] if c["moving"] == moving]
            points = []
            for contact in seen:
                origin = np.asarray(contact["point_m"]) * MM
                points.append(origin)
                v.ellipse_curves(plot, outer, origin, contact["frame"], _ellipses(contact, 4.0, 2.0), 0.003 * radius,
                                 scale)
                v.text(plot, origin - 0.22 * radius * np.asarray(contact["frame"][2]),
                       f"{contact['name']} {contact['normal_force_N']:.1f} N")
            outward = -np.sum([np.asarray(c["frame"][2]) for c in seen], axis=0)
            outward /= np.linalg.norm(outward)
            direction = -outward - 0.35 * look  # from the bisector of the two contacts, tilted along the track
            screen_up = np.cross(np.cross(direction, look), direction)
            if np.cross(direction, screen_up) @ (points[0] - centre) > 0.0:
                screen_up = -screen_up
            body = f"the {ball['loaded_body']}" if moving else "the clamped body"
            v.title(plot, f"ball {row + 1}: the contacts with {body.replace('_', ' ')}, seen from its side; "
                          f"displacements x {scale:g}")
            v.view(plot, np.mean(points, axis=0), direction, screen_up, 0.55 * radius)
    v.caption(plot, ELLIPSE_NOTE, bar=(actor, "contact pressure [MPa]", n_labels, "p = 0"))
    return v.save(plot, path)


def _module_pressure_contacts(grids, meta, heading, path: Path) -> Path:
    balls = meta["balls"]
    top, n_labels = _pressure_top(grids, balls)
    rows, columns = len(balls), len(balls[0]["contacts"])
    width, height = 1900, 330 * rows
    plot = v.plotter((rows, columns), (width, height), f"{heading}\ncontact pressure on the deformed ball surface "
                                                      "(true scale), each contact seen along its normal from the "
                                                      "flank (e1 across the groove, e2 up); one colour scale",
                     caption=62)
    a_max = max(c["hertz"]["a_m"] for ball in balls for c in ball["contacts"]) * MM
    half_width = 1.2 * a_max
    half = half_width * (height / rows) / (width / columns)
    for row, (grid, ball) in enumerate(zip(grids, balls)):
        outer = v.surface(grid, 0)
        centres = np.asarray(outer.cell_centers().points)
        for column, contact in enumerate(ball["contacts"]):
            v.subplot(plot, row, column)
            origin = np.asarray(contact["point_m"]) * MM
            frame = np.asarray(contact["frame"])
            near = outer.extract_cells(np.flatnonzero(np.linalg.norm(centres - origin, axis=1) <= 2.0 * a_max))
            near = near.extract_surface(algorithm="dataset_surface")
            actor = v.pressure_surface(plot, near, top, n_labels)
            v.ellipse_curves(plot, near, origin, frame, _ellipses(contact), 0.04 * contact["hertz"]["b_m"] * MM, 1.0)
            fe = contact["fe_ellipse"]
            fe_words = "" if fe is None else f", FE {fe['p0_Pa'] * MPA:.0f}"
            v.title(plot, f"ball {row + 1} {contact['name']}: {contact['normal_force_N']:.1f} N, "
                          f"{math.degrees(contact['contact_angle_rad']):.2f} deg; peak "
                          f"{contact['peak_pressure_Pa'] * MPA:.0f} MPa\np0: Hertz "
                          f"{contact['hertz']['p0_Pa'] * MPA:.0f}{fe_words} MPa")
            if column == 0:
                v.scale_bar(plot, origin + 0.95 * half_width * frame[0] - 0.8 * half * frame[1], -frame[0],
                            v.nice(0.5 * a_max))
            v.view(plot, origin - 0.12 * half * frame[1], frame[2], frame[1], half)
    v.caption(plot, ELLIPSE_NOTE, bar=(actor, "contact pressure [MPa]", n_labels, "p = 0"))
    return v.save(plot, path)


def _module_stress(grids, meta, heading, path: Path) -> Path:
    balls = meta["balls"]
    nu = meta["poisson_ratio"]
    rows, columns = len(balls), 1 + len(balls[0]["contacts"])
    width, height = 2300, 440 * rows
    weights = [1.25] + [1.0] * (columns - 1)
    column_width = width / sum(weights)
    aspect = (height / rows) / column_width
    a_max = max(c["hertz"]["a_m"] for ball in balls for c in ball["contacts"]) * MM
    half_width = 1.2 * a_max
    half_height = 0.92 * aspect * half_width / 1.45  # the view shows 1.45 times the window's height
    plans, tops = [], []
    for grid, ball in zip(grids, balls):
        centre, look, up, right = _module_frame(ball)
        plan = []
        for contact in ball["contacts"]:
            frame = np.asarray(contact["frame"])
            fe = contact["fe_ellipse"]
            origin = np.asarray(contact["point_m"]) * MM + (0.0 if fe is None else fe["x0_m"] * MM) * frame[0]
            hertz = contact["hertz"]
            depth, value = v.hertz_maximum(hertz["a_m"], hertz["b_m"], hertz["p0_Pa"], nu)
            face = v.cut(grid, origin, look, np.cross(look, frame[2]), frame[2], half_width, half_height)
            tops += [value, float(np.max(face.cell_data["vm_MPa"]))]
            plan.append((contact, origin, frame[2], depth, value, face))
        plans.append((centre, look, up, right, plan))
    top, n_labels = v.colour_scale(max(tops))
    plot = v.plotter((rows, columns), (width, height), f"{heading}\nvon Mises stress (element means of the P2 "
                                                       "stress) on the cut through the ball centre that holds the "
                                                       "contact normals: the e1-e3 plane of each contact",
                     caption=62, column_weights=weights)
    for row, (grid, ball, (centre, look, up, right, plan)) in enumerate(zip(grids, balls, plans)):
        v.subplot(plot, row, 0)
        radius = ball["ball_radius_m"] * MM
        shown = v.clipped(grid, [(centre, look)])
        plot.add_mesh(v.surface(shown), scalars="vm_MPa", cmap=STRESS_CMAP, clim=(0.0, top), show_scalar_bar=False,
                      lighting=False)
        v.title(plot, f"ball {row + 1}")
        v.view(plot, centre - 0.25 * radius * right, look, up, 1.75 * radius)
        for column, (contact, origin, e3, depth, value, face) in enumerate(plan, start=1):
            v.subplot(plot, row, column)
            marks = [origin + depth * e3, origin - depth * e3]
            found, actor = v.stress_window(plot, grid, origin, look, np.cross(look, e3), e3, half_width, half_height,
                                        top, n_labels, marks, bar=False, face=face)
            words = [f"FE, {'ball' if body == 0 else ball['bodies'][body].replace('_', ' ')}: {peak:.0f} MPa, "
                     f"{abs((where - origin) @ e3) * 1e3:.0f} um deep" for body, peak, where in found]
            v.title(plot, f"ball {row + 1} {contact['name']}, {contact['normal_force_N']:.1f} N (the ball above)\n"
                          + "\n".join(words) + f"\nHertz: {value:.0f} MPa, {depth * 1e3:.0f} um deep")
    v.caption(plot, "green dots: the largest FE element mean of each body in the window;\nblue rings: the Hertz "
                    "subsurface maximum at the FE force (both bodies);\nelement means smooth the peak on coarse "
                    "meshes", bar=(actor, "von Mises stress [MPa]", n_labels))
    return v.save(plot, path)


def _module_helix(grids, meta, heading, path: Path) -> Path:
    balls, placed, radius, colours, opacity, centres = _module_bodies(grids, meta, 0.25)
    _, look, up, _ = _module_frame(balls[0])  # look: the helix tangent at ball 1, up: radially out (to the nut)
    if len(centres) > 1 and look @ (centres[1] - centres[0]) < 0.0:
        look = -look
    plot = v.plotter((1, 1), (1400, 900), f"{heading}\nthe two-ball module seen along the helix from behind ball 1 "
                                          f"(the {balls[0]['loaded_body']} above, transparent)")
    v.subplot(plot, 0, 0)
    v.transparency(plot)
    for k, (grid, rotation, _) in enumerate(placed):
        v.bodies(plot, grid, colours, opacity=opacity, smooth=True)
        v.text(plot, centres[k] + 1.05 * radius * (rotation @ up), f"ball {k + 1}")
    v.frame_axes(plot)
    focal = np.mean(centres, axis=0)
    v.look_from(plot, centres[0] - 7.0 * radius * look + 1.8 * radius * up, focal, up, 32.0)
    return v.save(plot, path)
