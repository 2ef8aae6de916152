"""Contact pair of a ball in a helical screw or nut groove (one flank; lin2019 Sec 3.1,
Table 4), in the contact-pair frame of docs/developing.md.

Parts: the ball cap (sphere ``|X - (0, 0, R_B)| <= R_B`` cut at ``z = cap_height``) and
the helical groove block of :mod:`meshes.parts.groove_block`, moved from the screw
frame into the exact contact frame of :func:`lowmodel.geometry.groove.contact_frame`; the groove
face's nodes are then moved onto the exact helical surface
(:func:`meshes.snapping.snap_to_groove`).  All lengths in metres, angles in radians.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.groove import contact_frame, helical_groove
from ballbench.meshes.gmsh_tools import cached_msh, physical, session, write_msh
from ballbench.meshes.parts.groove_block import add_groove_block
from ballbench.meshes.refinement import check_fine_ellipse, check_fine_zone, check_refinement, refine_contact
from ballbench.meshes.snapping import snap_to_groove

__all__ = ["ball_in_screw_groove_pair", "screw_block_limit"]

MESH_FORMAT_VERSION = "helical-1"


def screw_block_limit(ball_radius: float, conformity: float, pitch_radius: float, lead: float, contact_angle: float,
                      body: str = "screw", flank: str = "left", profile_plane: str = "normal") -> float:
    """The largest arc half-width [m] of the helical counter block of :func:`ball_in_screw_groove_pair` (same
    arguments): 90 % of the flank's arc from the contact point to the groove bottom, so the other flank is never
    meshed."""
    groove = helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank, profile_plane)
    return 0.9 * abs(groove.bottom_theta - groove.contact_theta) * groove.groove_radius


def ball_in_screw_groove_pair(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                              contact_angle: float, body: str = "screw", h_contact: float = 2e-5,
                              growth: float = 1.3, *, flank: str = "left", profile_plane: str = "normal",
                              h_max: float | None = None, fine_radius: float | None = None,
                              fine_half_length: float = 0.0, fine_patch: tuple[float, float] | None = None,
                              fine_ellipse: tuple[float, float, float] | None = None,
                              block_half_width: float | None = None, block_half_length: float | None = None,
                              block_depth: float | None = None, cap_height: float | None = None,
                              element_order: int = 1, cache: bool = True) -> Path:
    """Contact pair of a ball in a helical screw or nut groove, as a cached gmsh 4.1 ``.msh`` [m].

    Frame (docs/developing.md, contact-pair meshes): the undeformed contact point
    at the origin, ``+z`` the groove normal pointing into the ball (ball centre at
    ``(0, 0, R_B)``), ``x`` the principal direction of the groove nearest its
    cross-section profile (across the groove: the major axis ``a`` of the Hertz
    ellipse), ``y`` the principal direction nearest the helix (along the groove,
    towards increasing azimuth).  x and y are the exact principal directions at
    the contact point (:func:`lowmodel.geometry.groove.contact_frame`).

    Bodies: the ball truncated to the cap ``z <= cap_height`` (default ``R_B``: a
    hemisphere, load on its flat face), the groove truncated to a helical block:
    the annular sector ``r_g <= r <= r_g + block_depth`` about the flank's arc
    centre spanning the arc length ``+-block_half_width`` around the contact,
    swept along the helix for ``+-block_half_length`` of the contact point's path.
    Defaults ``0.6 R_B`` each, the width limited to 90 % of the way to the groove
    bottom so the other flank is never meshed.

    Physical groups: volumes ``ball``, ``counter``; surfaces ``ball_contact``
    (spherical cap), ``ball_load`` (flat face of the cap), ``counter_contact``
    (groove face; its nodes lie exactly on the helical surface), ``counter_support``
    (the back face of the block).  Mesh size (:mod:`meshes.refinement`):
    ``h(r) = min(h_max, h_contact + (growth - 1) max(0, r - fine_radius))``, ``r`` the
    distance from the contact point, or from the segment ``|x| <= fine_half_length`` of
    the x axis (as :func:`meshes.assemblies.contact_pairs.ball_in_groove_pair`:
    ``fine_radius ~ b``, ``fine_half_length ~ a``); or, with ``fine_patch = (l_x, l_y[, l_z])``
    [m], ``r`` the distance from the box ``|x| <= l_x, |y| <= l_y, |z| <= l_z`` (``l_z``
    default 0: the rectangle of the contact plane), e.g. ``(1.15 a, 1.4 b, 0.6 a)``; or, with
    ``fine_ellipse = (l_1, l_2, l_3)`` [m], ``r`` the distance from the elliptic slab
    ``x^2/l_1^2 + y^2/l_2^2 <= 1, |z| <= l_3`` (:func:`meshes.refinement.ellipse_distance`, docs/fem.md).

    ``h_contact`` [m] size at the contact, ``growth`` the size ratio of
    neighbouring elements away from the fine zone of radius ``fine_radius`` [m]
    (default 0), ``h_max`` [m] (default ``R_B/3``), ``element_order`` 1 or 2.
    """
    groove = helical_groove(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank, profile_plane)
    radius = groove.ball_radius
    h_contact, growth, h_max, fine_radius = check_refinement(radius, h_contact, growth, h_max, fine_radius)
    r_g = groove.groove_radius
    limit = screw_block_limit(ball_radius, conformity, pitch_radius, lead, contact_angle, body, flank, profile_plane)
    half_width = 0.6 * radius if block_half_width is None else \
        checks.positive("block_half_width", block_half_width, "m")
    if half_width > limit:
        half_width = limit if block_half_width is None else half_width
        if block_half_width is not None:
            raise ValueError(f"block_half_width must lie in (0, {limit!r}] m (90 % of the arc to the groove bottom), "
                             f"got {block_half_width!r}")
    half_length = 0.6 * radius if block_half_length is None else \
        checks.positive("block_half_length", block_half_length, "m")
    depth = 0.6 * radius if block_depth is None else checks.positive("block_depth", block_depth, "m")
    cap = radius if cap_height is None else checks.positive("cap_height", cap_height, "m")
    if cap >= 2.0 * radius:
        raise ValueError(f"cap_height must lie in (0, 2 ball_radius) = (0, {2 * radius!r}) m (the cap needs its "
                         f"flat loaded face), got {cap!r}")
    element_order = checks.count("element_order", element_order, 1, 2)
    fine_half_length, fine_patch = check_fine_zone(fine_half_length, fine_patch)
    fine_ellipse = check_fine_ellipse(fine_ellipse)
    if fine_ellipse is not None and (fine_patch is not None or fine_half_length > 0.0):
        raise ValueError("fine_ellipse excludes fine_patch and fine_half_length: give one fine zone")
    if groove.body == "screw" and depth >= groove.pitch_radius - radius:
        raise ValueError(f"block_depth must be smaller than pitch_radius - ball_radius, got {depth!r}")

    params = dict(builder="ball_in_screw_groove_pair", groove=[radius, groove.conformity, groove.pitch_radius,
                  groove.lead, groove.contact_angle, groove.body, groove.flank, groove.profile_plane],
                  h_contact=h_contact, growth=growth, h_max=h_max, fine_radius=fine_radius, half_width=half_width,
                  half_length=half_length, depth=depth, cap=cap, order=element_order, fine_patch=fine_patch,
                  fine_half_length=fine_half_length)
    if fine_ellipse is not None:  # only then: the cache keys of the other fine zones stay as they were
        params["fine_ellipse"] = list(fine_ellipse)
    path, build = cached_msh("screw-pair", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path

    frame = contact_frame(groove)
    with session("screw_pair") as gmsh:
        occ = gmsh.model.occ
        speed = float(np.linalg.norm(np.cross([0.0, 0.0, 1.0], frame.point) + [0.0, 0.0, groove.lead_per_radian]))
        dphi = half_length / speed  # |dS/dphi| of the contact point
        counter_tag, groove_face, support_face = add_groove_block(gmsh, groove, half_width / r_g, dphi, depth)
        # screw frame -> contact frame: x = Q (X - P)
        rotation = frame.rotation
        shift = -rotation @ frame.point
        affine = np.hstack([rotation, shift[:, None]]).ravel().tolist() + [0.0, 0.0, 0.0, 1.0]
        occ.affineTransform([(3, counter_tag)], affine)
        sphere = occ.addSphere(0.0, 0.0, radius, radius)
        box = occ.addBox(-2 * radius, -2 * radius, -radius, 4 * radius, 4 * radius, radius + cap)
        ball, _ = occ.intersect([(3, sphere)], [(3, box)])
        occ.synchronize()
        (_, ball_tag), = ball
        ball_faces = [tag for _, tag in gmsh.model.getBoundary(ball, oriented=False)]
        ball_contact = [tag for tag in ball_faces if gmsh.model.getType(2, tag) == "Sphere"]
        ball_load = [tag for tag in ball_faces if gmsh.model.getType(2, tag) == "Plane"]
        physical(gmsh, 3, [ball_tag], "ball")
        physical(gmsh, 3, [counter_tag], "counter")
        physical(gmsh, 2, ball_contact, "ball_contact")
        physical(gmsh, 2, ball_load, "ball_load")
        physical(gmsh, 2, [groove_face], "counter_contact")
        physical(gmsh, 2, [support_face], "counter_support")
        refine_contact(gmsh, h_contact, growth, h_max, fine_radius=fine_radius, fine_half_length=fine_half_length,
                       fine_patch=fine_patch, fine_ellipse=fine_ellipse)
        gmsh.model.mesh.generate(3)
        if element_order == 2:
            gmsh.model.mesh.setOrder(2)
        snap_to_groove(gmsh, groove, [groove_face], rotation.T, frame.point)
        write_msh(gmsh, path)
    return path
