"""Exceptions shared by the models."""
from __future__ import annotations


class ConvergenceError(RuntimeError):
    """A solver stopped without meeting its tolerance.

    Attributes: ``residual`` (final residual norm, in the solver's stated
    units), ``iterations`` and ``tolerance``; ``reason`` (why no state was
    found: e.g. ``"spin-capacity ratio < 1"``, ``"fold of the continuation
    path"``, empty if unknown) and ``last_converged`` (``(parameter name,
    value)`` of the last converged point of a continuation path, or None).
    """

    def __init__(self, message: str, *, residual: float, iterations: int, tolerance: float, reason: str = "",
                 last_converged: tuple | None = None):
        super().__init__(f"{message} (residual {residual:.3e} after {iterations} iterations, "
                         f"tolerance {tolerance:.1e})")
        self.residual = residual
        self.iterations = iterations
        self.tolerance = tolerance
        self.reason = reason
        self.last_converged = last_converged
