"""Exceptions shared by the models."""
from __future__ import annotations


class ConvergenceError(RuntimeError):
    """A solver stopped without meeting its tolerance.

    Attributes: ``residual`` (final residual norm, in the solver's stated
    units), ``iterations`` and ``tolerance``.
    """

    def __init__(self, message: str, *, residual: float, iterations: int, tolerance: float):
        super().__init__(f"{message} (residual {residual:.3e} after {iterations} iterations, "
                         f"tolerance {tolerance:.1e})")
        self.residual = residual
        self.iterations = iterations
        self.tolerance = tolerance
