"""The mixed LCP of a condensed contact module (:mod:`fem.fourpoint`, :mod:`fem.screw_module`).

With the compliance ``W = B K^-1 B^T`` of the contact multipliers, the weighted initial gaps ``g0``
and the rigid modes ``G`` (one column per rigid unknown ``q``), the contact state solves

    g = g0 + W lam + G q >= 0,   lam >= 0,   lam . g = 0,   G^T lam = r,

the optimality conditions of the convex QP ``min 1/2 lam W lam + g0 . lam``, ``lam >= 0``,
``G^T lam = r`` (``W`` symmetric positive definite).  ``W`` of P2 mortar contact is not an M-matrix
(about 44 % positive off-diagonal entries) and the primal-dual active set method (Hintermueller,
Ito & Kunisch 2002) cycles from a cold start, so the QP is solved by the dual active-set method of
Goldfarb & Idnani (1983, quadprog); from a warm start (the previous active set of a geometric update)
the active set iteration is tried first.  Either way the answer is one exact solve on the final
active set, checked for complementarity (ConvergenceError otherwise).
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["solve_lcp"]


def solve_lcp(model, r: np.ndarray, tol: float, g0: np.ndarray, start: np.ndarray | None = None):
    """``(lam, q, active, iterations, residual)`` of the mixed LCP of a condensed module (module docstring).

    ``model``: a :class:`fem.fourpoint.ModuleModel` (its ``W``, ``G``, ``weights``, ``contact_of``, ``patches``
    and ``geometry.contact_names``); ``r`` the right-hand side of ``G^T lam = r`` [N], ``g0`` the weighted
    initial gaps [m^3], ``tol`` the complementarity tolerance (scaled as in :func:`fem.fourpoint.solve`).

    With ``start`` (an active set, e.g. of the previous geometric update) the primal-dual active set
    iteration is tried first (it converges in a few steps near the solution); if it cycles or does not
    converge, or without ``start``, the QP is solved by quadprog.  Either way the answer is the exact
    solve on the final active set, checked for complementarity."""
    import quadprog

    W, G = model.W, model.G
    n = g0.size
    n_rigid = G.shape[1]
    n_contacts = len(model.patches)
    names = model.geometry.contact_names
    w_scale = float(np.median(np.diag(W)))
    force_scale = float(np.max(np.abs(r)))
    pressure_scale = force_scale / float(np.sum(model.weights)) * 50.0  # a typical peak pressure [Pa]
    length_scale = 1e-6  # q in um
    # x = lam / pressure_scale; objective / (pressure_scale^2 w_scale)
    hessian = W / w_scale
    linear = -g0 / (pressure_scale * w_scale)
    coupling = G * (length_scale / (w_scale * pressure_scale))
    equality = G * (pressure_scale / force_scale)

    def on_active(active):
        idx = np.flatnonzero(active)
        m = idx.size
        mat = np.zeros((m + n_rigid, m + n_rigid))
        mat[:m, :m] = hessian[np.ix_(idx, idx)]
        mat[:m, m:] = coupling[idx]
        mat[m:, :m] = equality[idx].T
        sol = np.linalg.solve(mat, np.concatenate([linear[idx], r / force_scale]))
        x = np.zeros(n)
        x[idx] = sol[:m]
        gap = hessian @ x + coupling @ sol[m:] - linear  # scaled: gap / (pressure_scale w_scale)
        return x, sol[m:], gap

    def residual_of(x, q_scaled, gap, active):
        lam_scale = float(np.mean(x[active]))
        gap_scale = float(np.max(np.abs(q_scaled))) * length_scale * float(np.median(model.weights)) / (
            pressure_scale * w_scale)
        return float(np.max(np.abs(np.minimum(x / lam_scale, gap / gap_scale))))

    iterations = 0
    solution = None
    if start is not None and start.any():
        active = start.copy()
        seen = set()
        for _ in range(30):
            iterations += 1
            x, q_scaled, gap = on_active(active)
            new = x - gap > 0.0  # lam - c g with c = 1 / median diag W, in scaled units
            if np.array_equal(new, active):
                if residual_of(x, q_scaled, gap, active) <= tol:
                    solution = (x, q_scaled, gap, active)
                break
            if new.tobytes() in seen or not all(new[model.contact_of == i].any() for i in range(n_contacts)):
                break
            seen.add(active.tobytes())
            active = new
    if solution is None:
        constraints = np.hstack([equality, np.eye(n)])
        bounds = np.concatenate([r / force_scale, np.zeros(n)])
        try:
            x, _, _, (qp_iterations, _), _, _ = quadprog.solve_qp(hessian, linear, constraints, bounds, n_rigid)
        except ValueError as error:  # quadprog: "constraints are inconsistent, no solution"
            raise ConvergenceError(f"four-point module: QP failed ({error})", residual=float("inf"),
                                   iterations=iterations, tolerance=tol) from None
        iterations += int(qp_iterations)
        active = x > 1e-12 * np.max(x)
        for i in range(n_contacts):
            if not active[model.contact_of == i].any():
                raise ValueError(f"four-point module: contact {names[i]} lost (lin2017 eq 37)")
        x, q_scaled, gap = on_active(active)  # exact solve on the QP's active set
        solution = (x, q_scaled, gap, active)
    x, q_scaled, gap, active = solution
    residual = residual_of(x, q_scaled, gap, active)
    if not residual <= tol:
        raise ConvergenceError("four-point module: complementarity not met", residual=residual,
                               iterations=iterations, tolerance=tol)
    return x * pressure_scale, q_scaled * length_scale, active, iterations, residual
