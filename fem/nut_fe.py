"""The FE rung of the whole nut: an elastic nut body (scikit-fem, P2 tetrahedra on a gmsh mesh) on its balls, against
the nut as a bar (docs/nut.md, "Elastic nut").

The body (meshes.parts.nut_body: a tube from the bar's bore ``R_P + R_B`` to the nut's outer radius, its end face at
the nut's ``flange`` held by the table: at the loaded end or the far end, lowmodel.screw.load_distribution.FLANGES)
is linear-elastic, so it
enters the load distribution through one matrix: the compliance ``G`` (n x n) [m/N] of its balls, the move of each
ball's nut groove along its push under a unit axial ball load, as an axial shift.  Each ball pushes the nut along
its loaded contact's normal ``e`` (the nut flank towards the loaded end at the nominal contact angle ``beta_0``,
in the ball's frame of lowmodel.geometry.helix.cs3_frame: ``e = cos beta_0 x3 - sin beta_0 z3``); the force
``q e / |e_z|`` carries the axial load ``q``, and the groove's move is read along the same ``e / |e_z|`` (an approach
along the normal of ``delta`` is an axial shift ``delta / |e_z|`` of a two-point ball), so ``G`` is symmetric.  The
force enters the bore over a patch (the bore's vertices within ``patch_radius`` of the contact point projected
radially on it), the move is read from the same patch's rigid motion at the contact point (fem.patches), and the
patch's own flattening, which the ball's Hertz law already holds, is removed (Boussinesq's mean disk displacement
along ``e / |e_z|``, capped by the patches' stiffest mode; fem.patches):

    G = P K^-1 P^T  -  local,

``P`` the patches' operator (n x dofs), ``K`` the body's stiffness with the flange clamped.  The screw stays a bar.
:func:`compare` solves the nut's load distribution with the bar nut and with ``G`` (lowmodel.screw.nut.distribution's
``nut_compliance``): per ball, the worst ball and the axial stiffness.

Left out: the groove is not cut (the bar's section, the patches on the bore), the nut's radial expansion under the
preload (ring expansion), the screw's own elasticity beyond the bar, the return channels.
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
from ballbench.lowmodel.geometry import helix
from ballbench.lowmodel.screw import load_distribution as ld
from ballbench.lowmodel.screw import nut as screw_nut
from ballbench.meshes.parts.nut_body import nut_body

__all__ = ["NutShape", "nut_shape", "contact_points", "default_patch_radius", "patch_operator", "NutCompliance",
           "nut_compliance", "Comparison", "compare", "write_vtu", "MIN_PATCH_NODES"]


@dataclass(frozen=True)
class NutShape:
    """The nut body's tube (meshes.parts.nut_body) [m]: ``start`` the flange's z (the loaded end), ``end``."""

    inner_radius: float
    outer_radius: float
    start: float
    end: float


def nut_shape(nut: screw_nut.Nut) -> NutShape:
    """The tube of ``nut``: bore and outer radius the bar's (lowmodel.screw.load_distribution.bar_sections), from a
    ball diameter before the first ball to a ball diameter beyond the last (the flange at the start)."""
    module = nut.module
    z = module.lead * screw_nut.positions(nut) / (2.0 * math.pi)
    outer = (ld.NUT_OUTER_RADIUS_FACTOR * module.pitch_radius if nut.nut_outer_radius is None
             else nut.nut_outer_radius)
    diameter = 2.0 * module.ball_radius
    return NutShape(module.pitch_radius + module.ball_radius, outer, float(z.min()) - diameter,
                    float(z.max()) + diameter)


def contact_points(nut: screw_nut.Nut) -> tuple[np.ndarray, np.ndarray]:
    """``(points, normals)`` (n, 3): each ball's loaded nut contact point [m] and its unit normal ``e`` from the
    ball into the nut, towards the loaded end (module docstring)."""
    module = nut.module
    psi = screw_nut.positions(nut)
    frame = helix.cs3_frame(psi, module.lead_angle)  # (n, 3, 3), columns x3, y3, z3
    beta = module.nominal_angle
    normals = math.cos(beta) * frame[:, :, 0] - math.sin(beta) * frame[:, :, 2]
    centres = module.pitch_radius * frame[:, :, 0]
    centres[:, 2] = module.lead * psi / (2.0 * math.pi)
    return centres + module.ball_radius * normals, normals


def default_patch_radius(nut: screw_nut.Nut) -> float:
    """m, the patches' radius: the ball radius, at most half the distance of two balls' contact points."""
    points, _ = contact_points(nut)
    gaps = np.linalg.norm(points[:, None, :] - points[None, :, :], axis=2)
    np.fill_diagonal(gaps, math.inf)
    return float(min(nut.module.ball_radius, 0.5 * gaps.min()))


def patch_operator(nut: screw_nut.Nut, pair, basis, shape: NutShape, radius: float):
    """``(P, vertices per patch, normals)``: the balls' patches operator (n x dofs; ``pair``, ``basis`` the nut's
    mesh and P2 basis, ``radius`` [m] the patch's): each ball's contact point projected radially on the bore, the
    bore's vertices within ``radius`` of it, read at the contact point along ``e / |e_z|`` (module docstring)."""
    points, normals = contact_points(nut)
    bore = pair.nodes("bore")
    patches = []
    for point in points:
        on_bore = np.array([*(shape.inner_radius * point[:2] / np.hypot(*point[:2])), point[2]])
        patches.append(bore[np.linalg.norm(pair.points[bore] - on_bore, axis=1) <= radius])
    directions = [(e / abs(e[2]))[None, :] for e in normals]
    operator = rigid_patches.patch_operator(basis, pair.points, patches, points, directions)
    return operator, np.array([p.size for p in patches]), normals


NutCompliance = rigid_patches.PatchCompliance  # the balls' compliance (n, n), ``shape`` the NutShape


def nut_compliance(nut: screw_nut.Nut, *, h_max: float, h_bore: float | None = None,
                   patch_radius: float | None = None, youngs_modulus: float | None = None,
                   poisson_ratio: float | None = None, cache: bool = True) -> NutCompliance:
    """The balls' compliance of the nut body (module docstring) on a mesh of size ``h_max`` [m], ``h_bore`` on the
    bore (default a third of the patch radius); ``patch_radius`` [m] (default :func:`default_patch_radius`); the
    material (default the screw's)."""
    start = time.perf_counter()
    module = nut.module
    if nut.arrangement != "single":
        raise ValueError("nut_compliance: a single nut's (arrangement 'single')")
    shape = nut_shape(nut)
    youngs_modulus = module.youngs_modulus if youngs_modulus is None else youngs_modulus
    poisson_ratio = module.poisson_ratio if poisson_ratio is None else poisson_ratio
    radius = default_patch_radius(nut) if patch_radius is None else checks.positive("patch_radius", patch_radius, "m")
    path = nut_body(inner_radius=shape.inner_radius, outer_radius=shape.outer_radius, start=shape.start,
                    end=shape.end, h_max=checks.positive("h_max", h_max, "m"),
                    h_bore=radius / 3.0 if h_bore is None else h_bore,
                    held="start" if nut.flange == "loaded end" else "end", cache=cache)
    pair = load_pair(path, {"nut": 0})
    stiffness, basis = stiffness_fast(pair, (youngs_modulus, poisson_ratio), order=2)
    operator, counts, normals = patch_operator(nut, pair, basis, shape, radius)
    matrix, vertex = rigid_patches.condense(pair, stiffness, basis, "flange", operator)  # vertex (v, 3, n)
    # Boussinesq's disk along e / |e_z| (alike normal to the bore and along it, as fem.carriage_fe)
    boussinesq = rigid_patches.boussinesq_disk(radius, youngs_modulus, poisson_ratio) / float(
        np.min(np.abs(normals[:, 2]))) ** 2
    matrix, local = rigid_patches.without_local(matrix, boussinesq, f"h_max {h_max!r} m")
    return NutCompliance(matrix, local, boussinesq, counts, int(basis.N),
                         float(h_max), str(path), time.perf_counter() - start, pair.points, pair.tets, vertex, shape)


@dataclass(frozen=True)
class Comparison:
    """The elastic nut against the bar at an axial load (:func:`compare`): the two ``NutLoads`` (``bar``,
    ``elastic``), ``error`` (n,) the bar's ball loads less the elastic's over the largest elastic ball load, the
    ``worst`` ball, the axial ``stiffness`` [N/m] of each (load over the shift at the flange, from the preloaded
    state) and its relative change ``stiffness_change`` (bar over elastic less 1), the ``compliance``."""

    bar: screw_nut.NutLoads
    elastic: screw_nut.NutLoads
    error: np.ndarray
    worst: int
    stiffness_bar: float
    stiffness_elastic: float
    compliance: NutCompliance

    @property
    def stiffness_change(self) -> float:
        """The bar's axial stiffness over the elastic nut's, less 1."""
        return self.stiffness_bar / self.stiffness_elastic - 1.0


def compare(nut: screw_nut.Nut, axial_load: float, *, h_max: float, law: str = "frictionless",
            **options) -> Comparison:
    """The case's nut under ``axial_load`` [N] as a bar and elastic (:func:`nut_compliance` on ``h_max``,
    ``options``), the balls' law ``law`` (lowmodel.screw.nut.ball_table).  Both shifts are taken at the FE body's
    flange (the bar's nut and screw from there)."""
    axial_load = checks.positive("axial_load", axial_load, "N")
    compliance = nut_compliance(nut, h_max=h_max, **options)
    table = screw_nut.ball_table(nut.module, 3.0 * axial_load / nut.balls, law)
    bar = screw_nut.distribution(nut, axial_load, table)
    elastic = screw_nut.distribution(nut, axial_load, table, nut_compliance=compliance.matrix)
    error = (bar.ball_loads - elastic.ball_loads) / float(elastic.ball_loads.max())
    worst = int(np.argmax(np.abs(error)))
    # from the FE tube's ends: the screw from z0 < 0, the bar nut to the tube's flange (the elastic's G holds it)
    module, shape = nut.module, compliance.shape
    screw_part = axial_load * -shape.start / (module.youngs_modulus * nut.sections.screw_area)
    beyond = -shape.start if nut.flange == "loaded end" else shape.end - float(bar.z.max())
    nut_part = axial_load * beyond / (module.youngs_modulus * nut.sections.nut_area)
    shift_bar = bar.shift + screw_part + nut_part
    shift_elastic = elastic.shift + screw_part
    stiffness_bar, stiffness_elastic = axial_load / shift_bar, axial_load / shift_elastic
    return Comparison(bar, elastic, error, worst, stiffness_bar, stiffness_elastic, compliance)


def write_vtu(path, comparison: Comparison) -> Path:
    """The elastic nut of ``comparison`` as a VTU (meshio; ParaView): its tetrahedra, the point data
    ``displacement_m`` (the flange held) and its magnitude."""
    import meshio

    compliance = comparison.compliance
    field = compliance.displacement(comparison.elastic.ball_loads)
    meshio.Mesh(compliance.points, [("tetra", compliance.tets)],
                point_data={"displacement_m": field,
                            "displacement_magnitude_m": np.linalg.norm(field, axis=1)}).write(str(path))
    return Path(path)
