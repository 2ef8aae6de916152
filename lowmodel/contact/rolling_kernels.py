"""Compiled (numba) twin of the prepared dense rolling solve: the numpy code of
:mod:`lowmodel.contact.rolling_newton` as loops (docs/rolling_contact.md, 'Solver' and 'Costs').

Loaded by :func:`lowmodel.kernels.load` (never imported by ``import ballbench.lowmodel``); used for prepared
dense problems (``(c C)^-1`` built, up to :data:`lowmodel.contact.rolling_newton.DIRECT_CELLS` contact cells),
where a solve of some hundred cells is otherwise some hundreds of small numpy calls.  The same algorithm, step
for step:

* :func:`marching_start`: :meth:`TangentialProblem.marching_start` (the local solution marched from the leading
  edge with the traction bound);
* :func:`newton`: :func:`lowmodel.contact.rolling_newton.semismooth_newton` on ``F(p) = p - Proj_g(p - c s(p))``
  with the generalised Jacobian ``J = (I - D) + c D C``, each step through the smaller of the two low-rank forms
  of :func:`lowmodel.contact.rolling_newton.low_rank_step` (Sherman-Morrison-Woodbury, Golub & Van Loan 2013,
  Sec 2.1.4; LU with partial pivoting by LAPACK through ``np.linalg.solve``) and the same backtracking on
  ``|F|^2``;
* :func:`check_values`: the values of :func:`lowmodel.contact.rolling_newton.check_solution` (Coulomb bound,
  stick, slip direction, dissipation) from the traction alone; the caller compares them with the tolerance and
  raises naming the check.

Arrays: ``matrix`` ``C`` (2n, 2n) on the contact cells (x, y interleaved per cell), ``inverse`` ``(c C)^-1``,
``g`` (n,) the traction bound, ``w`` (n, 2) the rigid slip, ``p`` (n, 2) the traction.
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["marching_start", "newton", "check_values", "warm_up", "CONVERGED", "NOT_CONVERGED"]

CONVERGED, NOT_CONVERGED = 0, 1

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")


@_jit
def marching_start(w, flexibility, g_lines, line_of, position):
    """:meth:`TangentialProblem.marching_start`: ``p`` (n, 2) marched along ``-x`` on every grid line."""
    n_lines, nx = g_lines.shape
    n = w.shape[0]
    scaled = np.zeros((n_lines, nx, 2))
    for k in range(n):
        scaled[line_of[k], position[k], 0] = w[k, 0] / flexibility
        scaled[line_of[k], position[k], 1] = w[k, 1] / flexibility
    lines = np.zeros((n_lines, nx, 2))
    for line in range(n_lines):
        u0 = 0.0
        u1 = 0.0
        for i in range(nx - 1, -1, -1):
            t0 = u0 - scaled[line, i, 0]
            t1 = u1 - scaled[line, i, 1]
            norm = math.hypot(t0, t1)
            limit = g_lines[line, i]
            if norm > limit:
                factor = limit / (norm if norm > 0.0 else 1.0)
                t0 *= factor
                t1 *= factor
            lines[line, i, 0] = u0 = t0
            lines[line, i, 1] = u1 = t1
    p = np.empty((n, 2))
    for k in range(n):
        p[k, 0] = lines[line_of[k], position[k], 0]
        p[k, 1] = lines[line_of[k], position[k], 1]
    return p


@_jit
def _residual(matrix, c, g, w, p, F, z, norm, sliding, scale):
    # F(p), z = p - c s, |z|, the slip mask and min(1, g/|z|) (TangentialProblem.residual); returns sum F^2
    n = g.size
    s = matrix @ p.reshape(-1)
    total = 0.0
    for k in range(n):
        z0 = p[k, 0] - c * (w[k, 0] + s[2 * k])
        z1 = p[k, 1] - c * (w[k, 1] + s[2 * k + 1])
        z[k, 0] = z0
        z[k, 1] = z1
        r = math.hypot(z0, z1)
        norm[k] = r
        if r > g[k]:
            sliding[k] = True
            scale[k] = g[k] / r
        else:
            sliding[k] = False
            scale[k] = 1.0
        f0 = p[k, 0] - z0 * scale[k]
        f1 = p[k, 1] - z1 * scale[k]
        F[k, 0] = f0
        F[k, 1] = f1
        total += f0 * f0 + f1 * f1
    return total


@_jit
def _max_abs(F):
    value = 0.0
    for k in range(F.shape[0]):
        value = max(value, abs(F[k, 0]), abs(F[k, 1]))
    return value


@_jit
def _woodbury_step(inverse, F, z, norm, scale, slip):
    # lowmodel.contact.rolling_newton.woodbury_step: J = c C + U W changed in the slip cells' rows only
    n = F.shape[0]
    b = -F.reshape(-1)
    x0 = inverse @ b
    m = slip.size
    if m == 0:
        return x0
    k = 2 * m
    rows = np.empty(k, dtype=np.int64)
    for i in range(m):
        rows[2 * i] = 2 * slip[i]
        rows[2 * i + 1] = 2 * slip[i] + 1
    E = np.empty((m, 2, 2))  # E = I - D in the slip cells
    for i in range(m):
        cell = slip[i]
        u0 = z[cell, 0] / norm[cell]
        u1 = z[cell, 1] / norm[cell]
        s = scale[cell]
        E[i, 0, 0] = 1.0 - s * (1.0 - u0 * u0)
        E[i, 1, 1] = 1.0 - s * (1.0 - u1 * u1)
        E[i, 0, 1] = E[i, 1, 0] = s * u0 * u1
    capacitance = np.empty((k, k))
    rhs = np.empty(k)
    for i in range(m):
        for a in range(2):
            e0 = E[i, a, 0]
            e1 = E[i, a, 1]
            r0 = rows[2 * i]
            r1 = rows[2 * i + 1]
            for col in range(k):
                x_0 = inverse[r0, rows[col]] - (1.0 if col == 2 * i else 0.0)
                x_1 = inverse[r1, rows[col]] - (1.0 if col == 2 * i + 1 else 0.0)
                capacitance[2 * i + a, col] = e0 * x_0 + e1 * x_1
            capacitance[2 * i + a, 2 * i + a] += 1.0
            rhs[2 * i + a] = e0 * (x0[r0] - b[r0]) + e1 * (x0[r1] - b[r1])
    y = np.linalg.solve(capacitance, rhs)
    step = x0.copy()
    for row in range(2 * n):
        acc = 0.0
        for col in range(k):
            acc += inverse[row, rows[col]] * y[col]
        step[row] -= acc
    return step


@_jit
def _identity_step(matrix, c, F, z, norm, scale, slip, stick):
    # lowmodel.contact.rolling_newton.identity_step: J = I + U W, two columns per stick cell, one per slip cell
    n = F.shape[0]
    b = -F.reshape(-1)
    ms = slip.size
    k = 2 * stick.size
    m = k + ms
    rows = np.empty(k, dtype=np.int64)
    for i in range(stick.size):
        rows[2 * i] = 2 * stick[i]
        rows[2 * i + 1] = 2 * stick[i] + 1
    t0 = np.empty(ms)
    t1 = np.empty(ms)
    for j in range(ms):
        cell = slip[j]
        t0[j] = -z[cell, 1] / norm[cell]
        t1[j] = z[cell, 0] / norm[cell]
    W = np.empty((m, 2 * n))
    for r in range(k):
        row = rows[r]
        for col in range(2 * n):
            W[r, col] = c * matrix[row, col]
        W[r, row] -= 1.0
    for j in range(ms):
        cell = slip[j]
        s = scale[cell]
        a0 = c * s * t0[j]
        a1 = c * s * t1[j]
        for col in range(2 * n):
            W[k + j, col] = a0 * matrix[2 * cell, col] + a1 * matrix[2 * cell + 1, col]
        W[k + j, 2 * cell] -= s * t0[j]
        W[k + j, 2 * cell + 1] -= s * t1[j]
    capacitance = np.empty((m, m))
    for r in range(m):
        for col in range(k):
            capacitance[r, col] = W[r, rows[col]]
        for j in range(ms):
            cell = slip[j]
            capacitance[r, k + j] = W[r, 2 * cell] * t0[j] + W[r, 2 * cell + 1] * t1[j]
        capacitance[r, r] += 1.0
    y = np.linalg.solve(capacitance, W @ b)
    for r in range(k):
        b[rows[r]] -= y[r]
    for j in range(ms):
        cell = slip[j]
        b[2 * cell] -= t0[j] * y[k + j]
        b[2 * cell + 1] -= t1[j] * y[k + j]
    return b


@_jit
def newton(matrix, inverse, c, g, w, gmax, tolerance, max_iterations, p):
    """:func:`lowmodel.contact.rolling_newton.semismooth_newton` from the start ``p`` (n, 2) (overwritten):
    returns ``(p, iterations, residual, status)``, status :data:`CONVERGED` or :data:`NOT_CONVERGED`."""
    n = g.size
    F = np.empty((n, 2))
    z = np.empty((n, 2))
    norm = np.empty(n)
    sliding = np.empty(n, dtype=np.bool_)
    scale = np.empty(n)
    tF = np.empty((n, 2))
    tz = np.empty((n, 2))
    tnorm = np.empty(n)
    tsliding = np.empty(n, dtype=np.bool_)
    tscale = np.empty(n)
    trial = np.empty((n, 2))
    norm_F = _residual(matrix, c, g, w, p, F, z, norm, sliding, scale)
    residual = _max_abs(F) / gmax
    for iteration in range(1, max_iterations + 1):
        if residual <= tolerance:
            return p, iteration - 1, residual, CONVERGED
        slipping = 0
        for cell in range(n):
            if sliding[cell]:
                slipping += 1
        slip = np.empty(slipping, dtype=np.int64)
        stick = np.empty(n - slipping, dtype=np.int64)
        a = 0
        for cell in range(n):
            if sliding[cell]:
                slip[a] = cell
                a += 1
            else:
                stick[cell - a] = cell
        if 2 * slipping <= 2 * (n - slipping) + slipping:
            step = _woodbury_step(inverse, F, z, norm, scale, slip)
        else:
            step = _identity_step(matrix, c, F, z, norm, scale, slip, stick)
        t = 1.0
        trial_F = 0.0
        for _ in range(8):  # backtracking on |F|^2: the first step that decreases it
            for cell in range(n):
                trial[cell, 0] = p[cell, 0] + t * step[2 * cell]
                trial[cell, 1] = p[cell, 1] + t * step[2 * cell + 1]
            trial_F = _residual(matrix, c, g, w, trial, tF, tz, tnorm, tsliding, tscale)
            if trial_F <= (1.0 - 1e-4 * t) * norm_F:
                break
            t *= 0.5
        p, trial = trial, p
        F, tF = tF, F
        z, tz = tz, z
        norm, tnorm = tnorm, norm
        sliding, tsliding = tsliding, sliding
        scale, tscale = tscale, scale
        norm_F = trial_F
        residual = _max_abs(F) / gmax
    if residual <= tolerance:
        return p, max_iterations, residual, CONVERGED
    return p, max_iterations, residual, NOT_CONVERGED


@_jit
def check_values(matrix, c, g, w, gmax, p, limit):
    """The slip ``s`` (n, 2), the stick mask (n,) and the four values of
    :func:`lowmodel.contact.rolling_newton.check_solution` (Coulomb bound, stick, slip direction (0 without a
    moving slip cell), dissipation), each to be ``<= limit``."""
    n = g.size
    s = (matrix @ p.reshape(-1)).reshape(n, 2)
    stick = np.empty(n, dtype=np.bool_)
    bound = -np.inf
    stick_slip = 0.0
    direction = -np.inf
    work = np.inf
    moving_any = False
    for k in range(n):
        s0 = w[k, 0] + s[k, 0]
        s1 = w[k, 1] + s[k, 1]
        s[k, 0] = s0
        s[k, 1] = s1
        magnitude = math.hypot(p[k, 0], p[k, 1])
        slip_norm = math.hypot(s0, s1)
        sliding = math.hypot(p[k, 0] - c * s0, p[k, 1] - c * s1) > g[k]
        stick[k] = not sliding
        bound = max(bound, magnitude - g[k])
        if not sliding:
            stick_slip = max(stick_slip, c * slip_norm)
        elif c * slip_norm > limit * gmax:
            moving_any = True
            d0 = p[k, 0] + g[k] * s0 / slip_norm
            d1 = p[k, 1] + g[k] * s1 / slip_norm
            direction = max(direction, math.hypot(d0, d1))
        work = min(work, -(p[k, 0] * s0 + p[k, 1] * s1) * c)
    values = np.empty(4)
    values[0] = bound / gmax
    values[1] = stick_slip / gmax
    values[2] = direction / gmax if moving_any else 0.0
    values[3] = max(0.0, -work) / gmax ** 2
    return s, stick, values


def warm_up() -> None:
    """Compile (or load from numba's disk cache) the kernels with the argument types the solver passes
    (the prepared ``C`` and ``(c C)^-1`` are read-only)."""
    n = 4
    matrix = np.eye(2 * n) + 0.1 * np.ones((2 * n, 2 * n))
    inverse = np.linalg.inv(matrix)
    matrix.setflags(write=False)
    inverse.setflags(write=False)
    g = np.array([0.5, 1.0, 1.0, 0.5])
    w = np.array([[0.3, 0.0], [0.3, 0.1], [0.3, 0.0], [0.3, -0.1]])
    g_lines = np.array([[0.5, 1.0], [1.0, 0.5]])
    g_lines.setflags(write=False)
    index = np.array([0, 0, 1, 1], dtype=np.int64)
    position = np.array([0, 1, 0, 1], dtype=np.int64)
    p = marching_start(w, 1.0, g_lines, index, position)
    p, _, _, _ = newton(matrix, inverse, 1.0, g, w, 1.0, 1e-10, 60, p)
    check_values(matrix, 1.0, g, w, 1.0, p, 1e-7)
