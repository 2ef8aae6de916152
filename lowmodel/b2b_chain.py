"""Ball-to-ball (B2B) chain complementarity: the one implementation shared by the B2B models.

``n`` balls in a row (or a closed ring), each in equilibrium on its own, coupled where
neighbours touch by a normal force and its friction: lin2019 eqs 5-10 for the linear
bearing (:mod:`lowmodel.linear_bearing.b2b`), eqs 56-61 for the ball screw
(:mod:`lowmodel.screw.b2b`), and the FE-informed solves of both with sampled contact
tractions (:mod:`lowmodel.linear_bearing.b2b_traction`, :mod:`lowmodel.screw.b2b_traction`).

Pairs.  Pair ``j`` is (ball ``j``, ball ``j+1``) for ``j < n - 1`` (ball ``j`` behind), and
pair ``n - 1`` is (ball ``n - 1``, ball 0) in a ring.  A touching pair carries the normal
force ``F_j`` with the complementarity of lin2019 eqs 9-10 (linear bearing) and 60-61
(screw)::

    F_j >= 0,   r_j >= 0,   F_j r_j = 0,      r_j the separation rate of the pair

(``v_B,j+1 - v_B,j`` in the linear bearing, ``omega_B,j+1 - omega_B,j`` in the screw),
written as ``phi(F_j / F_unit, gamma r_j / r_unit) = 0`` with an NCP function ``phi``
(``gamma`` = :data:`COMPLEMENTARITY_SCALE`) and solved by a semismooth Newton method
together with the equilibrium of every ball (no enumeration of contact patterns).  Two
functions ``phi``, chosen per model:

* ``"min"``: ``min(a, b)``, the primal-dual active-set method; the linear-bearing models
  (lin2019 eqs 9-10).
* ``"fischer-burmeister"``: ``a + b - sqrt(a^2 + b^2)``, whose squared residual is
  continuously differentiable: the Levenberg-Marquardt merit of the solver has no kink.
  The ball-screw models (eqs 60-61): with ``min`` the Levenberg-Marquardt steps of a
  100-ball screw chain find no descent at a kink (lin2019-screw-stability's 100-ball case,
  docs/ball_screw.md).

Both have the same solutions; :func:`chain_forces` checks them the same way.  An open pair
carries no force.

Unknowns.  Ball ``j`` owns the block ``(x_j, s_j)`` of ``K = k + 1`` unknowns: its ``k``
unknowns and the force slot ``s_j = F_j / F_unit`` of pair ``j`` (fixed at 0 by the row
``s_j = 0`` where pair ``j`` is open, and for the last ball of an open chain); after the
blocks come ``g`` global unknowns shared by all balls (the common nut shift of a ball
screw under a total axial load).  A ball couples only to its pair partners and to the
forces between them, so the Jacobian is built from ``K x K`` blocks: block tridiagonal
for a chain (:class:`lowmodel.solvers.BlockTridiagonal`: Newton's normal equations go
straight into band storage, cost linear in ``n``), with corner blocks for a ring and a
border of ``g`` rows and columns for global unknowns (scipy CSR from the blocks); a dense
array below :data:`SPARSE_BALLS` balls (faster there).

The seams, so that other physics and a faster solver plug in without touching the chain:

* ``ball_function(balls, extra) -> BallBlocks``: the residual of every ball on its own and
  its Jacobian (lin2019 eq 4 with the full-sliding friction map, eq 54 with the offset
  ellipse friction, or pointwise Coulomb over sampled tractions).  A stick/slip friction
  law per contact is another ball function.
* ``pair_function(balls, forces) -> PairBlocks``: the B2B loads of every pair (eqs 5-8,
  56-59) with their derivatives.
* :func:`jacobian_matrix`: the one place where the blocks become the matrix Newton solves
  with.  Every array has the balls (or pairs) as its leading axis, so a batched solve of
  many cases (one more leading axis, block-diagonal over cases) or a compiled kernel of
  the assembly replaces this function and :func:`chain_system`'s array code, not the models.
"""
from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy import sparse

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.solvers import BlockTridiagonal

__all__ = ["COMPLEMENTARITY_SCALE", "SPARSE_BALLS", "COMPLEMENTARITY_FUNCTIONS", "ChainLayout", "BallBlocks",
           "PairBlocks", "chain_system", "jacobian_matrix", "chain_forces", "fischer_burmeister"]

COMPLEMENTARITY_SCALE = 10.0  # gamma: weighs the separation rate against the force in phi (the path only)
SPARSE_BALLS = 6  # chains of at least this many balls keep the block Jacobian (dense arrays are faster below)
COMPLEMENTARITY_FUNCTIONS = ("min", "fischer-burmeister")
_FB_SMOOTHING = 1e-14  # keeps the Fischer-Burmeister function differentiable at (0, 0)


@dataclass(frozen=True)
class ChainLayout:
    """Where the unknowns of a B2B chain sit in the state vector ``z`` (module docstring).

    n_balls : n >= 1;  n_unknowns : k, per ball;  touching : indices of the touching pairs (into :attr:`pairs`)
    ring : the balls form a closed ring (pair (n-1, 0) as well; n >= 2);  n_global : g global unknowns
    """

    n_balls: int
    n_unknowns: int
    touching: np.ndarray
    ring: bool = False
    n_global: int = 0

    def __post_init__(self):   # touching read-only: the live slots are cached from it
        checks.freeze_arrays(self, "touching")

    def __reduce__(self):
        return checks.rebuilt_through_init(self)

    @cached_property
    def pairs(self) -> np.ndarray:
        """(p, 2) the pairs (behind, ahead): (j, j+1), and (n-1, 0) in a ring (read-only, cached)."""
        n = self.n_balls
        behind = np.arange(n if self.ring and n > 1 else n - 1)
        return checks.read_only(np.stack([behind, (behind + 1) % n], axis=1))

    @property
    def block(self) -> int:
        """K = k + 1 unknowns per ball (its own and the force slot of its pair)."""
        return self.n_unknowns + 1

    @property
    def size(self) -> int:
        return self.n_balls * self.block + self.n_global

    @property
    def live(self) -> np.ndarray:
        """(n,) bool: the force slot of ball j holds a touching pair's force (a new array at every read)."""
        return self._live.copy()

    @cached_property
    def _live(self) -> np.ndarray:
        """:attr:`live`, read-only and cached: what this file's loops read."""
        live = np.zeros(self.n_balls, dtype=bool)
        live[np.asarray(self.touching, dtype=int)] = True
        return checks.read_only(live)

    def unpack(self, z: np.ndarray):
        """``(balls (n, k), forces (p,) in slot units, 0 for open pairs, extra (g,))`` of a state ``z``."""
        n, k = self.n_balls, self.n_unknowns
        blocks = z[:n * (k + 1)].reshape(n, k + 1)
        p = len(self.pairs)
        return blocks[:, :k], np.where(self._live[:p], blocks[:p, k], 0.0), z[n * (k + 1):]

    def pack(self, balls: np.ndarray, forces=None, extra=None) -> np.ndarray:
        """The state ``z`` of ball unknowns (n, k), pair forces (p,) [slot units; touching pairs only; default 0]
        and global unknowns (g,) (default 0)."""
        n, k = self.n_balls, self.n_unknowns
        z = np.zeros(self.size)
        blocks = z[:n * (k + 1)].reshape(n, k + 1)
        blocks[:, :k] = balls
        if forces is not None:
            touching = np.asarray(self.touching, dtype=int)
            blocks[touching, k] = np.asarray(forces, dtype=float)[touching]
        if extra is not None:
            z[n * (k + 1):] = extra
        return z


@dataclass
class BallBlocks:
    """What a ball function returns: every ball on its own (module docstring).

    residual (n, k), jacobian (n, k, k) = d residual_j / d x_j (or a function of no arguments returning it, where it
    costs more than the residual: :func:`chain_system` defers it); with global unknowns also
    coupling (n, k, g) = d residual_j / d extra, global_residual (g,), global_rows (g, n, k) = d global / d x_j,
    global_block (g, g) = d global / d extra.
    """

    residual: np.ndarray
    jacobian: np.ndarray
    coupling: np.ndarray | None = None
    global_residual: np.ndarray | None = None
    global_rows: np.ndarray | None = None
    global_block: np.ndarray | None = None


@dataclass
class PairBlocks:
    """What a pair function returns: the B2B loads of the pairs (p pairs, k unknowns per ball).

    load : (n, L), L <= k, the loads summed on every ball, added to its first L residual rows
    d_balls : (p, 2, 2, k, k), d (load on the ball behind, ahead) / d (x behind, x ahead) of each pair
    d_force : (p, 2, k), d (load on the ball behind, ahead) / d (force in slot units)
    slip : (p,) slip speed of each pair (the model's units)
    """

    load: np.ndarray
    d_balls: np.ndarray
    d_force: np.ndarray
    slip: np.ndarray


def fischer_burmeister(a, b):
    """Fischer-Burmeister function of the complementarity ``a >= 0, b >= 0, a b = 0`` (lin2019 eqs 60-61).

    ``phi = a + b - sqrt(a^2 + b^2 + s^2)`` (``s`` a 1e-14 smoothing, differentiable at (0, 0));
    ``phi = 0`` is the complementarity.  Returns ``(phi, d phi / d a, d phi / d b)``, arrays like ``a``;
    ValueError naming ``a`` or ``b`` where they are not finite.
    """
    return _fischer_burmeister(np.asarray(checks.finite("a", a), dtype=float),
                               np.asarray(checks.finite("b", b), dtype=float))


def _fischer_burmeister(a: np.ndarray, b: np.ndarray):
    """:func:`fischer_burmeister` without the input check (the chain's inner loop)."""
    with np.errstate(over="ignore"):
        squared = a * a + b * b + _FB_SMOOTHING**2
    root = np.sqrt(squared)
    if not np.all(np.isfinite(root)):   # |a| or |b| beyond ~1e154: no overflow of the squares
        root = np.where(np.isfinite(root), root, np.hypot(np.hypot(a, b), _FB_SMOOTHING))
    return a + b - root, 1.0 - a / root, 1.0 - b / root


def chain_system(ball_function, pair_function, layout: ChainLayout, *, rate_index: int, rate_scale: float,
                 complementarity: str = "min"):
    """Residual and Jacobian ``function(z) -> (residual (size,), jacobian)`` of a B2B chain (module docstring).

    ``ball_function(balls (n, k), extra (g,)) -> BallBlocks`` (its ``jacobian`` may be a function of no arguments: the
    chain's Jacobian is then deferred too, :func:`lowmodel.solvers.newton`); ``pair_function(balls, forces (p,)) ->
    PairBlocks``
    (forces in slot units, 0 on open pairs); the separation rate of pair (behind, ahead) in the units of the
    force slot is ``(x_ahead[rate_index] - x_behind[rate_index]) * rate_scale`` (``rate_scale`` includes
    ``gamma``); ``complementarity`` one of :data:`COMPLEMENTARITY_FUNCTIONS`.  The Jacobian is
    :func:`jacobian_matrix` of the blocks.
    """
    if complementarity not in COMPLEMENTARITY_FUNCTIONS:
        raise ValueError(f"complementarity must be one of {COMPLEMENTARITY_FUNCTIONS}, got {complementarity!r}")
    smooth = complementarity == "fischer-burmeister"
    n, k, g = layout.n_balls, layout.n_unknowns, layout.n_global
    big_k = k + 1
    pairs = layout.pairs
    behind, ahead = pairs[:, 0], pairs[:, 1]
    live = layout._live
    placeholder = ~live
    live_pairs = live[behind]
    every_pair = bool(live_pairs.all())
    chain = not layout.ring and n > 1
    c = int(rate_index)

    def function(z):
        blocks = z[:n * big_k].reshape(n, big_k)
        balls = blocks[:, :k]
        slots = blocks[:, k]
        extra = z[n * big_k:]
        lam = np.where(live, slots, 0.0)
        forces = lam[behind]
        ball = ball_function(balls, extra)
        pair = pair_function(balls, forces)
        residual = np.empty((n, big_k))
        residual[:, :k] = ball.residual
        residual[:, :pair.load.shape[1]] += pair.load  # the B2B loads on every ball (eqs 8, 59)
        # eqs 9-10 / 60-61 as phi(F, gamma separation rate) = 0 (semismooth); placeholders: z = 0
        rate = np.zeros(n)
        rate[behind] = (balls[ahead, c] - balls[behind, c]) * rate_scale
        if smooth:  # d phi / d F and d phi / d rate; placeholders: 1 and 0
            phi, d_lam, d_rate = _fischer_burmeister(lam, rate)
            residual[:, k] = np.where(placeholder, slots, phi)
            d_lam = np.where(placeholder, 1.0, d_lam)
            d_rate = np.where(placeholder, 0.0, d_rate * rate_scale)
        else:  # min(): the active branch
            force_branch = lam <= rate
            force_branch |= placeholder
            residual[:, k] = np.where(force_branch, np.where(placeholder, slots, lam), rate)
            d_lam = force_branch
            d_rate = np.where(force_branch, 0.0, rate_scale)  # d (rate) / d x_ahead[c] on the rate branch
        if g:
            residual = np.concatenate([residual.reshape(-1), ball.global_residual])
        if callable(ball.jacobian):  # the balls' Jacobian deferred (lowmodel.solvers.newton calls it where needed)
            return residual.reshape(-1), lambda: assemble(ball, ball.jacobian(), pair, d_lam, d_rate)
        return residual.reshape(-1), assemble(ball, ball.jacobian, pair, d_lam, d_rate)

    def assemble(ball, ball_jacobian, pair, d_lam, d_rate):
        diagonal = np.zeros((n, big_k, big_k))
        above = np.zeros((len(pairs), big_k, big_k))  # block (behind, ahead) of each pair
        below = np.zeros((len(pairs), big_k, big_k))  # block (ahead, behind)
        diagonal[:, :k, :k] = ball_jacobian
        d_balls = pair.d_balls
        if chain:  # behind = 0..n-2, ahead = 1..n-1: slices (the ring below needs add.at)
            diagonal[:-1, :k, :k] += d_balls[:, 0, 0]
            diagonal[1:, :k, :k] += d_balls[:, 1, 1]
        elif len(pairs):
            np.add.at(diagonal[:, :k, :k], behind, d_balls[:, 0, 0])
            np.add.at(diagonal[:, :k, :k], ahead, d_balls[:, 1, 1])
        above[:, :k, :k] = d_balls[:, 0, 1]
        below[:, :k, :k] = d_balls[:, 1, 0]
        # force columns (slot k of the block of the ball behind): its rows (diagonal) and the rows of the ball ahead
        d_force = pair.d_force if every_pair else np.where(live_pairs[:, None, None], pair.d_force, 0.0)
        if chain:
            diagonal[:-1, :k, k] = d_force[:, 0]
        elif len(pairs):
            diagonal[behind, :k, k] = d_force[:, 0]
        below[:, :k, k] = d_force[:, 1]
        diagonal[:, k, k] = d_lam
        above[:, k, c] = d_rate[behind]
        diagonal[:, k, c] = -d_rate
        extra_blocks = None
        if g:
            extra_blocks = (ball.coupling, ball.global_rows, ball.global_block)
        return jacobian_matrix(layout, diagonal, above, below, extra_blocks)

    return function


def jacobian_matrix(layout: ChainLayout, diagonal, above, below, extra_blocks=None):
    """The chain's Jacobian from its blocks: dense below :data:`SPARSE_BALLS` balls, else a
    :class:`lowmodel.solvers.BlockTridiagonal` (open chain, no global unknowns) or a scipy CSR matrix.

    ``diagonal`` (n, K, K); ``above``/``below`` (p, K, K) the blocks (behind, ahead) and (ahead, behind) of each
    pair; ``extra_blocks`` ``(coupling (n, k, g), global_rows (g, n, k), global_block (g, g))`` or None.
    """
    n, k, g = layout.n_balls, layout.n_unknowns, layout.n_global
    big_k = k + 1
    dense = n < SPARSE_BALLS
    if not layout.ring and not g:
        lower = np.zeros_like(diagonal)
        upper = np.zeros_like(diagonal)
        lower[1:] = below
        upper[:-1] = above
        matrix = BlockTridiagonal(lower, diagonal, upper)
        return matrix.toarray() if dense else matrix
    pairs = layout.pairs
    rows = [np.arange(n), pairs[:, 0], pairs[:, 1]]
    cols = [np.arange(n), pairs[:, 1], pairs[:, 0]]
    values = [diagonal, above, below]
    size = layout.size
    if dense:
        matrix = np.zeros((size, size))
        square = matrix[:n * big_k, :n * big_k].reshape(n, big_k, n, big_k)
        for r, c, v in zip(rows, cols, values):
            np.add.at(square, (r, slice(None), c, slice(None)), v)
        if g:
            coupling, global_rows, global_block = extra_blocks
            matrix[:n * big_k, n * big_k:].reshape(n, big_k, g)[:, :k] = coupling
            matrix[n * big_k:, :n * big_k].reshape(g, n, big_k)[:, :, :k] = global_rows
            matrix[n * big_k:, n * big_k:] = global_block
        return matrix
    local = np.arange(big_k)
    data = [v.reshape(-1) for v in values]
    row_index = [np.broadcast_to(r[:, None, None] * big_k + local[None, :, None], v.shape).reshape(-1)
                 for r, v in zip(rows, values)]
    col_index = [np.broadcast_to(c[:, None, None] * big_k + local[None, None, :], v.shape).reshape(-1)
                 for c, v in zip(cols, values)]
    if g:
        coupling, global_rows, global_block = extra_blocks
        ball_rows = (np.arange(n)[:, None] * big_k + np.arange(k)[None, :]).reshape(-1)
        extra = n * big_k + np.arange(g)
        data += [coupling.reshape(-1), global_rows.reshape(-1), np.asarray(global_block).reshape(-1)]
        row_index += [np.repeat(ball_rows, g), np.repeat(extra, n * k), np.repeat(extra, g)]
        col_index += [np.tile(extra, n * k), np.tile(ball_rows, g), np.tile(extra, g)]
    return sparse.csr_matrix((np.concatenate(data), (np.concatenate(row_index), np.concatenate(col_index))),
                             shape=(size, size))


def chain_forces(z: np.ndarray, layout: ChainLayout, *, rate_index: int, rate_scale: float, tolerance: float,
                 iterations: int, what: str):
    """Ball unknowns (n, k), pair forces (p,) [slot units] and global unknowns (g,) of a converged state of
    :func:`chain_system`, after its one complementarity check: ConvergenceError if eqs 9-10 / 60-61 are violated
    (a negative force or a negative separation rate of a touching pair, in slot units) by more than
    ``10 tolerance``.  Pairs on the ``F = 0`` branch (``F <= gamma r``: the active branch of min(), and the
    separating pairs of a Fischer-Burmeister solution, whose force is round-off) get exactly zero force."""
    balls, forces, extra = layout.unpack(z)
    touching = np.asarray(layout.touching, dtype=int)
    pairs = layout.pairs[touching]
    rate = (balls[pairs[:, 1], rate_index] - balls[pairs[:, 0], rate_index]) * rate_scale
    violation = max(float(np.max(-forces[touching], initial=0.0)), float(np.max(-rate, initial=0.0)))
    if violation > 10 * tolerance:
        raise ConvergenceError(f"{what}: complementarity violated", residual=violation, iterations=iterations,
                               tolerance=tolerance, reason="complementarity violated")
    on_force_branch = touching[forces[touching] <= rate]
    forces = np.maximum(forces, 0.0)
    forces[on_force_branch] = 0.0  # active min() branch F = 0: exactly zero
    return balls, forces, extra
