"""The elastic carriage's load distribution (docs/carriage.md, "Elastic carriage"): the rigid carriage's balls
(lowmodel.linear_bearing.carriage) with the carriage's grooves moving by ``w = G f`` beyond the rigid carriage, ``G``
the grooves' compliance (fem.carriage_fe condenses it) and ``f`` the balls' forces on the carriage's contacts.
Newton on ``(q, v, w)`` from the rigid state with the dense Jacobian; :func:`lowmodel.linear_bearing.carriage.solve`
calls it (``groove_compliance=``) and builds the state.
"""
from __future__ import annotations

import numpy as np

from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["newton"]


def newton(geometry, displacement, ball_shift, external, compliance, tolerance: float, max_iterations: int,
           measure):
    """Newton on ``(q, v, w)`` of an elastic carriage from the rigid state ``(displacement (5,), ball_shift
    (r, k, 2))``: residuals the carriage's and balls' balance (``measure(carriage, balls, loads)``, the rigid solve's)
    and ``w - G f``; the dense Jacobian from the contacts' local stiffness.  ``geometry``: the carriage's geometry at
    its travel (``carriage.solve`` builds it: ``system``, ``grooves``, ``jac``, ``normal``, ``z``).  Returns ``(q, v,
    elastic (r, k, c, 2), schur (5, 5), iterations)``, the Schur complement onto ``q`` the stiffness's negative;
    ValueError for a compliance of the wrong shape, ConvergenceError naming the check."""
    index = geometry.grooves
    m = len(index)
    compliance = np.asarray(compliance, dtype=float)
    if compliance.shape != (2 * m, 2 * m) or not np.all(np.isfinite(compliance)):
        raise ValueError(f"groove_compliance must be a finite ({2 * m}, {2 * m}) matrix [m/N] over the carriage's "
                         f"{m} contacts (groove_points), got shape {compliance.shape}")
    rows, balls_n = geometry.normal.shape[0], len(geometry.z)
    nv = 2 * rows * balls_n
    r_, k_, c_ = index.T

    def unpack(x):
        elastic = np.zeros(geometry.normal.shape[:1] + (balls_n,) + geometry.normal.shape[1:2] + (2,))
        elastic[r_, k_, c_] = x[5 + nv:].reshape(m, 2)
        return x[:5], x[5:5 + nv].reshape(rows, balls_n, 2), elastic

    def evaluate(x):
        q, v, elastic = unpack(x)
        carriage, balls, blocks, loads, e, _ = geometry.system(q, v, external, elastic=elastic)
        forces = (loads[..., None] * e)[r_, k_, c_].reshape(-1)
        residual = np.concatenate([carriage, balls.reshape(-1), x[5 + nv:] - compliance @ forces])
        scale = max(float(np.max(np.abs(compliance))) * float(loads.max()), 1e-300)  # m: the grooves' largest move
        return residual, blocks, loads, max(measure(carriage, balls, loads), np.max(np.abs(residual[5 + nv:])) / scale)

    def jacobian(blocks):
        a_block, b_block, c_block, d_block, loose, _, local = blocks
        n = 5 + nv + 2 * m
        jac = np.zeros((n, n))
        jac[:5, :5] = a_block
        ball = np.arange(rows * balls_n)
        floor = 1e-12 * max(float(np.max(np.abs(d_block))), 1e-300)
        for b, (r, k) in enumerate(np.ndindex(rows, balls_n)):
            jac[:5, 5 + 2 * b:7 + 2 * b] = b_block[r, k]
            jac[5 + 2 * b:7 + 2 * b, :5] = c_block[r, k]
            jac[5 + 2 * b:7 + 2 * b, 5 + 2 * b:7 + 2 * b] = d_block[r, k] - floor * np.eye(2)
        top_local = local[r_, k_, c_]  # (m, 2, 2) d f / d (ball centre - groove centre)
        top_jac = geometry.jac[r_, k_, c_]  # (m, 2, 5)
        balls_of = ball.reshape(rows, balls_n)[r_, k_]
        df_dq = -np.einsum("mab,mbj->maj", top_local, top_jac).reshape(2 * m, 5)
        df_dv = np.zeros((2 * m, nv))
        df_dw = np.zeros((2 * m, 2 * m))
        for i in range(m):
            df_dv[2 * i:2 * i + 2, 2 * balls_of[i]:2 * balls_of[i] + 2] = top_local[i]
            df_dw[2 * i:2 * i + 2, 2 * i:2 * i + 2] = -top_local[i]
            jac[:5, 5 + nv + 2 * i:7 + nv + 2 * i] = -top_jac[i].T @ top_local[i]
            b = 5 + 2 * balls_of[i]
            jac[b:b + 2, 5 + nv + 2 * i:7 + nv + 2 * i] = top_local[i]
        jac[5 + nv:, :5] = -compliance @ df_dq
        jac[5 + nv:, 5:5 + nv] = -compliance @ df_dv
        jac[5 + nv:, 5 + nv:] = np.eye(2 * m) - compliance @ df_dw
        return jac

    x = np.concatenate([np.asarray(displacement, dtype=float), np.asarray(ball_shift, dtype=float).reshape(-1),
                        np.zeros(2 * m)])
    (residual, blocks, _, norm), iterations = evaluate(x), 0
    while norm > tolerance:
        if iterations >= max_iterations:
            raise ConvergenceError("carriage.solve (elastic grooves): the load balance and the grooves' compliance "
                                   "missed", residual=norm, iterations=iterations, tolerance=tolerance,
                                   reason="load balance missed")
        step = np.linalg.solve(jacobian(blocks), -residual)
        factor, accepted = 1.0, False
        for _ in range(40):
            trial = x + factor * step
            r_t, b_t, _, n_t = evaluate(trial)
            if n_t < norm or n_t <= tolerance:
                x, residual, blocks, norm, accepted = trial, r_t, b_t, n_t, True
                break
            factor *= 0.5
        iterations += 1
        if not accepted:
            raise ConvergenceError("carriage.solve (elastic grooves): no step reduces the residual", residual=norm,
                                   iterations=iterations, tolerance=tolerance, reason="no descent step")
    jac = jacobian(blocks)
    inner = jac[5:, 5:]
    schur = jac[:5, :5] - jac[:5, 5:] @ np.linalg.solve(inner, jac[5:, :5])
    q, v, elastic = unpack(x)
    return q, v, elastic, schur, iterations
