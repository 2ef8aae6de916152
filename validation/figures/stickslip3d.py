"""3D screenshots of the stick and slip areas of rolling contacts (docs/render3d.md, "Stick and slip").

:func:`write_fields` saves the tangential solutions (:class:`~lowmodel.contact.rolling.RollingContact`, Kalker's
frame: ``x`` rolling, ``y`` lateral) of a scene's contacts as ``stickslip_<name>.npz`` with ``stickslip_<name>.json``
beside it, and each contact as ``stickslip_<name>_<k>.vtu`` (:func:`write_vtu`: the grid's cells as quadrilaterals
with SI cell data, for ParaView; docs/render3d.md); :func:`picture` draws ``3d_stickslip_<name>.png`` from the NPZ
and JSON only (nothing is solved again).

Each contact is a surface over its grid raised by the traction magnitude ``|q|`` [MPa]: the slip area coloured by
``|q| = mu p`` (``viridis``, one colour scale for the picture), the stick area (``|q| < mu p``) in one flat colour
(Okabe-Ito vermillion) with the bound ``mu p`` above it as a wire mesh, the direction of the slip velocity as
arrows on the slip area, the outline of the contact area (the cells with ``p > 0``) and, where the scene gives it,
the Hertz ellipse on the contact plane.  Deterministic as the other screenshots (:mod:`validation.figures.views3d`).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ballbench.validation.figures import views3d as v

__all__ = ["write_fields", "write_vtu", "picture", "artifacts", "STICK_COLOUR", "SLIP_CMAP", "VTU_ARRAYS"]

MM, MPA = v.MM, v.MPA
STICK_COLOUR = v.VERMILLION  # flat: apart from every colour of viridis
SLIP_CMAP = v.PRESSURE_CMAP
_ARRAYS = ("pressure", "traction", "slip", "stick", "contact")
VIEW = (0.5, 0.0, -0.87)  # the cameras' direction: along the rolling direction, 60 degrees down
# the cell data of stickslip_<name>_<k>.vtu (write_vtu): names carry their SI units
VTU_ARRAYS = ("p [Pa]", "q_x [Pa]", "q_y [Pa]", "|q| [Pa]", "mu p [Pa]", "stick [1]", "contact [1]",
              "slip direction [1]")


def write_vtu(path, solution) -> Path:
    """One tangential solution (a RollingContact) as a VTU file at ``path``: the grid's ``nx ny`` cells as
    quadrilaterals in the plane z = 0 (corners at the cell edges [m], Kalker's frame: x rolling, y lateral), cell
    (i, j) the ``i ny + j``-th, with the cell data of :data:`VTU_ARRAYS`: the normal pressure ``p``, the traction
    on body 1 ``q_x``, ``q_y`` and ``|q|``, the traction bound ``mu p`` [Pa], ``stick`` (1 in the stick area, 0
    elsewhere), ``contact`` (1 where ``p > 0``), and ``slip direction``, the unit vector of the slip of body 1
    relative to body 2 in the slip area (x, y, 0), zero in stick and outside the contact.  Returns the path."""
    import meshio

    grid = solution.grid
    x, y = np.asarray(grid.x, float), np.asarray(grid.y, float)
    x_edges = np.r_[x - 0.5 * grid.dx, x[-1] + 0.5 * grid.dx]
    y_edges = np.r_[y - 0.5 * grid.dy, y[-1] + 0.5 * grid.dy]
    X, Y = np.meshgrid(x_edges, y_edges, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
    index = np.arange(X.size).reshape(X.shape)
    quads = np.column_stack([index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(),
                             index[:-1, 1:].ravel()])
    pressure = np.asarray(solution.pressure, float)
    traction = np.asarray(solution.traction, float)
    contact, stick = np.asarray(solution.contact, bool), np.asarray(solution.stick, bool)
    slip = np.asarray(solution.slip, float)
    norm = np.linalg.norm(slip, axis=-1)
    moving = contact & ~stick & (norm > 0.0)
    direction = np.zeros(slip.shape[:2] + (3,))
    direction[moving, :2] = slip[moving] / norm[moving, None]
    values = (pressure, traction[..., 0], traction[..., 1], np.linalg.norm(traction, axis=-1),
              float(solution.friction_coefficient) * pressure, stick.astype(float), contact.astype(float))
    data = {key: [np.asarray(value).ravel()] for key, value in zip(VTU_ARRAYS, values)}
    data[VTU_ARRAYS[-1]] = [direction.reshape(-1, 3)]
    path = Path(path)
    meshio.Mesh(points, [("quad", quads)], cell_data=data).write(path)
    return path


def write_fields(directory, name: str, contacts, *, scene: str, fidelity: str, title: str,
                 ellipses=None) -> list[Path]:
    """Save the tangential solutions of ``contacts`` (``[(label, RollingContact), ...]``) as
    ``<directory>/stickslip_<name>.npz`` (per contact ``k``: ``x_k`` (nx,), ``y_k`` (ny,) [m] the cell centres,
    ``pressure_k`` (nx, ny) [Pa], ``traction_k`` and ``slip_k`` (nx, ny, 2) [Pa], [-] (a shift: [m]),
    ``stick_k``, ``contact_k`` (nx, ny) bool) and ``stickslip_<name>.json`` (scene, fidelity, title, per contact
    its label, friction coefficient, normal force, stick fraction, optional Hertz ellipse ``(a_x, b_y)`` [m] and its
    VTU file) and per contact ``stickslip_<name>_<k>.vtu`` (:func:`write_vtu`, ``k`` from 0);
    ``ellipses``: per contact ``(a_x, b_y)`` or None.  Returns ``[npz, json, vtu_0, vtu_1, ...]``."""
    directory = Path(directory)
    contacts = list(contacts)
    if not contacts:
        raise ValueError("contacts must hold at least one (label, RollingContact)")
    ellipses = [None] * len(contacts) if ellipses is None else list(ellipses)
    if len(ellipses) != len(contacts):
        raise ValueError(f"ellipses must have one entry per contact ({len(contacts)}), got {len(ellipses)}")
    arrays, entries, vtus = {}, [], []
    directory.mkdir(parents=True, exist_ok=True)
    for k, (label, solution) in enumerate(contacts):
        vtus.append(write_vtu(directory / f"stickslip_{name}_{k}.vtu", solution))
        arrays[f"x_{k}"], arrays[f"y_{k}"] = np.asarray(solution.grid.x, float), np.asarray(solution.grid.y, float)
        for key in _ARRAYS:
            arrays[f"{key}_{k}"] = np.asarray(getattr(solution, key))
        ellipse = ellipses[k]
        entries.append({"label": str(label),
                        "friction_coefficient": float(solution.friction_coefficient),
                        "normal_force_N": float(solution.normal_force),
                        "stick_fraction": float(solution.stick_fraction),
                        "ellipse_m": None if ellipse is None else [float(ellipse[0]), float(ellipse[1])],
                        "vtu": vtus[-1].name})
    data_path, meta_path = directory / f"stickslip_{name}.npz", directory / f"stickslip_{name}.json"
    np.savez_compressed(data_path, **arrays)
    meta_path.write_text(json.dumps({"kind": "stickslip", "scene": scene, "fidelity": fidelity, "title": title,
                                     "file": data_path.name, "frame": "Kalker: x rolling, y lateral, z normal",
                                     "vtu_arrays": list(VTU_ARRAYS), "contacts": entries}, indent=1))
    return [data_path, meta_path, *vtus]


def artifacts(run, name: str, contacts, *, title: str, ellipses=None) -> None:
    """For a scene run (``validation.scene.Run``): :func:`write_fields` into its folder, :func:`picture`, and
    register the files as the run's artifacts; a picture that cannot be drawn becomes a note, never a failure."""
    paths = write_fields(run.path(""), name, contacts, scene=run.scene.name, fidelity=run.fidelity, title=title,
                         ellipses=ellipses)
    for path in paths:
        run.add_artifact(path)  # the NPZ, JSON and one VTU per contact
    try:
        run.add_artifact(picture(paths[1]))
    except Exception as error:  # the picture is an extra; the checks stand without it
        run.note(f"3D screenshot of {paths[0].name} not drawn: {type(error).__name__}: {error}")


def _corner_heights(values, contact, step: int = 1) -> np.ndarray:
    """Heights at the cell corners ((nx + 1, ny + 1), or every ``step``-th corner): the mean of the four cells about
    each corner, those outside the contact counted as zero (so the surface meets the plane at the contact's edge)."""
    padded = np.pad(np.where(contact, values, 0.0), 1)
    corners = 0.25 * (padded[:-1, :-1] + padded[1:, :-1] + padded[:-1, 1:] + padded[1:, 1:])
    return corners if step == 1 else corners[_every(corners.shape[0], step)][:, _every(
        corners.shape[1], step)]


def _every(n: int, step: int) -> np.ndarray:
    """Every ``step``-th index of ``range(n)`` and the last one."""
    return np.unique(np.r_[np.arange(0, n, step), n - 1])


def _cells_surface(pv, x_edges, y_edges, heights, mask, values):
    """One quadrilateral per cell of ``mask`` between the corners ``x_edges`` (nx + 1,), ``y_edges`` (ny + 1,) [mm]
    at ``heights`` (nx + 1, ny + 1), with the cell data ``q`` = ``values`` of those cells (NaN: the stick colour)."""
    X, Y = np.meshgrid(x_edges, y_edges, indexing="ij")
    points = np.stack([X.ravel(), Y.ravel(), heights.ravel()], 1)
    index = np.arange(X.size).reshape(X.shape)
    quads = np.stack([index[:-1, :-1], index[1:, :-1], index[1:, 1:], index[:-1, 1:]], -1)[mask]
    mesh = pv.PolyData(points, np.hstack([np.full((len(quads), 1), 4), quads]).ravel())
    mesh.cell_data["q"] = values[mask]
    return mesh


def _outline(x, y, mask) -> np.ndarray:
    """The edges between the cells ``mask`` and the others (``(k, 2, 3)`` segments on z = 0) [mm]."""
    dx, dy = 0.5 * float(x[1] - x[0]), 0.5 * float(y[1] - y[0])
    padded = np.pad(mask, 1)
    segments = []
    for i, j in zip(*np.nonzero(padded[1:, 1:-1] != padded[:-1, 1:-1])):  # edges at x_(i-1/2)
        xe = x[i] - dx if i < len(x) else x[-1] + dx
        segments.append([[xe, y[j] - dy, 0.0], [xe, y[j] + dy, 0.0]])
    for i, j in zip(*np.nonzero(padded[1:-1, 1:] != padded[1:-1, :-1])):  # edges at y_(j-1/2)
        ye = y[j] - dy if j < len(y) else y[-1] + dy
        segments.append([[x[i] - dx, ye, 0.0], [x[i] + dx, ye, 0.0]])
    return np.asarray(segments, float).reshape(-1, 2, 3)


def _length(mm: float) -> str:
    return f"{mm * 1e3:.3g} um" if mm < 1.0 else f"{mm:.3g} mm"


def _segments(pv, segments):
    points = segments.reshape(-1, 3)
    lines = np.hstack([np.full((len(segments), 1), 2), np.arange(2 * len(segments)).reshape(-1, 2)]).ravel()
    return pv.PolyData(points, lines=lines)


def picture(meta_path) -> Path:
    """``3d_stickslip_<name>.png`` of ``stickslip_<name>.json`` (:func:`write_fields`): one viewport per contact,
    two columns, the module docstring's surface; returns the PNG path."""
    pv = v.pyvista()
    meta_path = Path(meta_path)
    meta = json.loads(meta_path.read_text())
    entries = meta["contacts"]
    with np.load(meta_path.parent / meta["file"]) as data:
        fields = [{key: data[f"{key}_{k}"] for key in ("x", "y", *_ARRAYS)} for k in range(len(entries))]
    columns = min(2, len(entries))
    rows = -(-len(entries) // columns)
    bounds = [e["friction_coefficient"] * f["pressure"] * MPA for e, f in zip(entries, fields)]
    top, n_labels = v.colour_scale(max(float(np.max(b)) for b in bounds))
    spans = [(float(np.ptp(f["x"])) * MM, float(np.ptp(f["y"])) * MM) for f in fields]
    long = max(max(span) for span in spans)
    height = 0.12 * long / top  # mm of height per MPa
    width, row_height = 1800, 330
    plot = v.plotter((rows, columns), (width, row_height * rows),
                     f"{meta['scene']}: {meta['title']}, {meta['fidelity']} level\nq: the magnitude of the tangential "
                     f"traction (height and colour; 100 MPa = {_length(100.0 * height)} high); x rolling (leading "
                     "edge +x), y lateral", caption=62)
    actor = None
    aspect = (width / columns) / row_height
    across = max(span[1] for span in spans)  # the lateral extent: horizontal on the screen
    deep = max(span[0] for span in spans) * abs(VIEW[2]) + top * height * abs(VIEW[0])  # rolling extent and heights
    half_height = max(0.55 * across / aspect, 0.62 * deep)  # room for the title's line above
    for k, (f, entry, bound) in enumerate(zip(fields, entries, bounds)):
        v.subplot(plot, k // columns, k % columns)
        actor = _contact(plot, pv, f, entry, bound, top, height, half_height) or actor
    legend = ("vermillion: the stick area (q < mu p); the slip area (q = mu p) coloured by q;\n"
              "grey wire: the bound mu p over the stick area; black arrows: the direction of the slip velocity;\n"
              "black outline: the contact area (p > 0); blue: the Hertz ellipse (where the scene gives it)")
    v.caption(plot, legend, bar=None if actor is None else (actor, "q = mu p in the slip area [MPa]", n_labels))
    return v.save(plot, meta_path.parent / f"3d_{meta_path.stem}.png")


def _contact(plot, pv, f, entry, bound, top, height, half_height):
    """One contact's viewport; returns the slip surface's actor (the colour bar's) or None."""
    x, y = f["x"] * MM, f["y"] * MM
    q = np.linalg.norm(f["traction"], axis=-1) * MPA
    contact, stick = f["contact"].astype(bool), f["stick"].astype(bool)
    slip = contact & ~stick
    dx, dy = float(x[1] - x[0]), float(y[1] - y[0])
    base = pv.Plane(center=(0.5 * (x[0] + x[-1]), 0.5 * (y[0] + y[-1]), -0.01 * top * height), direction=(0, 0, 1),
                    i_size=float(np.ptp(x)) + dx, j_size=float(np.ptp(y)) + dy, i_resolution=1, j_resolution=1)
    plot.add_mesh(base, color=v.ZERO_PRESSURE_COLOUR, lighting=False)
    x_edges = np.r_[x - 0.5 * dx, x[-1] + 0.5 * dx]
    y_edges = np.r_[y - 0.5 * dy, y[-1] + 0.5 * dy]
    corners = _corner_heights(q, contact) * height
    surface = _cells_surface(pv, x_edges, y_edges, corners, contact, np.where(stick, np.nan, q))
    actor = plot.add_mesh(surface, scalars="q", cmap=SLIP_CMAP, clim=(0.0, top), nan_color=STICK_COLOUR,
                          show_scalar_bar=False)
    if stick.any():
        k = max(1, -(-max(len(x), len(y)) // 24))  # at most about 24 wires across: blocks of k x k cells
        rows, columns = _every(len(x) + 1, k), _every(len(y) + 1, k)
        blocks = np.add.reduceat(np.add.reduceat(stick.astype(int), rows[:-1], axis=0), columns[:-1], axis=1) > 0
        wire = _cells_surface(pv, x_edges[rows], y_edges[columns], _corner_heights(bound, contact, k) * height,
                              blocks, np.zeros(blocks.shape))
        plot.add_mesh(wire, style="wireframe", color="#505050", line_width=1, lighting=False)
    step = max(1, int(round(np.sqrt(slip.sum() / 60.0))))
    pick = slip & (np.add.outer(np.arange(len(x)) % step, np.arange(len(y)) % step) == 0)
    s = f["slip"][pick]
    norm = np.linalg.norm(s, axis=-1)
    keep = norm > 0.0
    if keep.any():
        ii, jj = np.nonzero(pick)
        lift = 0.04 * top * height
        middle = 0.25 * (corners[ii, jj] + corners[ii + 1, jj] + corners[ii, jj + 1] + corners[ii + 1, jj + 1])
        centres = np.stack([x[ii], y[jj], np.maximum(middle, q[ii, jj] * height) + lift], 1)[keep]
        arrows = pv.PolyData(centres)
        arrows.point_data["direction"] = np.hstack([s[keep] / norm[keep, None], np.zeros((int(keep.sum()), 1))])
        length = 0.8 * step * min(dx, dy)
        plot.add_mesh(arrows.glyph(orient="direction", scale=False, factor=length,
                                   geom=pv.Arrow(start=(-0.5, 0, 0), tip_length=0.4, tip_radius=0.2,
                                                 shaft_radius=0.07)),
                      color="black", lighting=False)
    plot.add_mesh(_segments(pv, _outline(x, y, contact)), color="black", line_width=2)
    if entry["ellipse_m"] is not None:
        a, b = (value * MM for value in entry["ellipse_m"])
        plot.add_mesh(v.polyline(v.ellipse((0.0, 0.0, 0.0), (1, 0, 0), (0, 1, 0), a, b)), color=v.BLUE,
                      line_width=3)
    force = entry["normal_force_N"]
    force_words = f"{force:.1f} N" if force < 1e3 else f"{force * 1e-3:.1f} kN"
    v.title(plot, f"{entry['label']}: F = {force_words}, mu = {entry['friction_coefficient']:g}; stick "
                  f"{100.0 * entry['stick_fraction']:.1f} %")
    v.scale_bar(plot, (x[0] - 2.5 * dx, y[0], 0.0), (0, 1, 0), v.nice(0.4 * float(np.ptp(y))))
    v.view(plot, (0.5 * (x[0] + x[-1]), 0.5 * (y[0] + y[-1]), 0.5 * top * height), VIEW, (0, 0, 1), half_height)
    return actor
