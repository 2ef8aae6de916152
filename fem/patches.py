"""Rigid patches on an elastic body: how a low-order model's contact forces enter an FE body and how the body's move
is read back (the FE rungs of the whole carriage and the whole nut, fem.carriage_fe and fem.nut_fe).

A contact's force enters the body's surface over a patch of vertices around its contact point, and the contact's
move is read from the same patch: the rigid motion ``a + omega x r`` that fits the patch's vertex displacements by
least squares, evaluated at a point of the contact's normal line along chosen directions (exact for a rigid motion
of the body; along the normal the same at any point of the line).  The load is the transpose of the read (the
patch's resultant and moment shared by the same fit), so that the condensed compliance ``P K^-1 P^T`` is
symmetric.  What the contact law already holds, the patch's own flattening, is removed as Boussinesq's mean
displacement of a uniform load on a disk of radius ``rho`` on a half-space, ``16 (1 - nu^2) / (3 pi^2 rho E)`` per
newton (Johnson, Contact Mechanics, Sec 3.4; docs/carriage.md, "Elastic carriage"), capped by the stiffest mode of
the patches (more would leave the compliance indefinite).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp

from ballbench.fem.linsolve import factorize
from ballbench.fem.mortar import edge_index, surface_dofs

__all__ = ["skew", "rigid_fit_read", "patch_operator", "boussinesq_disk", "without_local", "condense",
           "PatchCompliance", "MIN_PATCH_NODES"]

MIN_PATCH_NODES = 4  # vertices a contact's patch needs (else the mesh is too coarse for it)


def skew(r) -> np.ndarray:
    """The matrix of ``r x``: ``skew(r) @ w = r x w``."""
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def rigid_fit_read(at, point, directions) -> np.ndarray:
    """(k, 3n): the rigid motion fitting the displacements of the ``n`` vertices ``at`` (n, 3) [m] (least squares;
    vertex-major x, y, z) read at ``point`` (3,) along the ``directions`` (k, 3)."""
    at = np.asarray(at, dtype=float)
    mean = at.mean(axis=0)
    fit = np.zeros((3 * len(at), 6))  # u_n = a + omega x r_n: [I, -skew(r_n)] per vertex (x, y, z rows)
    for j, r in enumerate(at - mean):
        fit[3 * j:3 * j + 3, :3] = np.eye(3)
        fit[3 * j:3 * j + 3, 3:] = -skew(r)
    return np.asarray(directions, dtype=float) @ np.hstack([np.eye(3), -skew(np.asarray(point) - mean)]) @ \
        np.linalg.pinv(fit)


def patch_operator(basis, vertices, patches, points, directions):
    """The patches' operator P (sparse, (sum of the directions' rows) x dofs): ``basis`` the body's vector basis
    (scikit-fem, its ``nodal_dofs``), ``vertices`` (n, 3) [m] the mesh's vertices, ``patches`` a list of vertex
    index arrays, ``points`` (M, 3) where each is read, ``directions`` a list of (k_i, 3) arrays (module
    docstring).  A patch of fewer than
    :data:`MIN_PATCH_NODES` vertices raises ValueError (``h_max``: refine the mesh)."""
    rows, cols, vals = [], [], []
    row = 0
    for i, (nodes, point, along) in enumerate(zip(patches, points, directions)):
        if len(nodes) < MIN_PATCH_NODES:
            raise ValueError(f"h_max: contact {i}'s patch holds {len(nodes)} vertices (at least {MIN_PATCH_NODES}): "
                             "refine the mesh")
        read = rigid_fit_read(vertices[nodes], point, along)
        dofs = np.stack([basis.nodal_dofs[c][nodes] for c in range(3)], axis=1).reshape(-1)  # vertex-major
        for k in range(len(read)):
            rows.append(np.full(dofs.size, row))
            cols.append(dofs)
            vals.append(read[k])
            row += 1
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(row, basis.N))


def boussinesq_disk(radius: float, youngs_modulus: float, poisson_ratio: float) -> float:
    """m/N, the mean normal displacement of a uniform load of one newton on a disk of ``radius`` [m] on an elastic
    half-space (Johnson, Contact Mechanics, Sec 3.4)."""
    return 16.0 * (1.0 - poisson_ratio ** 2) / (3.0 * math.pi ** 2 * radius * youngs_modulus)


def without_local(matrix, local, name: str = "h_max"):
    """``(matrix - l I, l)``, ``l = min(local, the smallest eigenvalue of matrix)`` (module docstring); a matrix
    that is not positive raises ValueError naming ``name``."""
    matrix = 0.5 * (matrix + matrix.T)
    stiffest = float(np.linalg.eigvalsh(matrix).min())
    if stiffest <= 0.0:
        raise ValueError(f"{name}: the FE compliance of the patches is not positive (smallest eigenvalue "
                         f"{stiffest!r} m/N): refine the mesh")
    removed = min(local, stiffest)
    return matrix - removed * np.eye(len(matrix)), removed


def condense(pair, stiffness, basis, held: str, operator):
    """``(P K^-1 P^T, response)``: the body's stiffness ``stiffness`` (scikit-fem ``basis``, P2) with the surface
    ``held`` of ``pair`` clamped, condensed on the patches' ``operator`` P; ``response`` (v, 3, k) each vertex's
    displacement under a unit load on each row of P."""
    edges = edge_index(basis.mesh)
    fixed = np.unique(np.concatenate([surface_dofs(basis, pair, held, c, 2, edges) for c in range(3)]))
    free = np.setdiff1d(np.arange(basis.N), fixed)
    solve = factorize(stiffness[free][:, free])
    response = solve(operator[:, free].T.toarray())
    if getattr(solve, "free", None):
        solve.free()
    matrix = operator[:, free] @ response
    full = np.zeros((basis.N, response.shape[1]))
    full[free] = response
    return matrix, np.stack([full[basis.nodal_dofs[c]] for c in range(3)], axis=1)


@dataclass(frozen=True)
class PatchCompliance:
    """An elastic body condensed on its contacts' patches: ``matrix`` (k, k) [m/N] (:func:`without_local`);
    ``local`` [m/N] removed from each row, ``boussinesq`` [m/N] its estimate; ``patch_nodes`` (M,) vertices per
    patch; ``dofs`` of the body; ``h_max`` [m]; ``mesh`` the ``.msh`` path; ``time_s``; ``points``, ``tets`` the
    body's mesh and ``response`` (v, 3, k) the vertices' displacement under a unit load on each row
    (:meth:`displacement`); ``shape`` the body's dimensions where the builder keeps them."""

    matrix: np.ndarray
    local: float
    boussinesq: float
    patch_nodes: np.ndarray
    dofs: int
    h_max: float
    mesh: str
    time_s: float
    points: np.ndarray | None = None
    tets: np.ndarray | None = None
    response: object = None
    shape: object = None

    def displacement(self, loads) -> np.ndarray:
        """(v, 3) m, the body's vertex displacements under the rows' ``loads`` (k,) [N], the held surface fixed."""
        return np.einsum("nij,j->ni", self.response, np.asarray(loads, dtype=float))
