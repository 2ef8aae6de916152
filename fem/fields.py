"""Saved fields of solved FE four-point modules, for pictures (``ballbench show``) and ParaView.

:func:`write_module_fields` writes, for each solved one-ball module (:mod:`fem.fourpoint`: the linear bearing's
rails, :mod:`fem.screw_module`: the ball screw's segments) one ``fields_ball<k>.vtu`` and for all of them one
``fields.json``:

* the VTU holds the module's quadratic tetrahedra (VTK node order: 4 vertices, then the edges 0-1, 1-2, 0-2, 0-3,
  1-3, 2-3, scikit-fem's ``t2e`` order) in the module's own frame (as solved), with the point data
  ``displacement_m`` (the P2 displacement at all 10 nodes, :func:`fem.fourpoint.full_displacement`: the ball's
  rigid translation is left out, it carries no stress), ``contact_pressure_Pa`` (the mortar multipliers, the
  nodal pressure of the ball's candidate vertices, 0 elsewhere) and ``contact_index`` (the contact whose candidate
  zone holds the vertex, -1 elsewhere), and the cell data ``body`` (the module's volume index) and
  ``von_mises_stress_Pa`` (the element mean of the P2 stress, :func:`fem.fourpoint.von_mises`);
* the JSON (:func:`module_meta`) names the bodies and for each ball its placement in the two-ball assembly
  (:func:`placement`), its centre and radius, the load on the loaded body (the contact forces on it along its load
  face's rigid motion: the rails' ``(N_x, -N_y)``, the nut's axial share; the held directions' reaction apart) and,
  per contact, the undeformed
  contact point and frame ``(e1, e2, e3)`` (major axis, minor axis, normal into the ball), the FE normal force,
  loaded contact angle and approach, the FE moment ellipse (:func:`fem.postprocess.moment_ellipse`) and the
  Hertz ellipse at the FE force (:func:`lowmodel.contact.hertz.solve_load` on the contact's curvatures).

The Hertz ellipse is the one of the FE's own contact force, so a picture compares shapes, not forces (the scenes'
tables compare the forces).  Materials are one ``(E, nu)`` for all bodies, as the modules are solved.

:func:`write_surface_fields` writes fields on a regular surface grid (the BEM and EHL solutions of
``lowmodel.contact``) the same way: one VTU of quadrilaterals and one JSON.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ballbench.fem import fourpoint
from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import groove, helix

__all__ = ["FIELD_NAMES", "p2_nodes", "placement", "module_meta", "write_module_fields", "write_surface_fields"]

FIELD_NAMES = {
    "displacement": "displacement_m",        # point data: the P2 displacement at all 10 nodes [m]
    "pressure": "contact_pressure_Pa",       # point data: nodal contact pressure of the ball's candidate vertices [Pa]
    "contact": "contact_index",              # point data: index of the contact of a candidate vertex, -1 elsewhere
    "von_mises": "von_mises_stress_Pa",      # cell data: element mean of the P2 von Mises stress [Pa]
}


def p2_nodes(basis, u: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(points (n, 3) [m], tetra10 (m, 10), displacement (n, 3) [m])`` of the P2 DOF vector ``u`` on the
    scikit-fem vector basis ``basis``: the mesh vertices followed by the edge midpoints (straight edges), with
    the connectivity in VTK's quadratic-tetrahedron order."""
    mesh = basis.mesh
    n_vertices = mesh.p.shape[1]
    if basis.edge_dofs.size == 0:
        raise ValueError("p2_nodes needs a P2 basis (edge DOFs)")
    node_of = np.vstack([mesh.t, n_vertices + mesh.t2e])                      # (10, m)
    points = np.vstack([mesh.p.T, mesh.p[:, mesh.edges].mean(axis=1).T])
    displacement = np.vstack([u[basis.nodal_dofs].T, u[basis.edge_dofs].T])
    return points, node_of.T, displacement


def placement(geometry, ball: int, n_balls: int) -> dict:
    """Rigid placement ``{"rotation": (3, 3), "translation": (3,) [m]}`` of ball ``ball``'s module (solved about
    its own centre) in the assembly of ``n_balls`` touching balls, and the plane that separates it from its
    neighbours (``"keep"``: a list of ``(point, normal)`` half-spaces [m] that keep this module's bodies).

    Linear bearing (:class:`fem.fourpoint.ModuleGeometry`): ball ``k`` at ``z = (k - (n - 1) / 2) 2 R_B`` (ball 1
    behind, lin2019 Fig 7), the rails cut halfway between the balls.  Ball screw
    (:class:`fem.screw_module.ScrewModuleGeometry`): ball ``k`` at the azimuth ``k dphi`` with ``dphi`` the
    helix chord of two touching balls (:func:`lowmodel.geometry.helix.ball_centre_azimuths`; ball 1 behind,
    :mod:`lowmodel.screw.b2b`), i.e. the module turned by ``k dphi`` about the screw axis and moved by
    ``p k dphi`` along it (the screw symmetry of the helical grooves), cut by the planes normal to the helix
    halfway between the balls.
    """
    radius = float(geometry.ball_radius)
    if hasattr(geometry, "pitch_radius"):
        p = float(geometry.lead) / (2.0 * math.pi)
        step = float(helix.ball_centre_azimuths(geometry.pitch_radius, geometry.lead, 2.0 * radius)) \
            if n_balls > 1 else 0.0

        def centre(phi):
            return np.array([geometry.pitch_radius * math.cos(phi), geometry.pitch_radius * math.sin(phi), p * phi])

        def tangent(phi):
            t = np.array([-geometry.pitch_radius * math.sin(phi), geometry.pitch_radius * math.cos(phi), p])
            return t / np.linalg.norm(t)

        phi = ball * step
        rotation = np.asarray(helix.rotation_z(phi), dtype=float)
        translation = np.array([0.0, 0.0, p * phi])
        keep = []
        if ball > 0:
            keep.append((centre(phi - 0.5 * step), tangent(phi - 0.5 * step)))
        if ball < n_balls - 1:
            keep.append((centre(phi + 0.5 * step), -tangent(phi + 0.5 * step)))
    else:
        z = (ball - 0.5 * (n_balls - 1)) * 2.0 * radius
        rotation = np.eye(3)
        translation = np.array([0.0, 0.0, z])
        keep = []
        if ball > 0:
            keep.append((np.array([0.0, 0.0, z - radius]), np.array([0.0, 0.0, 1.0])))
        if ball < n_balls - 1:
            keep.append((np.array([0.0, 0.0, z + radius]), np.array([0.0, 0.0, -1.0])))
    return {"rotation": rotation.tolist(), "translation": translation.tolist(),
            "keep": [{"point_m": point.tolist(), "normal": normal.tolist()} for point, normal in keep]}


def _hertz_geometry(geometry, i: int, materials):
    """Hertz geometry of contact ``i``: the ball against the exact helical flank's curvatures (screw) or against
    the straight groove (rails)."""
    youngs_modulus, poisson_ratio = materials
    if hasattr(geometry, "flank"):
        frame = groove.contact_frame(geometry.flank(i))
        radius = geometry.ball_radius
        return hertz.from_curvatures((1 / radius, 1 / radius), (frame.curvature_major, frame.curvature_minor),
                                     youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)
    return hertz.ball_in_groove(geometry.ball_radius, geometry.conformity, youngs_modulus=youngs_modulus,
                                poisson_ratio=poisson_ratio)


def _body_of_surface(pair, name: str) -> int:
    """Body index of the tetrahedra that hold the named surface."""
    node = int(pair.surfaces[name][0, 0])
    cell = int(np.flatnonzero((pair.tets == node).any(axis=1))[0])
    return int(pair.body[cell])


def module_meta(model, result, materials) -> dict:
    """What a picture of one solved module needs besides its VTU (module docstring), JSON-ready."""
    geometry = model.geometry
    contacts = []
    load = np.zeros(3)
    for i, contact in enumerate(result.contacts):
        frame = np.asarray(geometry.frame(i), dtype=float)
        force = float(contact.normal_force)
        ref = hertz.solve_load(_hertz_geometry(geometry, i, materials), max(force, 0.0))
        fit = contact.ellipse
        if geometry.moving(i):
            load += force * frame[2]  # the loaded body's balance: its contacts push it along -e3
        contacts.append({
            "name": contact.name, "point_m": np.asarray(geometry.contact_point(i), dtype=float).tolist(),
            "frame": frame.tolist(), "normal_force_N": force, "contact_angle_rad": float(contact.contact_angle),
            "approach_m": float(contact.approach), "moving": bool(geometry.moving(i)),
            "peak_pressure_Pa": float(np.max(contact.nodal_pressure, initial=0.0)),
            "hertz": {"a_m": float(ref.a), "b_m": float(ref.b), "p0_Pa": float(ref.p0)},
            "fe_ellipse": None if fit is None else {"a_m": fit.a, "b_m": fit.b, "p0_Pa": fit.p0, "x0_m": fit.x0,
                                                    "y0_m": fit.y0},
        })
    # the applied load: the part of the contact forces' balance along the load face's rigid motion (the rails'
    # U_x, U_y; the nut's axial U); the rest is the reaction of the load face's other, held directions
    motions = np.array([geometry.load_face_motion(unit) for unit in np.eye(len(geometry.rigid_names))])
    motions = motions[np.linalg.norm(motions, axis=1) > 0.0]
    free = np.linalg.svd(motions)[2][:np.linalg.matrix_rank(motions)]  # orthonormal rows spanning the motion
    applied = free.T @ (free @ load)
    names = {index: name for name, index in geometry.volumes.items()}
    loaded = _body_of_surface(model.pair, geometry.load_face)
    clamped = [name for name in geometry.clamped if name != geometry.load_face]
    return {
        "ball_centre_m": np.asarray(geometry.ball_centre, dtype=float).tolist(),
        "ball_radius_m": float(geometry.ball_radius),
        "bodies": [names[k] for k in sorted(names)],
        "loaded_body": names[loaded],
        "load_N": applied.tolist(),
        "load_face_reaction_N": (load - applied).tolist(),
        "load_face": geometry.load_face,
        "load_point_m": model.pair.points[model.pair.nodes(geometry.load_face)].mean(axis=0).tolist(),
        "support_faces": clamped,
        "rigid": dict(zip(geometry.rigid_names, np.asarray(result.rigid, dtype=float).tolist())),
        "contacts": contacts,
    }


def write_module_fields(directory, models, results, *, materials, scene: str, fidelity: str, level: dict,
                        case: str = "") -> list[Path]:
    """Write ``fields_ball<k>.vtu`` for each solved module and ``fields.json`` into ``directory`` (module
    docstring); returns the paths (VTUs first).

    ``models``: one :class:`fem.fourpoint.ModuleModel` per ball, or one shared by all balls; ``results``: one
    :class:`fem.fourpoint.ModuleResult` per ball (ball 1 behind); ``materials`` ``(E [Pa], nu)``; ``scene``,
    ``fidelity``, ``level`` (the mesh level, e.g. ``{"h_contact_m": 3e-5, "growth": 1.35}``) and ``case`` (words)
    name the run in the pictures.  One sparse solve per ball for the full displacement (the condensation's
    factor) and one stress evaluation.
    """
    import meshio

    results = list(results)
    models = list(models) if isinstance(models, (list, tuple)) else [models] * len(results)
    if len(models) != len(results) or not results:
        raise ValueError(f"give one model (or one shared model) per result, got {len(models)} models for "
                         f"{len(results)} results")
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    youngs_modulus, poisson_ratio = (float(m) for m in materials)
    balls, paths = [], []
    for k, (model, result) in enumerate(zip(models, results)):
        u = fourpoint.full_displacement(model, result)
        points, cells, displacement = p2_nodes(model.basis, u)
        if not np.allclose(points[:len(model.pair.points)], model.pair.points):
            raise ValueError("write_module_fields needs the P2 model of the module's own vertices")
        pressure = np.zeros(len(points))
        contact_index = -np.ones(len(points))
        for i, (patch, contact) in enumerate(zip(model.patches, result.contacts)):
            pressure[patch.candidates] = contact.nodal_pressure
            contact_index[patch.candidates] = i
        von_mises = fourpoint.von_mises(model, u, (youngs_modulus, poisson_ratio))
        mesh = meshio.Mesh(points, [("tetra10", cells)],
                           point_data={FIELD_NAMES["displacement"]: displacement,
                                       FIELD_NAMES["pressure"]: pressure, FIELD_NAMES["contact"]: contact_index},
                           cell_data={"body": [np.asarray(model.pair.body)],
                                      FIELD_NAMES["von_mises"]: [von_mises]})
        path = directory / f"fields_ball{k + 1}.vtu"
        mesh.write(path)
        paths.append(path)
        ball = module_meta(model, result, (youngs_modulus, poisson_ratio))
        ball.update(file=path.name, placement=placement(model.geometry, k, len(results)))
        balls.append(ball)
    kind = "ball screw" if hasattr(models[0].geometry, "pitch_radius") else "linear bearing"
    meta = {
        "kind": "module", "module": kind, "scene": scene, "fidelity": fidelity, "case": case, "level": level,
        "youngs_modulus_Pa": youngs_modulus, "poisson_ratio": poisson_ratio, "fields": FIELD_NAMES,
        "cells": "tetra10 (P2 at vertices and edge midpoints), each ball's module in its own frame (as solved)",
        "frame": ("linear bearing: lin2017 Fig 2, ball centre at the origin, z along the rails, y up; ball screw: "
                  "the screw frame, z the screw axis, the ball centre at azimuth 0"),
        "balls": balls,
    }
    meta_path = directory / "fields.json"
    meta_path.write_text(json.dumps(meta, indent=2))
    return paths + [meta_path]


def write_surface_fields(directory, name: str, x, y, fields: dict, meta: dict) -> list[Path]:
    """Write fields on a regular surface grid (a BEM or EHL solution) as ``surface_<name>.vtu`` (the cell centres
    ``x`` (nx,) and ``y`` (ny,) [m] as points of quadrilaterals in the plane z = 0, each field (nx, ny) as point
    data under its name, which carries its unit, e.g. ``pressure_Pa``, ``film_m``) and ``surface_<name>.json``
    (``meta`` plus the kind, the file and the field names); returns the two paths."""
    import meshio

    x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
    if x.ndim != 1 or y.ndim != 1 or x.size < 2 or y.size < 2:
        raise ValueError(f"x and y must be 1-D grids of at least 2 points, got shapes {x.shape} and {y.shape}")
    data = {}
    for key, values in fields.items():
        values = np.asarray(values, dtype=float)
        if values.shape != (x.size, y.size):
            raise ValueError(f"field {key!r} has shape {values.shape}, the grid is {(x.size, y.size)}")
        data[key] = values.ravel()  # point (i, j) -> i ny + j
    X, Y = np.meshgrid(x, y, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
    index = np.arange(X.size).reshape(X.shape)
    quads = np.column_stack([index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(),
                             index[:-1, 1:].ravel()])
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    vtu = directory / f"surface_{name}.vtu"
    meshio.Mesh(points, [("quad", quads)], point_data=data).write(vtu)
    meta_path = directory / f"surface_{name}.json"
    meta_path.write_text(json.dumps({**meta, "kind": "surface", "file": vtu.name, "fields": list(fields)}, indent=2))
    return [vtu, meta_path]
