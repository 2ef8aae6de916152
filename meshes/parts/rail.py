"""Straight gothic-arch rail segment: the OCC body of a bottom rail, its faces by role,
and the ``rail_segment`` builder (the rails of :mod:`meshes.assemblies.fourpoint_module`).

Frame of lin2017 Fig 2 / lin2019 Fig 2: the ball centre at the origin, ``z``
along the rail (the rolling direction), ``x``-``y`` the cross-section, the
bottom rail below (``y < 0``).  The groove cross-section (flank arcs, contact
points, bottom, edges, contact angle deviations) is the geometry core's
:class:`lowmodel.geometry.groove.GothicArch`; the rail is the box below the land
minus the lens ``disc(C_left) & disc(C_right)``.

All lengths in metres, angles in radians.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.groove import GothicArch, gothic_arch
from ballbench.meshes.gmsh_tools import cached_msh, face_point, physical, session, write_msh
from ballbench.meshes.refinement import check_refinement, size_at_points

__all__ = ["rail_segment", "add_bottom_rail", "classify_rail_faces"]

MESH_FORMAT_VERSION = "rail-1"


# --------------------------------------------------------------------------
# gmsh construction (shared with meshes.assemblies.fourpoint_module)
# --------------------------------------------------------------------------
def add_bottom_rail(occ, arch: GothicArch, width: float, depth: float, length: float,
                    z_start: float) -> int:
    """OCC volume of a bottom rail: the box ``|x| <= width/2``, ``land - depth <= y <= land``,
    ``z_start <= z <= z_start + length`` minus the gothic-arch lens.  Returns its tag."""
    r_g = arch.groove_radius
    box = occ.addBox(-width / 2, arch.land_height - depth, z_start, width, depth, length)
    c_l, c_r = arch.arc_centre("left"), arch.arc_centre("right")
    pad = 0.1 * length
    cyl_l = occ.addCylinder(c_l[0], c_l[1], z_start - pad, 0.0, 0.0, length + 2 * pad, r_g)
    cyl_r = occ.addCylinder(c_r[0], c_r[1], z_start - pad, 0.0, 0.0, length + 2 * pad, r_g)
    lens, _ = occ.intersect([(3, cyl_l)], [(3, cyl_r)])
    rail, _ = occ.cut([(3, box)], lens)
    (_, tag), = rail
    return tag


def classify_rail_faces(gmsh, volume: int, arch: GothicArch, depth: float) -> dict[str, list[int]]:
    """Faces of a bottom rail (before any rotation) by role: 'left', 'right' (groove
    flanks), 'land', 'support' (bottom face), 'other'."""
    roles: dict[str, list[int]] = {"left": [], "right": [], "land": [], "support": [], "other": []}
    r_g = arch.groove_radius
    tol = 1e-6 * arch.ball_radius
    for _, tag in gmsh.model.getBoundary([(3, volume)], oriented=False):
        x, y, _ = face_point(gmsh, tag)
        kind = gmsh.model.getType(2, tag)
        if kind == "Cylinder":
            d_l = abs(np.hypot(x - arch.arc_centre("left")[0], y - arch.arc_centre("left")[1]) - r_g)
            d_r = abs(np.hypot(x - arch.arc_centre("right")[0], y - arch.arc_centre("right")[1]) - r_g)
            roles["left" if d_l < d_r else "right"].append(tag)
        elif abs(y - arch.land_height) < tol:
            roles["land"].append(tag)
        elif abs(y - (arch.land_height - depth)) < tol:
            roles["support"].append(tag)
        else:
            roles["other"].append(tag)
    return roles


def rail_segment(ball_radius: float, conformity: float, contact_angle: float, deviation_left: float = 0.0,
                 deviation_right: float = 0.0, *, land_height: float | None = None, width: float | None = None,
                 depth: float | None = None, length: float | None = None, h_contact: float | None = None,
                 growth: float = 1.3, h_max: float | None = None, fine_radius: float | None = None,
                 cache: bool = True) -> Path:
    """A straight gothic-arch rail segment (bottom rail) as a cached gmsh 4.1 ``.msh`` [m].

    Frame of the module docstring (ball centre at the origin, rail along z from
    ``-length/2`` to ``length/2``).  Defaults: ``width = 2.6 R_B``, ``depth``
    (land to bottom face) ``= 1.6 R_B``, ``length = 2 R_B``.  With ``h_contact``
    [m] the mesh is refined around the two contact points of a ball at the
    origin (:func:`meshes.refinement.size_at_points`); otherwise uniform ``h_max``
    (default ``R_B / 3``).

    Physical groups: volume ``rail``; surfaces ``groove_left``, ``groove_right``
    (the flanks), ``land``, ``support`` (bottom face), ``rail_free`` (sides, ends).
    """
    arch = gothic_arch(ball_radius, conformity, contact_angle, deviation_left, deviation_right, land_height)
    radius = arch.ball_radius
    width = 2.6 * radius if width is None else checks.positive("width", width, "m")
    depth = 1.6 * radius if depth is None else checks.positive("depth", depth, "m")
    length = 2.0 * radius if length is None else checks.positive("length", length, "m")
    bottom_y = arch.bottom[1]
    if arch.land_height - depth >= bottom_y:
        raise ValueError(f"depth must exceed the groove depth {arch.land_height - bottom_y!r} m, got {depth!r}")
    for side in ("left", "right"):
        if abs(arch.edge(side)[0]) >= width / 2:
            raise ValueError(f"width must exceed the groove width {2 * abs(arch.edge(side)[0])!r} m, got {width!r}")
    refine = h_contact is not None
    h_contact, growth, h_max, fine_radius = check_refinement(radius, radius / 4 if h_contact is None else h_contact,
                                                             growth, h_max, fine_radius)
    params = dict(builder="rail_segment", arch=[radius, arch.conformity, arch.contact_angle_left,
                  arch.contact_angle_right, arch.land_height], width=width, depth=depth, length=length,
                  refine=refine, h_contact=h_contact, growth=growth, h_max=h_max, fine_radius=fine_radius)
    path, build = cached_msh("rail", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path
    with session("rail") as gmsh:
        volume = add_bottom_rail(gmsh.model.occ, arch, width, depth, length, -length / 2)
        gmsh.model.occ.synchronize()
        roles = classify_rail_faces(gmsh, volume, arch, depth)
        physical(gmsh, 3, [volume], "rail")
        for role, name in (("left", "groove_left"), ("right", "groove_right"), ("land", "land"),
                           ("support", "support"), ("other", "rail_free")):
            physical(gmsh, 2, roles[role], name)
        contacts = [np.append(arch.contact_point(side), 0.0) for side in ("left", "right")]
        size_at_points(gmsh, contacts if refine else None, h_contact, growth, h_max, fine_radius)
        gmsh.model.mesh.generate(3)
        write_msh(gmsh, path)
    return path
