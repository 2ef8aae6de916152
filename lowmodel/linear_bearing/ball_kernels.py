"""Compiled (numba) kernels of the linear-bearing ball and its B2B chain: the numpy code as loops.

The same equations and the same algorithm as the numpy path, written for one ball or one chain at a time
so that nothing allocates per operation (loaded by :func:`lowmodel.kernels.load`; never imported by
``import ballbench.lowmodel``):

* :func:`ball_terms`: lin2019 eq 4 and the slip kinematics of one ball in its slip-angle formulation,
  with the friction map of eqs A4-A6 (the bicubic patches of
  :func:`lowmodel.contact.ellipse_friction.friction_angle_at`) and its Jacobian; the numpy original is
  :func:`lowmodel.linear_bearing.ball.ball_terms`.
* :func:`chain_terms`: the B2B chain of :func:`lowmodel.b2b_chain.chain_system` for the open chain of
  :mod:`lowmodel.linear_bearing.b2b` (B2B loads of eqs 5-8, ``min`` complementarity of eqs 9-10) as the
  blocks of its block-tridiagonal Jacobian.
* :func:`newton`: :func:`lowmodel.solvers.newton` (Levenberg-Marquardt with Nielsen's update; the loop is
  :func:`lowmodel.newton_kernels.levenberg_marquardt`, its steps are this module's): dense
  normal equations solved by LU with partial pivoting below :data:`lowmodel.b2b_chain.SPARSE_BALLS`
  balls; from there on each iteration tries the plain Newton step first, by a block LU of the
  block-tridiagonal ``J`` (:func:`_block_factor`, :func:`_block_solve`; the slip angles of a ball eliminated first,
  :func:`_slip_factor`), and where that is refused takes the
  Levenberg-Marquardt step with ``J^T J`` in band storage and a banded Cholesky (what ``dpbsv`` does).
* :func:`solve_branch`: :func:`lowmodel.linear_bearing.ball.solve_branch` (restart a converged point
  whose slip speed is negative with its slip angle turned by pi).
* :func:`solve_free_cases`, :func:`solve_chain_cases`: the solves of :func:`lowmodel.linear_bearing.ball.solve`
  (every ball alone) and of :func:`lowmodel.linear_bearing.b2b.solve` (its first two attempts) for many
  independent cases of the same size, up to the fields of the state (a one-case solve is a batch of one; a
  Monte Carlo chunk a batch of many).

Per-ball data (``geometry``, shape (n, 4, FIELDS), built by
:func:`lowmodel.linear_bearing.ball_fast.geometry`): per contact ``n_x``, ``n_y``, ``a_i / R_B``, the
groove velocity of the contact (0 bottom, ``sign v`` top), ``F_i / F_ref``, the friction map's
``log(b/a)`` cell, the powers of ``log(b/a)`` about that cell's centre, ``a_i`` [m] and the contact angle [rad].
Status codes of the solves:
:data:`CONVERGED`, :data:`NOT_CONVERGED`, :data:`STATIONARY`, :data:`NO_DESCENT`, :data:`REJECTED`
(the numpy path names them in its ConvergenceError messages, and runs again where a kernel fails).

One concept in one file (about 1,100 lines): the compiled twin of the ball and chain solves.  The kernels call
one another and numba compiles and caches them per module, so one module keeps one compile cache.
"""
from __future__ import annotations

import math
import sys

import numba
import numpy as np

from ballbench.lowmodel.contact.ellipse_friction import friction_angle_at
from ballbench.lowmodel.linear_bearing import ball_fast
from ballbench.lowmodel.newton_kernels import levenberg_marquardt, ordered_dot

__all__ = ["ball_terms", "chain_terms", "newton", "solve_branch", "solve_free_cases", "solve_chain_cases",
           "contact_terms", "warm_up",
           "workspace_size", "FIELDS", "CONVERGED", "NOT_CONVERGED", "STATIONARY", "NO_DESCENT", "REJECTED",
           "VIOLATED"]

NX, NY, ARM, TOP, LOAD, CELL, POWER_Y, SEMI_MAJOR, ANGLE = 0, 1, 2, 3, 4, 5, 6, 10, 11
FIELDS = 12
CONVERGED, NOT_CONVERGED, STATIONARY, NO_DESCENT, REJECTED, VIOLATED = 0, 1, 2, 3, 4, 5
SPARSE_BALLS = 6  # as lowmodel.b2b_chain.SPARSE_BALLS: dense normal equations below, band storage from here
_REGULARISATION = 1e-14  # as lowmodel.linear_bearing.b2b: the |dv| floor in dv/|dv|

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")
_inline = numba.njit(inline="always", nogil=True, error_model="numpy")   # the steps of newton, inlined into it


@_jit
def friction_at(phi, g, nodes_x, mid_x, n_mid_y, flat, out):
    """(force, moment, loss) x (value, d/d phi) per unit slip speed at slip angle ``phi`` (lin2019 eqs A4-A6, the
    bicubic patch of the cell), into ``out`` (3, 2); ``g`` the contact's data (its log(b/a) cell and powers)."""
    x = np.remainder(phi + math.pi, 2.0 * math.pi) - math.pi
    last = mid_x.size - 1
    if x != x:
        i = last
    else:
        lo, hi = 0, nodes_x.size
        while lo < hi:
            middle = (lo + hi) >> 1
            if nodes_x[middle] < x:
                lo = middle + 1
            else:
                hi = middle
        i = min(lo - 1, last)
    dx = x - mid_x[i]
    cell = i * n_mid_y + int(g[CELL])
    px = (1.0, dx, dx * dx, dx * dx * dx)
    sx = (0.0, 1.0, 2.0 * dx, 3.0 * (dx * dx))
    py0, py1, py2, py3 = g[POWER_Y], g[POWER_Y + 1], g[POWER_Y + 2], g[POWER_Y + 3]
    for q in range(3):
        value = 0.0
        slope = 0.0
        for a in range(4):  # sum_a dphi^a (sum_b c_ab dlog(b/a)^b), and its phi derivative
            inner = (flat[cell, q, 4 * a] * py0 + flat[cell, q, 4 * a + 1] * py1 + flat[cell, q, 4 * a + 2] * py2
                     + flat[cell, q, 4 * a + 3] * py3)
            value += px[a] * inner
            slope += sx[a] * inner
        out[q, 0] = value
        out[q, 1] = slope


@_jit
def ball_terms(x, g, nodes_x, mid_x, n_mid_y, flat, residual, jacobian, slip, table):
    """Residual (7,) of lin2019 eq 4 (rows 0-2, units mu F_ref) and of the slip kinematics (rows 3-6, units |v|)
    of one ball with unknowns ``x`` (7,), its Jacobian into ``jacobian`` (7, 7; entries not written stay as
    given: zero), the slip speeds into ``slip`` (4,); ``table`` (3, 2) scratch."""
    residual[0] = 0.0
    residual[1] = 0.0
    residual[2] = 0.0
    for i in range(4):
        gi = g[i]
        nx, ny, arm, load = gi[NX], gi[NY], gi[ARM], gi[LOAD]
        slide = x[0] + ny * x[1] + (-nx) * x[2] - gi[TOP]  # lin2019 eqs 1, A1-A3
        spin = (-nx * arm) * x[1] + (-ny * arm) * x[2]  # eq 2, omega_i a_i
        phi = x[3 + i]
        cos, sin = math.cos(phi), math.sin(phi)
        friction_at(phi, gi, nodes_x, mid_x, n_mid_y, flat, table)
        load_arm = load * arm
        force, d_force = table[0, 0] * load, table[0, 1] * load  # eq A4
        moment, d_moment = table[1, 0] * load_arm, table[1, 1] * load_arm  # eq A5, M_{i,O}/R_B
        residual[0] += force  # eq 4 rows
        residual[1] += ny * force + nx * moment
        residual[2] += -nx * force + ny * moment
        residual[3 + i] = slide * cos - spin * sin
        speed = slide * sin + spin * cos
        slip[i] = speed
        jacobian[0, 3 + i] = d_force
        jacobian[1, 3 + i] = ny * d_force + nx * d_moment
        jacobian[2, 3 + i] = -nx * d_force + ny * d_moment
        jacobian[3 + i, 0] = cos
        jacobian[3 + i, 1] = cos * ny - sin * (-nx * arm)
        jacobian[3 + i, 2] = cos * (-nx) - sin * (-ny * arm)
        jacobian[3 + i, 3 + i] = -speed


@_jit
def contact_terms(x, g, nodes_x, mid_x, n_mid_y, flat, out):
    """Per contact of one ball at unknowns ``x`` (7,): (slide, omega_i a_i, slip speed, force, moment, eq A6 loss)
    in the units of :class:`lowmodel.linear_bearing.ball.BallTerms`, into ``out`` (4, 6)."""
    table = np.empty((3, 2))
    for i in range(4):
        gi = g[i]
        nx, ny, arm, load = gi[NX], gi[NY], gi[ARM], gi[LOAD]
        slide = x[0] + ny * x[1] + (-nx) * x[2] - gi[TOP]
        spin = (-nx * arm) * x[1] + (-ny * arm) * x[2]
        phi = x[3 + i]
        friction_at(phi, gi, nodes_x, mid_x, n_mid_y, flat, table)
        speed = slide * math.sin(phi) + spin * math.cos(phi)
        out[i, 0] = slide
        out[i, 1] = spin
        out[i, 2] = speed
        out[i, 3] = table[0, 0] * load
        out[i, 4] = table[1, 0] * (load * arm)
        out[i, 5] = table[2, 0] * load * speed


@_jit
def chain_terms(z, n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, residual, diagonal,
                upper, lower, slip, table):
    """Residual (n K,) and Jacobian blocks of ``n`` balls: ``K = 7`` one ball alone (``n = 1``), ``K = 8`` an open
    chain with the B2B loads of lin2019 eqs 5-8 and the ``min`` complementarity of eqs 9-10 on the force slot
    (units mu F_ref; ``live[j]``: pair (j, j+1) touches).  Blocks: ``diagonal[j]``, ``upper[j]`` = (j, j+1),
    ``lower[j]`` = (j, j-1), each (n, K, K), overwritten.  With ``K = 8`` only the entries the chain can fill are
    written (``ball_terms``' pattern, rows and columns 1-2 of the pair loads, column 7 of rows 0-2, row 7 columns 0
    and 7): the blocks must hold zeros elsewhere (allocated by ``np.zeros`` and written by this function only)."""
    if big_k == 7:
        diagonal[:] = 0.0
        upper[:] = 0.0
        lower[:] = 0.0
    for j in range(n):
        base = big_k * j
        if big_k == 8:  # the entries of the pair loads and eqs 9-10, added to or set below
            for a in range(3):
                diagonal[j, a, 7] = 0.0
                lower[j, a, 7] = 0.0
            for a in range(1, 3):
                for b in range(1, 3):
                    diagonal[j, a, b] = 0.0
                    upper[j, a, b] = 0.0
                    lower[j, a, b] = 0.0
            diagonal[j, 7, 0] = 0.0
            diagonal[j, 7, 7] = 0.0
            upper[j, 7, 0] = 0.0
        ball_terms(z[base:base + 7], geometry[j], nodes_x, mid_x, n_mid_y, flat, residual[base:base + 7],
                   diagonal[j], slip[j], table)
    if big_k == 7:
        return
    for p in range(n - 1):  # pair (p, p + 1): eqs 5-8
        behind, ahead = big_k * p, big_k * (p + 1)
        force = z[behind + 7] if live[p] else 0.0
        u0 = z[behind + 1] + z[ahead + 1]
        u1 = z[behind + 2] + z[ahead + 2]
        norm = math.sqrt(u0 * u0 + u1 * u1 + _REGULARISATION * _REGULARISATION)
        e0, e1 = u0 / norm, u1 / norm
        scale = -mu * force
        residual[behind] += -force  # eq 8 on the ball behind; the ball ahead: the force flips, the moment not
        residual[ahead] += force
        residual[behind + 1] += scale * e0
        residual[behind + 2] += scale * e1
        residual[ahead + 1] += scale * e0
        residual[ahead + 2] += scale * e1
        c = -scale / norm
        b00, b01, b11 = (e0 * e0 - 1.0) * c, (e0 * e1) * c, (e1 * e1 - 1.0) * c
        for blocks, index in ((diagonal, p), (diagonal, p + 1), (upper, p), (lower, p + 1)):
            block = blocks[index]
            block[1, 1] += b00
            block[1, 2] += b01
            block[2, 1] += b01
            block[2, 2] += b11
        if live[p]:
            diagonal[p, 0, 7] = -1.0
            diagonal[p, 1, 7] = -mu * e0
            diagonal[p, 2, 7] = -mu * e1
            lower[p + 1, 0, 7] = 1.0
            lower[p + 1, 1, 7] = -mu * e0
            lower[p + 1, 2, 7] = -mu * e1
    for j in range(n):  # eqs 9-10: min(F, gamma (v_B,j+1 - v_B,j)/|v|) = 0; placeholders: slot = 0
        base = big_k * j
        slot = z[base + 7]
        rate = (z[base + big_k] - z[base]) * rate_scale if j < n - 1 else 0.0
        lam = slot if live[j] else 0.0
        if lam <= rate or not live[j]:
            residual[base + 7] = slot if not live[j] else lam
            diagonal[j, 7, 7] = 1.0
        else:
            residual[base + 7] = rate
            diagonal[j, 7, 0] = -rate_scale
            upper[j, 7, 0] = rate_scale


@_jit
def _matvec(diagonal, upper, lower, x, out):
    n, k = diagonal.shape[0], diagonal.shape[1]
    for j in range(n):
        for a in range(k):
            total = 0.0
            for b in range(k):
                total += diagonal[j, a, b] * x[k * j + b]
            if j > 0:
                for b in range(k):
                    total += lower[j, a, b] * x[k * (j - 1) + b]
            if j < n - 1:
                for b in range(k):
                    total += upper[j, a, b] * x[k * (j + 1) + b]
            out[k * j + a] = total


@_jit
def _matvec_reach(diagonal, upper, lower, reach, x, out):
    """:func:`_matvec` over the rows of ``lower[j]`` below ``reach[j, 0]`` and the columns of ``upper[j]`` below
    ``reach[j, 1]`` only (:func:`_block_factor`: the rest of those blocks is zero)."""
    n, k = diagonal.shape[0], diagonal.shape[1]
    for j in range(n):
        base = k * j
        for a in range(k):
            total = 0.0
            for b in range(k):
                total += diagonal[j, a, b] * x[base + b]
            out[base + a] = total
        if j > 0:
            for a in range(reach[j, 0]):
                total = 0.0
                for b in range(k):
                    total += lower[j, a, b] * x[base - k + b]
                out[base + a] += total
        if j < n - 1:
            for a in range(k):
                total = 0.0
                for b in range(reach[j, 1]):
                    total += upper[j, a, b] * x[base + k + b]
                out[base + a] += total


@_jit
def _rmatvec(diagonal, upper, lower, r, out):
    n, k = diagonal.shape[0], diagonal.shape[1]
    for j in range(n):
        for b in range(k):
            total = 0.0
            for a in range(k):
                total += diagonal[j, a, b] * r[k * j + a]
            if j < n - 1:
                for a in range(k):
                    total += lower[j + 1, a, b] * r[k * (j + 1) + a]
            if j > 0:
                for a in range(k):
                    total += upper[j - 1, a, b] * r[k * (j - 1) + a]
            out[k * j + b] = total


@_jit
def _dense(diagonal, upper, lower, out):
    n, k = diagonal.shape[0], diagonal.shape[1]
    out[:] = 0.0
    for j in range(n):
        for a in range(k):
            for b in range(k):
                out[k * j + a, k * j + b] = diagonal[j, a, b]
                if j > 0:
                    out[k * j + a, k * (j - 1) + b] = lower[j, a, b]
                if j < n - 1:
                    out[k * j + a, k * (j + 1) + b] = upper[j, a, b]


@_jit
def _normal_dense(jacobian, normal, columns, values):
    """``J^T J`` of a dense ``J``, summed row by row over its nonzero entries (a ball's Jacobian is mostly zeros)."""
    size = jacobian.shape[1]
    normal[:] = 0.0
    for r in range(jacobian.shape[0]):
        count = 0
        for c in range(size):
            if jacobian[r, c] != 0.0:
                columns[count] = c
                values[count] = jacobian[r, c]
                count += 1
        for u in range(count):
            cu, vu = columns[u], values[u]
            for v in range(count):
                normal[cu, columns[v]] += vu * values[v]


@_jit
def _lu_solve(matrix, rhs, out):
    """``matrix^-1 rhs`` by LU with partial pivoting (``matrix`` overwritten); False where a pivot is 0."""
    size = rhs.size
    for i in range(size):
        out[i] = rhs[i]
    for col in range(size):
        pivot = col
        best = abs(matrix[col, col])
        for row in range(col + 1, size):
            if abs(matrix[row, col]) > best:
                best = abs(matrix[row, col])
                pivot = row
        if best == 0.0:
            return False
        if pivot != col:
            for c in range(size):
                matrix[col, c], matrix[pivot, c] = matrix[pivot, c], matrix[col, c]
            out[col], out[pivot] = out[pivot], out[col]
        inverse = 1.0 / matrix[col, col]
        for row in range(col + 1, size):
            factor = matrix[row, col] * inverse
            if factor != 0.0:
                for c in range(col + 1, size):
                    matrix[row, c] -= factor * matrix[col, c]
                out[row] -= factor * out[col]
    for row in range(size - 1, -1, -1):
        total = out[row]
        for c in range(row + 1, size):
            total -= matrix[row, c] * out[c]
        out[row] = total / matrix[row, row]
    return True


@_jit
def _normal_band(diagonal, upper, lower, band):
    """``J^T J`` of the block-tridiagonal ``J`` in lower band storage by columns, ``band[col, d] = N[col + d, col]``
    (``d < 3 K``), as :meth:`lowmodel.solvers.BlockTridiagonal.normal_band` (there transposed, for LAPACK)."""
    n, k = diagonal.shape[0], diagonal.shape[1]
    band[:] = 0.0
    for a in range(n):  # block column a: N[a, a], N[a + 1, a] = N[a, a + 1]^T, N[a + 2, a]
        for q in range(k):
            col = k * a + q
            for p in range(q, k):  # N[a, a][p, q] = D_a^T D_a + U_{a-1}^T U_{a-1} + L_{a+1}^T L_{a+1}
                total = 0.0
                for r in range(k):
                    total += diagonal[a, r, p] * diagonal[a, r, q]
                if a > 0:
                    for r in range(k):
                        total += upper[a - 1, r, p] * upper[a - 1, r, q]
                if a < n - 1:
                    for r in range(k):
                        total += lower[a + 1, r, p] * lower[a + 1, r, q]
                band[col, p - q] = total
            if a < n - 1:  # N[a + 1, a][p, q] = (D_a^T U_a + L_{a+1}^T D_{a+1})[q, p]
                for p in range(k):
                    total = 0.0
                    for r in range(k):
                        total += diagonal[a, r, q] * upper[a, r, p]
                        total += lower[a + 1, r, q] * diagonal[a + 1, r, p]
                    band[col, k + p - q] = total
            if a < n - 2:  # N[a + 2, a][p, q] = (L_{a+1}^T U_{a+1})[q, p]
                for p in range(k):
                    total = 0.0
                    for r in range(k):
                        total += lower[a + 1, r, q] * upper[a + 1, r, p]
                    band[col, 2 * k + p - q] = total


_CHAIN_ORDER = np.array([4, 5, 6, 0, 1, 2, 3, 7])  # ball unknowns in the band: phi_1..4, v_B, omega_x, omega_y, F


@_jit
def _normal_band_sparse(diagonal, upper, lower, order, band):
    """``P^T J^T J P`` in lower band storage by columns (``band[col, d] = N[col + d, col]``), summed row by row of
    ``J`` over its nonzero entries only; ``P`` puts unknown ``l`` of ball ``j`` at ``K j + order[l]``.  With
    :data:`_CHAIN_ORDER` the bandwidth of a chain is ``2 K + 1`` (``omega`` of balls ``j - 1`` and ``j + 1`` meet
    in the rows of ball ``j``) instead of ``3 K - 1``."""
    n, k = diagonal.shape[0], diagonal.shape[1]
    width = band.shape[1] - 1
    band[:] = 0.0
    columns = np.empty(3 * k, dtype=np.int64)
    values = np.empty(3 * k)
    for j in range(n):
        for a in range(k):
            count = 0
            for b in range(k):
                if j > 0 and lower[j, a, b] != 0.0:
                    columns[count] = k * (j - 1) + order[b]
                    values[count] = lower[j, a, b]
                    count += 1
                if diagonal[j, a, b] != 0.0:
                    columns[count] = k * j + order[b]
                    values[count] = diagonal[j, a, b]
                    count += 1
                if j < n - 1 and upper[j, a, b] != 0.0:
                    columns[count] = k * (j + 1) + order[b]
                    values[count] = upper[j, a, b]
                    count += 1
            for u in range(count):
                cu, vu = columns[u], values[u]
                for v in range(count):
                    cv = columns[v]
                    if cu >= cv:
                        offset = cu - cv
                        if offset > width:
                            return False
                        band[cv, offset] += vu * values[v]
    return True


@_jit
def _band_solve(band, damping, rhs, factor, out):
    """``(N + damping I)^-1 rhs`` by banded Cholesky (``factor`` scratch like ``band``); False where the matrix
    is not positive definite.  The updates run over the nonzeros of each column only: the factor of a chain
    fills its envelope, about a third of the band (:data:`_CHAIN_ORDER`)."""
    size, width = band.shape[0], band.shape[1] - 1
    nonzero = np.empty(width + 1, dtype=np.int64)
    factor[:] = band
    for j in range(size):
        factor[j, 0] += damping
    for j in range(size):
        pivot = factor[j, 0]
        if not pivot > 0.0:
            return False
        pivot = math.sqrt(pivot)
        factor[j, 0] = pivot
        reach = min(width, size - 1 - j)
        count = 0
        for d in range(1, reach + 1):  # the nonzeros of column j below the diagonal (the envelope of a chain)
            value = factor[j, d]
            if value != 0.0:
                factor[j, d] = value / pivot
                nonzero[count] = d
                count += 1
        for ub in range(count):
            b = nonzero[ub]
            lb = factor[j, b]
            for ua in range(ub, count):
                a = nonzero[ua]
                factor[j + b, a - b] -= factor[j, a] * lb
    for j in range(size):
        out[j] = rhs[j]
    for j in range(size):  # L y = rhs
        out[j] /= factor[j, 0]
        value = out[j]
        if value != 0.0:
            for d in range(1, min(width, size - 1 - j) + 1):
                out[j + d] -= factor[j, d] * value
    for j in range(size - 1, -1, -1):  # L^T x = y
        total = out[j]
        for d in range(1, min(width, size - 1 - j) + 1):
            total -= factor[j, d] * out[j + d]
        out[j] = total / factor[j, 0]
    return True


@_jit
def _block_factor(diagonal, upper, lower, factor, pivots, coupling, reach):  # noqa: C901 - one factorisation loop
    """Block LU of the block-tridiagonal ``J`` (the block Thomas algorithm): ``J = L U`` with ``L`` block lower
    bidiagonal (diagonal ``M_j = D_j - L_j G_{j-1}``, below it ``L_j``) and ``U`` unit block upper bidiagonal
    (above the diagonal ``G_j = M_j^-1 U_j``).  ``factor[j]``: the LU of ``M_j`` with partial pivoting (row
    exchanges ``pivots[j]``), ``coupling[j]``: ``G_j``; ``reach[j]``: the last nonzero row of ``L_j`` and column of
    ``U_j`` plus one (a chain couples balls through rows and columns 0-2 and the force slot only, so the updates
    run over those).  No pivoting across blocks: False where a pivot is 0 (then the caller takes the normal
    equations)."""
    n, k = diagonal.shape[0], diagonal.shape[1]
    for j in range(n):
        rows, columns = 0, 0
        for a in range(k):
            for b in range(k):
                if j > 0 and lower[j, a, b] != 0.0:
                    rows = a + 1
                if j < n - 1 and upper[j, a, b] != 0.0:
                    columns = max(columns, b + 1)
        reach[j, 0] = rows
        reach[j, 1] = columns
        for a in range(k):
            for b in range(k):
                factor[j, a, b] = diagonal[j, a, b]
        if j > 0:
            width = reach[j - 1, 1]
            for a in range(rows):
                for b in range(k):
                    value = lower[j, a, b]
                    if value != 0.0:
                        for c in range(width):
                            factor[j, a, c] -= value * coupling[j - 1, b, c]
        if _slip_eliminable(factor, j):
            if not _slip_factor(factor, pivots, j):
                return False
        elif not _full_factor(factor, pivots, j):
            return False
        for c in range(columns):
            for a in range(k):
                coupling[j, a, c] = upper[j, a, c]
            _block_apply(factor, pivots, j, coupling[j, :, c])
    return True


_SCHUR_ROWS = np.array([0, 1, 2, 7])  # R of the slip elimination: v_B, omega_x, omega_y, F
_ALL_ROWS = np.arange(8)  # every row of a pivot block (K <= 8)
_SLIP_PIVOT = 1e-4  # a slip-angle pivot |d r_i / d phi_i| = |slip speed| below this times its row: the full LU


@_jit
def _slip_eliminable(factor, j):
    """Whether the pivot block ``factor[j]`` (K = 8) has the slip-angle pattern of a chain ball (rows and columns 3-6
    diagonal: the slip kinematics of contact ``i`` hold only its own angle) with every slip-angle pivot at least
    :data:`_SLIP_PIVOT` of the largest other entry of its row (a contact near sticking: the full LU instead)."""
    if factor.shape[1] != 8:
        return False
    for s in range(3, 7):
        largest = 0.0
        for c in range(8):
            if c != s:
                if 3 <= c <= 6 and factor[j, s, c] != 0.0:
                    return False
                largest = max(largest, abs(factor[j, s, c]))
        if not abs(factor[j, s, s]) > _SLIP_PIVOT * largest:
            return False
    return True


@_jit
def _slip_factor(factor, pivots, j):
    """LU of the pivot block with the slip angles eliminated first: with ``R`` = (0, 1, 2, 7) and ``S`` = 3-6 (``S``
    diagonal), ``M = [[A, B], [C, S]]`` gives the 4 x 4 Schur complement ``A - B S^-1 C``, factored with partial
    pivoting (row exchanges within ``R`` in ``pivots[j, 0:4]``, ``pivots[j, 7] = -1`` marks the block).  In
    ``factor[j]``: ``1 / S`` on the slip diagonal, ``S^-1 C`` in the rows of ``S``, ``B`` as it was, the LU in
    ``R x R``.  False where a pivot of the complement is 0 (``M`` is then singular)."""
    for s in range(3, 7):
        inverse = 1.0 / factor[j, s, s]
        factor[j, s, s] = inverse
        for a in range(4):
            ra = _SCHUR_ROWS[a]
            factor[j, s, ra] *= inverse
    for a in range(4):
        ra = _SCHUR_ROWS[a]
        for b in range(4):
            rb = _SCHUR_ROWS[b]
            total = factor[j, ra, rb]
            for s in range(3, 7):
                total -= factor[j, ra, s] * factor[j, s, rb]
            factor[j, ra, rb] = total
    if not _lu(factor, pivots, j, _SCHUR_ROWS, 4):
        return False
    pivots[j, 7] = -1
    return True


@_jit
def _lu(factor, pivots, j, rows, count):
    """LU with partial pivoting of ``factor[j]`` restricted to rows and columns ``rows[:count]`` (in place: the
    multipliers below, ``U`` on and above the diagonal); row exchanges within them in ``pivots[j, :count]`` (positions
    in ``rows``).  False where a pivot is 0."""
    for col in range(count):
        rc = rows[col]
        pivot = col
        best = abs(factor[j, rc, rc])
        for row in range(col + 1, count):
            rr = rows[row]
            if abs(factor[j, rr, rc]) > best:
                best = abs(factor[j, rr, rc])
                pivot = row
        if not best > 0.0:
            return False
        pivots[j, col] = pivot
        if pivot != col:
            rp = rows[pivot]
            for c in range(count):
                q = rows[c]
                factor[j, rc, q], factor[j, rp, q] = factor[j, rp, q], factor[j, rc, q]
        inverse = 1.0 / factor[j, rc, rc]
        for row in range(col + 1, count):
            rr = rows[row]
            multiplier = factor[j, rr, rc] * inverse
            factor[j, rr, rc] = multiplier
            if multiplier != 0.0:
                for c in range(col + 1, count):
                    q = rows[c]
                    factor[j, rr, q] -= multiplier * factor[j, rc, q]
    return True


@_jit
def _lu_apply(factor, pivots, j, rows, count, x):
    """``x[rows[:count]] <- (LU)^-1 x[rows[:count]]`` with the factors of :func:`_lu`."""
    for col in range(count):
        p = pivots[j, col]
        if p != col:
            rc, rp = rows[col], rows[p]
            x[rc], x[rp] = x[rp], x[rc]
    for col in range(count):
        rc = rows[col]
        value = x[rc]
        if value != 0.0:
            for row in range(col + 1, count):
                rr = rows[row]
                x[rr] -= factor[j, rr, rc] * value
    for row in range(count - 1, -1, -1):
        rr = rows[row]
        total = x[rr]
        for c in range(row + 1, count):
            q = rows[c]
            total -= factor[j, rr, q] * x[q]
        x[rr] = total / factor[j, rr, rr]


@_jit
def _full_factor(factor, pivots, j):
    """LU of the pivot block ``factor[j]`` with partial pivoting over all K rows; False where a pivot is 0."""
    return _lu(factor, pivots, j, _ALL_ROWS, factor.shape[1])


@_jit
def _slip_apply(factor, pivots, j, x):
    """``x <- M_j^-1 x`` with the LU of :func:`_slip_factor`."""
    for s in range(3, 7):
        x[s] *= factor[j, s, s]
    for a in range(4):
        ra = _SCHUR_ROWS[a]
        total = x[ra]
        for s in range(3, 7):
            total -= factor[j, ra, s] * x[s]
        x[ra] = total
    _lu_apply(factor, pivots, j, _SCHUR_ROWS, 4, x)
    for s in range(3, 7):
        total = x[s]
        for a in range(4):
            ra = _SCHUR_ROWS[a]
            total -= factor[j, s, ra] * x[ra]
        x[s] = total


@_jit
def _block_apply(factor, pivots, j, x):
    """``x <- M_j^-1 x`` with the LU of :func:`_block_factor` (of :func:`_slip_factor` where ``pivots[j, 7] < 0``:
    ``y = S^-1 x_S``, ``(A - B S^-1 C) u_R = x_R - B y``, ``u_S = y - S^-1 C u_R``)."""
    k = x.size
    if pivots[j, k - 1] < 0:
        _slip_apply(factor, pivots, j, x)
        return
    _lu_apply(factor, pivots, j, _ALL_ROWS, k, x)


@_jit
def _block_solve(factor, pivots, coupling, reach, lower, rhs, out, x):
    """``out = J^-1 rhs`` with the factors of :func:`_block_factor` (``x`` scratch of size K): ``L y = rhs`` ball by
    ball forwards, then ``U out = y`` backwards."""
    n, k = factor.shape[0], factor.shape[1]
    for j in range(n):
        base = k * j
        for a in range(k):
            x[a] = rhs[base + a]
        for a in range(reach[j, 0]):
            total = 0.0
            for b in range(k):
                total += lower[j, a, b] * out[base - k + b]
            x[a] -= total
        _block_apply(factor, pivots, j, x)
        for a in range(k):
            out[base + a] = x[a]
    for j in range(n - 2, -1, -1):
        base = k * j
        width = reach[j, 1]
        for a in range(k):
            total = 0.0
            for c in range(width):
                total += coupling[j, a, c] * out[base + k + c]
            out[base + a] -= total


@_jit
def _column_norm_max(diagonal, upper, lower):
    """The largest squared column norm of the block-tridiagonal ``J``: the largest diagonal entry of ``J^T J``."""
    n, k = diagonal.shape[0], diagonal.shape[1]
    largest = 0.0
    for j in range(n):
        for b in range(k):
            total = 0.0
            for a in range(k):
                total += diagonal[j, a, b] * diagonal[j, a, b]
                if j < n - 1:
                    total += lower[j + 1, a, b] * lower[j + 1, a, b]
                if j > 0:
                    total += upper[j - 1, a, b] * upper[j - 1, a, b]
            largest = max(largest, total)
    return largest


@_inline
def _evaluate(evaluation, z, state):
    """:func:`chain_terms` at ``z`` into ``state`` (residual, diagonal, upper, lower): the evaluation of
    :func:`lowmodel.newton_kernels.levenberg_marquardt`."""
    n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, slip, table = evaluation
    residual, diagonal, upper, lower = state
    chain_terms(z, n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, residual, diagonal,
                upper, lower, slip, table)
    return CONVERGED


@_inline
def _dense_prepare(steps, state, _first):
    """Below :data:`SPARSE_BALLS` balls: the dense normal equations ``J^T J`` (summed over ``J``'s nonzeros) and
    ``-J^T r``; no plain Newton step."""
    jacobian, normal, _, columns, values, gradient, rhs = steps
    residual, diagonal, upper, lower = state
    _dense(diagonal, upper, lower, jacobian)
    _normal_dense(jacobian, normal, columns, values)
    diagonal_max = -np.inf
    for i in range(residual.size):
        diagonal_max = max(diagonal_max, normal[i, i])
    _rmatvec(diagonal, upper, lower, residual, gradient)
    for i in range(residual.size):
        rhs[i] = -gradient[i]
    return diagonal_max, False


@_inline
def _dense_step(steps, _state, damping, _plain, step):
    """``(J^T J + damping I) dx = -J^T r`` by LU with partial pivoting; False at a zero pivot."""
    normal, system, rhs = steps[1], steps[2], steps[6]
    system[:] = normal
    for i in range(rhs.size):
        system[i, i] += damping
    return _lu_solve(system, rhs, step)


@_inline
def _dense_multiply(_steps, state, step, _plain, change):
    """``change = J step``."""
    _matvec(state[1], state[2], state[3], step, change)


@_inline
def _banded_prepare(steps, state, first):
    """From :data:`SPARSE_BALLS` balls on: the block LU of ``J`` (the plain Newton step offered where it has no zero
    pivot) and, where ``first``, the largest column norm; the banded normal equations are formed where a step needs
    them (:func:`_banded_step`)."""
    blocks, pivots, coupling, reach, formed = steps[:5]
    diagonal, upper, lower = state[1], state[2], state[3]
    formed[0] = False
    factored = _block_factor(diagonal, upper, lower, blocks, pivots, coupling, reach)
    return (_column_norm_max(diagonal, upper, lower) if first else 0.0), factored


@_inline
def _banded_step(steps, state, damping, plain, step):
    """The plain step ``J dx = -r`` by the block LU of :func:`_banded_prepare`; else ``(J^T J + damping I) dx =
    -J^T r`` in band storage (the permutation :data:`_CHAIN_ORDER`) by Cholesky; False where there is none."""
    blocks, pivots, coupling, reach, formed, band, factor, permuted, position, solution, scratch, gradient, rhs = steps
    residual, diagonal, upper, lower = state
    size = residual.size
    if plain:
        for i in range(size):
            solution[i] = -residual[i]
        _block_solve(blocks, pivots, coupling, reach, lower, solution, step, scratch)
        return True
    if not formed[0]:
        if not _normal_band_sparse(diagonal, upper, lower, _CHAIN_ORDER, band):
            return False  # not a B2B chain's pattern (cannot happen for eqs 4-10)
        _rmatvec(diagonal, upper, lower, residual, gradient)
        for i in range(size):
            rhs[i] = -gradient[i]
        formed[0] = True
    for i in range(size):
        permuted[position[i]] = rhs[i]
    solved = _band_solve(band, damping, permuted, factor, solution)
    for i in range(size):
        step[i] = solution[position[i]]
    return solved


@_inline
def _banded_multiply(steps, state, step, plain, change):
    """``change = J step`` (after a plain step over the reach of the block LU's blocks only)."""
    if plain:
        _matvec_reach(state[1], state[2], state[3], steps[3], step, change)
    else:
        _matvec(state[1], state[2], state[3], step, change)


# the statuses of lowmodel.newton_kernels in this module's (an iteration limit and a non-finite residual alike)
_STATUS = np.array([CONVERGED, NOT_CONVERGED, NOT_CONVERGED, NOT_CONVERGED, STATIONARY, NO_DESCENT])


@_jit
def newton(z, n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, tolerance, max_iterations,
           residual, work):
    """:func:`lowmodel.solvers.newton` on :func:`chain_terms` from ``z`` (overwritten with the last iterate);
    the residual at it into ``residual`` (n K,).  Returns ``(status, iterations, max |residual|)``.

    The loop is :func:`lowmodel.newton_kernels.levenberg_marquardt`; its steps here: below :data:`SPARSE_BALLS` balls
    the dense normal equations by LU; from there on each iteration first tries the plain Newton step ``J dx = -r`` by
    the block LU of ``J`` (:func:`_block_factor`, O(n K^3) with small constants), accepted by the same gain test as a
    Levenberg-Marquardt step (and only where ``max|r + J dx| <= NEWTON_DEFECT max|r|``,
    :data:`lowmodel.newton_kernels.NEWTON_DEFECT`); where the LU has a zero pivot or the step is refused, the
    Levenberg-Marquardt steps of :func:`lowmodel.solvers.newton` follow from the same damping (banded Cholesky of the
    permuted normal equations).  The damping follows Nielsen's update after either step.  The convergence test
    (``max|r| <= tolerance`` at an evaluated point) is the same either way.

    ``work``: scratch of at least :func:`workspace_size` floats for the eight (n, K, K) block arrays of the sparse
    path, reused between solves (fresh memory of that size costs more page faults than the solve's LU); smaller
    (e.g. empty): allocated here."""
    size = n * big_k
    count = n * big_k * big_k
    if n >= SPARSE_BALLS and work.size >= 8 * count:
        blocks = work[0:8 * count].reshape((8, n, big_k, big_k))
        blocks[0:6] = 0.0
    else:  # the dense path needs no factors (blocks 6, 7)
        blocks = np.zeros((8 if n >= SPARSE_BALLS else 6, n, big_k, big_k))
    diagonal, upper, lower, trial_diagonal, trial_upper, trial_lower = (blocks[0], blocks[1], blocks[2], blocks[3],
                                                                        blocks[4], blocks[5])
    evaluation = (n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, np.empty((n, 4)),
                  np.empty((3, 2)))
    state = (residual, diagonal, upper, lower)
    trial_state = (np.empty(size), trial_diagonal, trial_upper, trial_lower)
    limits, weight = np.full(size, tolerance), np.ones(size)
    if n < SPARSE_BALLS:
        steps = (np.empty((size, size)), np.empty((size, size)), np.empty((size, size)), np.empty(size, dtype=np.int64),
                 np.empty(size), np.empty(size), np.empty(size))
        status, iterations, norm, _ = levenberg_marquardt(
            _evaluate, _dense_prepare, _dense_step, _dense_multiply, ordered_dot, evaluation, steps, z, state,
            trial_state, limits, weight, max_iterations, residual)
        return _STATUS[status], iterations, norm
    position = np.empty(size, dtype=np.int64)  # where unknown i sits in the band
    for j in range(n):
        for b in range(big_k):
            position[big_k * j + b] = big_k * j + _CHAIN_ORDER[b]
    steps = (blocks[6], np.empty((n, big_k), dtype=np.int64), blocks[7], np.empty((n, 2), dtype=np.int64),
             np.zeros(1, dtype=np.bool_), np.empty((size, 2 * big_k + 2)), np.empty((size, 2 * big_k + 2)),
             np.empty(size), position, np.empty(size), np.empty(big_k), np.empty(size), np.empty(size))
    status, iterations, norm, _ = levenberg_marquardt(
        _evaluate, _banded_prepare, _banded_step, _banded_multiply, ordered_dot, evaluation, steps, z, state,
        trial_state, limits, weight, max_iterations, residual)
    return _STATUS[status], iterations, norm


def workspace_size(n_balls: int) -> int:
    """Floats of the scratch ``work`` of :func:`newton` (and :func:`solve_chain_cases`) for chains of ``n_balls``
    balls: eight (n, 8, 8) block arrays from :data:`SPARSE_BALLS` balls on, none below."""
    return 8 * 64 * n_balls if n_balls >= SPARSE_BALLS else 0


@_jit
def solve_branch(z, n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, tolerance,
                 max_iterations, attempts, residual, work):
    """:func:`newton`, then the physical branch: a converged point with a contact slip speed below
    ``-1e3 tolerance`` is restarted with that slip angle turned by pi, at most ``attempts`` runs sharing
    ``max_iterations`` (:func:`lowmodel.solvers.solve_with_restarts`).  ``z`` is overwritten; returns
    ``(status, iterations, max |residual|)``."""
    total = 0
    norm = np.inf
    for _ in range(attempts):
        if total < max_iterations:
            status, iterations, norm = newton(z, n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y,
                                              flat, tolerance, max_iterations - total, residual, work)
            if status != CONVERGED:
                return status, total + iterations, norm
        else:  # the budget is spent: the restart point counts only if it solves the system as it is
            diagonal = np.zeros((n, big_k, big_k))
            chain_terms(z, n, big_k, geometry, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat, residual,
                        diagonal, np.zeros((n, big_k, big_k)), np.zeros((n, big_k, big_k)), np.empty((n, 4)),
                        np.empty((3, 2)))
            norm = np.abs(residual).max() if residual.size else 0.0
            if not norm <= tolerance:
                return NOT_CONVERGED, total, norm
            iterations = 0
        total += iterations
        wrong = False
        for j in range(n):
            base = big_k * j
            for i in range(4):
                gi = geometry[j, i]
                nx, ny, arm = gi[NX], gi[NY], gi[ARM]
                slide = z[base] + ny * z[base + 1] + (-nx) * z[base + 2] - gi[TOP]
                spin = (-nx * arm) * z[base + 1] + (-ny * arm) * z[base + 2]
                phi = z[base + 3 + i]
                if slide * math.sin(phi) + spin * math.cos(phi) < -1e3 * tolerance:
                    wrong = True
                    z[base + 3 + i] = phi + math.pi
        if not wrong:
            return CONVERGED, total, norm
    return REJECTED, total, norm


@_jit
def _case_geometry(geometry, case, n, reference, out):
    """The data of case ``case`` (balls ``case n .. case n + n - 1`` of ``geometry``) into ``out`` (n, 4, FIELDS),
    its normal forces per unit ``reference`` [N] (as ball_terms: ``F_i / F_ref``)."""
    for j in range(n):
        for i in range(4):
            for f in range(FIELDS):
                out[j, i, f] = geometry[case * n + j, i, f]
            out[j, i, LOAD] = geometry[case * n + j, i, LOAD] / reference


@_jit
def _guess(n, geometry, velocity, x):
    """Rolling about x at v/2 with its slip angles, the start of every solve
    (:func:`lowmodel.linear_bearing.ball.initial_guess`), into ``x`` (n, 7)."""
    direction = math.copysign(1.0, velocity)
    for j in range(n):
        cos_sum = 0.0
        for i in range(4):
            cos_sum += math.cos(geometry[j, i, ANGLE])
        x[j, 0] = 0.5 * direction
        x[j, 1] = 0.5 * direction / (cos_sum / 4.0)
        x[j, 2] = 0.0
        for i in range(4):
            gi = geometry[j, i]
            slide = x[j, 0] + gi[NY] * x[j, 1] + (-gi[NX]) * x[j, 2] - gi[TOP]
            spin = (-gi[NX] * gi[ARM]) * x[j, 1] + (-gi[NY] * gi[ARM]) * x[j, 2]
            x[j, 3 + i] = math.atan2(slide, spin)


@_jit
def _state(n, z, big_k, geometry, scalars, nodes_x, mid_x, n_mid_y, flat, out_ball, out_contact):
    """The fields of :func:`lowmodel.linear_bearing.ball.ball_state` [SI] of converged balls; returns the input
    power [W].  ``out_ball`` (n, 4): v_B, omega_x, omega_y, epsilon; ``out_contact`` (n, 4, 7): spin, slide,
    c/a, friction force, friction moment, eq A6 loss, power loss.  ``scalars``: v, R_B, mu, F_ref."""
    velocity, radius, mu, reference = scalars[0], scalars[1], scalars[2], scalars[3]
    speed = abs(velocity)
    mu_f = mu * reference
    terms = np.empty((4, 6))
    top = 0.0
    for j in range(n):
        base = big_k * j
        contact_terms(z[base:base + 7], geometry[j], nodes_x, mid_x, n_mid_y, flat, terms)
        ball_velocity = z[base] * speed
        out_ball[j, 0] = ball_velocity
        out_ball[j, 1] = z[base + 1] * speed / radius
        out_ball[j, 2] = z[base + 2] * speed / radius
        out_ball[j, 3] = 2.0 * ball_velocity / velocity - 1.0
        for i in range(4):
            phi = z[base + 3 + i]
            spin = terms[i, 1] * speed / geometry[j, i, SEMI_MAJOR]
            slide = terms[i, 0] * speed
            if abs(math.cos(phi)) > 1e-15:
                c_over_a = math.tan(phi)
            else:
                c_over_a = math.copysign(np.inf, math.sin(phi)) if math.sin(phi) != 0.0 else 0.0 * np.inf
            force = terms[i, 3] * mu_f
            moment = terms[i, 4] * mu_f * radius
            out_contact[j, i, 0] = spin
            out_contact[j, i, 1] = slide
            out_contact[j, i, 2] = c_over_a
            out_contact[j, i, 3] = force
            out_contact[j, i, 4] = moment
            out_contact[j, i, 5] = terms[i, 5] * mu_f * speed
            out_contact[j, i, 6] = -(force * slide - moment * spin)  # power of the tractions on the slip field
            if i >= 2:  # TR, TL: the moving groove
                top += force
    return velocity * top


@_jit
def _free(n, x, geometry, scalars, nodes_x, mid_x, n_mid_y, flat, tolerance, max_iterations):
    """Every ball alone from ``x`` (n, 7, overwritten): ``(status, largest iterations, largest residual)``."""
    live = np.zeros(1, dtype=np.bool_)
    residual = np.empty(7)
    worst_iterations, worst_residual = 0, 0.0
    for j in range(n):
        status, iterations, norm = solve_branch(x[j], 1, 7, geometry[j:j + 1], live, scalars[2], 0.0, nodes_x,
                                                mid_x, n_mid_y, flat, tolerance, max_iterations, 4, residual,
                                                np.empty(0))
        if status != CONVERGED:
            return status, iterations, norm
        worst_iterations = max(worst_iterations, iterations)
        worst_residual = max(worst_residual, norm)
    return CONVERGED, worst_iterations, worst_residual


@_jit
def solve_free_cases(geometry, balls_per_case, scalars, tolerance, max_iterations, nodes_x, mid_x, n_mid_y, flat,
                     status, iterations, residual, out_ball, out_contact, input_power):
    """``m`` cases of ``n`` balls, every ball alone (lin2019 eq 4; :func:`lowmodel.linear_bearing.ball.solve`):
    ``geometry`` (m n, 4, FIELDS) (field LOAD: the normal force [N]), ``scalars`` (m, 4) v, R_B, mu, F_ref; per case
    ``status``, largest
    ``iterations`` and ``residual``, the state (:func:`_state`) and ``input_power`` (m,)."""
    m, n = geometry.shape[0] // balls_per_case, balls_per_case
    x = np.empty((n, 7))
    g = np.empty((n, 4, FIELDS))
    for c in range(m):
        _case_geometry(geometry, c, n, scalars[c, 3], g)
        _guess(n, g, scalars[c, 0], x)
        status[c], iterations[c], residual[c] = _free(n, x, g, scalars[c], nodes_x, mid_x, n_mid_y, flat,
                                                      tolerance, max_iterations)
        if status[c] == CONVERGED:
            input_power[c] = _state(n, x.reshape(-1), 7, g, scalars[c], nodes_x, mid_x, n_mid_y, flat,
                                    out_ball[c], out_contact[c])


@_jit
def solve_chain_cases(geometry, balls_per_case, live, scalars, rate_scale, tolerance, max_iterations, nodes_x, mid_x,
                      n_mid_y, flat, status, iterations, residual, out_ball, out_contact, out_pair, input_power,
                      work):
    """``m`` open B2B chains of ``n`` balls (:func:`lowmodel.linear_bearing.b2b.solve`'s first two attempts: the
    coupled Newton from rolling at v/2, else from every ball solved alone), ``live`` (n,) the touching pairs;
    the complementarity check of :func:`lowmodel.b2b_chain.chain_forces` (status :data:`VIOLATED`); per case
    the state (:func:`_state`), ``out_pair`` (m, n - 1, 3): F_B2B [N], B2B slip [m/s], B2B loss [W]; ``work``
    the scratch of :func:`newton` (:func:`workspace_size` floats; smaller: allocated per solve)."""
    m, n = geometry.shape[0] // balls_per_case, balls_per_case
    big_k = 8
    x = np.empty((n, 7))
    z = np.empty(n * big_k)
    chain_residual = np.empty(n * big_k)
    g = np.empty((n, 4, FIELDS))
    for c in range(m):
        scalar = scalars[c]
        _case_geometry(geometry, c, n, scalar[3], g)
        mu = scalar[2]
        _guess(n, g, scalar[0], x)
        for j in range(n):
            z[big_k * j:big_k * j + 7] = x[j]
            z[big_k * j + 7] = 0.0
        state, count, norm = solve_branch(z, n, big_k, g, live, mu, rate_scale, nodes_x, mid_x, n_mid_y, flat,
                                          tolerance, max_iterations, 4, chain_residual, work)
        if state != CONVERGED:  # from every ball solved on its own
            state, free_count, norm = _free(n, x, g, scalar, nodes_x, mid_x, n_mid_y, flat, tolerance,
                                            max_iterations)
            if state == CONVERGED:
                for j in range(n):
                    z[big_k * j:big_k * j + 7] = x[j]
                    z[big_k * j + 7] = 0.0
                state, count, norm = solve_branch(z, n, big_k, g, live, mu, rate_scale, nodes_x, mid_x, n_mid_y,
                                                  flat, tolerance, max_iterations, 4, chain_residual, work)
                count += free_count
        status[c], iterations[c], residual[c] = state, count, norm
        if state != CONVERGED:
            continue
        violation = 0.0  # eqs 9-10 at the converged point (touching pairs): F >= 0, separation rate >= 0
        for p in range(n - 1):
            if live[p]:
                force = z[big_k * p + 7]
                rate = (z[big_k * (p + 1)] - z[big_k * p]) * rate_scale
                violation = max(violation, -force, -rate)
        if violation > 10.0 * tolerance:
            status[c], residual[c] = VIOLATED, violation
            continue
        input_power[c] = _state(n, z, big_k, g, scalar, nodes_x, mid_x, n_mid_y, flat, out_ball[c], out_contact[c])
        speed = abs(scalar[0])
        for p in range(n - 1):
            force = 0.0
            if live[p]:
                force = z[big_k * p + 7]
                rate = (z[big_k * (p + 1)] - z[big_k * p]) * rate_scale
                if force <= rate:  # the F = 0 branch: exactly zero
                    force = 0.0
                force = max(force, 0.0)
            u0 = z[big_k * p + 1] + z[big_k * (p + 1) + 1]
            u1 = z[big_k * p + 2] + z[big_k * (p + 1) + 2]
            b2b_force = force * mu * scalar[3]
            slip = math.sqrt(u0 * u0 + u1 * u1) * speed  # eq 5
            out_pair[c, p, 0] = b2b_force
            out_pair[c, p, 1] = slip
            out_pair[c, p, 2] = mu * b2b_force * slip  # eq 7


def warm_up() -> None:
    """Compile (or load from numba's disk cache) the kernels with the argument types the models pass."""
    friction_angle_at(np.array([0.5]))  # the default map's patches
    ball_fast.warm_up(sys.modules[__name__])
