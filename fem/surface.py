"""Contact-surface geometry shared by the node-to-surface (:mod:`fem.contact`) and mortar
(:mod:`fem.mortar`) contact models: nodal areas and the projection along the contact
normal z onto the counter surface.  ``points`` (n, 3) [m], triangles as node indices.
"""
from __future__ import annotations

import numpy as np

__all__ = ["lumped_area", "locate_along_z"]


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


def locate_along_z(points: np.ndarray, triangles: np.ndarray, xy: np.ndarray, tol: float = 1e-6):
    """Triangle (nodes (n, 3)), barycentric weights (n, 3) and ``inside`` (n,) bool of the z-projection of
    ``xy`` (n, 2) [m] on the surface ``triangles``.

    ``inside`` is False where ``xy`` lies outside the xy footprint of the surface (no barycentric
    coordinate above ``-tol``); there the nodes and weights are those of the nearest triangle found
    (clipped weights) and must not be used as a projection.  The search takes the 32 triangles with
    the nearest centroids and, for the points not found among them (a large triangle next to small
    ones: its centroid lies far from the point), every triangle.
    """
    from scipy.spatial import cKDTree

    xy = np.atleast_2d(np.asarray(xy, dtype=float))
    p = points[triangles][:, :, :2]
    a, e1, e2 = p[:, 0], p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]

    def barycentric(point, cand):
        v = point - a[cand]
        l1 = (v[:, 0] * e2[cand, 1] - v[:, 1] * e2[cand, 0]) / det[cand]
        l2 = (e1[cand, 0] * v[:, 1] - e1[cand, 1] * v[:, 0]) / det[cand]
        return np.column_stack([1.0 - l1 - l2, l1, l2])

    tree = cKDTree(p.mean(axis=1))
    k = min(32, len(triangles))
    _, near = tree.query(xy, k=k)
    near = np.asarray(near).reshape(len(xy), k)
    every = np.arange(len(triangles))
    nodes = np.empty((len(xy), 3), dtype=np.int64)
    weights = np.empty((len(xy), 3))
    inside = np.empty(len(xy), dtype=bool)
    for i, (point, cand) in enumerate(zip(xy, near)):
        bary = barycentric(point, cand)
        worst = bary.min(axis=1)
        if worst.max() < -tol:  # not among the nearest centroids: search every triangle
            cand = every
            bary = barycentric(point, cand)
            worst = bary.min(axis=1)
        best = int(np.argmax(worst))
        inside[i] = worst[best] >= -tol
        nodes[i] = triangles[cand[best]]
        weights[i] = np.clip(bary[best], 0.0, 1.0)
        weights[i] /= weights[i].sum()
    return nodes, weights, inside

