"""Helical groove block: the counter body of a ball in a screw or nut groove (one flank).

The annular sector ``r_g <= r <= r_g + depth`` about the flank's arc centre, spanning
the arc angles ``theta_c -+ gamma`` around the contact, swept along the ball-centre
helix over the azimuths ``-+ dphi`` (lin2019 Sec 3.1; exact geometry in
:mod:`lowmodel.geometry.groove`).  Built in the screw frame; faces identified by their distance
from the exact helical arc surfaces.  All lengths in metres, angles in radians.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.geometry.groove import HelicalGroove, surface_residual
from ballbench.meshes.gmsh_tools import face_point

__all__ = ["add_groove_block"]


def _section_loop(occ, groove: HelicalGroove, phi: float, theta_range: tuple[float, float],
                  depth: float) -> int:
    """Curve loop of the annular-sector block cross-section at azimuth ``phi``:
    arc angles ``theta_range`` around the flank's arc centre, radii ``r_g`` .. ``r_g + depth``."""
    r_g = groove.groove_radius
    corners = [(theta_range[0], r_g), (theta_range[1], r_g), (theta_range[1], r_g + depth),
               (theta_range[0], r_g + depth)]
    tags = []
    for theta, radius in corners:
        u, w = groove.profile(theta, radius)
        tags.append(occ.addPoint(*groove.to_world(u, w, phi)))
    centre = occ.addPoint(*groove.to_world(groove.arc_centre[0], groove.arc_centre[1], phi))
    curves = [occ.addCircleArc(tags[0], centre, tags[1]), occ.addLine(tags[1], tags[2]),
              occ.addCircleArc(tags[2], centre, tags[3]), occ.addLine(tags[3], tags[0])]
    loop = occ.addCurveLoop(curves)
    occ.remove([(0, centre)])
    return loop


def _sweep_along_helix(occ, groove: HelicalGroove, face: int, phi_range: tuple[float, float],
                       path_points: int = 17) -> list[tuple[int, int]]:
    """Sweep ``face`` (lying in the profile plane at ``phi_range[0]``) along the helix.

    The helix is an interpolating spline through ``path_points`` exact points;
    the Frenet trihedron of a helix is carried by the screw motion, so the swept
    surface is the screw motion of the section (OCC approximation ~1e-8 m,
    removed afterwards by :func:`meshes.snapping.snap_to_groove`).
    """
    phis = np.linspace(phi_range[0], phi_range[1], path_points)
    points = [occ.addPoint(*xyz) for xyz in groove.helix(phis)]
    spline = occ.addSpline(points)
    wire = occ.addWire([spline])
    volumes = occ.addPipe([(2, face)], wire, "Frenet")
    occ.remove([(1, wire)], recursive=True)
    return volumes


def add_groove_block(gmsh, groove: HelicalGroove, gamma: float, dphi: float, depth: float) -> tuple[int, int, int]:
    """Add the block (module docstring: arc half-angle ``gamma`` [rad], azimuth half-range
    ``dphi`` [rad], ``depth`` [m]) to the open model, synchronised; returns
    ``(volume tag, groove face tag, support face tag)`` (the support: the back face ``r = r_g + depth``)."""
    occ = gmsh.model.occ
    r_g = groove.groove_radius
    theta_c = groove.contact_theta
    loop = _section_loop(occ, groove, -dphi, (theta_c - gamma, theta_c + gamma), depth)
    face = occ.addPlaneSurface([loop])
    counter = _sweep_along_helix(occ, groove, face, (-dphi, dphi))
    occ.synchronize()
    (_, counter_tag), = [vt for vt in counter if vt[0] == 3]
    groove_faces, support_faces = [], []
    for _, tag in gmsh.model.getBoundary([(3, counter_tag)], oriented=False):
        xyz = face_point(gmsh, tag)[None, :]
        if abs(surface_residual(groove, xyz)[0]) < 0.01 * depth:
            groove_faces.append(tag)
        elif abs(surface_residual(groove, xyz, r_g + depth)[0]) < 0.01 * depth:
            support_faces.append(tag)
    if len(groove_faces) != 1 or len(support_faces) != 1:
        raise RuntimeError(f"helical block faces not identified: groove {groove_faces}, support {support_faces}")
    return counter_tag, groove_faces[0], support_faces[0]
