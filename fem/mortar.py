"""Mortar (segment-to-segment) frictionless contact for P1 or P2 tetrahedra.

The contact pressure is a piecewise-linear field on the ball's contact
triangles, ``p = sum_i lambda_i phi_i`` (``phi_i`` the P1 hat function of vertex
i, ``lambda_i`` [Pa]), and non-penetration is imposed on the weighted gaps

    g~_i = int phi_i g dA >= 0,  lambda_i >= 0,  lambda_i g~_i = 0,

with ``g = g0 + u_z(ball) - u_z(counter at the z-projection)`` and the
integrals over the xy-projection of the ball triangles (the Hertz pressure
acts on the projected area).  Contact forces ``f = B^T lambda`` with
``B_i = int phi_i (N_ball - N_counter) e_z dA`` (P1 or P2 shape functions N on
either surface), so the discrete problem is the same LCP as node-to-surface
(:mod:`fem.contact`) with the rigid translation weighted by ``m_i = int phi_i dA``.
Quadrature: each ball triangle split into 16 sub-triangles (centroid rule),
the counter interpolated at every point.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ballbench.fem import linsolve
from ballbench.fem.contact import ContactModel, load_and_assemble
from ballbench.fem.elasticity import PairMesh
from ballbench.fem.surface import locate_along_z, lumped_area

__all__ = ["build_mortar_model", "weighted_gaps", "projected_quadrature", "surface_dofs", "edge_index",
           "triangle_dofs", "surface_shape", "sub_triangle_points"]

SUBDIVISIONS = 4


def edge_index(mesh) -> dict:
    """Edge number of each sorted vertex pair ``(a, b)`` of a scikit-fem mesh (P2 edge DOFs)."""
    edges = mesh.edges.T
    return {(int(min(a, b)), int(max(a, b))): i for i, (a, b) in enumerate(edges)}


def triangle_dofs(basis, triangles: np.ndarray, component: int, edge_map: dict | None) -> np.ndarray:
    """(k, 3 or 6) DOFs of ``component`` on the triangles: vertices, then edges (01, 12, 20)."""
    vert = basis.nodal_dofs[component][triangles]
    if edge_map is None:
        return vert
    pairs = [(0, 1), (1, 2), (2, 0)]
    edge = np.array([[edge_map[(min(t[i], t[j]), max(t[i], t[j]))] for i, j in pairs] for t in triangles])
    return np.hstack([vert, basis.edge_dofs[component][edge]])


def surface_dofs(basis, pair: PairMesh, name: str, component: int, order: int, edge_map=None) -> np.ndarray:
    """All DOFs of ``component`` on the named surface (vertex and, for P2, edge DOFs)."""
    if name not in pair.surfaces:
        return np.zeros(0, dtype=np.int64)
    if order == 1:
        return basis.nodal_dofs[component][pair.nodes(name)]
    return np.unique(triangle_dofs(basis, pair.surfaces[name], component, edge_map))


def surface_shape(bary: np.ndarray, order: int) -> np.ndarray:
    """Shape-function values (q, 3 or 6) at barycentric points (q, 3)."""
    if order == 1:
        return bary
    l0, l1, l2 = bary.T
    return np.column_stack([l0 * (2 * l0 - 1), l1 * (2 * l1 - 1), l2 * (2 * l2 - 1), 4 * l0 * l1, 4 * l1 * l2,
                            4 * l2 * l0])


def sub_triangle_points(s: int) -> np.ndarray:
    """Barycentric centroids (s^2, 3) of the ``s^2`` congruent sub-triangles of a triangle (mortar quadrature)."""
    pts = []
    for i in range(s):
        for j in range(s - i):
            pts.append(((i + 1 / 3) / s, (j + 1 / 3) / s))
            if i + j < s - 1:
                pts.append(((i + 2 / 3) / s, (j + 2 / 3) / s))
    pts = np.array(pts)
    return np.column_stack([1.0 - pts.sum(axis=1), pts])


def projected_quadrature(p2: np.ndarray, tri_index: np.ndarray, bary: np.ndarray):
    """Mortar quadrature on triangles projected on a plane: ``p2`` (k, 3, 2) their vertices in the plane [m],
    ``tri_index`` (k, 3) the multiplier index of each vertex (-1: none), ``bary`` (s, 3) the barycentric points
    (:func:`sub_triangle_points`, equal weights).  Returns the points ``xq`` (k s, 2) [m], weights ``wq``
    (k s,) [m^2], hats ``phi`` (k s, 3) and multiplier indices ``mult`` (k s, 3)."""
    nq = len(bary)
    e1, e2 = p2[:, 1] - p2[:, 0], p2[:, 2] - p2[:, 0]
    area = 0.5 * np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    xq = np.einsum("qv,kvd->kqd", bary, p2).reshape(-1, 2)
    wq = np.repeat(area / nq, nq)
    phi = np.tile(bary, (len(p2), 1))
    mult = np.repeat(tri_index, nq, axis=0)
    return xq, wq, phi, mult


def weighted_gaps(mult: np.ndarray, phi: np.ndarray, wq: np.ndarray, g0q: np.ndarray, n_multipliers: int,
                  couplings=(), row_offset: int = 0):
    """Mortar integrals of one contact surface (the one implementation: contact pairs and the four-point module).

    Quadrature points ``q`` on the multiplier side: ``mult`` (q, 3) the multiplier index of each
    triangle vertex (-1: none), ``phi`` (q, 3) the hat functions there, ``wq`` (q,) the weights [m^2],
    ``g0q`` (q,) the initial gap [m].  ``couplings``: ``(dofs (q, k), shape (q, k), factor)`` per
    displacement field entering the gap, ``g = g0 + sum factor * shape . u[dofs]`` (e.g. ball and
    counter z, or the components of ``(u_ball - u_rail) . e3``).

    Returns ``g~0_i = int phi_i g0 dA`` (n,) [m^3], ``m_i = int phi_i dA`` (n,) [m^2] and the COO
    triplets ``(rows, cols, vals)`` (lists of arrays) of ``B_ij = int phi_i factor N_j dA`` with the
    rows shifted by ``row_offset``.
    """
    g0 = np.zeros(n_multipliers)
    weights = np.zeros(n_multipliers)
    rows, cols, vals = [], [], []
    for k in range(3):
        ok = mult[:, k] >= 0
        i = mult[ok, k]
        wphi = wq[ok] * phi[ok, k]
        np.add.at(g0, i, wphi * g0q[ok])
        np.add.at(weights, i, wphi)
        for dofs, shape, factor in couplings:
            rows.append(np.repeat(i + row_offset, dofs.shape[1]))
            cols.append(dofs[ok].ravel())
            vals.append((factor * wphi[:, None] * shape[ok]).ravel())
    return g0, weights, rows, cols, vals


def build_mortar_model(mesh: PairMesh | Path | str, materials, gap_limit: float, *, order: int = 2,
                       method: str = "augmented", initial_gap=None, min_candidates: int = 20) -> ContactModel:
    """Mortar contact model (see module docstring); arguments as :func:`fem.contact.build_model`.

    ``order`` 1 or 2 (P1 / P2 tetrahedra on the mesh vertices; P2 edge nodes on
    straight edges).  The returned model's multipliers are nodal pressures [Pa]
    (``multiplier == "pressure"``), its ``weights`` the integrals ``m_i`` [m^2].
    """
    if order not in (1, 2):
        raise ValueError(f"order must be 1 or 2, got {order!r}")
    pair, K, basis, timings = load_and_assemble(mesh, materials, order=order, gap_limit=gap_limit)
    edge_map = edge_index(basis.mesh) if order == 2 else None
    fixed = [surface_dofs(basis, pair, "counter_support", c, order, edge_map) for c in range(3)]
    fixed += [surface_dofs(basis, pair, "ball_load", c, order, edge_map) for c in range(3)]
    fixed += [surface_dofs(basis, pair, "symmetry_x", 0, order, edge_map),
              surface_dofs(basis, pair, "symmetry_y", 1, order, edge_map)]
    fixed = np.unique(np.concatenate(fixed))
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    load_dofs = surface_dofs(basis, pair, "ball_load", 2, order, edge_map)

    points = pair.points
    ball_tris = pair.surfaces["ball_contact"]
    counter_tris = pair.surfaces["counter_contact"]
    z_top = np.max(points[np.unique(counter_tris), 2]) + gap_limit
    low = ball_tris[(points[ball_tris, 2] <= z_top).all(axis=1)]
    if low.size == 0:
        raise ValueError("no ball triangle near the counter surface: check the mesh frame")
    # initial gap at the vertices decides the multiplier set.  The z window above takes every ball vertex below
    # the highest counter node; on a concave counter (a nut groove) that node lies at the block's rising edge, so
    # the window holds ball vertices beside the block: outside its xy footprint there is no counter, no gap and
    # no candidate (a candidate zone that reaches the footprint's edge raises below: the block is too small)
    verts = np.unique(low)
    if initial_gap is None:
        tri_v, w_v, inside = locate_along_z(points, counter_tris, points[verts, :2])
        g_vert = np.where(inside, points[verts, 2] - np.einsum("ij,ij->i", points[tri_v, 2], w_v), np.inf)
    else:
        g_vert = np.asarray(initial_gap(points[verts, 0], points[verts, 1]), float)
    candidates = verts[g_vert <= gap_limit]
    if candidates.size < min_candidates:
        raise ValueError(f"only {candidates.size} candidate contact nodes (need >= {min_candidates}): refine the "
                         "mesh at the contact (smaller h_contact) or raise gap_limit")
    index = -np.ones(len(points), dtype=np.int64)
    index[candidates] = np.arange(candidates.size)
    tris = low[(index[low] >= 0).any(axis=1)]
    # quadrature points on the projected ball triangles
    bary = sub_triangle_points(SUBDIVISIONS)  # (s2, 3)
    nq = len(bary)
    xq, wq, phi, mult = projected_quadrature(points[tris][:, :, :2], index[tris], bary)
    zq_ball = np.einsum("qv,kv->kq", bary, points[tris][:, :, 2]).ravel()
    ball_dofs = np.repeat(triangle_dofs(basis, tris, 2, edge_map), nq, axis=0)
    ball_shape = np.tile(surface_shape(bary, order), (len(tris), 1))
    c_tris, c_bary, inside = locate_along_z(points, counter_tris, xq)  # barycentric in the order of c_tris' nodes
    if not inside.all():
        raise ValueError(f"the candidate zone (gap <= gap_limit = {gap_limit!r} m) reaches the edge of "
                         f"counter_contact at xy = {xq[int(np.argmin(inside))]} [m]: enlarge the counter block or "
                         "lower gap_limit")
    counter_dofs = triangle_dofs(basis, c_tris, 2, edge_map)
    counter_shape = surface_shape(c_bary, order)
    if initial_gap is None:
        g0q = zq_ball - np.einsum("ij,ij->i", points[c_tris, 2], c_bary)
    else:
        g0q = np.asarray(initial_gap(xq[:, 0], xq[:, 1]), float)
    n_c = candidates.size
    g0, weights, rows, cols, vals = weighted_gaps(mult, phi, wq, g0q, n_c,
                                                  [(ball_dofs, ball_shape, 1.0), (counter_dofs, counter_shape, -1.0)])
    B = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(n_c, K.shape[0]))
    B.sum_duplicates()
    if np.min(g0 / weights) < -1e-9 * np.ptp(points[:, 2]):
        raise ValueError(f"initial penetration {-np.min(g0 / weights):.3e} m: the bodies overlap")
    # zone edge: candidates that are vertices of a triangle with a non-candidate vertex
    edge_tris = tris[(index[tris] < 0).any(axis=1)]
    boundary = np.isin(candidates, edge_tris)
    K_ff = K[free][:, free].tocsr()
    t0 = time.perf_counter()
    W, factor = linsolve.compliance(K_ff, B[:, free], method=method, keep_factor=True)
    timings["condense_s"] = time.perf_counter() - t0
    lumped = lumped_area(points, pair.surfaces["ball_contact"], len(points))[candidates]
    return ContactModel(pair, candidates, g0, W, lumped, B.tocsr(), K, free, basis, load_dofs, boundary, timings,
                        weights=weights, multiplier="pressure", factor=factor)
