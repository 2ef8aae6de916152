"""FE contact of one ball against its counter body (a :class:`ContactCase`) against exact Hertz.

The FE rung of the ladder for a single contact: mesh the pair of the case (meshes.assemblies.contact_pairs, or
the helical pair of meshes.assemblies.screw_pair), solve the frictionless contact (fem.hertz_case: P2
tetrahedra, mortar contact with Hertz's quadratic initial gap, condensed compliance, primal-dual active set)
over a load sweep, and fit a, b, p0 and the contact approach delta (bulk compliance removed).  Mesh levels:
``n`` elements across the Hertz minor semi-axis b (``h_contact = b / n``) and the growth rate away from the
fine zone (the case's :class:`ContactFe`).  The ``fe-hertz-*`` scenes, ``ballbench calibrate`` and ``show``
use it.
"""
from __future__ import annotations

import contextlib
import io
import json
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ballbench.fem import contact, hertz_case, postprocess
from ballbench.fem.contact import full_solution
from ballbench.fem.postprocess import nodal_stress
from ballbench.lowmodel.contact import hertz
from ballbench.validation.cases.case import ContactCase
from ballbench.validation.figures import render3d
from ballbench.validation.figures.style import save

__all__ = ["PairModel", "pair_model", "hertz_geometry", "block_half_width", "block_room", "BLOCK_MARGIN",
           "DEFAULT_BLOCK",
           "solve_level", "level_dofs", "mesh_dofs", "write_fields",
           "compute_fields", "load_sweep", "load_fields", "show_fields", "FIELD_NAMES"]

# the counter block of a groove pair holds the candidate zone with this margin (block_half_width); the builders'
# default half-width is DEFAULT_BLOCK R_B (meshes.assemblies.contact_pairs.ball_in_groove_pair, screw_pair)
BLOCK_MARGIN = 1.15
DEFAULT_BLOCK = 0.6

FIELD_NAMES = {
    "displacement": "displacement_m",          # the P2 solution at all 10 nodes of each quadratic tetrahedron [m]
    "pressure": "contact_pressure_Pa",         # nodal contact pressure of the ball's candidate vertices [Pa]
    "von_mises": "von_mises_stress_Pa",        # element mean of the P2 stress, averaged at the nodes [Pa]
    "sigma_zz": "sigma_zz_Pa",                 # normal stress along the contact normal z, the same way [Pa]
}


@dataclass(frozen=True)
class PairModel:
    """What an FE level solves: the case, a mesh builder of ``(h_contact [m], growth)``, the Hertz geometry of
    the pair and the source text of the Hertz reference."""

    case: ContactCase
    builder: object
    geometry: hertz.HertzGeometry
    source: str

    @property
    def force(self) -> float:
        return self.case.force


def _fe(case: ContactCase):
    if case.fe is None:
        raise ValueError(f"case {case.name!r} has no FE settings (ContactCase.fe)")
    return case.fe


def _pair_geometry(case: ContactCase) -> tuple[hertz.HertzGeometry, tuple, str]:
    """Hertz geometry (lowmodel.contact.hertz.pair_geometry), the helical groove's arguments (screw pairs) and the
    source text of the reference."""
    radius, load = case.ball_radius, f"{case.force:g} N"
    geometry = hertz.pair_geometry(case)
    if case.pair == "flat":
        return geometry, (), f"lowmodel.contact.hertz.ball_on_flat (R_B {radius * 1e3:g} mm, {load})"
    if case.pair == "ball":
        return geometry, (), f"lowmodel.contact.hertz.ball_on_ball (R_B {radius * 1e3:g} mm each, {load})"
    if case.pair == "groove":
        return (geometry, (), f"lowmodel.contact.hertz.ball_in_groove (conformity {case.conformity}, R_B "
                              f"{radius * 1e3:g} mm, {load})")
    return (geometry, hertz.helical_pair(case), f"lowmodel.contact.hertz.from_curvatures of the exact helical "
                                                f"{case.pair} frame ({case.name}, {load})")


def hertz_geometry(case: ContactCase) -> hertz.HertzGeometry:
    """The Hertz geometry of the pair of ``case`` (the exact helical frame for screw and nut pairs)."""
    return _pair_geometry(case)[0]


def pair_model(case: ContactCase) -> PairModel:
    """The FE pair of ``case``: its mesh builder with the fine zone of ``case.fe`` about the Hertz ellipse at
    the case's force."""
    from ballbench.meshes.assemblies import contact_pairs, screw_pair

    fe = _fe(case)
    geometry, args, source = _pair_geometry(case)
    ref = hertz.solve_load(geometry, case.force)
    radius = case.ball_radius
    if fe.fine_zone == "ellipse":
        a, b = float(ref.a), float(ref.b)
        ellipse = (fe.zone[0] * a, fe.zone[1] * b, fe.zone[2] * b)
        zone = {"fine_ellipse": ellipse}
    else:
        zone = {"fine_radius": fe.zone[0] * ref.b}
        if fe.zone[1]:
            zone["fine_half_length"] = fe.zone[1] * ref.a
    width = block_half_width(case, geometry, ref)
    if width is not None:
        zone["block_half_width"] = width
    if case.pair == "flat":
        def build(h, growth):
            return contact_pairs.ball_on_flat_pair(radius, h, growth, **zone)
    elif case.pair == "ball":
        def build(h, growth):
            return contact_pairs.ball_on_ball_pair(radius, h, growth, **zone)
    elif case.pair == "groove":
        def build(h, growth):
            return contact_pairs.ball_in_groove_pair(radius, case.conformity, h, growth, **zone)
    else:
        def build(h, growth):
            return screw_pair.ball_in_screw_groove_pair(*args, h_contact=h, growth=growth, **zone)
    return PairModel(case, build, geometry, source)


def block_half_width(case: ContactCase, geometry: hertz.HertzGeometry, ref) -> float | None:
    """The counter block's half-width across a groove [m] (the major axis a of a ball in a groove, straight or
    helical) that holds the candidate zone of ``case``: :data:`BLOCK_MARGIN` times the zone's reach along the major
    axis, ``sqrt(gap_limit delta / min(A, B))`` (Hertz's separation; ``ref`` the Hertz solution at the case's
    force), when that passes the builders' default ``0.6 R_B`` (meshes.assemblies.contact_pairs, screw_pair); None
    (the default block, the mesh cache's key unchanged) otherwise, and for a flat or a ball counter body.  A block
    the groove cannot hold (a straight groove's ``0.9 r_g``, a helical flank's 90 % of the arc to its bottom) raises
    the builder's ValueError naming the width: the ellipse is then near the groove's shoulder (docs/truncation.md)."""
    if case.pair not in ("groove", "screw", "nut"):
        return None
    reach = math.sqrt(_fe(case).gap_limit * float(ref.delta) / min(geometry.A, geometry.B))
    width = BLOCK_MARGIN * reach
    return width if width > DEFAULT_BLOCK * case.ball_radius else None


def block_room(case: ContactCase) -> str:
    """"" when the counter block of ``case``'s FE pair (:func:`block_half_width`) fits its groove, else why not: the
    candidate zone reaches further across the groove than the block the groove holds (meshes.assemblies
    .contact_pairs.groove_block_limit, screw_pair.screw_block_limit): the contact ellipse runs towards the groove's
    bottom or shoulder, where no FE pair of the ladder resolves it (docs/truncation.md)."""
    from ballbench.meshes.assemblies import contact_pairs, screw_pair

    if case.pair not in ("groove", "screw", "nut"):
        return ""
    geometry = hertz.pair_geometry(case)
    width = block_half_width(case, geometry, hertz.solve_load(geometry, case.force))
    if width is None:
        return ""
    limit = (contact_pairs.groove_block_limit(case.ball_radius, case.conformity) if case.pair == "groove" else
             screw_pair.screw_block_limit(*hertz.helical_pair(case)))
    if width <= limit:
        return ""
    return (f"the FE pair's counter block would need {width * 1e3:.4g} mm across the groove to hold the contact's "
            f"candidate zone ({BLOCK_MARGIN:g} times its reach at 1.5 times the force), and the groove holds "
            f"{limit * 1e3:.4g} mm: the contact ellipse is too large for the FE pair (docs/truncation.md)")


def mesh_dofs(path) -> int:
    """The P2 DOFs of the tetrahedral mesh at ``path`` (``.msh``): 3 per vertex and per edge of its tetrahedra,
    the DOFs fem.hertz_case solves (before the support's Dirichlet DOFs are removed)."""
    import meshio

    mesh = meshio.read(path, file_format="gmsh")  # by name: meshio tries other readers and prints their errors
    tets = np.vstack([block.data for block in mesh.cells if block.type == "tetra"]).astype(np.int64)
    edges = np.sort(np.concatenate([tets[:, [i, j]] for i, j in ((0, 1), (1, 2), (0, 2), (0, 3), (1, 3), (2, 3))]),
                    axis=1)
    n_edges = np.unique(edges[:, 0] * (int(edges.max()) + 1) + edges[:, 1]).size
    return 3 * (np.unique(tets).size + n_edges)


def level_dofs(pair: PairModel, level) -> int:
    """The P2 DOFs of ``pair`` at the mesh level ``(n = b/h, growth)``, from its mesh alone (meshed, or taken from
    the mesh cache; no assembly, no solve): what the memory of the level is predicted from."""
    n, growth = level
    ref = hertz.solve_load(pair.geometry, pair.force)
    return mesh_dofs(pair.builder(float(ref.b) / n, growth))


def solve_level(pair: PairModel, level):
    """FE result (fem.hertz_case.CaseResult) and Hertz reference at the mesh level ``(n = b/h, growth)``."""
    n, growth = level
    fe = _fe(pair.case)
    ref = hertz.solve_load(pair.geometry, pair.force)
    geometry = pair.geometry

    def hertz_gap(x, y):  # Hertz's separation of the undeformed surfaces (Johnson 1985 eq 4.1)
        return geometry.A * x * x + geometry.B * y * y

    result = hertz_case.solve_case(lambda: pair.builder(ref.b / n, growth), pair.force, pair.case.material.pair,
                                   gap_limit=fe.gap_limit * float(ref.delta), initial_gap=hertz_gap,
                                   formulation=fe.formulation, order=fe.order)
    return result, ref


def write_fields(result, ref, directory, *, scene_name: str, fidelity: str, level, material) -> list:
    """Write ``fields.vtu`` (quadratic tetrahedra carrying the P2 solution at all nodes; field names carry their
    units) and ``fields.json`` (what ``show`` needs).  One more sparse solve for the full displacement field,
    with the factor the condensation kept (no second factorisation).  ``material``: the case's
    :class:`Material`.  Returns the two paths.
    """
    import meshio

    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    model, state = result.model, result.state
    pair, basis = model.pair, model.basis
    mesh = basis.mesh
    if basis.edge_dofs.size == 0 or not np.allclose(mesh.p.T, pair.points):
        raise ValueError("write_fields needs the P2 model of the pair's own vertices")
    u = full_solution(model, state)
    n_vertices = mesh.p.shape[1]
    # VTK's quadratic tetrahedron: 4 vertices, then the edges 0-1, 1-2, 0-2, 0-3, 1-3, 2-3 (scikit-fem's t2e order)
    node_of = np.vstack([mesh.t, n_vertices + mesh.t2e])                     # (10, n_elements)
    points = np.vstack([mesh.p.T, mesh.p[:, mesh.edges].mean(axis=1).T])
    displacement = np.vstack([u[basis.nodal_dofs].T, u[basis.edge_dofs].T])
    pressure = np.zeros(len(points))
    pressure[model.candidates] = state.pressure
    candidate = np.zeros(len(points))
    candidate[model.candidates] = 1.0
    von_mises, sigma_zz = nodal_stress(basis, u, material.youngs_modulus, material.poisson_ratio, node_of)
    vtk = meshio.Mesh(points, [("tetra10", node_of.T)],
                      point_data={FIELD_NAMES["displacement"]: displacement, FIELD_NAMES["pressure"]: pressure,
                                  FIELD_NAMES["von_mises"]: von_mises, FIELD_NAMES["sigma_zz"]: sigma_zz,
                                  "contact_candidate": candidate},
                      cell_data={"body": [np.asarray(pair.body)]})
    vtu = directory / "fields.vtu"
    vtk.write(vtu)
    meta = {
        "scene": scene_name, "fidelity": fidelity, "level": {"n": level[0], "growth": level[1]},
        "force_N": float(result.force_sum), "youngs_modulus_Pa": material.youngs_modulus,
        "poisson_ratio": material.poisson_ratio,
        "hertz": {"a_m": float(ref.a), "b_m": float(ref.b), "p0_Pa": float(ref.p0), "delta_m": float(ref.delta)},
        "fe": {"a_m": float(result.a), "b_m": float(result.b), "p0_Pa": float(result.p0),
               "delta_m": float(result.delta)},
        "symmetry": {"x": "symmetry_x" in pair.surfaces, "y": "symmetry_y" in pair.surfaces},
        "fields": FIELD_NAMES,
        "cells": "tetra10 (P2 at vertices and edge midpoints)",
        "frame": "contact point at the origin, normal +z from the counter body into the ball, a along x, b along y",
    }
    meta_path = directory / "fields.json"
    meta_path.write_text(json.dumps(meta, indent=2))
    return [vtu, meta_path]


def compute_fields(case: ContactCase, scene_name: str, fidelity: str, directory, *,
                   show_progress: bool = False) -> list:
    """Solve the checked level of ``case`` at ``fidelity`` and write its fields into ``directory`` (named
    ``scene_name`` in ``fields.json``).  What ``ballbench show`` runs when ``validate`` left no fields behind.
    Returns the written paths."""
    fe = _fe(case)
    level = fe.levels.checked(fidelity)
    pair = pair_model(case)
    steps = ["solve", "fields"]
    if show_progress:
        from tqdm.auto import tqdm

        steps = tqdm(steps, desc=f"{scene_name}: solve, then write fields", leave=False)
    paths = []
    for step in steps:
        if step == "solve":
            result, ref = solve_level(pair, level)
        else:
            paths = write_fields(result, ref, directory, scene_name=scene_name, fidelity=fidelity, level=level,
                                 material=case.material)
    return paths


def load_sweep(case: ContactCase, fidelity: str = "quick", load_factors=(0.5, 0.75, 1.0, 1.25, 1.5)) -> dict:
    """FE load sweep of ``case``'s pair: ``force`` [N], ``approach`` [m], ``a`` [m] at every load factor
    (times the case's force; sorted).

    One mesh and one condensation (the checked level at ``fidelity``), then a contact solve and a Hertz-field
    fit per load.  Returns also ``ball_radius`` [m], the Hertz ``geometry``, the ``level``, ``ndofs`` and the
    wall time [s].
    """
    start = time.perf_counter()
    pair = pair_model(case)
    n, growth = _fe(case).levels.checked(fidelity)
    result, _ = solve_level(pair, (n, growth))  # mesh, condensation, the case's own load sweep
    model = result.model
    operator = postprocess.force_operator(model.pair.points, model.pair.surfaces["ball_contact"], model.candidates)
    forces, approaches, semi_axes = [], [], []
    state = None
    for factor in np.sort(np.asarray(load_factors, dtype=float)):
        state = contact.solve_force(model, factor * case.force, start=state)
        fit = hertz_case.fit_contact_patch(model, state, operator)  # the fit solve_case makes at the nominal load
        forces.append(state.force)
        approaches.append(state.approach)
        semi_axes.append(fit.a)
    return {"force": np.array(forces), "approach": np.array(approaches), "a": np.array(semi_axes),
            "ball_radius": case.ball_radius, "geometry": pair.geometry, "level": (n, growth),
            "ndofs": result.ndofs, "wall_time_s": time.perf_counter() - start}


def load_fields(directory) -> tuple[dict, dict]:
    """The fields :func:`write_fields` saved in ``directory``: ``(mesh, meta)``; FileNotFoundError if missing,
    ValueError naming the file if damaged.

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


def show_fields(case: ContactCase, scene_dir, fidelity: str, solve: bool = False, *, cost_s: float = 0.0) -> list[Path]:
    """The ``show`` hook of an FE contact scene: ``pressure.png`` and ``stress.png`` (figures.fe_contact) drawn
    from the fields saved in ``scene_dir`` (named after the scene).  None saved: FileNotFoundError, or with
    ``solve`` the checked level at ``fidelity`` solved first (about ``cost_s`` [s]), saying so on stderr."""
    from ballbench.validation.figures import fe_contact as figures
    levels = _fe(case).levels
    if fidelity not in levels:
        raise ValueError(f"fidelity must be one of {('quick', 'default', 'fine')}, got {fidelity!r}")
    directory = Path(scene_dir)
    scene_name = directory.name
    try:
        data, meta = load_fields(directory)
    except FileNotFoundError:
        if not solve:
            raise
        hint = ""
        results = directory.parent / "results.json"
        if fidelity != "quick" and results.is_file():
            try:
                if json.loads(results.read_text()).get("fidelity") == "quick":
                    hint = (f"; the report there is a --quick run, which saves no fields ('ballbench show "
                            f"{scene_name} --quick' draws the quick level)")
            except (OSError, ValueError):
                pass
        print(f"ballbench: no saved fields in {directory}; solving the {fidelity} level of {scene_name} first "
              f"(about {cost_s:.0f} s){hint}", file=sys.stderr, flush=True)
        compute_fields(case, scene_name, fidelity, directory, show_progress=sys.stderr.isatty())
        data, meta = load_fields(directory)
    if not math.isfinite(meta["hertz"]["a_m"]):
        raise ValueError(f"{directory / 'fields.json'}: no Hertz reference")
    return [save(figures.pressure_figure(data, meta), directory / "pressure.png", dpi=100, tight=True),
            save(figures.stress_figure(data, meta), directory / "stress.png", dpi=100)] + render3d.render(directory)
