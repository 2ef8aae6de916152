"""Screw-shaft or nut segment with its helical gothic-arch groove (lin2019 Sec 3.1, Fig 13).

The body is an annular wedge about the screw axis minus the gothic-arch lens (the
region inside both flank circles) swept along the ball-centre helix; both flanks
are exact helical arc surfaces (:mod:`lowmodel.geometry.groove`) after :func:`snap_segment`.
Used alone (:func:`screw_groove_segment`) and by :mod:`meshes.assemblies.ball_screw_module`.

Screw frame: axis z, ball-centre helix ``H(phi) = (R_P cos phi, R_P sin phi, p phi)``,
the groove's nominal contacts at phi = 0.  All lengths in metres, angles in radians.
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.groove import MAX_DEVIATION, HelicalGroove, helical_groove, surface_residual
from ballbench.meshes.gmsh_tools import cached_msh, face_point, physical, session, write_msh
from ballbench.meshes.refinement import check_refinement, size_at_points
from ballbench.meshes.snapping import snap_to_bottom, snap_to_groove

__all__ = ["BODY_DEPTH", "MIN_CORE", "screw_groove_segment", "segment_grooves", "segment_dimensions",
           "add_groove_segment", "snap_segment", "flank_intersections"]

MESH_FORMAT_VERSION = "helical-1"
# Default depth of the bodies [R_B from the pitch radius]: screw core at R_P - BODY_DEPTH R_B, nut outside at
# R_P + BODY_DEPTH R_B, i.e. 5 R_B beyond the lands: the depth of the validated FE ball-screw module (measured
# against the shallower bodies in docs/fe_b2b.md, "Depth of the FE bodies").
BODY_DEPTH = 5.25
# A screw thinner than that keeps a core of MIN_CORE R_P (a clamp on the axis itself is singular; Table 4's deep
# core is 0.116 R_P).
MIN_CORE = 0.1


def segment_grooves(ball_radius, conformity, pitch_radius, lead, contact_angle, body, deviations,
                    profile_plane) -> tuple[HelicalGroove, HelicalGroove]:
    """The validated (left, right) flanks of a groove with contact angle deviations (left, right) [rad]
    in [-15, 15] deg (lin2019 Fig 17, eq 17 ``b = b_0 + db``)."""
    try:
        deviations = [float(d) for d in deviations]
    except (TypeError, ValueError):
        raise ValueError(f"deviations must be two angles (left, right) [rad], got {deviations!r}") from None
    if len(deviations) != 2 or not all(math.isfinite(d) and abs(d) <= MAX_DEVIATION for d in deviations):
        raise ValueError(f"deviations must be two angles (left, right) in [-15, 15] deg [rad], got {deviations!r}")
    contact_angle = checks.contact_angle("contact_angle", contact_angle)
    return tuple(helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle + deviation, body,
                                flank, profile_plane) for flank, deviation in zip(("left", "right"), deviations))


def flank_intersections(left: HelicalGroove, right: HelicalGroove) -> tuple[np.ndarray, np.ndarray]:
    """(u, w) [m] of the two intersections of the flank circles: (groove bottom, top of the lens)."""
    c_l, c_r = left.arc_centre, right.arc_centre
    r_g = left.groove_radius
    mid = (c_l + c_r) / 2
    half = float(np.linalg.norm(c_r - c_l)) / 2
    along = (c_r - c_l) / (2 * half)
    perp = np.array([along[1], -along[0]])
    points = [mid + s * math.sqrt(r_g**2 - half**2) * perp for s in (-1.0, 1.0)]
    points.sort(key=lambda uw: -left.sign_u * uw[0])  # the bottom lies deepest in the body
    return points[0], points[1]


def segment_dimensions(grooves, land_radius, back_radius, half_angle, axial_half_width,
                       prefix: str = "") -> tuple[float, float, float, float]:
    """Validated (land radius [m], back radius [m], half angle [rad], axial half width [m])
    of a groove segment; ``None`` gives the defaults of :func:`screw_groove_segment`."""
    left = grooves[0]
    radius, r_p, p = left.ball_radius, left.pitch_radius, left.lead_per_radian
    sign = left.sign_u
    land = r_p + sign * 0.25 * radius if land_radius is None else \
        checks.positive(f"{prefix}land_radius", land_radius, "m")
    if back_radius is None:
        back = r_p + sign * BODY_DEPTH * radius
        back = max(back, MIN_CORE * r_p) if sign < 0 else back
    else:
        back = checks.positive(f"{prefix}back_radius", back_radius, "m")
    contact_u = sign * radius * min(math.cos(g.contact_angle) for g in grooves)
    if not sign * (land - r_p) < sign * contact_u - 0.05 * radius:
        raise ValueError(f"{prefix}land_radius must leave the contact points (at radius {r_p + contact_u!r} m) "
                         f"in the groove (loss of four-point contact), got {land!r}")
    bottom_u = flank_intersections(*grooves)[0][0]
    if not sign * (back - r_p) > sign * bottom_u + 0.05 * radius:
        raise ValueError(f"{prefix}back_radius must lie beyond the groove bottom (radius {r_p + bottom_u!r} m), "
                         f"got {back!r}")
    half_angle = 2.0 * radius / r_p if half_angle is None else checks.positive("half_angle", half_angle, "rad")
    if half_angle > math.pi / 2:
        raise ValueError(f"half_angle must lie in (0, pi/2] rad, got {half_angle!r}")
    limit = p * math.pi if p > 0 else math.inf  # lead / 2
    width = min(p * half_angle + 1.5 * radius, limit) if axial_half_width is None else \
        checks.positive("axial_half_width", axial_half_width, "m")
    if width > limit:
        raise ValueError(f"axial_half_width must lie in (0, lead/2] = (0, {limit!r}] m, got {width!r}")
    return land, back, half_angle, width


def _lens_loop(occ, grooves: tuple[HelicalGroove, HelicalGroove], phi: float) -> int:
    """Curve loop of the gothic-arch lens (inside both flank circles) in the profile plane at ``phi``."""
    left, right = grooves
    apexes = flank_intersections(left, right)
    tags = [occ.addPoint(*left.to_world(a[0], a[1], phi)) for a in apexes]
    centres = [occ.addPoint(*left.to_world(c[0], c[1], phi)) for c in (left.arc_centre, right.arc_centre)]
    # each flank circle bounds the lens on the side away from its centre; both arcs are
    # shorter than pi (the centres lie inside the lens), so OCC's arc is the right one
    arcs = [occ.addCircleArc(tags[0], centres[1], tags[1]), occ.addCircleArc(tags[1], centres[0], tags[0])]
    loop = occ.addCurveLoop(arcs)
    occ.remove([(0, c) for c in centres])
    return loop


def add_groove_segment(gmsh, grooves, land: float, back: float, half_angle: float,
                       width: float) -> tuple[list[int], dict[str, list[int]]]:
    """OCC groove segment (annular wedge minus the lens lofted along the helix) in the open
    model; returns its volume tags and faces by role ('flank_left', 'flank_right', 'land',
    'back', 'free').  Dimensions from :func:`segment_dimensions`."""
    occ = gmsh.model.occ
    left = grooves[0]
    radius, r_p = left.ball_radius, left.pitch_radius
    r_in, r_out = min(land, back), max(land, back)
    outer = occ.addCylinder(0.0, 0.0, -width, 0.0, 0.0, 2 * width, r_out, angle=2 * half_angle)
    inner = occ.addCylinder(0.0, 0.0, -2 * width, 0.0, 0.0, 4 * width, r_in)
    wedge, _ = occ.cut([(3, outer)], [(3, inner)])
    occ.rotate(wedge, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, -half_angle)
    # the cutter runs past the wedge's end planes (a profile plane spans azimuths within
    # ~ 2 R_B sin(lambda) / rho of its own); loft through exact lens sections (OCC: 1e-7 m
    # from the exact surface, against 1e-6 m for a pipe over this reach; flank nodes are
    # snapped afterwards)
    reach = 1.1 * half_angle + 0.02 + 3 * radius * math.sin(left.lead_angle) / (r_p - 2 * radius * (left.sign_u < 0))
    sections = [_lens_loop(occ, grooves, phi) for phi in np.linspace(-reach, reach, 9)]
    cutter = occ.addThruSections(sections, makeSolid=True, makeRuled=False)
    result, _ = occ.cut(wedge, [vt for vt in cutter if vt[0] == 3])
    occ.synchronize()
    volumes = [tag for dim, tag in result if dim == 3]
    roles: dict[str, list[int]] = {"flank_left": [], "flank_right": [], "land": [], "back": [], "free": []}
    for _, tag in gmsh.model.getBoundary([(3, v) for v in volumes], combined=True, oriented=False):
        xyz = face_point(gmsh, tag)
        rho = math.hypot(xyz[0], xyz[1])
        kind = gmsh.model.getType(2, tag)
        residuals = [abs(surface_residual(g, xyz[None, :])[0]) for g in grooves]
        if kind == "Cylinder" and abs(rho - land) < 1e-6 * radius:
            roles["land"].append(tag)
        elif kind == "Cylinder" and abs(rho - back) < 1e-6 * radius:
            roles["back"].append(tag)
        elif kind not in ("Plane", "Cylinder") and min(residuals) < 0.01 * radius:
            roles["flank_left" if residuals[0] < residuals[1] else "flank_right"].append(tag)
        else:
            roles["free"].append(tag)
    if not roles["flank_left"] or not roles["flank_right"]:
        raise RuntimeError(f"groove flanks not identified: {roles}")
    return volumes, roles


def snap_segment(gmsh, grooves, roles: dict[str, list[int]]) -> None:
    """After meshing: flank nodes onto the exact helical flanks, bottom-edge nodes onto the bottom helix."""
    for groove, name in zip(grooves, ("flank_left", "flank_right")):
        snap_to_groove(gmsh, groove, roles[name], np.eye(3), np.zeros(3))
    snap_to_bottom(gmsh, grooves[0], flank_intersections(*grooves)[0], roles["flank_left"], roles["flank_right"])


def screw_groove_segment(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                         contact_angle: float, body: str = "screw", *, deviations=(0.0, 0.0),
                         profile_plane: str = "normal", land_radius: float | None = None,
                         back_radius: float | None = None, half_angle: float | None = None,
                         axial_half_width: float | None = None, h_contact: float | None = None,
                         growth: float = 1.3, h_max: float | None = None, fine_radius: float | None = None,
                         cache: bool = True) -> Path:
    """A screw-shaft (``body="screw"``) or nut segment with its helical gothic-arch groove,
    as a cached gmsh 4.1 ``.msh`` in the screw frame [m] (axis z, ball-centre helix
    ``H(phi)``, the groove's nominal contacts at phi = 0).

    The body is the annular wedge ``|phi| <= half_angle`` between ``land_radius``
    (the land: default ``R_P -+ 0.25 R_B``) and ``back_radius`` (core of the screw /
    outside of the nut, default ``R_P -+ BODY_DEPTH R_B`` = ``R_P -+ 5.25 R_B``, the screw's core at least
    ``MIN_CORE R_P`` = ``0.1 R_P``: the validated FE depth, docs/fe_b2b.md), within ``|z| <= axial_half_width``
    (default ``p half_angle + 1.5 R_B``, at most ``lead/2`` so no other turn of the
    groove enters), minus the gothic-arch lens swept along the helix (both flanks;
    lin2019 Fig 13).  Default ``half_angle``: ``2 R_B / R_P``.  With ``h_contact``
    the mesh is refined around the two contact points of a ball at phi = 0
    (:func:`meshes.refinement.size_at_points`), else uniform ``h_max``.
    ``deviations`` [rad]: contact angle deviations (left, right) of the two flanks
    (lin2019 Fig 17, eq 17 ``b = b_0 + db``): a flank's arc centre turns about the
    ball centre so a ball on the helix touches it at ``contact_angle + db``.

    Physical groups: volume ``screw`` or ``nut``; surfaces ``flank_left``,
    ``flank_right`` (nodes on the exact helical surface), ``land``, ``back``,
    ``segment_free`` (the cut faces).
    """
    grooves = segment_grooves(ball_radius, conformity, pitch_radius, lead, contact_angle, body, deviations,
                              profile_plane)
    left = grooves[0]
    land, back, half_angle, width = segment_dimensions(grooves, land_radius, back_radius, half_angle,
                                                       axial_half_width)
    refine = h_contact is not None
    h_contact, growth, h_max, fine_radius = check_refinement(left.ball_radius, left.ball_radius / 4 if h_contact
                                                             is None else h_contact, growth, h_max, fine_radius)
    params = dict(builder="screw_groove_segment", groove=[left.ball_radius, left.conformity, left.pitch_radius,
                  left.lead, left.contact_angle, grooves[1].contact_angle, left.body, left.profile_plane],
                  land=land, back=back, half_angle=half_angle, width=width, refine=refine, h_contact=h_contact,
                  growth=growth, h_max=h_max, fine_radius=fine_radius)
    path, build = cached_msh(f"{left.body}-segment", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path
    with session("groove_segment") as gmsh:
        volumes, roles = add_groove_segment(gmsh, grooves, land, back, half_angle, width)
        physical(gmsh, 3, volumes, left.body)
        for name, tags in roles.items():
            if tags:
                physical(gmsh, 2, tags, "segment_free" if name == "free" else name)
        contacts = [g.surface(g.contact_theta, 0.0) for g in grooves]
        size_at_points(gmsh, contacts if refine else None, h_contact, growth, h_max, fine_radius)
        gmsh.model.mesh.generate(3)
        snap_segment(gmsh, grooves, roles)
        write_msh(gmsh, path)
    return path
