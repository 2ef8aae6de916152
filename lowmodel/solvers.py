"""Generic damped Newton solvers shared by the models (numpy/scipy only).

* :func:`newton`: Newton's method globalised by Levenberg-Marquardt on
  ``function(x) -> (residual, jacobian)`` with an analytic Jacobian; dense
  normal equations, sparse ones above :data:`SPARSE_SIZE` unknowns.
* :func:`solve_with_restarts`: :func:`newton`, then a model-supplied check of
  the converged point (e.g. the physical branch of a multivalued formulation)
  that may restart it from a corrected point.
* :func:`check_solver_options`: the shared check of ``tolerance`` and
  ``max_iterations``.
* :func:`continuation`: natural-parameter continuation with step control along
  a homotopy ``s`` from 0 (a problem that converges) to 1 (the target), for
  when Newton from the cheap start fails; reports the path, and raises
  ConvergenceError naming the last converged ``s`` where the path stops
  (a fold, or no state beyond it).

A solver that does not converge raises
:class:`ballbench.lowmodel.errors.ConvergenceError` with its residual; it
never returns an unconverged point.  Used by the linear-bearing ball models
(:mod:`lowmodel.linear_bearing.ball`, :mod:`lowmodel.linear_bearing.b2b`)
and meant for the ball-screw model.
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import sparse as sp
from scipy.linalg.lapack import dpbsv
from scipy.sparse.linalg import spsolve

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["newton", "solve_with_restarts", "check_solver_options", "continuation", "ContinuationStep",
           "SPARSE_SIZE", "BlockTridiagonal", "equilibrium_tolerance", "ROUNDOFF_MARGIN"]

SPARSE_SIZE = 60  # unknowns above which newton() uses sparse normal equations


def check_solver_options(tolerance, max_iterations) -> None:
    """ValueError unless ``tolerance`` is finite and > 0 and ``max_iterations`` an integer >= 1 (not a bool)."""
    if type(tolerance) is float and 0.0 < tolerance < math.inf and type(max_iterations) is int and max_iterations >= 1:
        return  # the common case, without the array checks
    if isinstance(tolerance, (bool, np.bool_)) or not isinstance(tolerance, (int, float, np.floating, np.integer)):
        raise ValueError(f"tolerance must be a finite number > 0, got {tolerance!r}")
    checks.positive("tolerance", tolerance)
    checks.count("max_iterations", max_iterations, 1)


ROUNDOFF_MARGIN = 64.0  # times the round-off floor eps * lever of an equilibrium of contact forces (measured 0.3-2.7)


def equilibrium_tolerance(tolerance: float, friction_coefficient: float, lever: float) -> float:
    """Tolerance of a residual row in units of ``mu F_ref`` that sums contact forces of size ``F_ref``.

    A contact force ``F = (delta / C)^(3/2)`` comes from an approach ``delta`` that is the small difference of
    lengths of size ``L`` (arc-centre distance against groove radius minus ball radius), so it carries a
    round-off of ``1.5 eps L / delta`` relative, ``lever = L / delta``; in units of ``mu F_ref`` that is
    ``eps lever / mu``, which passes any fixed tolerance as ``mu -> 0`` (lin2019 Table 4, mu = 1e-4: 1e-9
    against 1e-10).  Returns ``max(tolerance, ROUNDOFF_MARGIN eps lever / mu)``: the residual relative to
    ``mu F_ref``, or to the loads themselves (``64 eps lever F_ref``) where that is the larger.
    """
    floor = ROUNDOFF_MARGIN * np.finfo(float).eps * float(lever) / float(friction_coefficient)
    return max(float(tolerance), floor)


def newton(function, x0: np.ndarray, *, tolerance: float, max_iterations: int, what: str, row_tolerance=None,  # noqa: C901 - one Levenberg-Marquardt loop over dense, banded and sparse steps
           row_weight=None):
    """Newton's method globalised by Levenberg-Marquardt on ``function(x) -> (residual, jacobian)``.

    Each iteration solves ``(J^T J + lam I) dx = -J^T r`` with the analytic
    Jacobian ``J``; ``lam`` follows the gain ratio of actual to predicted
    decrease of ``|r|^2`` (Nielsen's update), so far from the solution the
    steps are short gradient-like steps (friction saturates: the residual is
    bounded and plain Newton steps can be huge), and near it ``lam -> 0``
    gives Newton steps and quadratic convergence.  Stops when
    ``max|r| <= tolerance``, or with ``row_tolerance`` (an array like ``r``, e.g. from
    :func:`equilibrium_tolerance`) when ``|r_i| <= row_tolerance_i`` for every row.  ``jacobian`` may be a dense
    array (sparse normal equations above :data:`SPARSE_SIZE` unknowns) or a scipy sparse matrix (always sparse).
    Returns ``(x, residual_vector, iterations)``; raises ConvergenceError with the residual and a ``reason``
    (``"iteration limit"``, ``"non-finite residual"``, ``"stationary point of |residual|"``, ``"no descent
    step"``) otherwise; a NaN residual never passes as converged.  ``row_weight`` (an array like ``r``, > 0):
    the Levenberg-Marquardt steps minimise ``|W r|^2`` (rows equilibrated: the normal equations square the
    condition of ``J``), the convergence test stays on ``r``; dense, scipy sparse and :class:`BlockTridiagonal`
    Jacobians alike.  ``jacobian`` may also be a function of no arguments that returns it: it is then called only
    where a step needs it (not for a rejected trial point, nor at the converged one), for a model whose Jacobian
    costs much more than its residual.
    """
    check_solver_options(tolerance, max_iterations)
    limits = tolerance if row_tolerance is None else np.asarray(row_tolerance, dtype=float)
    weight = 1.0  # the reported residual is the caller's (unweighted) one
    if row_weight is not None:
        weight = np.asarray(row_weight, dtype=float)
        plain = function

        def function(x):
            residual_, jacobian_ = plain(x)
            if callable(jacobian_):
                return residual_ * weight, lambda: _scaled_rows(jacobian_(), weight)
            return residual_ * weight, _scaled_rows(jacobian_, weight)

        limits = limits * weight
    x = np.array(x0, dtype=float)
    residual, jacobian = function(x)
    norm = float(np.max(np.abs(residual / weight))) if residual.size else 0.0
    iterations = 0
    damping = None
    growth = 2.0
    while not bool(np.all(np.abs(residual) <= limits)):
        if iterations >= max_iterations or not np.isfinite(norm):
            reason = "iteration limit" if np.isfinite(norm) else "non-finite residual"
            raise ConvergenceError(f"{what}: Newton did not converge", residual=norm, iterations=iterations,
                                   tolerance=tolerance, reason=reason)
        iterations += 1
        if callable(jacobian):  # deferred by the model until a step needs it
            jacobian = jacobian()
        blocks = isinstance(jacobian, BlockTridiagonal)
        sparse = blocks or x.size > SPARSE_SIZE or not isinstance(jacobian, np.ndarray)
        if blocks:  # ball chains: J^T J in band storage straight from the blocks (no sparse matrix at all)
            band = jacobian.normal_band()
            diagonal_max = float(band.storage[0].max()) if damping is None else 0.0  # used once, below
        elif sparse:  # many balls: the Jacobian is block tridiagonal (a scipy sparse matrix is used as given)
            jac_sparse = jacobian if sp.isspmatrix_csr(jacobian) else sp.csr_matrix(jacobian)
            jacobian = jac_sparse
            normal = (jac_sparse.T @ jac_sparse).tocoo()
            lower = normal.row >= normal.col
            band = _Band(normal.row[lower], normal.col[lower], normal.data[lower], x.size)
            if band.narrow:  # banded Cholesky below: no CSC copy, no identity
                diagonal_max = float(band.storage[0].max())
            else:
                normal = normal.tocsc()
                identity = sp.identity(x.size, format="csc")
                diagonal_max = float(normal.diagonal().max())
        else:
            normal = jacobian.T @ jacobian
            identity = np.eye(x.size)
            diagonal_max = float(np.max(np.diag(normal)))
        gradient = jacobian.rmatvec(residual) if blocks else jacobian.T @ residual
        if damping is None:
            damping = 1e-8 * diagonal_max
        merit = float(residual @ residual)
        while True:
            try:
                if sparse and band.narrow:  # banded SPD system (block-tridiagonal J): Cholesky, O(n b^2)
                    step = band.solve(damping, -gradient)
                elif sparse:
                    with warnings.catch_warnings():  # a singular matrix gives NaN: handled below
                        warnings.simplefilter("ignore")
                        step = spsolve(normal + damping * identity, -gradient)
                else:
                    step = np.linalg.solve(normal + damping * identity, -gradient)
            except (np.linalg.LinAlgError, RuntimeError):
                step = np.full(x.size, np.nan)
            change = jacobian.matvec(step) if blocks else jacobian @ step
            linear = residual + change  # the linear model's residual
            predicted = merit - float(linear @ linear)
            finite = bool(np.isfinite(step).all())
            if finite and predicted > 0.0:
                trial = x + step
                trial_residual, trial_jacobian = function(trial)
                with np.errstate(over="ignore", invalid="ignore"):  # a huge trial step: merit inf, rejected below
                    trial_merit = float(trial_residual @ trial_residual)
                gain = (merit - trial_merit) / predicted
                if math.isfinite(trial_merit) and gain > 1e-4:
                    damping *= max(1.0 / 3.0, 1.0 - (2.0 * gain - 1.0) ** 3)
                    growth = 2.0
                    break
            elif finite and predicted <= 0.0 and np.max(np.abs(step)) == 0.0:
                raise ConvergenceError(f"{what}: stationary point of |residual|", residual=norm,
                                       iterations=iterations, tolerance=tolerance,
                                       reason="stationary point of |residual|")
            damping *= growth
            growth *= 2.0
            if not np.isfinite(damping) or damping > 1e30:
                raise ConvergenceError(f"{what}: no descent step (damping diverged)", residual=norm,
                                       iterations=iterations, tolerance=tolerance, reason="no descent step")
        x, residual, jacobian = trial, trial_residual, trial_jacobian
        norm = float(np.abs(residual / weight).max())
    return x, residual / weight, iterations


class _Band:
    """Lower band storage of the normal matrix ``J^T J`` for LAPACK's banded Cholesky (``dpbsv``).

    ``narrow`` when the bandwidth is small against the size (banded systems of
    the ball chains: bandwidth ~ 30 whatever the number of balls), else the caller uses SuperLU.
    """

    def __init__(self, rows, cols, values, size, storage=None):
        if storage is not None:  # already in lower band storage (BlockTridiagonal.normal_band)
            self.width, self.narrow, self.storage = storage.shape[0] - 1, True, storage
            return
        self.width = int(np.max(rows - cols, initial=0))
        self.narrow = (self.width + 1) * 8 < size
        if self.narrow:
            self.storage = np.zeros((self.width + 1, size))
            self.storage[rows - cols, cols] = values

    def solve(self, damping, rhs):
        """``(N + damping I)^-1 rhs`` by LAPACK's banded Cholesky ``dpbsv`` (what ``scipy.linalg.solveh_banded``
        calls, without its per-call input checks); NaN where the matrix is not positive definite."""
        storage = self.storage.copy(order="F")  # LAPACK's column-major band storage: no further copy
        storage[0] += damping
        _, step, info = dpbsv(storage, rhs, lower=1, overwrite_ab=1)
        return step if info == 0 else np.full(rhs.size, np.nan)


def _scaled_rows(jacobian, weight: np.ndarray):
    """``diag(weight) @ jacobian`` for a dense array, a scipy sparse matrix or a :class:`BlockTridiagonal`."""
    if isinstance(jacobian, BlockTridiagonal):
        rows = weight.reshape(jacobian.blocks, jacobian.block_size, 1)
        return BlockTridiagonal(jacobian.lower * rows, jacobian.diagonal * rows, jacobian.upper * rows)
    if isinstance(jacobian, np.ndarray):
        return jacobian * weight[:, None]
    return sp.csr_matrix(sp.diags(weight) @ jacobian)


class BlockTridiagonal:
    """A square block-tridiagonal matrix of ``n`` blocks of size ``K`` (``n K`` unknowns).

    ``lower``, ``diagonal``, ``upper`` : (n, K, K); block row ``i`` holds ``lower[i]`` in block column
    ``i - 1``, ``diagonal[i]`` in ``i`` and ``upper[i]`` in ``i + 1`` (``lower[0]`` and ``upper[-1]`` are
    ignored).  :func:`newton` forms the normal matrix ``J^T J`` (block pentadiagonal) directly in the
    lower band storage of scipy's banded Cholesky, so a Newton step costs O(n K^3) with a handful of
    batched numpy operations whatever ``n`` (the ball chains of :mod:`lowmodel.linear_bearing.b2b`).
    """

    def __init__(self, lower: np.ndarray, diagonal: np.ndarray, upper: np.ndarray):
        self.lower, self.diagonal, self.upper = lower, diagonal, upper
        self.blocks, self.block_size = diagonal.shape[0], diagonal.shape[1]
        self.shape = (self.blocks * self.block_size,) * 2

    def matvec(self, x: np.ndarray) -> np.ndarray:
        """``J @ x`` for ``x`` of shape (n K,)."""
        xb = x.reshape(self.blocks, self.block_size, 1)
        y = np.matmul(self.diagonal, xb)
        y[1:] += np.matmul(self.lower[1:], xb[:-1])
        y[:-1] += np.matmul(self.upper[:-1], xb[1:])
        return y.reshape(-1)

    def rmatvec(self, r: np.ndarray) -> np.ndarray:
        """``J^T @ r`` for ``r`` of shape (n K,)."""
        rb = r.reshape(self.blocks, 1, self.block_size)
        y = np.matmul(rb, self.diagonal)
        y[:-1] += np.matmul(rb[1:], self.lower[1:])
        y[1:] += np.matmul(rb[:-1], self.upper[:-1])
        return y.reshape(-1)

    def toarray(self) -> np.ndarray:
        """The dense (n K, n K) matrix."""
        n, k = self.blocks, self.block_size
        dense = np.zeros((n, k, n, k))
        index = np.arange(n)
        dense[index, :, index, :] = self.diagonal
        dense[index[1:], :, index[:-1], :] = self.lower[1:]
        dense[index[:-1], :, index[1:], :] = self.upper[:-1]
        return dense.reshape(n * k, n * k)

    def normal_band(self) -> "_Band":
        """``J^T J`` in lower band storage (bandwidth ``3 K - 1``).

        Block columns ``a``: ``N[a, a] = D_a^T D_a + U_{a-1}^T U_{a-1} + L_{a+1}^T L_{a+1}``,
        ``N[a, a+1] = D_a^T U_a + L_{a+1}^T D_{a+1}``, ``N[a, a+2] = L_{a+1}^T U_{a+1}``.
        """
        n, k = self.blocks, self.block_size
        low, diag, up = self.lower, self.diagonal, self.upper
        diag_t = diag.transpose(0, 2, 1)
        n0 = np.matmul(diag_t, diag)
        n0[1:] += np.matmul(up[:-1].transpose(0, 2, 1), up[:-1])
        n0[:-1] += np.matmul(low[1:].transpose(0, 2, 1), low[1:])
        n1 = np.matmul(diag_t[:-1], up[:-1]) + np.matmul(low[1:].transpose(0, 2, 1), diag[1:])
        n2 = np.matmul(low[1:-1].transpose(0, 2, 1), up[1:-1])
        index0, index1, index2, source0 = _normal_band_pattern(n, k)
        columns = np.zeros(3 * k * n * k)  # band storage column by column (LAPACK's column-major order)
        columns[index0] = n0.reshape(n, k * k)[:, source0].reshape(-1)
        columns[index1] = n1.reshape(-1)
        columns[index2] = n2.reshape(-1)
        return _Band(None, None, None, n * k, storage=columns.reshape(n * k, 3 * k).T)


@lru_cache(maxsize=16)
def _normal_band_pattern(n: int, k: int):
    """Flat positions in the (3 k, n k) lower band storage, stored column-major (Fortran order, what LAPACK
    reads), of the blocks N[a, a] (lower triangle, in the order of ``source0``), N[a, a+1] and N[a, a+2] (all
    entries, row-major), for :meth:`BlockTridiagonal.normal_band`.  Entry ``(row, col)`` with ``row >= col`` of
    the matrix goes to ``(row - col, col)``, flat position ``col * 3 k + row - col``."""
    size = 1  # stride of the band row index d; the stride of the column index is 3 k
    p, q = np.meshgrid(np.arange(k), np.arange(k), indexing="ij")  # block row p, block column q
    keep = p >= q
    source0 = (p * k + q)[keep]
    width = 3 * k
    base = k * np.arange(n)[:, None]
    index0 = ((p - q)[keep][None, :] * size + (base + q[keep][None, :]) * width).reshape(-1)
    # N[a, a+1][p, q] sits at (a k + p, (a+1) k + q); its mirror (row (a+1) k + q, col a k + p) is stored
    index1 = ((k + q - p).reshape(-1)[None, :] * size + (base[:-1] + p.reshape(-1)[None, :]) * width).reshape(-1)
    index2 = ((2 * k + q - p).reshape(-1)[None, :] * size + (base[:-2] + p.reshape(-1)[None, :]) * width).reshape(-1)
    return tuple(checks.read_only(index) for index in (index0, index1, index2, source0))  # cached: shared


def solve_with_restarts(function, x0: np.ndarray, restart, *, tolerance: float, max_iterations: int, what: str,
                        rejection: str = "converged only to rejected points", attempts: int = 4,
                        rejection_reason: str = ""):
    """:func:`newton` from ``x0``, then ``restart(x)`` judges the converged point.

    ``restart(x)`` returns ``None`` to accept ``x``, or ``(x_new, violation)``
    to run Newton again from ``x_new`` (``violation`` >= 0: how far ``x`` is
    from acceptable, in the model's residual units).  At most ``attempts``
    runs share ``max_iterations``.  Returns ``(x, residual_vector,
    iterations)``; raises ConvergenceError (message ``what: rejection``,
    residual the last violation, reason ``rejection_reason``) when no run ends at an accepted point.
    """
    check_solver_options(tolerance, max_iterations)
    attempts = checks.count("attempts", attempts, 1)
    x = np.array(x0, dtype=float)
    total = 0
    violation = math.inf
    for _ in range(attempts):
        if total < max_iterations:
            x, residual, iterations = newton(function, x, tolerance=tolerance, max_iterations=max_iterations - total,
                                             what=what)
        else:  # earlier runs used the whole budget: the restart point counts only if it solves the system as it is
            residual = function(x)[0]
            norm = float(np.max(np.abs(residual))) if residual.size else 0.0
            if not norm <= tolerance:
                raise ConvergenceError(f"{what}: Newton did not converge", residual=norm, iterations=total,
                                       tolerance=tolerance, reason="iteration limit")
            iterations = 0
        total += iterations
        verdict = restart(x)
        if verdict is None:
            return x, residual, total
        x, violation = verdict
    raise ConvergenceError(f"{what}: {rejection}", residual=float(violation), iterations=total, tolerance=tolerance,
                           reason=rejection_reason)


@dataclass(frozen=True)
class ContinuationStep:
    """One converged point of a continuation path: homotopy parameter ``s`` in [0, 1] and Newton iterations."""

    parameter: float
    iterations: int


def continuation(solve_at, x_start: np.ndarray, *, what: str, name: str = "s", initial_step: float = 0.25,
                 min_step: float = 1.0 / 1024.0, max_steps: int = 200):
    """Follow the solution of a homotopy from ``s = 0`` (where ``x_start`` solves it) to ``s = 1``.

    ``solve_at(s, x0)`` solves the problem at ``s`` by Newton from ``x0`` and returns
    ``(x, residual_vector, iterations)`` or raises ConvergenceError.  Natural-parameter
    continuation: the predictor is the secant through the last two converged points,
    a converged step in at most 6 iterations doubles the next one, a failed one
    halves it; below ``min_step`` the path stops and ConvergenceError is raised with
    ``last_converged = (name, s)`` and ``reason = "continuation stopped (fold or no state beyond)"``,
    or, when the last failed step ended at a converged point that the model rejected with a reason
    (``ConvergenceError.reason`` of ``solve_at``: the branch continues, but outside the model's validity),
    ``"<that reason> beyond <name> = s"``.  Returns ``(x, residual_vector, path)`` with ``path`` a
    tuple of :class:`ContinuationStep` (``s = 0`` first, ``s = 1`` last).
    """
    initial_step = checks.bounded("initial_step", initial_step, 0.0, 1.0, upper_closed=True)
    min_step = checks.bounded("min_step", min_step, 0.0, initial_step, upper_closed=True,
                              note="at most initial_step")
    max_steps = checks.count("max_steps", max_steps, 1)
    x = np.array(x_start, dtype=float)
    previous = None  # (s, x) of the point before the last
    s = 0.0
    step = float(initial_step)
    path = [ContinuationStep(0.0, 0)]
    residual = None
    last_error = None
    for _ in range(max_steps):
        target = min(1.0, s + step)
        if previous is not None:  # secant predictor
            guess = x + (x - previous[1]) * (target - s) / (s - previous[0])
        else:
            guess = x
        try:
            x_new, residual, iterations = solve_at(target, guess)
        except ConvergenceError as error:
            last_error = error
            if previous is not None and not np.array_equal(guess, x):
                try:  # the secant may overshoot a bend: retry from the last point itself
                    x_new, residual, iterations = solve_at(target, x)
                except ConvergenceError as error_again:
                    last_error = error_again
                    x_new = None
            else:
                x_new = None
            if x_new is None:
                step *= 0.5
                if step < min_step:
                    break
                continue
        previous = (s, x)
        s, x = target, x_new
        path.append(ContinuationStep(s, int(iterations)))
        if s >= 1.0:
            return x, residual, tuple(path)
        if iterations <= 6:
            step *= 2.0
    else:  # max_steps used up before s = 1 (no break: the step never fell below min_step): not a fold
        stopped = ConvergenceError(
            f"{what}: continuation in {name} used all max_steps = {max_steps} and stopped at {name} = {s:.6g} of 1",
            residual=float(np.max(np.abs(residual), initial=0.0)) if residual is not None else 0.0,
            iterations=sum(p.iterations for p in path), tolerance=0.0, reason="max_steps reached",
            last_converged=(name, s))
        stopped.last_state = x
        raise stopped
    residual_norm = last_error.residual if last_error is not None else math.inf
    if last_error is not None and last_error.reason:  # the branch goes on, but the model rejects it
        reason = f"{last_error.reason} beyond {name} = {s:.6g}"
        because = f"{last_error.reason}: {str(last_error).split(' (residual')[0]}"
    else:
        reason, because = "continuation stopped (fold or no state beyond)", "fold or no state beyond"
    stopped = ConvergenceError(f"{what}: continuation in {name} stopped at {name} = {s:.6g} of 1 ({because})",
                               residual=residual_norm, iterations=sum(p.iterations for p in path),
                               tolerance=last_error.tolerance if last_error is not None else 0.0,
                               reason=reason, last_converged=(name, s))
    stopped.last_state = x  # the last converged point (at s), for the caller's diagnosis
    raise stopped
