"""Straight gothic-arch groove: cross-section geometry and rail-segment meshes.

Frame of lin2017 Fig 2 / lin2019 Fig 2: the ball centre at the origin, ``z``
along the rail (the rolling direction), ``x``-``y`` the cross-section, the
bottom rail below (``y < 0``).  Contact angles are measured from ``-y``
(bottom rail) towards ``-x`` (left, BL) and ``+x`` (right, BR); the contact
point of BL is ``R_B (-sin b_BL, -cos b_BL, 0)`` (lin2017 eq 1).

Gothic arch: each flank is a circular arc of radius ``r_g = conformity * 2 R_B``
(lin2019 Sec 2.3.1, ``conf = R_G / 2 R_B``) whose centre lies ``r_g - R_B`` from
the ball centre, opposite its contact point, so that the ball touches the flank
at its contact angle with the normal through the ball centre.  A contact angle
deviation (lin2017 Sec 4 / lin2019 eq 17: ``b_i = b_0 + db_i``, "manufacturing
error and/or misalignment") turns that arc centre about the ball centre by
``db_i``: the ball keeps its centre and touches the flank at ``b_0 + db_i``.
The groove is the lens ``disc(C_left) & disc(C_right)`` below the land.

All lengths in metres, angles in radians.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ballbench.meshes import inputs as checks
from ballbench.meshes.gmsh_tools import cached_msh, face_point, physical, session, write_msh
from ballbench.meshes.refinement import check_refinement, refine_at_points, uniform_size

__all__ = ["GothicArch", "gothic_arch", "rail_segment", "add_bottom_rail", "classify_rail_faces"]

MESH_FORMAT_VERSION = "rail-1"
MAX_DEVIATION = math.radians(15.0)


@dataclass(frozen=True)
class GothicArch:
    """Cross-section of a bottom gothic-arch groove (build with :func:`gothic_arch`).

    ``contact_angle_left/right`` [rad] are the actual contact angles (nominal plus
    deviation) of the left (-x) and right (+x) flanks; ``land_height`` [m] is the
    ``y`` of the rail's top face (negative: below the ball centre).
    """

    ball_radius: float
    conformity: float
    contact_angle_left: float
    contact_angle_right: float
    land_height: float

    @property
    def groove_radius(self) -> float:
        return self.conformity * 2.0 * self.ball_radius

    def contact_point(self, side: str) -> np.ndarray:
        """(x, y) of the contact point of flank ``side`` ('left' or 'right') [m] (lin2017 eq 1)."""
        beta = self.contact_angle_left if side == "left" else self.contact_angle_right
        sign = -1.0 if side == "left" else 1.0
        return self.ball_radius * np.array([sign * math.sin(beta), -math.cos(beta)])

    def arc_centre(self, side: str) -> np.ndarray:
        """(x, y) of the centre of flank ``side``: ``-(r_g - R_B)`` along its contact direction [m]."""
        return -(self.groove_radius - self.ball_radius) * self.contact_point(side) / self.ball_radius

    @property
    def bottom(self) -> np.ndarray:
        """(x, y) of the groove bottom, the lower intersection of the two flank circles [m]."""
        c_l, c_r = self.arc_centre("left"), self.arc_centre("right")
        mid = (c_l + c_r) / 2
        half = np.linalg.norm(c_r - c_l) / 2
        along = (c_r - c_l) / max(2 * half, 1e-300)
        normal = np.array([along[1], -along[0]])
        if normal[1] > 0:
            normal = -normal
        return mid + math.sqrt(self.groove_radius**2 - half**2) * normal

    def edge(self, side: str) -> np.ndarray:
        """(x, y) where flank ``side`` meets the land [m]."""
        centre = self.arc_centre(side)
        sign = -1.0 if side == "left" else 1.0
        dy = self.land_height - centre[1]
        return np.array([centre[0] + sign * math.sqrt(self.groove_radius**2 - dy**2), self.land_height])


def gothic_arch(ball_radius: float, conformity: float, contact_angle: float, deviation_left: float = 0.0,
                deviation_right: float = 0.0, land_height: float | None = None) -> GothicArch:
    """Validated bottom gothic-arch groove.

    ``contact_angle`` [rad] the nominal angle ``b_0`` in (0, pi/2); deviations
    [rad] in [-15, 15] deg; ``land_height`` [m] (default ``-0.25 R_B``) in
    ``(-R_B, 0]``.  Raises ``ValueError`` if a contact point does not lie on the
    groove boundary between its bottom and the land (loss of four-point contact).
    """
    ball_radius = checks.positive("ball_radius", ball_radius, "m")
    conformity = checks.conformity("conformity", conformity)
    contact_angle = checks.contact_angle("contact_angle", contact_angle)
    for name, value in (("deviation_left", deviation_left), ("deviation_right", deviation_right)):
        value = checks.finite(name, value, "rad")
        if abs(value) > MAX_DEVIATION:
            raise ValueError(f"{name} must lie in [-15, 15] deg ([-0.2618, 0.2618] rad), got {value!r}")
    left = checks.contact_angle("contact_angle + deviation_left", contact_angle + float(deviation_left))
    right = checks.contact_angle("contact_angle + deviation_right", contact_angle + float(deviation_right))
    land = -0.25 * ball_radius if land_height is None else checks.finite("land_height", land_height, "m")
    if not -ball_radius < land <= 0.0:
        raise ValueError(f"land_height must lie in (-ball_radius, 0] = ({-ball_radius!r}, 0] m, got {land!r}")
    arch = GothicArch(ball_radius, conformity, left, right, land)
    # Each contact point lies inside the other flank's disc, hence on the groove boundary:
    # |P_right - C_left|^2 = r_g^2 - 2 R_B (r_g - R_B) (1 - cos(b_left + b_right)) < r_g^2.
    # Four-point contact is lost only where a contact point rises above the land.
    for side in ("left", "right"):
        point = arch.contact_point(side)
        if point[1] > land - 0.05 * ball_radius:
            raise ValueError(f"loss of four-point contact: the {side} contact point lies above the land "
                             f"(land_height must be above {point[1] + 0.05 * ball_radius!r} m)")
    return arch


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
    origin (:func:`meshes.refinement.refine_at_points`); otherwise uniform ``h_max``
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
        if refine:
            contacts = [np.append(arch.contact_point(side), 0.0) for side in ("left", "right")]
            refine_at_points(gmsh, contacts, h_contact, growth, h_max, fine_radius)
        else:
            uniform_size(gmsh, h_max)
        gmsh.model.mesh.generate(3)
        write_msh(gmsh, path)
    return path
