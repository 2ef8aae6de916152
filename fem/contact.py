"""Frictionless unilateral contact of two linear-elastic bodies (small deformation).

Formulation (docs/fem.md):

* bodies and boundary conditions: the counter body is clamped on
  ``counter_support``; the ball's ``ball_load`` face is held rigid and moved by
  ``-U`` along z (the approach of the two reference faces, U > 0 pushes the
  ball into the counter); symmetry cuts carry ``u_x = 0`` (``symmetry_x``) and
  ``u_y = 0`` (``symmetry_y``).  Every rigid-body mode is thus removed.
* node-to-surface contact along the contact normal z: candidate ball nodes
  ``j`` (``ball_contact`` nodes with initial gap ``g0_j <= gap_limit``) are
  projected along z onto the ``counter_contact`` triangles; the gap
  ``g_j = g0_j + u_z(ball node j) - sum_k N_k(j) u_z(counter node k)`` [m].
* contact forces ``lambda_j >= 0`` [N] act on ball node j along +z and, with the
  weights ``-N_k(j)``, on the counter nodes: ``f = B^T lambda``, ``g = g0 - U + B u``.
* condensed contact compliance ``W = B K^-1 B^T`` [m/N] (``K`` with the
  boundary conditions above; :func:`fem.linsolve.inverse_block`); the rigid
  translation of the ball adds ``-U`` to every gap:  ``g = g0 - U + W lambda``.
* the linear complementarity problem ``lambda >= 0, g >= 0, lambda . g = 0``,
  with either the force ``sum lambda = F / symmetry_factor`` (U unknown) or U
  given, is solved exactly by a primal-dual active set method (Hintermueller,
  Ito & Kunisch 2002): no penalty parameter enters the answer.

The solve stops when the active set repeats and the complementarity residual
``max_j |min(lambda_j / F_s, g_j / g_s)|`` (``F_s`` the mean active force,
``g_s`` = U) is below ``tol``; otherwise :class:`lowmodel.errors.ConvergenceError`.
"""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ballbench.fem.elasticity import PairMesh, contact_pair, stiffness_fast as stiffness
from ballbench.fem import linsolve
from ballbench.fem.surface import locate_along_z, lumped_area
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["ContactModel", "ContactState", "build_model", "solve_force", "solve_approach", "full_displacement",
           "full_solution", "solve_free"]


@dataclass
class ContactModel:
    """The condensed two-body contact problem of a mesh.

    ``candidates`` (n_c,) ball node indices; ``g0`` (n_c,) initial gaps [m];
    ``W`` (n_c, n_c) contact compliance [m/N]; ``area`` (n_c,) tributary
    contact area of each candidate, projected on the xy plane [m^2] (the model's cut);
    ``B`` (n_c, ndof) sparse gap operator; ``K`` the constrained stiffness.
    """

    pair: PairMesh
    candidates: np.ndarray
    g0: np.ndarray
    W: np.ndarray
    area: np.ndarray
    B: sp.csr_matrix
    K: sp.csr_matrix
    free: np.ndarray
    basis: object
    load_dofs: np.ndarray
    boundary_candidates: np.ndarray
    timings: dict = field(default_factory=dict)
    weights: np.ndarray | None = None
    multiplier: str = "force"
    factor: object = field(default=None, repr=False)  # the factor W was computed with (linsolve.compliance)

    def __post_init__(self):
        if self.weights is None:
            self.weights = np.ones(self.candidates.size)

    @property
    def ndofs(self) -> int:
        return int(self.K.shape[0])

    @property
    def symmetry_factor(self) -> int:
        return self.pair.symmetry_factor

    @property
    def xy(self) -> np.ndarray:
        return self.pair.points[self.candidates, :2]


@dataclass(frozen=True)
class ContactState:
    """Solution at one load.  ``force`` [N] full-model force, ``approach`` U [m],
    ``forces`` (n_c,) nodal contact forces of the model's cut [N], ``gaps`` (n_c,) [m],
    ``pressure`` (n_c,) nodal pressure [Pa], ``active`` (n_c,) bool, ``iterations``,
    ``residual`` (dimensionless complementarity residual)."""

    force: float
    approach: float
    forces: np.ndarray
    gaps: np.ndarray
    pressure: np.ndarray
    active: np.ndarray
    iterations: int
    residual: float


def build_model(mesh: PairMesh | Path | str, materials, gap_limit: float, *, order: int = 1,
                method: str = "augmented", min_candidates: int = 20, initial_gap=None) -> ContactModel:
    """Assemble, constrain and condense the contact problem of a contact-pair mesh.

    ``materials``: ``(E [Pa], nu)`` or one pair per body (ball, counter).
    ``gap_limit`` [m]: ball nodes with initial gap at most this are contact
    candidates (it must exceed the approach; a contact reaching the edge of the
    candidate zone is refused at solve time).  ``order``: 1 (P1; contact is
    node-to-surface on P1 nodes; P2 is refused).  ``method``: see :mod:`fem.linsolve`.
    ``initial_gap``: None (the gap of the meshed surfaces: ball node to the
    facetted counter surface) or a callable ``g0(x, y)`` [m] of the ball node's
    xy position, e.g. Hertz's quadratic separation ``A x^2 + B y^2``
    (Johnson 1985 eq 4.1), to compare with Hertz under Hertz's own gap.
    """
    if order != 1:
        raise ValueError(f"order must be 1 for contact (node-to-surface on P1 nodes), got {order!r}")
    pair, K, basis, timings = load_and_assemble(mesh, materials, order=1, gap_limit=gap_limit)
    dofs = basis.nodal_dofs  # (3, nnodes)
    fixed = [dofs[:, pair.nodes("counter_support")].ravel(), dofs[:, pair.nodes("ball_load")].ravel(),
             dofs[0, pair.nodes("symmetry_x")], dofs[1, pair.nodes("symmetry_y")]]
    fixed = np.unique(np.concatenate(fixed))
    free = np.setdiff1d(np.arange(K.shape[0]), fixed)

    points = pair.points
    ball_nodes = pair.nodes("ball_contact")
    ball_nodes = ball_nodes[np.abs(points[ball_nodes, 2]) < 0.5 * np.ptp(points[:, 2])]
    counter_tris = pair.surfaces["counter_contact"]
    # initial gap of ball-contact nodes against the (facetted) counter surface
    near = ball_nodes[points[ball_nodes, 2] <= gap_limit + np.max(points[np.unique(counter_tris), 2])]
    if near.size == 0:
        raise ValueError("no ball node near the counter surface: check the mesh frame")
    # ball nodes outside the counter's xy footprint (beside a concave block's rising edge) have no gap
    tri_nodes, weights, inside = locate_along_z(points, counter_tris, points[near, :2])
    z_counter = np.einsum("ij,ij->i", points[tri_nodes, 2], weights)
    g0_all = np.where(inside, points[near, 2] - z_counter, np.inf)
    if initial_gap is not None:
        g0_all = np.asarray(initial_gap(points[near, 0], points[near, 1]), dtype=float)
    keep = g0_all <= gap_limit
    if not inside[keep].all():
        raise ValueError(f"a candidate node at xy = {points[near[keep & ~inside][0], :2]} [m] projects outside "
                         "counter_contact: enlarge the counter block or lower gap_limit")
    candidates, g0 = near[keep], g0_all[keep]
    tri_nodes, weights = tri_nodes[keep], weights[keep]
    if candidates.size < min_candidates:
        raise ValueError(f"only {candidates.size} candidate contact nodes (need >= {min_candidates}): refine the "
                         "mesh at the contact (smaller h_contact) or raise gap_limit")
    if np.min(g0) < -1e-9 * np.ptp(points[:, 2]):
        raise ValueError(f"initial penetration {-np.min(g0):.3e} m: the bodies overlap")
    # candidates whose ball-surface neighbours are outside the zone: the zone edge
    tris = pair.surfaces["ball_contact"]
    in_zone = np.zeros(len(points), bool)
    in_zone[candidates] = True
    touched = in_zone[tris]
    edge_tris = tris[touched.any(axis=1) & ~touched.all(axis=1)]
    boundary = np.isin(candidates, edge_tris)
    # gap operator B (n_c, ndof): +1 on the ball z DOF, -N_k on counter z DOFs
    n_c = candidates.size
    rows = np.concatenate([np.arange(n_c), np.repeat(np.arange(n_c), 3)])
    cols = np.concatenate([dofs[2, candidates], dofs[2, tri_nodes.ravel()]])
    vals = np.concatenate([np.ones(n_c), -weights.ravel()])
    B = sp.csr_matrix((vals, (rows, cols)), shape=(n_c, K.shape[0]))
    B.sum_duplicates()
    K_ff = K[free][:, free].tocsr()
    t0 = time.perf_counter()
    W, factor = linsolve.compliance(K_ff, B[:, free], method=method, keep_factor=True)
    timings["condense_s"] = time.perf_counter() - t0
    area = lumped_area(points, tris, len(points))[candidates]
    return ContactModel(pair, candidates, g0, W, area, B.tocsr(), K, free, basis,
                        dofs[2, pair.nodes("ball_load")], boundary, timings, factor=factor)


def _pdas(model: ContactModel, force: float | None, approach: float | None, tol: float, max_iter: int,
          active0: np.ndarray | None = None) -> ContactState:
    W, g0, weights = model.W, model.g0, model.weights
    n = g0.size
    scale_c = 1.0 / np.median(np.diag(W))  # [N/m], makes lambda - c g dimensionally consistent
    active = (g0 <= np.min(g0) + 1e-30) if active0 is None else active0.copy()
    cut_force = None if force is None else force / model.symmetry_factor
    history = []
    lam = np.zeros(n)
    U = 0.0
    residual = np.inf
    for iteration in range(1, max_iter + 1):
        idx = np.flatnonzero(active)
        lam = np.zeros(n)
        if force is not None:
            m = idx.size
            mat = np.zeros((m + 1, m + 1))
            mat[:m, :m] = W[np.ix_(idx, idx)]
            mat[:m, m] = -weights[idx]
            mat[m, :m] = weights[idx]
            rhs = np.concatenate([-g0[idx], [cut_force]])
            sol = np.linalg.solve(mat, rhs)
            lam[idx], U = sol[:m], sol[m]
        else:
            U = approach
            if idx.size:
                lam[idx] = np.linalg.solve(W[np.ix_(idx, idx)], U * weights[idx] - g0[idx])
        gap = g0 - U * weights + W @ lam
        new_active = lam - scale_c * gap > 0.0
        f_s = max(np.sum(lam) / max(idx.size, 1), 1e-300)
        g_s = max(abs(U) * float(np.median(weights)), 1e-300)
        with np.errstate(over="ignore", invalid="ignore"):
            residual = float(np.max(np.abs(np.minimum(lam / f_s, gap / g_s))))
        key = new_active.tobytes()
        if np.array_equal(new_active, active) and residual <= tol:
            break
        if key in history and not np.array_equal(new_active, active):
            raise ConvergenceError("primal-dual active set cycles", residual=residual, iterations=iteration,
                                   tolerance=tol)
        history.append(active.tobytes())
        active = new_active
        if not active.any():
            active = g0 <= np.min(g0)
    else:
        raise ConvergenceError("primal-dual active set did not converge", residual=residual, iterations=max_iter,
                               tolerance=tol)
    if np.any(active & model.boundary_candidates):
        raise ValueError("the contact reaches the edge of the candidate zone: raise gap_limit (and refine the mesh "
                         "over the larger zone)")
    total = float(weights @ lam) * model.symmetry_factor
    if model.multiplier == "pressure":  # mortar: lambda are nodal pressures [Pa]
        return ContactState(total, float(U), weights * lam, gap, lam, active, iteration, residual)
    return ContactState(total, float(U), lam, gap, lam / model.area, active, iteration, residual)


def solve_force(model: ContactModel, force: float, *, tol: float = 1e-10, max_iter: int = 50,
                start: ContactState | None = None) -> ContactState:
    """Contact under the total (full-model) force ``force`` [N] > 0 on the ball's load face.

    ``start``: a solved state whose active set starts the iteration (load sweeps)."""
    if not (np.isfinite(force) and force > 0):
        raise ValueError(f"force must be a finite number > 0 N, got {force!r}")
    return _pdas(model, float(force), None, tol, max_iter, None if start is None else start.active)


def solve_approach(model: ContactModel, approach: float, *, tol: float = 1e-10, max_iter: int = 50) -> ContactState:
    """Contact under the prescribed approach ``approach`` [m] > min(g0) of the load face."""
    if not (np.isfinite(approach) and approach > np.min(model.g0)):
        raise ValueError(f"approach must exceed the smallest initial gap {np.min(model.g0):.3e} m, got {approach!r}")
    return _pdas(model, None, float(approach), tol, max_iter)


def full_displacement(model: ContactModel, state: ContactState) -> np.ndarray:
    """Nodal displacement field (nnodes, 3) [m] at the mesh vertices of a solved state (one sparse solve)."""
    return full_solution(model, state)[model.basis.nodal_dofs].T.copy()


def full_solution(model: ContactModel, state: ContactState) -> np.ndarray:
    """Every DOF (ndof,) [m] of the displacement of a solved state (one sparse solve); numbering of
    ``model.basis`` (P2: vertex and edge DOFs, ``basis.nodal_dofs`` and ``basis.edge_dofs``).

    Reuses the factor the condensation kept (``model.factor``); factorises ``K`` only if it was freed."""
    ndof = model.K.shape[0]
    multipliers = state.pressure if model.multiplier == "pressure" else state.forces
    f = model.B.T @ multipliers
    u = np.zeros(ndof)
    u[model.load_dofs] = -state.approach
    rhs = f - model.K @ u
    u[model.free] = solve_free(model.K, model.free, rhs[model.free], model.factor)
    return u


def solve_free(K: sp.spmatrix, free: np.ndarray, rhs: np.ndarray, factor=None) -> np.ndarray:
    """``K_ff^-1 rhs`` (|free|,) with the kept ``factor`` of ``K_ff`` (:func:`fem.linsolve.compliance`)
    if it is still alive, else one factorisation of ``K_ff`` (freed after the solve)."""
    if factor is not None and getattr(factor, "alive", True):
        return factor(rhs)
    solve = linsolve.factorize(K[free][:, free])
    try:
        return solve(rhs)
    finally:
        solve.free()


def load_and_assemble(mesh, materials, *, order: int, gap_limit: float):
    """Load a contact pair (path or :class:`PairMesh`), check its physical groups and
    ``gap_limit`` [m], and assemble the stiffness; returns ``(pair, K, basis, timings)``."""
    if not (np.isfinite(gap_limit) and gap_limit > 0):
        raise ValueError(f"gap_limit must be a finite length > 0 m, got {gap_limit!r}")
    timings = {}
    t0 = time.perf_counter()
    pair = contact_pair(mesh)
    timings["load_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    K, basis = stiffness(pair, materials, order=order)
    timings["assembly_s"] = time.perf_counter() - t0
    return pair, K, basis, timings
