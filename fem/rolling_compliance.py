"""Contact compliance of two FE bodies condensed onto a rolling-contact grid (the FE rung of docs/rolling_contact.md).

The rolling solver (:mod:`lowmodel.contact.rolling`) needs the displacement difference ``u = u_ball - u_counter``
at the cell centres of its grid due to a uniform traction on each cell (on the ball, and its opposite on the
counter body).  With the stiffness ``K`` of a contact-pair mesh (:mod:`meshes.assemblies.contact_pairs`, the
ball's load face and the counter's support face clamped) this is the condensed compliance::

    W = P_eval K^-1 P_load^T        [m / Pa]

the same condensation ``W = B K^-1 B^T`` as the normal FE contact (:mod:`fem.contact`,
:func:`fem.linsolve.compliance`), with two sparse operators:

* ``P_eval`` (rows ``3 x points``): the FE interpolation (scikit-fem ``probes``) of ``u_ball - u_counter`` at
  each evaluation point, taken just inside each body's surface above / below the grid point;
* ``P_load`` (rows ``3 x cells``): the nodal forces of a uniform unit traction on the cell, on the ball minus
  on the counter, by ``3 x 3`` Gauss points on the cell's projection (``int N p dA``).

Both are stacked into one ``B``; its ``B K^-1 B^T`` (pardiso's Schur complement of the augmented matrix,
:func:`fem.linsolve.compliance`) holds ``W`` as the off-diagonal block.  The evaluation points are the cell
centres and one more column a cell upstream (``x + dx``), so the steady-state operator
``C = (W(x) - W(x + dx)) / dx`` of :mod:`lowmodel.contact.influence` follows row by row.

Frames: the contact-pair mesh has the contact at the origin, ``+z`` into the ball, the groove axis along
``y``.  Kalker's frame of the rolling solver (``x`` rolling = the groove axis, ``z`` into the ball):
``x_K = y``, ``y_K = -x``, ``z_K = z``.

Reuse: ``W`` depends on the mesh, the materials and the grid only; one condensation serves every load
case, creepage and spin on that grid (a creep curve, a B2B iteration), and the pressure enters only through
the traction bound.  ``condense(..., cache=True)`` keeps ``W`` on disk (``lowmodel.cache.cache_dir
("rolling_compliance")``), keyed by the mesh file's content, the materials, the grid, the element order, the
method, the evaluation depth and :data:`CONDENSATION_VERSION` (raise it when the assembly or the condensation
changes): a second run of a scene with the same mesh and grid loads it instead of condensing again.

Costs (docs/rolling_contact.md): one factorisation of ``K`` with ``m`` Schur rows
(``m = 3 (2 n_x + 1) n_y``), then each rolling solve costs what a half-space solve with dense products costs.
The full model is meshed (tangential loads break the contact pair's symmetries).
"""
from __future__ import annotations

import hashlib
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ballbench.fem import linsolve
from ballbench.fem.elasticity import PairMesh, contact_pair, stiffness_fast
from ballbench.fem.mortar import edge_index, surface_dofs
from ballbench.fem.surface import locate_along_z
from ballbench.lowmodel.cache import cache_dir, parameter_hash
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.rolling import MatrixOperator

__all__ = ["RollingCompliance", "condense", "to_mesh_xy", "CONDENSATION_VERSION"]

CONDENSATION_VERSION = "rolling-compliance-1"  # the disk cache's format and code version (module docstring)

# 3-point Gauss-Legendre on [-1, 1] (nodes in half-widths), weights scaled to sum to 1
_GAUSS = (np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)]), np.array([5.0, 8.0, 5.0]) / 18.0)


def to_mesh_xy(x_kalker: np.ndarray, y_kalker: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Mesh ``(x, y)`` of Kalker coordinates: ``x = -y_K``, ``y = x_K``."""
    return -np.asarray(y_kalker, dtype=float), np.asarray(x_kalker, dtype=float)


@dataclass
class RollingCompliance:
    """The condensed compliance on ``grid`` (Kalker's frame).

    ``W`` (3 (nx + 1) ny, 3 nx ny) [m/Pa]: rows the displacement difference ``(u_x, u_y, u_z)`` (Kalker) at the
    evaluation point ``(i, j)`` (``i = 0 .. nx``; ``i = nx`` one cell upstream of the last column), columns a
    unit traction ``(p_x, p_y, p_z)`` on cell ``(i, j)``; row / column index ``3 (i ny + j) + component``.
    ``ndofs``, ``timings`` [s] (mesh load, assembly, condensation).
    """

    grid: SurfaceGrid
    W: np.ndarray
    ndofs: int
    timings: dict = field(default_factory=dict)

    def operator(self, *, steady: bool = True, coupling: bool = True) -> MatrixOperator:
        """The :class:`~lowmodel.contact.rolling.MatrixOperator` of the tangential problem.

        ``steady``: rolling, ``C = (W(x) - W(x + dx)) / dx`` [1/Pa]; else a shift (``W`` at the cells).
        ``coupling``: the tangential displacement of the normal pressure enters as its slip (conformal or
        dissimilar bodies; zero for two identical half-spaces).
        """
        nx, ny = self.grid.nx, self.grid.ny
        W = self.W.reshape(nx + 1, ny, 3, nx * ny * 3)
        here = W[:nx].reshape(nx * ny, 3, nx * ny, 3)
        if steady:
            upstream = W[1:].reshape(nx * ny, 3, nx * ny, 3)
            block = (here - upstream) / self.grid.dx
        else:
            block = here
        tangential = np.ascontiguousarray(block[:, :2, :, :2]).reshape(2 * nx * ny, 2 * nx * ny)
        normal = np.ascontiguousarray(block[:, :2, :, 2]).reshape(2 * nx * ny, nx * ny) if coupling else None
        return MatrixOperator(self.grid, tangential, normal)


def _surface_points(pair: PairMesh, surface: str, x: np.ndarray, y: np.ndarray, inward: float) -> np.ndarray:
    # points (3, n) on the facetted surface above (x, y), moved by ``inward`` along z into the body
    points = pair.points
    tris = pair.surfaces[surface]
    nodes, weights, inside = locate_along_z(points, tris, np.stack([x, y], axis=1))
    if not np.all(inside):
        raise ValueError(f"a grid point at mesh xy {np.stack([x, y], 1)[~inside][0]} m lies outside the surface "
                         f"'{surface}': the mesh's contact surface must cover the grid")
    z = np.einsum("ij,ij->i", points[nodes, 2], weights)
    return np.stack([x, y, z + inward])


def _probe(basis, points: np.ndarray) -> sp.csr_matrix:
    # rows component-major (c * n + p), as scikit-fem's probes
    return sp.csr_matrix(basis.probes(points))


def _kalker_rows(matrix: sp.csr_matrix, n: int) -> sp.csr_matrix:
    # component-major mesh rows (x, y, z) -> point-major Kalker rows 3 p + (x_K, y_K, z_K) = (y, -x, z)
    order = np.empty(3 * n, dtype=np.int64)
    sign = np.empty(3 * n)
    p = np.arange(n)
    order[3 * p] = 1 * n + p
    sign[3 * p] = 1.0
    order[3 * p + 1] = 0 * n + p
    sign[3 * p + 1] = -1.0
    order[3 * p + 2] = 2 * n + p
    sign[3 * p + 2] = 1.0
    return sp.diags(sign) @ matrix[order]


def condense(mesh, materials, grid: SurfaceGrid, *, order: int = 2, depth: float | None = None,
             method: str = "augmented", cache: bool = False) -> RollingCompliance:
    """Condense a full contact-pair mesh's compliance onto the rolling ``grid`` (module docstring).

    ``mesh``: path of the ``.msh`` or a :class:`~fem.elasticity.PairMesh` (``symmetry="full"``: no cuts);
    ``materials``: ``(E, nu)`` or one pair per body; ``grid``: the rolling grid in Kalker's frame (cells
    centred on the contact point, :func:`lowmodel.contact.rolling.hertz_grid`); ``order``: P1 or P2;
    ``depth`` [m]: how far inside each surface the displacements are read (default 1e-6 of the cell size).
    ``cache``: load ``W`` from / store it in the disk cache (a mesh given as a path only; module docstring);
    a loaded compliance has ``timings["cached_s"]`` (the load time) in place of the assembly and condensation.
    """
    path = None
    if cache and not isinstance(mesh, PairMesh):
        path = _cache_path(mesh, materials, grid, order, depth, method)
        if path.exists():
            start = time.perf_counter()
            try:
                with np.load(path) as data:
                    W, ndofs = np.array(data["W"]), int(data["ndofs"])
                return RollingCompliance(grid, W, ndofs, {"cached_s": time.perf_counter() - start})
            except (OSError, KeyError, ValueError):
                pass  # unreadable entry: condense again below
    result = _condense(mesh, materials, grid, order=order, depth=depth, method=method)
    if path is not None:
        tmp = path.with_name(f"{path.stem}.{os.getpid()}.tmp.npz")  # unique per process, then atomic rename
        np.savez(tmp, W=result.W, ndofs=result.ndofs)
        tmp.replace(path)
    return result


def _cache_path(mesh, materials, grid: SurfaceGrid, order, depth, method):
    digest = hashlib.sha256(Path(mesh).read_bytes()).hexdigest()
    params = {"mesh": digest, "materials": np.asarray(materials, dtype=float).tolist(),
              "grid": [grid.nx, grid.ny, repr(float(grid.dx)), repr(float(grid.dy)), repr(float(grid.x_centre)),
                       repr(float(grid.y_centre))], "order": int(order), "depth": None if depth is None else
              repr(float(depth)), "method": str(method)}
    return cache_dir("rolling_compliance") / f"W-{parameter_hash(params, CONDENSATION_VERSION)}.npz"


def _condense(mesh, materials, grid: SurfaceGrid, *, order: int, depth: float | None,
              method: str) -> RollingCompliance:
    timings = {}
    start = time.perf_counter()
    pair = contact_pair(mesh)
    if "symmetry_x" in pair.surfaces or "symmetry_y" in pair.surfaces:
        raise ValueError("the mesh has symmetry cuts: tangential loads need the full model (symmetry='full')")
    timings["load_s"] = time.perf_counter() - start
    start = time.perf_counter()
    K, basis = stiffness_fast(pair, materials, order=order)
    timings["assembly_s"] = time.perf_counter() - start
    nx, ny = grid.nx, grid.ny
    inward = 1e-6 * min(grid.dx, grid.dy) if depth is None else float(depth)
    # evaluation points: the cell centres and one column upstream
    xe = np.concatenate([grid.x, [grid.x[-1] + grid.dx]])
    XK, YK = np.meshgrid(xe, grid.y, indexing="ij")
    mx, my = to_mesh_xy(XK.ravel(), YK.ravel())
    n_eval = mx.size
    ball = _probe(basis, _surface_points(pair, "ball_contact", mx, my, inward))
    counter = _probe(basis, _surface_points(pair, "counter_contact", mx, my, -inward))
    evaluate = _kalker_rows(ball - counter, n_eval)
    # loads: 3 x 3 Gauss points per cell, weights dA / 4 * w_i w_j
    nodes, weights = _GAUSS
    gx = (grid.x[:, None] + 0.5 * grid.dx * nodes[None, :])  # (nx, 3)
    gy = (grid.y[:, None] + 0.5 * grid.dy * nodes[None, :])  # (ny, 3)
    GX = np.broadcast_to(gx[:, None, :, None], (nx, ny, 3, 3)).ravel()
    GY = np.broadcast_to(gy[None, :, None, :], (nx, ny, 3, 3)).ravel()
    w = (np.outer(weights, weights) * grid.cell_area).ravel()  # per Gauss point of a cell (the rule sums to 1)
    mx, my = to_mesh_xy(GX, GY)
    n_gauss = mx.size
    ball = _probe(basis, _surface_points(pair, "ball_contact", mx, my, inward))
    counter = _probe(basis, _surface_points(pair, "counter_contact", mx, my, -inward))
    gauss = _kalker_rows(ball - counter, n_gauss)  # (3 n_gauss, ndof)
    # sum the 9 Gauss points of each cell with their weights: (3 cells, 3 n_gauss)
    cell_of = np.repeat(np.arange(nx * ny), 9)
    rows = (3 * cell_of[:, None] + np.arange(3)[None, :]).ravel()
    cols = (3 * np.arange(n_gauss)[:, None] + np.arange(3)[None, :]).ravel()
    summing = sp.csr_matrix((np.repeat(np.tile(w, nx * ny), 3), (rows, cols)), shape=(3 * nx * ny, 3 * n_gauss))
    load = summing @ gauss
    edge_map = edge_index(basis.mesh) if order == 2 else None
    fixed = np.unique(np.concatenate([surface_dofs(basis, pair, face, c, order, edge_map)
                                      for face in ("counter_support", "ball_load") for c in range(3)]))
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)
    B = sp.vstack([evaluate, load]).tocsr()[:, free]
    start = time.perf_counter()
    full = linsolve.compliance(K[free][:, free].tocsr(), B, method=method)
    timings["condense_s"] = time.perf_counter() - start
    W = np.ascontiguousarray(full[:3 * n_eval, 3 * n_eval:])
    return RollingCompliance(grid, W, int(K.shape[0]), timings)
