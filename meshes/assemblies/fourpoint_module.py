"""The four-point-contact cross-section module of a linear ball bearing: bottom
rail, top rail and one or two balls (lin2017 Figs 1-2; lin2019 Figs 2, 7 and 11).

Frame (lin2017 Fig 2): ``z`` along the rails (rolling direction), ``x``-``y``
the cross-section, the bottom rail below.  Ball ``k`` has its centre at
``(0, 0, z_k)``: one ball at ``z = 0``; two balls at ``z = -+ spacing/2`` (ball 1
behind, ball 2 in front; with ``spacing = 2 R_B`` they touch at the origin, the
ball-to-ball (B2B) contact of lin2019 Sec 2.2).  Contact angles ``b_i = b_0 +
db_i`` in the order ``(BL, BR, TR, TL)`` (docs/developing.md), measured from
``-y`` (bottom) or ``+y`` (top) as in lin2017 eq 1: the contact points are
``R_B (-sin b_BL, -cos b_BL)``, ``R_B (sin b_BR, -cos b_BR)``,
``R_B (sin b_TR, cos b_TR)``, ``R_B (-sin b_TL, cos b_TL)`` in each ball's
cross-section (:func:`lowmodel.geometry.fourpoint.contact_points`).  Each rail is the
gothic arch of :mod:`lowmodel.geometry.groove` built by :mod:`meshes.parts.rail`; the top rail
is the bottom construction turned by pi about ``z`` (its left flank becomes TR).
A contact angle deviation turns a flank's arc centre about the ball centre, so
every ball keeps touching all four flanks (lin2019 Fig 7: ``db_BL = -theta``,
``db_BR = theta`` on the bottom rail).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.fourpoint import CONTACT_NAMES, contact_points
from ballbench.lowmodel.geometry.groove import gothic_arch
from ballbench.meshes.gmsh_tools import cached_msh, physical, session, write_msh
from ballbench.meshes.parts.ball import add_split_ball, check_cap_angle
from ballbench.meshes.parts.rail import add_bottom_rail, classify_rail_faces
from ballbench.meshes.refinement import check_refinement, four_slabs, size_at_points

__all__ = ["CONTACTS", "fourpoint_module"]

MESH_FORMAT_VERSION = "fourpoint-1"
CONTACTS = CONTACT_NAMES  # flank and cap group names: the contact order (BL, BR, TR, TL) of the geometry core


def fourpoint_module(ball_radius: float, conformity: float, contact_angle: float, deviations=(0.0, 0.0, 0.0, 0.0),  # noqa: C901 - one gmsh geometry; the branches are its options and their checks
                     n_balls: int = 1, *, spacing: float | None = None, land_height: float | None = None,
                     width: float | None = None, depth: float | None = None, length: float | None = None,
                     h_contact: float | None = None, growth: float = 1.3, h_max: float | None = None,
                     fine_radius: float | None = None, cap_angle: float | None = None,
                     fine_ellipses=None, min_cap_angle: float | None = None, cache: bool = True) -> Path:
    """The four-point module as a cached gmsh 4.1 ``.msh`` [m].

    ``deviations`` [rad]: contact angle deviations ``(BL, BR, TR, TL)``;
    ``n_balls`` 1 or 2; ``spacing`` [m] centre distance of two balls (default
    ``2 R_B``: touching); rail geometry as :func:`meshes.parts.rail.rail_segment`
    (defaults ``width 2.6 R_B`` (the groove's width + 0.3 R_B where that is more), ``depth 1.6 R_B``,
    ``land_height -0.25 R_B``;
    ``length`` default ``(n_balls - 1) spacing + 2.4 R_B``).  With ``h_contact`` [m]
    the mesh is refined around every contact point (four per ball and the B2B
    point), else uniform ``h_max`` (default ``R_B / 3``).  ``fine_ellipses`` (with ``h_contact``): the fine
    zone of each contact shaped as its ellipse instead of a ball of ``fine_radius``: one ``(l_1, l_2, l_3)``
    [m] for all four contacts or four of them (BL, BR, TR, TL), the elliptic slab of semi-axes ``l_1``
    along ``e1 = (-n_y, n_x, 0)`` (the cross-section, the Hertz major axis), ``l_2`` along the rails and
    half-thickness ``l_3`` along the normal ``n`` (:func:`meshes.refinement.ellipse_distance`).

    Physical groups: volumes ``bottom_rail``, ``top_rail``, ``ball1`` (``ball2``);
    rail surfaces ``BL``, ``BR`` (bottom flanks), ``TR``, ``TL`` (top flanks),
    ``bottom_support`` (bottom face of the bottom rail), ``top_load`` (top face of
    the top rail), ``bottom_land``, ``top_land``, ``rail_free``; ball surfaces
    ``ball{k}_{BL,BR,TR,TL}`` (spherical caps of half-angle ``cap_angle`` centred on
    the contacts; default ``min(30 deg, 0.45 x the smallest angle between contacts)``, at least ``min_cap_angle``
    [rad] up to that limit when given: meshes.parts.ball.check_cap_angle),
    ``ball{k}_B2B`` (two balls: cap around the B2B point), ``ball{k}_free``.  Bodies share no nodes.
    """
    radius = checks.positive("ball_radius", ball_radius, "m")
    deviations = checks.four_angles("deviations", deviations, "(BL, BR, TR, TL)")
    bottom = gothic_arch(radius, conformity, contact_angle, deviations[0], deviations[1], land_height)
    top = gothic_arch(radius, conformity, contact_angle, deviations[2], deviations[3], land_height)
    n_balls = checks.count("n_balls", n_balls, 1, 2)
    spacing = 2.0 * radius if spacing is None else checks.finite("spacing", spacing, "m")
    if n_balls == 2 and spacing < 2.0 * radius:
        raise ValueError(f"spacing must lie in [2 ball_radius, inf) = [{2 * radius!r}, inf) m (balls may not "
                         f"overlap), got {spacing!r}")
    if width is None:  # 2.6 R_B, wider where a land raised for a heavy contact widens the groove
        groove_width = 2.0 * max(abs(arch.edge(side)[0]) for arch in (bottom, top) for side in ("left", "right"))
        width = max(2.6 * radius, groove_width + 0.3 * radius)
    else:
        width = checks.positive("width", width, "m")
    depth = 1.6 * radius if depth is None else checks.positive("depth", depth, "m")
    length = (n_balls - 1) * spacing + 2.4 * radius if length is None else checks.positive("length", length, "m")
    for arch in (bottom, top):
        if arch.land_height - depth >= arch.bottom[1]:
            raise ValueError(f"depth must exceed the groove depth {arch.land_height - arch.bottom[1]!r} m, "
                             f"got {depth!r}")
        if max(abs(arch.edge("left")[0]), abs(arch.edge("right")[0])) >= width / 2:
            raise ValueError(f"width must exceed the groove width, got {width!r}")
    if length < (n_balls - 1) * spacing + 2.0 * radius:
        raise ValueError(f"length must be at least (n_balls - 1) spacing + 2 ball_radius, got {length!r}")
    refine = h_contact is not None
    if fine_ellipses is not None:
        if not refine:
            raise ValueError("fine_ellipses needs h_contact (the size inside the ellipses)")
        fine_ellipses = four_slabs(fine_ellipses, "(BL, BR, TR, TL)")
    h_contact, growth, h_max, fine_radius = check_refinement(radius, radius / 4 if h_contact is None else h_contact,
                                                             growth, h_max, fine_radius)
    angles = [bottom.contact_angle_left, bottom.contact_angle_right, top.contact_angle_left,
              top.contact_angle_right]
    in_plane = contact_points(radius, angles)
    ball_directions = {name: np.append(point / radius, 0.0) for name, point in zip(CONTACTS, in_plane)}
    cap_angle = check_cap_angle(cap_angle, list(ball_directions.values()) + ([np.array([0.0, 0.0, 1.0])]
                                                                              if n_balls == 2 else []),
                                min_cap_angle)
    params = dict(builder="fourpoint_module", radius=radius, conformity=bottom.conformity, angles=angles,
                  land=bottom.land_height, n_balls=n_balls, spacing=spacing, width=width, depth=depth,
                  length=length, refine=refine, h_contact=h_contact, growth=growth, h_max=h_max,
                  fine_radius=fine_radius, cap_angle=cap_angle)
    if fine_ellipses is not None:  # only then: the cache names of the ball zones stay as they were
        params["fine_ellipses"] = [list(item) for item in fine_ellipses]
    path, build = cached_msh("fourpoint", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path

    centres = [np.array([0.0, 0.0, 0.0])] if n_balls == 1 else [np.array([0.0, 0.0, -spacing / 2]),
                                                                 np.array([0.0, 0.0, spacing / 2])]
    with session("fourpoint_module") as gmsh:
        occ = gmsh.model.occ
        bottom_rail = add_bottom_rail(occ, bottom, width, depth, length, -length / 2)
        top_rail = add_bottom_rail(occ, top, width, depth, length, -length / 2)
        occ.synchronize()
        bottom_faces = classify_rail_faces(gmsh, bottom_rail, bottom, depth)
        top_faces = classify_rail_faces(gmsh, top_rail, top, depth)
        occ.rotate([(3, top_rail)], 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, math.pi)  # left flank -> TR
        ball_groups = []
        for k, centre in enumerate(centres):
            directions = dict(ball_directions)
            if n_balls == 2:
                directions["B2B"] = np.array([0.0, 0.0, 1.0 if k == 0 else -1.0])
            ball_groups.append(add_split_ball(gmsh, centre, radius, directions, cap_angle))
        occ.synchronize()

        def add(dim, tags, name):
            physical(gmsh, dim, tags, name)

        add(3, [bottom_rail], name="bottom_rail")
        add(3, [top_rail], name="top_rail")
        add(2, bottom_faces["left"], name="BL")
        add(2, bottom_faces["right"], name="BR")
        add(2, top_faces["left"], name="TR")
        add(2, top_faces["right"], name="TL")
        add(2, bottom_faces["support"], name="bottom_support")
        add(2, top_faces["support"], name="top_load")
        add(2, bottom_faces["land"], name="bottom_land")
        add(2, top_faces["land"], name="top_land")
        add(2, bottom_faces["other"] + top_faces["other"], name="rail_free")
        for k, (volumes, surfaces) in enumerate(ball_groups, start=1):
            add(3, volumes, name=f"ball{k}")
            for name, tags in surfaces.items():
                if not tags:
                    raise RuntimeError(f"ball {k}: cap {name} not identified")
                add(2, tags, name=f"ball{k}_{name}")
        points = [np.append(p, c[2]) for c in centres for p in in_plane]
        if n_balls == 2:
            points.append((centres[0] + centres[1]) / 2)  # the B2B contact
        ellipses = None
        if fine_ellipses is not None:
            frames = [np.array([[-d[1], d[0], 0.0], [0.0, 0.0, 1.0], d]) for d in ball_directions.values()]
            ellipses = [(fine_ellipses[i], frames[i]) for _ in centres for i in range(4)]
            ellipses += [None] * (len(points) - len(ellipses))  # the B2B point keeps the ball zone
        size_at_points(gmsh, points if refine else None, h_contact, growth, h_max, fine_radius, ellipses=ellipses)
        gmsh.model.mesh.generate(3)
        write_msh(gmsh, path)
    return path
