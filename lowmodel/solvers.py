"""Generic damped Newton solvers shared by the models (numpy/scipy only).

* :func:`newton`: Newton's method globalised by Levenberg-Marquardt on
  ``function(x) -> (residual, jacobian)`` with an analytic Jacobian; dense
  normal equations, sparse ones above :data:`SPARSE_SIZE` unknowns.
* :func:`solve_with_restarts`: :func:`newton`, then a model-supplied check of
  the converged point (e.g. the physical branch of a multivalued formulation)
  that may restart it from a corrected point.
* :func:`check_solver_options`: the shared check of ``tolerance`` and
  ``max_iterations``.

A solver that does not converge raises
:class:`ballbench.lowmodel.errors.ConvergenceError` with its residual; it
never returns an unconverged point.  Used by the linear-bearing ball models
(:mod:`lowmodel.linear_bearing.bearing_ball`, :mod:`lowmodel.linear_bearing.b2b`)
and meant for the ball-screw model.
"""
from __future__ import annotations

import math
import warnings

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["newton", "solve_with_restarts", "check_solver_options", "SPARSE_SIZE"]

SPARSE_SIZE = 60  # unknowns above which newton() uses sparse normal equations


def check_solver_options(tolerance, max_iterations) -> None:
    """ValueError unless ``tolerance`` is finite and > 0 and ``max_iterations`` an integer >= 1 (not a bool)."""
    if isinstance(tolerance, (bool, np.bool_)) or not isinstance(tolerance, (int, float, np.floating, np.integer)):
        raise ValueError(f"tolerance must be a finite number > 0, got {tolerance!r}")
    checks.positive("tolerance", tolerance)
    checks.count("max_iterations", max_iterations, 1)


def newton(function, x0: np.ndarray, *, tolerance: float, max_iterations: int, what: str):
    """Newton's method globalised by Levenberg-Marquardt on ``function(x) -> (residual, jacobian)``.

    Each iteration solves ``(J^T J + lam I) dx = -J^T r`` with the analytic
    Jacobian ``J``; ``lam`` follows the gain ratio of actual to predicted
    decrease of ``|r|^2`` (Nielsen's update), so far from the solution the
    steps are short gradient-like steps (friction saturates: the residual is
    bounded and plain Newton steps can be huge), and near it ``lam -> 0``
    gives Newton steps and quadratic convergence.  Stops when
    ``max|r| <= tolerance``.  Returns ``(x, residual_vector, iterations)``;
    raises ConvergenceError with the residual otherwise.
    """
    x = np.array(x0, dtype=float)
    residual, jacobian = function(x)
    norm = float(np.max(np.abs(residual))) if residual.size else 0.0
    iterations = 0
    damping = None
    growth = 2.0
    while norm > tolerance:
        if iterations >= max_iterations or not np.isfinite(norm):
            raise ConvergenceError(f"{what}: Newton did not converge", residual=norm, iterations=iterations,
                                   tolerance=tolerance)
        iterations += 1
        sparse = x.size > SPARSE_SIZE
        if sparse:  # many balls: the Jacobian is block tridiagonal
            from scipy import sparse as sp
            from scipy.sparse.linalg import spsolve

            jac_sparse = sp.csr_matrix(jacobian)
            normal = (jac_sparse.T @ jac_sparse).tocsc()
            identity = sp.identity(x.size, format="csc")
            diagonal_max = float(normal.diagonal().max())
        else:
            normal = jacobian.T @ jacobian
            identity = np.eye(x.size)
            diagonal_max = float(np.max(np.diag(normal)))
        gradient = jacobian.T @ residual
        if damping is None:
            damping = 1e-8 * diagonal_max
        merit = float(residual @ residual)
        while True:
            try:
                if sparse:
                    with warnings.catch_warnings():  # a singular matrix gives NaN: handled below
                        warnings.simplefilter("ignore")
                        step = spsolve(normal + damping * identity, -gradient)
                else:
                    step = np.linalg.solve(normal + damping * identity, -gradient)
            except (np.linalg.LinAlgError, RuntimeError):
                step = np.full(x.size, np.nan)
            predicted = merit - float(np.sum((residual + jacobian @ step) ** 2))
            if np.all(np.isfinite(step)) and predicted > 0.0:
                trial = x + step
                trial_residual, trial_jacobian = function(trial)
                trial_merit = float(trial_residual @ trial_residual)
                gain = (merit - trial_merit) / predicted
                if np.isfinite(trial_merit) and gain > 1e-4:
                    damping *= max(1.0 / 3.0, 1.0 - (2.0 * gain - 1.0) ** 3)
                    growth = 2.0
                    break
            elif np.all(np.isfinite(step)) and predicted <= 0.0 and np.max(np.abs(step)) == 0.0:
                raise ConvergenceError(f"{what}: stationary point of |residual|", residual=norm,
                                       iterations=iterations, tolerance=tolerance)
            damping *= growth
            growth *= 2.0
            if not np.isfinite(damping) or damping > 1e30:
                raise ConvergenceError(f"{what}: no descent step (damping diverged)", residual=norm,
                                       iterations=iterations, tolerance=tolerance)
        x, residual, jacobian = trial, trial_residual, trial_jacobian
        norm = float(np.max(np.abs(residual)))
    return x, residual, iterations


def solve_with_restarts(function, x0: np.ndarray, restart, *, tolerance: float, max_iterations: int, what: str,
                        rejection: str = "converged only to rejected points", attempts: int = 4):
    """:func:`newton` from ``x0``, then ``restart(x)`` judges the converged point.

    ``restart(x)`` returns ``None`` to accept ``x``, or ``(x_new, violation)``
    to run Newton again from ``x_new`` (``violation`` >= 0: how far ``x`` is
    from acceptable, in the model's residual units).  At most ``attempts``
    runs share ``max_iterations``.  Returns ``(x, residual_vector,
    iterations)``; raises ConvergenceError (message ``what: rejection``,
    residual the last violation) when no run ends at an accepted point.
    """
    x = np.array(x0, dtype=float)
    total = 0
    violation = math.inf
    for _ in range(attempts):
        x, residual, iterations = newton(function, x, tolerance=tolerance, max_iterations=max_iterations - total,
                                         what=what)
        total += iterations
        verdict = restart(x)
        if verdict is None:
            return x, residual, total
        x, violation = verdict
    raise ConvergenceError(f"{what}: {rejection}", residual=float(violation), iterations=total, tolerance=tolerance)
