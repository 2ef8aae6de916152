"""Compiled (numba) Levenberg-Marquardt loop of the compiled Newtons: :func:`lowmodel.solvers.newton` as one loop.

:func:`levenberg_marquardt` is the loop of :func:`lowmodel.solvers.newton` (the gain ratio of actual to predicted
decrease of ``|r|^2``, Nielsen's damping update, the step refused and the damping raised, the same failure statuses)
for the compiled solves; what differs between them is passed in as jitted functions, on which numba specialises the
loop (each caller compiles its own loop, with direct calls):

* ``evaluate(evaluation, x, state) -> int``: the residual (rows weighted) and the Jacobian at ``x`` into ``state``
  (a tuple, ``state[0]`` the residual), ``evaluation`` the caller's data of the equations; :data:`CONVERGED` (0), or
  a status of the caller's own that the loop returns as it is (an evaluation handed back:
  :data:`lowmodel.screw.ball_kernels.FALLBACK`).
* ``prepare(steps, state, first) -> (diagonal_max, plain)``: what the steps of an iteration need from the Jacobian
  (the normal equations, a factorisation; ``steps`` the caller's scratch of its linear algebra); the largest diagonal
  entry of ``J^T J`` (read where ``first``: it sets the initial damping ``1e-8 diagonal_max``), and whether a plain
  Newton step is offered first.
* ``solve(steps, state, damping, plain, step) -> bool``: the step, ``J dx = -r`` where ``plain``, else
  ``(J^T J + damping I) dx = -J^T r``; False where there is none (a singular or indefinite matrix).
* ``multiply(steps, state, step, plain, change)``: ``change = J step``.
* ``dot(a, b)``: ``sum a_i b_i`` in the caller's order of operations (:func:`blas_dot`: BLAS's ``ddot``, as numpy's
  ``a @ b``; :func:`ordered_dot`: one term after the other), so that each caller keeps its numbers to the last bit.

A plain Newton step (the linear-bearing chain's block LU of ``J``, docs/speed.md 'The chain's Newton step') is taken
by the same gain test where ``max|r + J dx| <= NEWTON_DEFECT max|r|``; refused, the Levenberg-Marquardt step at the
same damping follows.  The loop is inlined into each caller (``inline="always"``, numba's own IR): a jitted function
passed as a value to a function that is compiled apart is lowered as the address of a Python object, which numba's
disk cache refuses (``cache=True`` would then recompile every kernel in every process); inlined, the functions are
resolved where the caller names them, and the caller is cached as before.  The callers inline their small steps too:
every array taken out of the tuples costs numba a reference count (an atomic add and subtract) per call, which
inlining keeps down; what remains is felt only by the smallest systems (a ball alone, a two-ball chain).

Loaded by the kernel modules that call it (:mod:`lowmodel.linear_bearing.ball_kernels`,
:mod:`lowmodel.screw.ball_kernels`, :mod:`lowmodel.screw.ring_kernels`); never imported by
``import ballbench.lowmodel``.  numba's disk cache keys a kernel on its own file only; ballbench keeps its cache in
one folder per version of all kernel sources (:func:`lowmodel.kernels.sources_key`), so an edit here compiles the
callers anew (with ``$NUMBA_CACHE_DIR`` set by hand, clear it after such an edit).
"""
from __future__ import annotations

import math

import numba
import numpy as np

__all__ = ["levenberg_marquardt", "blas_dot", "ordered_dot", "CONVERGED", "NOT_CONVERGED", "NON_FINITE", "STATIONARY",
           "NO_DESCENT", "NEWTON_DEFECT"]

CONVERGED = 0   # 1 is left to the callers: an evaluation handed back (lowmodel.screw.ball_kernels.FALLBACK)
NOT_CONVERGED, NON_FINITE, STATIONARY, NO_DESCENT = 2, 3, 4, 5   # reasons of lowmodel.solvers.newton's ConvergenceError
NEWTON_DEFECT = 1e-8  # a plain Newton step is taken only where max|r + J dx| <= this max|r|

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")


@_jit
def blas_dot(a, b):
    """``a @ b`` of two vectors (BLAS's ``ddot``, numpy's order of operations)."""
    return a @ b


@_jit
def ordered_dot(a, b):
    """``sum a_i b_i`` added one term after the other, ``i = 0, 1, ...``."""
    total = 0.0
    for i in range(a.size):
        total += a[i] * b[i]
    return total


@_jit
def _largest(values):
    """``max |values_i|`` (0 for none) of finite values."""
    largest = 0.0
    for i in range(values.size):
        largest = max(largest, abs(values[i]))
    return largest


@_jit
def _norm(residual, weight):
    """``max |residual_i / weight_i|``, the caller's (unweighted) residual; NaN where a row is NaN."""
    norm = 0.0
    for i in range(residual.size):
        value = abs(residual[i] / weight[i])
        if value != value:
            return value
        norm = max(norm, value)
    return norm


@_jit
def _finite(values):
    """Whether every value is finite."""
    for i in range(values.size):
        if not math.isfinite(values[i]):
            return False
    return True


@_jit
def _sum(a, b, out):
    """``out = a + b``."""
    for i in range(out.size):
        out[i] = a[i] + b[i]


@_jit
def _stop(status, iterations, norm, state, weight, result):
    """The loop's return: ``result = r / weight`` of ``state``'s residual ``r``, and the loop's outputs."""
    residual = state[0]
    for i in range(result.size):
        result[i] = residual[i] / weight[i]
    return status, iterations, norm, state


@_jit
def _within(residual, limits):
    """Whether ``|residual_i| <= limits_i`` for every row (False at a NaN row)."""
    for i in range(residual.size):
        if not abs(residual[i]) <= limits[i]:
            return False
    return True


@numba.njit(inline="always", nogil=True, error_model="numpy")
def levenberg_marquardt(evaluate, prepare, solve, multiply, dot, evaluation, steps, x, state, trial_state, limits,
                        weight, max_iterations, result):
    """:func:`lowmodel.solvers.newton` from ``x`` (overwritten with the last accepted iterate) with the functions of
    the module docstring; ``state``, ``trial_state``: two tuples of the same types for the evaluations (swapped as a
    step is accepted).  Converged where ``|r_i| <= limits_i`` for every row of the (weighted) residual ``r``;
    ``weight`` (> 0): the rows' weights, ``r_i / weight_i`` the caller's residual.  Returns ``(status, iterations,
    norm, state)``: status :data:`CONVERGED`, :data:`NOT_CONVERGED`, :data:`NON_FINITE`, :data:`STATIONARY`,
    :data:`NO_DESCENT` or an evaluation's own; ``norm`` ``max |r_i / weight_i|`` and ``state`` the evaluation at
    ``x``, its ``r / weight`` in ``result``; where the evaluation at the start is handed back: ``iterations`` and
    ``norm`` 0, ``result`` and ``state`` not written."""
    size = x.size
    trial, step, change, linear = np.empty(size), np.empty(size), np.empty(size), np.empty(size)
    status = evaluate(evaluation, x, state)
    if status != CONVERGED:
        return status, 0, 0.0, state
    residual = state[0]
    norm = _norm(residual, weight)
    iterations = 0
    damping = -1.0
    growth = 2.0
    while not _within(residual, limits):
        if iterations >= max_iterations or not math.isfinite(norm):
            return _stop(NOT_CONVERGED if math.isfinite(norm) else NON_FINITE, iterations, norm, state, weight, result)
        iterations += 1
        diagonal_max, plain = prepare(steps, state, damping < 0.0)
        if damping < 0.0:
            damping = 1e-8 * diagonal_max
        merit = dot(residual, residual)
        largest_residual = _largest(residual) if plain else 0.0
        while True:
            newton_try = plain  # the first try of the iteration where offered: the plain Newton step
            plain = False
            finite = solve(steps, state, damping, newton_try, step) and _finite(step)
            predicted = -1.0
            if finite:
                multiply(steps, state, step, newton_try, change)
                _sum(residual, change, linear)  # the linear model's residual
                predicted = merit - dot(linear, linear)
                if newton_try and not _largest(linear) <= NEWTON_DEFECT * largest_residual:
                    finite = False  # an inaccurate plain step: the Levenberg-Marquardt step instead
            if finite and predicted > 0.0:
                _sum(x, step, trial)
                status = evaluate(evaluation, trial, trial_state)
                if status != CONVERGED:
                    return _stop(status, iterations, norm, state, weight, result)
                trial_residual = trial_state[0]
                trial_merit = dot(trial_residual, trial_residual)
                gain = (merit - trial_merit) / predicted
                if math.isfinite(trial_merit) and gain > 1e-4:
                    damping *= max(1.0 / 3.0, 1.0 - (2.0 * gain - 1.0) ** 3)
                    growth = 2.0
                    break
            elif finite and predicted <= 0.0 and not newton_try and _largest(step) == 0.0:
                return _stop(STATIONARY, iterations, norm, state, weight, result)
            if newton_try:
                continue  # refused: the Levenberg-Marquardt step at the same damping
            damping *= growth
            growth *= 2.0
            if not math.isfinite(damping) or damping > 1e30:
                return _stop(NO_DESCENT, iterations, norm, state, weight, result)
        x[:] = trial
        state, trial_state = trial_state, state
        residual = trial_residual
        norm = _norm(residual, weight)
    return _stop(CONVERGED, iterations, norm, state, weight, result)
