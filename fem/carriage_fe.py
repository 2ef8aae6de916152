"""The FE rung of the whole carriage: an elastic carriage body (scikit-fem, P2 tetrahedra on a gmsh mesh) on its
balls as Hertz's springs, against the rigid carriage (docs/carriage.md, "Elastic carriage").

The body (meshes.parts.carriage_body: a block with the rail's slot, its mounting face bolted to the rigid table
that carries the external load) is linear-elastic, so it enters the carriage's equilibrium through one matrix: the
compliance ``G`` (2M x 2M) [m/N] of its M grooves (lowmodel.linear_bearing.carriage.groove_points), the move of each
groove's curvature centre beyond the rigid carriage's under the balls' forces on the grooves, the mounting face held.
Each contact's force enters the slot's wall over a patch (the wall's vertices within ``patch_radius`` of the
contact point projected on it), and the groove's move is read from the same patch: the rigid motion
``a + omega x r`` fitting its vertices' displacements by least squares, carried to the curvature centre (exact for a
rigid motion of the body); the load is its transpose (the patch's resultant and moment at the centre shared by the
same fit), so that ``G`` is symmetric:

    G = P K^-1 P^T  -  local,

``P`` the patches' operator (2M x dofs), ``K`` the body's stiffness with the mounting face clamped.  ``local``
removes what Hertz's law already holds, the patch's own flattening: Boussinesq's mean displacement of a uniform load
on a disk of radius ``rho`` on a half-space, ``16 (1 - nu^2) / (3 pi^2 rho E)`` per newton normal to the wall
(Johnson, Contact Mechanics, Sec 3.4), taken alike along the wall (convention: a rigid circular punch's tangential
compliance is ``(2 - nu) / (2 (1 - nu))``, 1.21 times its normal one, Johnson Sec 3.7; more than the FE's stiffest
mode would leave ``G`` indefinite), and capped by the smallest eigenvalue of ``P K^-1 P^T`` (the stiffest mode of
the patches, their flattening alone; on the example carriage it equals Boussinesq's within 0.5 %, docs/carriage.md).
The carriage is then solved with ``G`` (lowmodel.linear_bearing.carriage.solve's ``groove_compliance``).

``compare`` solves the case's load both ways: the balls' loads of the elastic body against the rigid carriage's,
per ball, the worst ball and the stiffness.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ballbench.fem import patches as rigid_patches
from ballbench.fem.elasticity import load_pair, stiffness_fast
from ballbench.fem.patches import MIN_PATCH_NODES
from ballbench.lowmodel import checks
from ballbench.lowmodel.linear_bearing import carriage
from ballbench.meshes.parts.carriage_body import carriage_body

__all__ = ["BodyShape", "body_shape", "default_patch_radius", "patch_operator", "GrooveCompliance",
           "groove_compliance", "groove_forces", "Comparison", "compare", "write_vtu", "MIN_PATCH_NODES"]



@dataclass(frozen=True)
class BodyShape:
    """The carriage body's block (meshes.parts.carriage_body) [m]."""

    half_width: float
    slot_half_width: float
    bottom: float
    slot_top: float
    top: float
    length: float


def body_shape(body: carriage.Carriage, *, wall: float | None = None, plate: float | None = None) -> BodyShape:
    """The block of ``body``: the slot's walls through the outermost carriage contact points, ``wall`` [m] the
    flanges' thickness beyond them and ``plate`` [m] the top plate above the slot (both default two ball
    diameters), the slot's top a ball radius above the highest contact point, the flanges' bottom a ball diameter
    below the lowest, the length the grooves' (``balls_per_row pitch``)."""
    points, _, _ = carriage.groove_points(body)
    diameter = 2.0 * body.guide.ball_radius
    wall = 2.0 * diameter if wall is None else checks.positive("wall", wall, "m")
    plate = 2.0 * diameter if plate is None else checks.positive("plate", plate, "m")
    slot = float(np.max(np.abs(points[:, 0])))
    slot_top = float(points[:, 1].max()) + 0.5 * diameter
    return BodyShape(slot + wall, slot, float(points[:, 1].min()) - diameter, slot_top, slot_top + plate,
                     body.balls_per_row * body.pitch)


GrooveCompliance = rigid_patches.PatchCompliance  # the grooves' compliance (2M, 2M): x, y of each groove


def patch_operator(pair, basis, points, centres, shape: BodyShape, radius: float):
    """The patches' operator P (2M x dofs, sparse; ``pair``, ``basis`` the body's mesh and P2 basis, ``points``,
    ``centres`` (M, 3) the contact points and curvature centres, ``shape`` the body, ``radius`` [m] the patch's)
    and the vertices per patch (module docstring; fem.patches)."""
    wall = pair.nodes("slot")
    xyz = pair.points[wall]
    patches = []
    for i, point in enumerate(points):
        side = math.copysign(1.0, point[0])
        near = (np.abs(xyz[:, 0] - side * shape.slot_half_width) < 1e-9 * shape.length) & (
            np.hypot(xyz[:, 1] - point[1], xyz[:, 2] - point[2]) <= radius)
        patches.append(wall[near])
        if patches[-1].size < MIN_PATCH_NODES:
            raise ValueError(f"h_max: contact {i}'s patch of radius {radius!r} m holds {patches[-1].size} vertices "
                             f"of the slot's wall (at least {MIN_PATCH_NODES}): refine the mesh")
    operator = rigid_patches.patch_operator(basis, pair.points, patches, centres, [np.eye(3)[:2]] * len(points))
    return operator, np.array([p.size for p in patches])


def default_patch_radius(body: carriage.Carriage) -> float:
    """m, the patches' radius: the ball radius, at most half the pitch and half the distance of a ball's closest
    carriage contacts (the patches do not overlap)."""
    points, _, _ = carriage.groove_points(body)
    spacing = [np.linalg.norm(points[i, :2] - points[j, :2]) for i in range(len(points)) for j in range(len(points))
               if i != j and points[i, 2] == points[j, 2]]
    return float(min(body.guide.ball_radius, 0.5 * body.pitch, 0.5 * min(spacing, default=math.inf)))


def groove_compliance(body: carriage.Carriage, *, h_max: float, h_wall: float | None = None,
                      patch_radius: float | None = None,
                      shape: BodyShape | None = None, youngs_modulus: float | None = None,
                      poisson_ratio: float | None = None, cache: bool = True) -> GrooveCompliance:
    """The compliance of the carriage body's grooves (module docstring) on a mesh of size ``h_max`` [m], ``h_wall``
    on the slot's walls (default a third of the patch radius); the patch ``patch_radius`` [m] (default
    :func:`default_patch_radius`); the body ``shape``
    (default :func:`body_shape`); its material (default the guide's)."""
    start = time.perf_counter()
    points, centres, _ = carriage.groove_points(body)
    shape = body_shape(body) if shape is None else shape
    material = body.guide.material
    youngs_modulus = material.youngs_modulus if youngs_modulus is None else youngs_modulus
    poisson_ratio = material.poisson_ratio if poisson_ratio is None else poisson_ratio
    radius = default_patch_radius(body) if patch_radius is None else checks.positive("patch_radius", patch_radius, "m")
    path = carriage_body(half_width=shape.half_width, slot_half_width=shape.slot_half_width, bottom=shape.bottom,
                         slot_top=shape.slot_top, top=shape.top, length=shape.length,
                         h_max=checks.positive("h_max", h_max, "m"),
                         h_wall=radius / 3.0 if h_wall is None else h_wall, cache=cache)
    pair = load_pair(path, {"carriage": 0})
    stiffness, basis = stiffness_fast(pair, (youngs_modulus, poisson_ratio), order=2)
    operator, counts = patch_operator(pair, basis, points, centres, shape, radius)
    matrix, vertex = rigid_patches.condense(pair, stiffness, basis, "mount", operator)  # vertex (n, 3, 2M)
    boussinesq = rigid_patches.boussinesq_disk(radius, youngs_modulus, poisson_ratio)
    matrix, local = rigid_patches.without_local(matrix, boussinesq, f"h_max {h_max!r} m")
    return GrooveCompliance(matrix, local, boussinesq, counts, int(basis.N), float(h_max), str(path),
                            time.perf_counter() - start, pair.points, pair.tets, vertex)


def groove_forces(body: carriage.Carriage, state: carriage.CarriageState) -> np.ndarray:
    """(2M,) N, the balls' forces on the carriage's grooves at ``state`` (x, y of each contact of
    lowmodel.linear_bearing.carriage.groove_points, in its order: rows, balls, contacts on the carriage)."""
    forces = [state.normal_force[r, k, c] * state.line[r, k, c] for r, row in enumerate(body.rows)
              for k in range(body.balls_per_row) for c, top in enumerate(row.carriage) if top]
    return np.asarray(forces, dtype=float).reshape(-1)


def write_vtu(path, comparison) -> Path:
    """The elastic carriage body of ``comparison`` (:func:`compare`) as a VTU (meshio; ParaView): its tetrahedra,
    the point data ``displacement_m`` (beyond the rigid motion, the mounting face held) and its magnitude."""
    import meshio

    compliance = comparison.compliance
    field = compliance.displacement(comparison.groove_forces)
    meshio.Mesh(compliance.points, [("tetra", compliance.tets)],
                point_data={"displacement_m": field,
                            "displacement_magnitude_m": np.linalg.norm(field, axis=1)}).write(str(path))
    return Path(path)


@dataclass(frozen=True)
class Comparison:
    """The elastic carriage against the rigid one at a load (:func:`compare`): the two ``CarriageState`` s, the
    largest ball load of each ball ``rigid_load`` / ``elastic_load`` (rows, balls) [N], ``error`` (rows, balls) the
    rigid's against the elastic's over the largest elastic ball load, the ``worst`` (row, ball) and the relative
    change of the stiffness's diagonal ``stiffness_change`` (5,) (rigid over elastic less 1), the
    ``compliance`` and the elastic state's ``groove_forces`` (:func:`groove_forces`)."""

    rigid: carriage.CarriageState
    elastic: carriage.CarriageState
    rigid_load: np.ndarray
    elastic_load: np.ndarray
    error: np.ndarray
    worst: tuple
    stiffness_change: np.ndarray
    compliance: GrooveCompliance
    groove_forces: np.ndarray | None = None


def compare(body: carriage.Carriage, load: carriage.Load, *, h_max: float, **options) -> Comparison:
    """The case's carriage under ``load`` rigid and elastic (:func:`groove_compliance` on ``h_max``, ``options``)."""
    compliance = groove_compliance(body, h_max=h_max, **options)
    rigid = carriage.solve(body, load)
    elastic = carriage.solve(body, load, groove_compliance=compliance.matrix)
    rigid_load = rigid.normal_force.max(axis=2)
    elastic_load = elastic.normal_force.max(axis=2)
    error = (rigid_load - elastic_load) / float(elastic_load.max())
    worst = tuple(int(i) for i in np.unravel_index(int(np.argmax(np.abs(error))), error.shape))
    change = np.diag(rigid.stiffness) / np.diag(elastic.stiffness) - 1.0
    return Comparison(rigid, elastic, rigid_load, elastic_load, error, worst, change, compliance,
                      groove_forces(body, elastic))
