"""Contact-surface geometry shared by the node-to-surface (:mod:`fem.contact`) and mortar
(:mod:`fem.mortar`) contact models: nodal areas and the projection along the contact
normal z onto the counter surface.  ``points`` (n, 3) [m], triangles as node indices.
"""
from __future__ import annotations

import numpy as np
from scipy.spatial import cKDTree

__all__ = ["lumped_area", "locate", "locate_along_z"]


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
    ``xy`` (n, 2) [m] on the surface ``triangles`` (:func:`locate`, whose rows index ``triangles``)."""
    rows, weights, inside = locate(points, triangles, xy, tol)
    return triangles[rows], weights, inside


def locate(points: np.ndarray, triangles: np.ndarray, xy: np.ndarray, tol: float = 1e-6):
    """Rows of ``triangles`` (n,), barycentric weights (n, 3) and ``inside`` (n,) bool of the z-projection of
    ``xy`` (n, 2) [m] on the surface ``triangles`` (the projection on the first two coordinates of ``points``;
    a contact frame's tangent-plane coordinates project along its normal).

    ``inside`` is False where ``xy`` lies outside the xy footprint of the surface (no barycentric
    coordinate above ``-tol``); there the row and weights are those of the nearest triangle found
    (clipped weights) and must not be used as a projection.  The search takes the 32 triangles with
    the nearest centroids and, for the points not found among them (a large triangle next to small
    ones: its centroid lies far from the point), every triangle.
    """
    xy = np.atleast_2d(np.asarray(xy, dtype=float))
    p = points[triangles][:, :, :2]
    a, e1, e2 = p[:, 0], p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    det = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0]

    def barycentric(point, cand):  # point (m, 2), cand (m, c) -> (m, c, 3)
        v = point[:, None, :] - a[cand]
        l1 = (v[..., 0] * e2[cand, 1] - v[..., 1] * e2[cand, 0]) / det[cand]
        l2 = (e1[cand, 0] * v[..., 1] - e1[cand, 1] * v[..., 0]) / det[cand]
        return np.stack([1.0 - l1 - l2, l1, l2], axis=-1)

    def best_of(point, cand):
        bary = barycentric(point, cand)
        worst = bary.min(axis=-1)
        best = np.argmax(worst, axis=1)
        pick = np.arange(len(point))
        return cand[pick, best], bary[pick, best], worst[pick, best]

    k = min(32, len(triangles))
    _, near = cKDTree(p.mean(axis=1)).query(xy, k=k)
    near = np.asarray(near).reshape(len(xy), k)
    rows = np.empty(len(xy), dtype=np.int64)
    weights = np.empty((len(xy), 3))
    worst = np.empty(len(xy))
    for start in range(0, len(xy), 4096):  # bounded memory: (chunk, 32, 3)
        chunk = slice(start, start + 4096)
        rows[chunk], weights[chunk], worst[chunk] = best_of(xy[chunk], near[chunk])
    missed = np.flatnonzero(worst < -tol)  # not among the nearest centroids: search every triangle
    every = np.arange(len(triangles))
    for index in missed:
        rows[index], weights[index], worst[index] = (value[0] for value in best_of(xy[index:index + 1],
                                                                                   every[None, :]))
    inside = worst >= -tol
    weights = np.clip(weights, 0.0, 1.0)
    weights /= weights.sum(axis=1, keepdims=True)
    return rows, weights, inside
