"""Compiled (numba) Newton of a long ball-screw chain with one nut shift per ball: the whole screw's ring.

The chain of :func:`lowmodel.screw.b2b._solve_attempt` with per-ball axial loads (lin2019 eqs 54-61; the
whole screw of lin2019 Sec 3.4, :mod:`lowmodel.screw.whole_screw`), for chains of at least
:data:`lowmodel.b2b_chain.SPARSE_BALLS` balls, open or closed (ring), as loops (loaded by
:func:`lowmodel.kernels.load`; never imported by ``import ballbench.lowmodel``):

* :func:`chain_blocks`: residual and Jacobian of the chain as ``K x K`` blocks (``K = 8``: the 7 unknowns of a ball
  with its own nut shift and the force slot of its pair; :mod:`lowmodel.b2b_chain`): ``diagonal[j]``,
  ``upper[j]`` = block (j, j+1) and ``lower[j]`` = block (j, j-1), indices modulo ``n`` (the ring's pair
  (n-1, 0) gives the corner blocks ``upper[n-1]`` and ``lower[0]``; zero in an open chain).  The ball terms and the
  B2B loads are those of :mod:`lowmodel.screw.ball_kernels` (the same loops as the dense chain there).
* :func:`newton`: :func:`lowmodel.solvers.newton` (Levenberg-Marquardt, Nielsen's damping update, row weights and
  row tolerances, the same acceptance, the same failure statuses: the loop of
  :func:`lowmodel.newton_kernels.levenberg_marquardt`) with the damped normal equations
  ``(J^T J + lam I) dx = -J^T r`` solved by a Cholesky factorisation that follows their structure: ``J^T J`` of a
  cyclic block-tridiagonal ``J`` is cyclic block-pentadiagonal; with the last two blocks of balls ordered last it is
  a band (half-bandwidth ``3 K - 1``) bordered by ``2 K`` dense rows and columns (the corner coupling of the ring),
  so the factor is a banded Cholesky of the first ``(n - 2) K`` unknowns, the border rows against it, and a dense
  Cholesky of the ``2 K x 2 K`` Schur complement (O(n K^3) per step, where the numpy path's sparse LU of the
  ring's normal equations fills in along the border as well).  The step solves the same equations as the numpy
  path's, so the iterates agree to round-off (tests/lowmodel/screw/test_ball_kernels.py).

A status other than :data:`CONVERGED` is :mod:`lowmodel.screw.ball_kernels`' (an evaluation handed back to the numpy
code, or a failure the caller raises as the ConvergenceError of :func:`lowmodel.solvers.newton`).
"""
from __future__ import annotations

import math
import sys

import numba
import numpy as np

from ballbench.lowmodel.newton_kernels import blas_dot, levenberg_marquardt
from ballbench.lowmodel.screw import b2b
from ballbench.lowmodel.screw.ball_kernels import (CONVERGED, FALLBACK, NO_DESCENT, NON_FINITE, NOT_CONVERGED,
                                                   STATIONARY, ball_outputs, chain_residual, copy_outputs)

__all__ = ["chain_blocks", "newton", "warm_up", "CONVERGED", "FALLBACK", "NOT_CONVERGED", "NON_FINITE", "STATIONARY",
           "NO_DESCENT"]

_K = 8  # block: x_B3, z_B3, omega_B, omega (3), the ball's nut shift, the force slot of its pair

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")
_inline = numba.njit(inline="always", nogil=True, error_model="numpy")   # the steps of newton, inlined into it


@_jit
def chain_blocks(z, n, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars,  # noqa: C901 - the Jacobian of lowmodel.b2b_chain.chain_system, blocks
                 residual, diagonal, upper, lower, terms):
    """Residual (n K,) (:func:`lowmodel.screw.ball_kernels.chain_residual`) and the blocks (n, K, K) of the chain's
    Jacobian (module docstring) at ``z``, the ball terms into ``terms``
    (:func:`lowmodel.screw.ball_kernels.ball_outputs`); returns the status of
    :func:`lowmodel.screw.ball_kernels.ball_terms`."""
    radius = pair_scalars[0]
    spin_scale, force_scale = scalars[2], scalars[3]
    k = _K - 1
    pairs = n if ring else n - 1
    status, d_spin, d_force, d_phi = chain_residual(z, n, _K, True, ring, live, targets, geometry, scalars, tables,
                                                    chord, rot, pair_scalars, residual, terms)
    if status != CONVERGED:
        return status
    ball_jac, axial_gradient = terms[1], terms[3]
    diagonal[:] = 0.0
    upper[:] = 0.0
    lower[:] = 0.0
    for j in range(n):
        for r in range(6):
            for q in range(7):
                diagonal[j, r, q] = ball_jac[j, r, q]
        for q in range(7):
            diagonal[j, 6, q] = axial_gradient[j, q]
    spin_factor = spin_scale / force_scale
    for p in range(pairs):
        behind, ahead = p, (p + 1) % n
        for side_row in range(2):
            for side_col in range(2):
                if side_row == side_col:
                    block = diagonal[behind if side_row == 0 else ahead]
                elif side_row == 0:
                    block = upper[behind]   # rows of the ball behind, columns of the ball ahead
                else:
                    block = lower[ahead]    # rows of the ball ahead, columns of the ball behind
                for r in range(6):
                    for q in range(3):
                        value = d_spin[p, side_row, side_col, r, q]
                        block[r, 3 + q] += (value / radius if r >= 3 else value) * spin_factor
            if live[p]:   # the force column: slot k of the ball behind
                block = diagonal[behind] if side_row == 0 else lower[ahead]
                for r in range(6):
                    value = d_force[p, side_row, r]
                    block[r, k] += value / radius if r >= 3 else value
    for j in range(n):   # eqs 60-61
        diagonal[j, k, k] = d_phi[j, 0]
        if live[j]:
            if j < pairs:
                upper[j, k, 2] += d_phi[j, 1]
            diagonal[j, k, 2] += -d_phi[j, 1]
    return CONVERGED


@_jit
def _matvec(diagonal, upper, lower, x, out):
    """``out = J x`` of the cyclic block-tridiagonal ``J``."""
    n = diagonal.shape[0]
    for j in range(n):
        after, before = ((j + 1) % n) * _K, ((j - 1) % n) * _K
        for r in range(_K):
            total = 0.0
            for q in range(_K):
                total += diagonal[j, r, q] * x[j * _K + q] + upper[j, r, q] * x[after + q] \
                    + lower[j, r, q] * x[before + q]
            out[j * _K + r] = total


@_jit
def _rmatvec(diagonal, upper, lower, r_vec, out):
    """``out = J^T r``: column block ``a`` collects ``D_a^T r_a + U_{a-1}^T r_{a-1} + L_{a+1}^T r_{a+1}``."""
    n = diagonal.shape[0]
    for a in range(n):
        before, after = ((a - 1) % n), ((a + 1) % n)
        for q in range(_K):
            total = 0.0
            for r in range(_K):
                total += diagonal[a, r, q] * r_vec[a * _K + r] + upper[before, r, q] * r_vec[before * _K + r] \
                    + lower[after, r, q] * r_vec[after * _K + r]
            out[a * _K + q] = total


@_jit
def _product_t(a_block, b_block, out, add):
    """``out (+)= A^T B`` of two K x K blocks."""
    for p in range(_K):
        for q in range(_K):
            total = 0.0
            for r in range(_K):
                total += a_block[r, p] * b_block[r, q]
            out[p, q] = out[p, q] + total if add else total


@_jit
def _normal(diagonal, upper, lower, band, border, corner):
    """``N = J^T J`` into the band (m, 3K) by columns (``band[j, d] = N[j + d, j]``, LAPACK's lower band storage,
    row by row), the border (m, 2K) (``border[j, r] = N[m + r, j]``) and the corner (2K, 2K) (lower triangle),
    ``m = (n - 2) K``: what the factorisation reads together lies together in memory.

    Blocks (indices modulo n): ``N[a, a] = D_a^T D_a + U_{a-1}^T U_{a-1} + L_{a+1}^T L_{a+1}``,
    ``N[a, a-1] = U_{a-1}^T D_{a-1} + D_a^T L_a``, ``N[a, a-2] = U_{a-1}^T L_{a-1}``."""
    n = diagonal.shape[0]
    m = (n - 2) * _K
    block = np.empty((_K, _K))
    for a in range(n):
        before, after, two = (a - 1) % n, (a + 1) % n, (a - 2) % n
        for e in range(3):
            if e == 0:
                _product_t(diagonal[a], diagonal[a], block, False)
                _product_t(upper[before], upper[before], block, True)
                _product_t(lower[after], lower[after], block, True)
                column = a
            elif e == 1:
                _product_t(upper[before], diagonal[before], block, False)
                _product_t(diagonal[a], lower[a], block, True)
                column = before
            else:
                _product_t(upper[before], lower[before], block, False)
                column = two
            for p in range(_K):
                for q in range(_K):
                    i, j = a * _K + p, column * _K + q
                    if i < j:
                        if e == 0:
                            continue   # the diagonal block's upper triangle
                        i, j = j, i
                    if i >= m:
                        if j >= m:
                            corner[i - m, j - m] = block[p, q]
                        else:
                            border[j, i - m] = block[p, q]
                    else:
                        band[j, i - j] = block[p, q]


@_jit
def _factor(band, border, corner, damping, l_band, l_border, l_corner):  # noqa: C901 - one Cholesky, band and border
    """Cholesky factor of ``N + damping I`` (:func:`_normal`'s storage) into ``l_*`` (same layout); False where the
    matrix is not (numerically) positive definite.

    Left-looking: entry ``(i, j)`` is ``N[i, j]`` minus ``L[i, t] L[j, t]`` for ``t = 0, 1, ...`` in that order, then
    divided by the pivot.  The sums of one column (its band rows, its border rows) and those of the corner's border
    part are advanced together, ``t`` outermost: independent chains the processor overlaps instead of one chain after
    the other, each sum's operations in the same order (the factor is the same to the last bit)."""
    m, width = band.shape[0], band.shape[1] - 1
    b = corner.shape[0]
    column = np.empty(width)
    rows = np.empty(b)
    for i in range(m):
        for d in range(width + 1):
            l_band[i, d] = band[i, d]
        l_band[i, 0] += damping
    for j in range(m):
        low = max(0, j - width)
        total = l_band[j, 0]
        for t in range(low, j):
            value = l_band[t, j - t]
            total -= value * value
        if not total > 0.0:
            return False
        pivot = math.sqrt(total)
        l_band[j, 0] = pivot
        last = min(j + width, m - 1)
        for i in range(j + 1, last + 1):
            column[i - j - 1] = l_band[j, i - j]
        for r in range(b):
            rows[r] = border[j, r]
        for t in range(low, j):
            l_jt = l_band[t, j - t]
            for i in range(j + 1, min(t + width, last) + 1):   # rows i with t >= i - width
                column[i - j - 1] -= l_band[t, i - t] * l_jt
            for r in range(b):
                rows[r] -= l_border[t, r] * l_jt
        for i in range(j + 1, last + 1):
            l_band[j, i - j] = column[i - j - 1] / pivot
        for r in range(b):
            l_border[j, r] = rows[r] / pivot
    for r in range(b):   # the corner: N + damping I minus the border's part, then its own dense Cholesky
        for s in range(r + 1):
            l_corner[r, s] = corner[r, s] + (damping if r == s else 0.0)
    for t in range(m):
        for r in range(b):
            rows[r] = l_border[t, r]
        for r in range(b):
            l_rt = rows[r]
            for s in range(r + 1):
                l_corner[r, s] -= l_rt * rows[s]
    for r in range(b):
        for s in range(r + 1):
            total = l_corner[r, s]
            for t in range(s):
                total -= l_corner[r, t] * l_corner[s, t]
            if r == s:
                if not total > 0.0:
                    return False
                l_corner[r, r] = math.sqrt(total)
            else:
                l_corner[r, s] = total / l_corner[s, s]
    return True


@_jit
def _solve(l_band, l_border, l_corner, rhs, x):
    """``x = (L L^T)^-1 rhs`` with the factor of :func:`_factor`."""
    m, width = l_band.shape[0], l_band.shape[1] - 1
    b = l_corner.shape[0]
    for i in range(m):
        total = rhs[i]
        for t in range(max(0, i - width), i):
            total -= l_band[t, i - t] * x[t]
        x[i] = total / l_band[i, 0]
    for r in range(b):
        total = rhs[m + r]
        for t in range(m):
            total -= l_border[t, r] * x[t]
        for s in range(r):
            total -= l_corner[r, s] * x[m + s]
        x[m + r] = total / l_corner[r, r]
    for r in range(b - 1, -1, -1):
        total = x[m + r]
        for s in range(r + 1, b):
            total -= l_corner[s, r] * x[m + s]
        x[m + r] = total / l_corner[r, r]
    for i in range(m - 1, -1, -1):
        total = x[i]
        for t in range(i + 1, min(i + width, m - 1) + 1):
            total -= l_band[i, t - i] * x[t]
        for r in range(b):
            total -= l_border[i, r] * x[m + r]
        x[i] = total / l_band[i, 0]


@_jit
def _weigh(residual, diagonal, upper, lower, row_weight):
    n = diagonal.shape[0]
    for j in range(n):
        for r in range(_K):
            w = row_weight[j * _K + r]
            residual[j * _K + r] *= w
            for q in range(_K):
                diagonal[j, r, q] *= w
                upper[j, r, q] *= w
                lower[j, r, q] *= w


@_inline
def _evaluate(evaluation, z, state):
    """:func:`chain_blocks` at ``z`` into ``state`` (residual, diagonal, upper, lower, ball terms), its rows weighted:
    the evaluation of :func:`lowmodel.newton_kernels.levenberg_marquardt`."""
    n, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, row_weight = evaluation
    residual, diagonal, upper, lower, terms = state
    status = chain_blocks(z, n, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, residual,
                          diagonal, upper, lower, terms)
    if status == CONVERGED:
        _weigh(residual, diagonal, upper, lower, row_weight)
    return status


@_inline
def _prepare(steps, state, _first):
    """``J^T J`` in :func:`_normal`'s storage and ``-J^T r``; no plain Newton step."""
    band, border, corner, gradient = steps[:4]
    residual, diagonal, upper, lower = state[:4]
    _normal(diagonal, upper, lower, band, border, corner)
    _rmatvec(diagonal, upper, lower, residual, gradient)
    for i in range(gradient.size):
        gradient[i] = -gradient[i]
    return _diagonal_max(band, corner), False


@_jit
def _diagonal_max(band, corner):
    """The largest diagonal entry of ``N`` in :func:`_normal`'s storage."""
    diagonal_max = -math.inf
    for i in range(band.shape[0]):
        diagonal_max = max(diagonal_max, band[i, 0])
    for r in range(corner.shape[0]):
        diagonal_max = max(diagonal_max, corner[r, r])
    return diagonal_max


@_inline
def _step(steps, _state, damping, _plain, step):
    """``(J^T J + damping I) dx = -J^T r`` by the Cholesky factor of :func:`_factor`; False where it fails."""
    band, border, corner, gradient, l_band, l_border, l_corner = steps
    if not _factor(band, border, corner, damping, l_band, l_border, l_corner):
        return False
    _solve(l_band, l_border, l_corner, gradient, step)
    return True


@_inline
def _multiply(_steps, state, step, _plain, change):
    """``change = J step``."""
    _matvec(state[1], state[2], state[3], step, change)


@_jit
def newton(z0, n, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, max_iterations,
           row_tolerance, row_weight, z, result, terms):
    """:func:`lowmodel.solvers.newton` (Levenberg-Marquardt, Nielsen's update: the loop of
    :func:`lowmodel.newton_kernels.levenberg_marquardt`) on :func:`chain_blocks` with the structured Cholesky of the
    module docstring; ``z`` the solution, ``result`` the residual (size,) unweighted, ``terms`` the ball terms at
    ``z``; returns ``(status, iterations, norm)`` as :func:`lowmodel.screw.ball_kernels.newton`."""
    size, m = z0.size, (n - 2) * _K
    evaluation = (n, ring, live, targets, geometry, scalars, tables, chord, rot, pair_scalars, row_weight)
    steps = (np.zeros((m, 3 * _K)), np.zeros((m, 2 * _K)), np.zeros((2 * _K, 2 * _K)), np.empty(size),
             np.zeros((m, 3 * _K)), np.zeros((m, 2 * _K)), np.zeros((2 * _K, 2 * _K)))
    state = (np.empty(size), np.empty((n, _K, _K)), np.empty((n, _K, _K)), np.empty((n, _K, _K)), terms)
    trial_state = (np.empty(size), np.empty((n, _K, _K)), np.empty((n, _K, _K)), np.empty((n, _K, _K)),
                   ball_outputs(n))
    z[:] = z0
    status, iterations, norm, state = levenberg_marquardt(_evaluate, _prepare, _step, _multiply, blas_dot, evaluation,
                                                          steps, z, state, trial_state, row_tolerance * row_weight,
                                                          row_weight, max_iterations, result)
    copy_outputs(state[4], terms)
    return status, iterations, norm


def warm_up() -> None:
    """Compile (or load from numba's disk cache) the kernel with the argument types the model passes."""
    b2b.warm_up_ring_kernel(sys.modules[__name__])
