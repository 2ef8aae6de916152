"""Forward-mode derivatives: dual numbers carrying a gradient array, and the algebra of 3-vectors.

:class:`Dual` holds a value ``v`` (shape (m,)) and its gradient ``g`` (shape (m, k)) with
respect to ``k`` unknowns; arithmetic and :meth:`Dual.sqrt` apply the chain rule exactly, so
a residual written once gives its analytic Jacobian (the ball-screw equilibrium of
:func:`lowmodel.screw.ball.ball_terms`: every contact quantity of lin2019 eqs 36-54 carries
its derivatives with respect to the ball's unknowns and the nut shift).  Vectors are
component triples ``(x, y, z)``; :func:`dot` and :func:`cross` work on triples of Duals and
of plain arrays alike (also :mod:`lowmodel.screw.kinematics`).

Why not a library: the gradients here are dense (m, k) arrays vectorised over every contact
of every ball, with ``k`` = 7 unknowns, through a friction model that supplies its own
Jacobian (:func:`lowmodel.contact.ellipse_friction_offset.friction_offset`).  jax would
differentiate this well but brings jaxlib (an XLA runtime of ~100 MB, first-call
compilation) into ``import ballbench.lowmodel``, which must stay numpy/scipy only; autograd
is reverse mode with per-call tracing in Python (k reverse passes for a Jacobian, each
tracing the whole residual); the scalar dual-number packages (``ad`` and others) hold one
number per object and are not vectorised.  This module is the 80 lines the models need.
"""
from __future__ import annotations

import numpy as np

__all__ = ["Dual", "constant", "variable", "dot", "cross"]


class Dual:
    """Value ``v`` (shape (m,)) with its gradient ``g`` (shape (m, k)): exact chain rule."""

    __slots__ = ("v", "g")

    def __init__(self, v, g):
        self.v = v
        self.g = g

    def __add__(self, other):
        if isinstance(other, Dual):
            return Dual(self.v + other.v, self.g + other.g)
        return Dual(self.v + other, self.g)

    __radd__ = __add__

    def __sub__(self, other):
        if isinstance(other, Dual):
            return Dual(self.v - other.v, self.g - other.g)
        return Dual(self.v - other, self.g)

    def __rsub__(self, other):
        return Dual(other - self.v, -self.g)

    def __neg__(self):
        return Dual(-self.v, -self.g)

    def __mul__(self, other):
        if isinstance(other, Dual):
            return Dual(self.v * other.v, self.g * other.v[:, None] + other.g * self.v[:, None])
        other = np.asarray(other, dtype=float)
        return Dual(self.v * other, self.g * (other[..., None] if other.ndim else other))

    __rmul__ = __mul__

    def __truediv__(self, other):
        if isinstance(other, Dual):
            inv = 1.0 / other.v
            return Dual(self.v * inv, (self.g - other.g * (self.v * inv)[:, None]) * inv[:, None])
        return self * (1.0 / np.asarray(other, dtype=float))

    def sqrt(self):
        root = np.sqrt(self.v)
        return Dual(root, self.g * (0.5 / root)[:, None])


def constant(value, k: int) -> Dual:
    """A Dual of ``value`` (m,) with a zero gradient (m, k)."""
    value = np.asarray(value, dtype=float)
    return Dual(value, np.zeros(value.shape + (k,)))


def variable(value, k: int, column: int, scale: float = 1.0) -> Dual:
    """The unknown ``column`` of ``k``, in units of ``scale``: value ``value * scale`` (m,), gradient ``scale``
    in that column."""
    value = np.asarray(value, dtype=float)
    grad = np.zeros(value.shape + (k,))
    grad[..., column] = scale
    return Dual(value * scale, grad)


def dot(a, b):
    """``a . b`` of two component triples (Duals or arrays)."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    """``a x b`` of two component triples (Duals or arrays), as a triple."""
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
