"""Contact-surface geometry shared by the node-to-surface (:mod:`fem.contact`) and mortar
(:mod:`fem.mortar`) contact models: nodal areas and the projection along the contact
normal z onto the counter surface.  ``points`` (n, 3) [m], triangles as node indices.
"""
from __future__ import annotations

import numpy as np

__all__ = ["lumped_area", "project_along_z"]


def lumped_area(points: np.ndarray, triangles: np.ndarray, n: int) -> np.ndarray:
    """Tributary area [m^2] of each of ``n`` nodes: a third of the area of every triangle
    (nodes (m, 3)) it belongs to, projected on the xy plane; shape (n,)."""
    p = points[triangles]
    e1, e2 = p[:, 1, :2] - p[:, 0, :2], p[:, 2, :2] - p[:, 0, :2]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])  # projected on xy
    out = np.zeros(n)
    for k in range(3):
        np.add.at(out, triangles[:, k], area / 3.0)
    return out


def project_along_z(points: np.ndarray, triangles: np.ndarray, xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Triangle (nodes (n, 3)) and barycentric weights (n, 3) of the z-projection of ``xy`` (n, 2)."""
    from scipy.spatial import cKDTree

    p = points[triangles][:, :, :2]
    centroid = p.mean(axis=1)
    tree = cKDTree(centroid)
    k = min(32, len(triangles))
    _, near = tree.query(xy, k=k)
    near = np.atleast_2d(near)
    nodes = np.empty((len(xy), 3), dtype=np.int64)
    weights = np.empty((len(xy), 3))
    for i, (point, cand) in enumerate(zip(xy, near)):
        a, b, c = p[cand, 0], p[cand, 1], p[cand, 2]
        v0, v1, v2 = b - a, c - a, point - a
        det = v0[:, 0] * v1[:, 1] - v0[:, 1] * v1[:, 0]
        l1 = (v2[:, 0] * v1[:, 1] - v2[:, 1] * v1[:, 0]) / det
        l2 = (v0[:, 0] * v2[:, 1] - v0[:, 1] * v2[:, 0]) / det
        l0 = 1.0 - l1 - l2
        worst = np.minimum(np.minimum(l0, l1), l2)
        best = int(np.argmax(worst))
        if worst[best] < -1e-6:
            raise ValueError(f"ball node at xy = {point} [m] projects outside counter_contact: enlarge the counter "
                             "block or lower gap_limit")
        nodes[i] = triangles[cand[best]]
        weights[i] = np.clip([l0[best], l1[best], l2[best]], 0.0, 1.0)
        weights[i] /= weights[i].sum()
    return nodes, weights
