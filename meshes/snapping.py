"""Mesh nodes moved onto the exact helical groove surfaces (after gmsh meshed OCC's
approximation of them: sweeps and lofts lie within about 1e-7 m of the exact surface).

* :func:`snap_to_groove` - the nodes of groove faces onto the flank's helical arc surface;
* :func:`snap_to_bottom` - the nodes shared by both flanks onto the groove-bottom helix.

Exact geometry: the geometry core, :mod:`lowmodel.geometry.groove`.
All lengths in metres.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.geometry.groove import HelicalGroove, profile_coordinates

__all__ = ["snap_to_groove", "snap_to_bottom"]


def snap_to_groove(gmsh, groove: HelicalGroove, surface_tags: list[int], to_world: np.ndarray,
                   origin: np.ndarray) -> float:
    """Move the mesh nodes of the groove surfaces onto the exact helical surface.

    Nodes are given in the mesh frame; ``to_world`` (3x3) and ``origin`` (3,) [m] map
    them to the screw frame (``X = origin + to_world @ x``).  Each node keeps its
    azimuth phi and its angle about the arc centre; only its distance from the centre
    is set to r_g.  Returns the largest correction [m].
    """
    worst = 0.0
    for tag in surface_tags:
        node_tags, coords, _ = gmsh.model.mesh.getNodes(2, tag, includeBoundary=True)
        local = coords.reshape(-1, 3)
        world = origin + local @ to_world.T
        phi, uw = profile_coordinates(groove, world)
        rel = uw - groove.arc_centre
        dist = np.linalg.norm(rel, axis=1)
        snapped = groove.arc_centre + rel * (groove.groove_radius / dist)[:, None]
        new_world = groove.to_world(snapped[:, 0], snapped[:, 1], phi)
        new_local = (new_world - origin) @ to_world
        worst = max(worst, float(np.max(np.linalg.norm(new_local - local, axis=1))))
        for node, xyz in zip(node_tags, new_local):
            gmsh.model.mesh.setNode(int(node), xyz.tolist(), [])
    return worst


def snap_to_bottom(gmsh, groove: HelicalGroove, bottom: np.ndarray, left_faces: list[int],
                   right_faces: list[int]) -> None:
    """Put the nodes shared by the faces of both flanks (the groove-bottom edge; mesh in the
    screw frame) on the helix of the profile point ``bottom`` = (u, w) [m] of ``groove``."""
    def node_set(faces):
        tags = [gmsh.model.mesh.getNodes(2, f, includeBoundary=True)[0] for f in faces]
        return set(np.concatenate(tags).tolist()) if tags else set()

    shared = sorted(node_set(left_faces) & node_set(right_faces))
    if not shared:
        return
    coords = np.array([gmsh.model.mesh.getNode(int(tag))[0] for tag in shared])
    phi, _ = profile_coordinates(groove, coords)
    exact = groove.to_world(np.full_like(phi, bottom[0]), np.full_like(phi, bottom[1]), phi)
    for tag, xyz in zip(shared, exact):
        gmsh.model.mesh.setNode(int(tag), xyz.tolist(), [])
