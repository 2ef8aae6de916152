"""The ball-screw module of lin2019 Fig 12(b) / Fig 18: a screw segment, a nut
segment and one or two balls in four-point contact with the helical gothic-arch
grooves (lin2019 Sec 3, Fig 13; Table 4 geometry).

Screw frame: axis ``z``; ball centres on the helix ``H(phi) = (R_P cos phi,
R_P sin phi, p phi)``, ``p = lead / 2 pi``: one ball at ``phi = 0``, two balls at
``phi = -+ dphi/2`` with the chord ``|H(dphi/2) - H(-dphi/2)| = spacing`` (default
``2 R_B``: they touch, the ball-to-ball contact of lin2019 Sec 3.2, Fig 16).  The
grooves are those of :mod:`meshes.parts.groove_segment` with the profile in the plane normal to
the helix (lin2019 eq 41), the only profile for which a ball on the helix touches
all four flanks.  Contacts in the order ``(SL, SR, NR, NL)`` (screw/nut,
left/right; left = the ``-z3`` side, lin2019 eq 37), contact angles
``beta_0 + dbeta_i``, uniform along the segments.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.helix import ball_centre_azimuths
from ballbench.meshes.gmsh_tools import cached_msh, physical, session, write_msh
from ballbench.meshes.parts import groove_segment
from ballbench.meshes.parts.ball import add_split_ball, check_cap_angle
from ballbench.meshes.parts.groove_segment import add_groove_segment, segment_dimensions, segment_grooves, snap_segment
from ballbench.meshes.refinement import check_refinement, four_factors, four_slabs, size_at_points

__all__ = ["CONTACTS", "ball_screw_module"]

MESH_FORMAT_VERSION = f"ballscrew-module-1/{groove_segment.MESH_FORMAT_VERSION}"
CONTACTS = ("SL", "SR", "NR", "NL")


def ball_screw_module(ball_radius: float, conformity: float, pitch_radius: float, lead: float,
                      contact_angle: float, deviations=(0.0, 0.0, 0.0, 0.0), n_balls: int = 1, *,
                      spacing: float | None = None, screw_land_radius: float | None = None,
                      screw_back_radius: float | None = None, nut_land_radius: float | None = None,
                      nut_back_radius: float | None = None, half_angle: float | None = None,
                      h_contact: float | None = None, growth: float = 1.3, h_max: float | None = None,
                      fine_radius: float | None = None, cap_angle: float | None = None,
                      min_cap_angle: float | None = None, fine_ellipses=None, size_factors=None,
                      cache: bool = True) -> Path:
    """The ball-screw module as a cached gmsh 4.1 ``.msh`` [m] (screw frame).

    ``deviations`` [rad]: contact angle deviations ``(SL, SR, NR, NL)``;
    ``n_balls`` 1 or 2; ``spacing`` [m] chord between two ball centres (default
    ``2 R_B``).  Segments as :func:`meshes.parts.groove_segment.screw_groove_segment` (screw land
    ``R_P - 0.25 R_B``, core ``R_P - 5.25 R_B`` (at least ``0.1 R_P``); nut land ``R_P + 0.25 R_B``, outside
    ``R_P + 5.25 R_B``: ``groove_segment.BODY_DEPTH``, the depth of the validated FE module, docs/fe_b2b.md;
    ``half_angle`` default ``dphi/2 + 2 R_B / R_P``).  With
    ``h_contact`` [m] the mesh is refined at every contact point (four per ball and
    the B2B point).  ``fine_ellipses`` (with ``h_contact``): the fine zone of each contact shaped as its ellipse
    instead of a ball of ``fine_radius``: one ``(l_1, l_2, l_3)`` [m] for all four contacts or four of them (SL, SR,
    NR, NL), the elliptic slab of semi-axes ``l_1`` across the groove (in the plane normal to the helix, the Hertz
    major axis), ``l_2`` along the helix and half-thickness ``l_3`` along the contact normal
    (:func:`meshes.refinement.ellipse_distance`); ``size_factors`` (with ``h_contact``): four factors in (0, 1]
    (SL, SR, NR, NL), the fine zone of contact ``i`` meshed at ``size_factors[i] h_contact``; the B2B point keeps
    ``h_contact`` (as :func:`meshes.assemblies.fourpoint_module.fourpoint_module`).

    Physical groups: volumes ``screw``, ``nut``, ``ball1`` (``ball2``); surfaces
    ``SL``, ``SR`` (screw flanks), ``NR``, ``NL`` (nut flanks), ``screw_land``,
    ``nut_land``, ``screw_support`` (the screw core), ``nut_load`` (the nut's outer
    face), ``screw_free``, ``nut_free``; ``ball{k}_{SL,SR,NR,NL}`` (spherical caps of
    half-angle ``cap_angle`` centred on the contacts; default ``min(30 deg, 0.45 x the
    smallest angle between contacts)``, at least ``min_cap_angle`` [rad] up to that limit when given:
    meshes.parts.ball.check_cap_angle), ``ball{k}_B2B`` (two balls),
    ``ball{k}_free``.  Bodies share no nodes.
    """
    deviations = checks.four_angles("deviations", deviations, "(SL, SR, NR, NL)")
    screw = segment_grooves(ball_radius, conformity, pitch_radius, lead, contact_angle, "screw",
                            (deviations[0], deviations[1]), "normal")
    nut = segment_grooves(ball_radius, conformity, pitch_radius, lead, contact_angle, "nut",
                          (deviations[3], deviations[2]), "normal")  # (left, right) = (NL, NR)
    radius, r_p = screw[0].ball_radius, screw[0].pitch_radius
    n_balls = checks.count("n_balls", n_balls, 1, 2)
    spacing = 2.0 * radius if spacing is None else checks.finite("spacing", spacing, "m")
    if n_balls == 2 and not 2.0 * radius <= spacing <= r_p:
        raise ValueError(f"spacing must lie in [2 ball_radius, pitch_radius] = [{2 * radius!r}, {r_p!r}] m, "
                         f"got {spacing!r}")
    dphi = ball_centre_azimuths(r_p, screw[0].lead, spacing) if n_balls == 2 else 0.0
    if half_angle is None:
        half_angle = dphi / 2 + 2.0 * radius / r_p
    half_angle = checks.positive("half_angle", half_angle, "rad")
    if half_angle < dphi / 2 + 1.2 * radius / r_p:
        raise ValueError(f"half_angle must be at least {dphi / 2 + 1.2 * radius / r_p!r} rad to hold the balls, "
                         f"got {half_angle!r}")
    s_land, s_back, half_angle, s_width = segment_dimensions(screw, screw_land_radius, screw_back_radius,
                                                             half_angle, None, prefix="screw_")
    n_land, n_back, _, n_width = segment_dimensions(nut, nut_land_radius, nut_back_radius, half_angle, None,
                                                    prefix="nut_")
    if n_land - s_land <= 0.0:
        raise ValueError("screw_land_radius must be smaller than nut_land_radius")
    phis = [0.0] if n_balls == 1 else [-dphi / 2, dphi / 2]
    flanks = {"SL": screw[0], "SR": screw[1], "NR": nut[1], "NL": nut[0]}
    centres = [screw[0].helix(phi) for phi in phis]
    ball_directions = []
    for k, (phi, centre) in enumerate(zip(phis, centres)):
        directions = {name: (groove.surface(groove.contact_theta, phi) - centre) / radius
                      for name, groove in flanks.items()}
        if n_balls == 2:
            chord = centres[1] - centres[0]
            directions["B2B"] = (1.0 if k == 0 else -1.0) * chord / np.linalg.norm(chord)
        ball_directions.append(directions)
    cap_angle = check_cap_angle(cap_angle, list(ball_directions[0].values()), min_cap_angle)
    refine = h_contact is not None
    if (fine_ellipses is not None or size_factors is not None) and not refine:
        raise ValueError("fine_ellipses and size_factors need h_contact (the size they shape)")
    fine_ellipses = None if fine_ellipses is None else four_slabs(fine_ellipses, "(SL, SR, NR, NL)")
    size_factors = None if size_factors is None else four_factors(size_factors, "(SL, SR, NR, NL)")
    h_contact, growth, h_max, fine_radius = check_refinement(radius, radius / 4 if h_contact is None else h_contact,
                                                             growth, h_max, fine_radius)
    params = dict(builder="ball_screw_module", radius=radius, conformity=screw[0].conformity, pitch_radius=r_p,
                  lead=screw[0].lead, angles=[g.contact_angle for g in (*screw, *nut)], n_balls=n_balls,
                  spacing=spacing, screw=[s_land, s_back], nut=[n_land, n_back], half_angle=half_angle,
                  widths=[s_width, n_width], refine=refine, h_contact=h_contact, growth=growth, h_max=h_max,
                  fine_radius=fine_radius, cap_angle=cap_angle)
    if fine_ellipses is not None:  # only then: the cache names of the other meshes stay as they were
        params["fine_ellipses"] = [list(item) for item in fine_ellipses]
    if size_factors is not None:
        params["size_factors"] = list(size_factors)
    path, build = cached_msh("ballscrew-module", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path

    with session("ball_screw_module") as gmsh:
        screw_volumes, screw_roles = add_groove_segment(gmsh, screw, s_land, s_back, half_angle, s_width)
        nut_volumes, nut_roles = add_groove_segment(gmsh, nut, n_land, n_back, half_angle, n_width)
        contact_points = [centre + radius * directions[name] for centre, directions in zip(centres, ball_directions)
                          for name in CONTACTS]
        ball_groups = [add_split_ball(gmsh, centre, radius, directions, cap_angle)
                       for centre, directions in zip(centres, ball_directions)]
        gmsh.model.occ.synchronize()
        physical(gmsh, 3, screw_volumes, "screw")
        physical(gmsh, 3, nut_volumes, "nut")
        physical(gmsh, 2, screw_roles["flank_left"], "SL")
        physical(gmsh, 2, screw_roles["flank_right"], "SR")
        physical(gmsh, 2, nut_roles["flank_right"], "NR")
        physical(gmsh, 2, nut_roles["flank_left"], "NL")
        physical(gmsh, 2, screw_roles["land"], "screw_land")
        physical(gmsh, 2, nut_roles["land"], "nut_land")
        physical(gmsh, 2, screw_roles["back"], "screw_support")
        physical(gmsh, 2, nut_roles["back"], "nut_load")
        physical(gmsh, 2, screw_roles["free"], "screw_free")
        physical(gmsh, 2, nut_roles["free"], "nut_free")
        for k, (volumes, surfaces) in enumerate(ball_groups, start=1):
            physical(gmsh, 3, volumes, f"ball{k}")
            for name, tags in surfaces.items():
                physical(gmsh, 2, tags, f"ball{k}_{name}")
        if n_balls == 2:
            contact_points.append((centres[0] + centres[1]) / 2)  # the B2B contact
        ellipses = None
        if fine_ellipses is not None:
            ellipses = [(fine_ellipses[i], _contact_frame(directions[name], screw[0], phi))
                        for phi, directions in zip(phis, ball_directions) for i, name in enumerate(CONTACTS)]
            ellipses += [None] * (len(contact_points) - len(ellipses))  # the B2B point keeps the ball zone
        extra = len(contact_points) - 4 * len(centres)  # the B2B point keeps h_contact
        sizes = h_contact if size_factors is None else \
            [h_contact * f for _ in centres for f in size_factors] + [h_contact] * extra
        size_at_points(gmsh, contact_points if refine else None, sizes, growth, h_max, fine_radius,
                       ellipses=ellipses)
        gmsh.model.mesh.generate(3)
        snap_segment(gmsh, screw, screw_roles)
        snap_segment(gmsh, nut, nut_roles)
        write_msh(gmsh, path)
    return path


def _contact_frame(normal, groove, phi: float) -> np.ndarray:
    """Rows ``(e1, e2, e3)`` of a contact's fine slab: ``e3`` the contact normal (ball centre to contact), ``e2``
    the helix tangent at the ball's azimuth ``phi`` made normal to it, ``e1 = e2 x e3`` (across the groove, in the
    plane normal to the helix: the Hertz major axis of the groove's conformal profile)."""
    n = np.asarray(normal, dtype=float) / np.linalg.norm(normal)
    tangent = np.array([-groove.pitch_radius * np.sin(phi), groove.pitch_radius * np.cos(phi),
                        groove.lead / (2.0 * np.pi)])
    e2 = tangent - (tangent @ n) * n
    e2 /= np.linalg.norm(e2)
    return np.array([np.cross(e2, n), e2, n])
