"""The semismooth Newton solver of the discrete tangential problem (docs/rolling_contact.md, 'Solver').

On the contact cells of a grid with traction bound ``g = mu p_n``, rigid slip ``w`` and an operator ``C``
(:mod:`lowmodel.contact.rolling_operators`), find ``p`` with ``F(p) = p - Proj_g(p - c s(p)) = 0``, ``s = w + C p``
(``Proj_g`` projects each cell's traction onto the disc ``|p| <= g``; ``c = 1/max diag C``, so ``c s`` is a
traction).  Generalised Jacobian ``J = (I - D) + c D C`` with ``D = Proj_g'`` (identity in stick cells,
``(g/|z|)(I - z z^T/|z|^2)`` in slip cells).  Each Newton system is solved by dense LU up to
:data:`DIRECT_CELLS` contact cells (a prepared problem, :meth:`TangentialProblem.prepare`: through the smaller of
two low-rank forms of ``J``, :func:`low_rank_step`), above by GMRES (right preconditioned, Saad 2003 Alg 9.5)
with the exact inverse of ``J`` restricted to each grid line along the rolling direction (the steady-state operator's
coupling is mostly along ``x``: the lateral neighbours carry 8-17 % of the diagonal); products with ``C`` are
dense below :data:`DENSE_CELLS` contact cells and FFT convolutions above.  Newton starts from the local
(FASTSIM-like) solution marched from the leading edge (:meth:`TangentialProblem.marching_start`).

:func:`check_solution` re-evaluates the slip from a traction alone and checks the conditions that define the
answer (Coulomb bound, zero slip in stick cells, traction opposite to the slip in slip cells, non-negative
dissipation in every cell), raising ConvergenceError naming the first that fails.
"""
from __future__ import annotations

import copy
import math

import numpy as np

from ballbench.lowmodel import kernels
from ballbench.lowmodel.errors import ConvergenceError

__all__ = ["TangentialProblem", "semismooth_newton", "check_solution", "low_rank_step", "woodbury_step",
           "identity_step", "compiled_solve", "sensitivity", "SENSITIVITY_TOLERANCE", "KERNELS", "DENSE_CELLS",
           "DIRECT_CELLS", "CHECK_TOLERANCE"]

DENSE_CELLS = 400  # contact cells up to which the operator's products are dense (measured, benchmarks)
DIRECT_CELLS = 150  # contact cells up to which each Newton system is solved by dense LU, not GMRES (benchmarks)
CHECK_TOLERANCE = 1e-7  # the defining conditions hold to this fraction of max(g) (traction units)
KERNELS = "contact.rolling_kernels"  # the compiled twin of the prepared dense solve (lowmodel.kernels.load)
_FORCING = 0.1  # GMRES relative tolerance per Newton step (inexact Newton; min(0.1, residual))
_RESTART = 30
SENSITIVITY_TOLERANCE = 1e-7  # GMRES relative tolerance of each sensitivity system


def _gmres(matvec, precondition, rhs: np.ndarray, tolerance: float, max_iterations: int, start=None):
    """Right-preconditioned restarted GMRES (Saad 2003, Alg 9.5) from ``start`` (default zero) to
    ``|rhs - A x| <= tolerance |rhs|``; returns ``(x, iterations)``."""
    n = rhs.size
    x = np.zeros(n)
    norm_b = math.sqrt(float(rhs @ rhs))
    if norm_b == 0.0:
        return x, 0
    residual = rhs
    if start is not None:
        x = np.array(start, dtype=float).reshape(n)
        residual = rhs - matvec(x)
    total = 0
    while True:
        beta = math.sqrt(float(residual @ residual))
        m = min(_RESTART, max_iterations - total)
        if m <= 0 or beta <= tolerance * norm_b:
            return x, total
        basis = np.empty((m + 1, n))
        upper = np.zeros((m, m))
        rotations = []
        g = [beta]
        basis[0] = residual / beta
        k = 0
        for j in range(m):
            total += 1
            w = matvec(precondition(basis[j]))
            norm_before = math.sqrt(float(w @ w))
            h = basis[:j + 1] @ w
            w -= h @ basis[:j + 1]
            norm_w = math.sqrt(float(w @ w))
            if norm_w < 0.5 * norm_before:  # cancellation: classical Gram-Schmidt once more (Daniel et al. 1976)
                correction = basis[:j + 1] @ w
                w -= correction @ basis[:j + 1]
                h += correction
                norm_w = math.sqrt(float(w @ w))
            column = h.tolist()
            column.append(norm_w)
            for i, (c, s_) in enumerate(rotations):
                column[i], column[i + 1] = c * column[i] + s_ * column[i + 1], -s_ * column[i] + c * column[i + 1]
            radius = math.hypot(column[j], column[j + 1])
            k = j + 1
            if radius == 0.0:
                k = j
                break
            c, s_ = column[j] / radius, column[j + 1] / radius
            rotations.append((c, s_))
            column[j] = radius
            upper[:j + 1, j] = column[:j + 1]
            g.append(-s_ * g[j])
            g[j] *= c
            if norm_w == 0.0 or abs(g[j + 1]) <= tolerance * norm_b:
                break
            basis[j + 1] = w / norm_w
        if k:
            y = np.linalg.solve(upper[:k, :k], np.asarray(g[:k]))
            x += precondition(y @ basis[:k])
        if abs(g[k]) <= tolerance * norm_b or total >= max_iterations or k == 0:
            return x, total
        residual = rhs - matvec(x)


class TangentialProblem:
    """The discrete tangential problem on the contact cells of a grid (shared by Newton and the checks)."""

    def __init__(self, operator, bound: np.ndarray, rigid: np.ndarray, dense: bool | None):
        grid = operator.grid
        self.operator = operator
        self.shape = (grid.nx, grid.ny)
        self.contact = bound > 0.0
        self.cells = np.flatnonzero(self.contact)
        self.n = self.cells.size
        self.g = bound.reshape(-1)[self.cells]
        self.w = rigid.reshape(-1, 2)[self.cells]
        self.gmax = float(self.g.max())
        self.c = 1.0 / float(np.max(operator.diagonal))
        if not (math.isfinite(self.c) and self.c > 0.0):
            raise ValueError("the operator's self-influence must be positive (a compliance)")
        self.dense = self.n <= DENSE_CELLS if dense is None else bool(dense)
        self.matrix = operator.dense(self.cells) if self.dense else None
        i, j = np.divmod(self.cells, grid.ny)
        self.lines, self.line_of = np.unique(j, return_inverse=True)
        self.position = i  # index along the line
        self._column = j
        self._padded = None  # the contact cells' index in the operator's padded FFT field, on first use
        self.flat = self.line_of * grid.nx + self.position
        self._inverse = None
        self._pattern = None
        self._pairs = None
        self._flexibility = None
        self._bound_lines = None
        self._stick_inverse = None
        self.workspace = None  # a dict kept by the caller across solves of one contact (preconditioner)

    def with_rigid(self, rigid_cells: np.ndarray) -> "TangentialProblem":
        """The same contact (cells, bound, operator and what is derived from them) with another rigid slip ``w``
        on the contact cells, (n, 2): a sweep over creepages reuses everything but ``w``."""
        problem = copy.copy(self)
        problem.w = rigid_cells
        problem._inverse = problem._pattern = None  # the preconditioner's state belongs to one solve
        return problem

    def prepare(self) -> "TangentialProblem":
        """Build now what every solve on this contact derives from the cells alone (the marching start's
        flexibility, the dense preconditioner's index), so that :meth:`with_rigid` copies carry it."""
        self.flexibility()
        self._line_bound()
        if self.matrix is not None and self.n > DIRECT_CELLS:
            self._pair_index()
        if self.matrix is not None and self.n <= DIRECT_CELLS:
            inverse = np.linalg.inv(self.c * self.matrix)  # (c C)^-1: J of an all-stick contact, inverted once
            if np.all(np.isfinite(inverse)):
                inverse.setflags(write=False)
                self._stick_inverse = inverse
        return self

    def stick_inverse(self) -> np.ndarray | None:
        """``(c C)^-1`` on the contact cells, (2n, 2n), when :meth:`prepare` built it (dense problems up to
        :data:`DIRECT_CELLS` cells), else None; with it the Newton steps use Woodbury's identity."""
        return self._stick_inverse

    def _pair_index(self):
        if self._pairs is None:  # kept on the operator per contact set, as its dense blocks
            cache = self.operator.__dict__.setdefault("_pair_cache", {})
            key = self.cells.tobytes()
            if key not in cache:
                if len(cache) >= 4:
                    cache.pop(next(iter(cache)))
                cache[key] = _pair_index_of(self)
            self._pairs = cache[key]
        return self._pairs

    def apply(self, v: np.ndarray) -> np.ndarray:
        """``C v`` on the contact cells, ``v`` (n, 2) -> (n, 2)."""
        if self.matrix is not None:
            return (self.matrix @ v.reshape(-1)).reshape(-1, 2)
        if hasattr(self.operator, "convolution"):  # the FFT product on the contact cells alone
            convolution = self.operator.convolution()
            if self._padded is None:
                self._padded = convolution.padded_index(self.position, self._column)
            return convolution.on_cells(self._padded, v)
        field = np.zeros(self.shape + (2,))
        field.reshape(-1, 2)[self.cells] = v
        return self.operator.apply(field).reshape(-1, 2)[self.cells]

    def slip(self, p: np.ndarray) -> np.ndarray:
        return self.w + self.apply(p)

    def residual(self, p: np.ndarray):
        """``F(p)``, ``z = p - c s``, its norm, the slip mask and ``min(1, g/|z|)``."""
        z = p - self.c * self.slip(p)
        norm = np.hypot(z[:, 0], z[:, 1])
        sliding = norm > self.g
        scale = np.where(sliding, self.g / np.where(sliding, norm, 1.0), 1.0)
        return p - z * scale[:, None], z, norm, sliding, scale

    def flexibility(self) -> float:
        """``L / dx`` of :meth:`marching_start`: the mean slip of a unit traction ramp along each line (one
        product with ``C``; it depends on the contact cells only, so it is kept)."""
        if self._flexibility is None:
            nx, n_lines = self.shape[0], self.lines.size
            ramp = np.zeros((n_lines, nx))
            ramp[self.line_of, self.position] = 1.0
            ramp = np.cumsum(ramp[:, ::-1], axis=1)[:, ::-1] * (ramp > 0)  # contact cells upstream, incl. itself
            test = np.repeat(ramp[self.line_of, self.position][:, None], 2, axis=1)
            response = self.apply(test)
            self._flexibility = float(np.median(response[test[:, 0] > 1.5]) if np.any(test[:, 0] > 1.5) else
                                      np.median(response))
        return self._flexibility

    def _line_bound(self) -> np.ndarray:
        if self._bound_lines is None:  # g on (lines, nx), zero off the contact
            g = np.zeros((self.lines.size, self.shape[0]))
            g[self.line_of, self.position] = self.g
            g.setflags(write=False)
            self._bound_lines = g
        return self._bound_lines

    def marching_start(self) -> np.ndarray:
        """A start for Newton: the local (FASTSIM-like) solution ``s = w + L (p_i - p_upstream) / dx = 0`` marched
        from the leading edge with the traction bound, ``L`` the flexibility that makes a unit traction ramp
        along each line give the operator's mean slip (:meth:`flexibility`)."""
        nx, n_lines = self.shape[0], self.lines.size
        flexibility = self.flexibility()  # L / dx
        if not (math.isfinite(flexibility) and flexibility > 0.0):
            return np.zeros((self.n, 2))
        w = np.zeros((n_lines, nx, 2))
        w[self.line_of, self.position] = self.w / flexibility
        g = self._line_bound()
        p = np.zeros((n_lines, nx, 2))
        upstream = np.zeros((n_lines, 2))
        for i in range(nx - 1, -1, -1):
            trial = upstream - w[:, i]
            norm = np.hypot(trial[:, 0], trial[:, 1])
            limit = g[:, i]
            # the quotient only where it is < 1 (limit >= 0): a subnormal |trial| cannot overflow it
            sliding = norm > limit
            trial *= np.where(sliding, limit / np.where(sliding, norm, 1.0), 1.0)[:, None]
            p[:, i] = upstream = trial
        return p[self.line_of, self.position]

    def preconditioner(self, D: np.ndarray, sliding: np.ndarray):
        """The inverse of ``J`` restricted to each grid line along ``x`` (line blocks; others identity).

        A line's inverse is rebuilt only when the stick/slip pattern of its cells changed since it was
        built (a stale slip direction only costs GMRES steps); single precision (a preconditioner).  With a
        :attr:`workspace` (a dict its caller keeps for one contact) the inverses outlive the solve: it keeps a copy of
        the last ones per contact set, and the next solve on the same cells (the ball's next Newton step) starts
        from them.
        """
        nx = self.shape[0]
        n_lines = self.lines.size
        pattern = np.zeros((n_lines, nx), dtype=bool)
        pattern.reshape(-1)[self.flat] = sliding
        cache = self.workspace  # the caller's store of the last line inverses per contact set, or None
        key = self.cells.tobytes() if cache is not None else None
        kept = cache.get(key) if self._inverse is None and cache is not None else None
        if kept is not None:  # a new solve on these cells starts from the last one's line inverses
            self._pattern, self._inverse = kept[0], kept[1].copy()
        if self._inverse is None:
            self._inverse = np.empty((n_lines, 2 * nx, 2 * nx), dtype=np.float32)
            todo = np.arange(n_lines)
        else:
            todo = np.flatnonzero(np.any(pattern != self._pattern, axis=1))
        self._pattern = pattern
        inverse = self._inverse
        if todo.size:
            full_D = np.zeros((n_lines * nx, 2, 2))
            full_D[self.flat] = D
            full_D = full_D.reshape(n_lines, nx, 2, 2)[todo]
            blocks = self.operator.line_blocks(self.lines)
            blocks = np.broadcast_to(blocks[0], (todo.size,) + blocks.shape[1:]) if blocks.strides[0] == 0 \
                else blocks[todo]
            rows = blocks.reshape(todo.size, nx, 2, 2 * nx)
            J = self.c * (full_D[..., 0, None] * rows[:, :, None, 0, :] + full_D[..., 1, None] * rows[:, :, None, 1, :])
            diagonal = J.reshape(todo.size, nx, 2, nx, 2)[:, np.arange(nx), :, np.arange(nx), :]  # (nx, lines, 2, 2)
            diagonal -= full_D.transpose(1, 0, 2, 3)
            diagonal[..., 0, 0] += 1.0
            diagonal[..., 1, 1] += 1.0
            J.reshape(todo.size, nx, 2, nx, 2)[:, np.arange(nx), :, np.arange(nx), :] = diagonal
            inverse[todo] = np.linalg.inv(J.reshape(todo.size, 2 * nx, 2 * nx).astype(np.float32))
            if cache is not None:
                cache[key] = (pattern, inverse.copy())  # a snapshot: this problem goes on updating its own
                for old in list(cache)[:-4]:  # the last four contact sets
                    cache.pop(old, None)
        flat = self.flat
        if self.matrix is not None:  # dense problems: the line inverses as one (2n, 2n) matrix, one product
            rows, cols, source = self._pair_index()
            dense = np.zeros((2 * self.n, 2 * self.n))
            dense[rows, cols] = inverse.reshape(-1)[source]
            return dense.__matmul__

        def apply(v):
            field = np.zeros((n_lines * nx, 2), dtype=np.float32)
            field[flat] = v.reshape(-1, 2)
            out = np.matmul(inverse, field.reshape(n_lines, 2 * nx, 1)).reshape(n_lines * nx, 2)
            return out[flat].reshape(-1).astype(float)

        return apply


def _pair_index_of(problem: "TangentialProblem"):
    # (row, column) in the (2n, 2n) problem and the flat index into the (lines, 2 nx, 2 nx) inverses of every
    # pair of components of two contact cells on one line
    nx = problem.shape[0]
    rows, cols, source = [], [], []
    for line in range(problem.lines.size):
        members = np.flatnonzero(problem.line_of == line)
        position = problem.position[members]
        for a in range(2):
            for b in range(2):
                r = (2 * members + a)[:, None]
                c = (2 * members + b)[None, :]
                pr = (2 * position + a)[:, None]
                pc = (2 * position + b)[None, :]
                rows.append(np.broadcast_to(r, (members.size, members.size)).ravel())
                cols.append(np.broadcast_to(c, (members.size, members.size)).ravel())
                source.append((line * 2 * nx * 2 * nx + pr * 2 * nx + pc).ravel())
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(source)


def _derivative(z: np.ndarray, norm: np.ndarray, sliding: np.ndarray, scale: np.ndarray) -> np.ndarray:
    # Proj_g'(z): identity in stick cells, (g/|z|)(I - zz^T/|z|^2) in slip cells; (n, 2, 2)
    unit = z / np.where(sliding, norm, np.inf)[:, None]
    D = np.empty((z.shape[0], 2, 2))
    D[:, 0, 0] = scale * (1.0 - unit[:, 0] ** 2)
    D[:, 1, 1] = scale * (1.0 - unit[:, 1] ** 2)
    D[:, 0, 1] = D[:, 1, 0] = -scale * unit[:, 0] * unit[:, 1]
    return D


def low_rank_step(matrix, c, inverse, F, E, z, norm, sliding, scale) -> np.ndarray:
    """The Newton step ``J dp = -F`` of a prepared dense problem through the smaller of two low-rank forms of
    ``J`` (Sherman-Morrison-Woodbury, Golub & Van Loan 2013, Sec 2.1.4): around ``c C`` (rank ``2 m``, ``m``
    slip cells; :func:`woodbury_step`) or around ``I`` (rank ``2 (n - m) + m``; :func:`identity_step`)."""
    slipping = int(np.count_nonzero(sliding))
    if 2 * slipping <= 2 * (F.shape[0] - slipping) + slipping:
        return woodbury_step(inverse, F, E, sliding)
    return identity_step(matrix, c, F, z, norm, sliding, scale)


def identity_step(matrix, c, F, z, norm, sliding, scale) -> np.ndarray:
    """The Newton step ``J dp = -F`` with ``J = I + U W`` (Woodbury around the identity).

    A stick cell's rows of ``J - I`` are those of ``c C - I``; a slip cell's are ``D (c C - I)`` with ``D = s t t^T``
    (``t`` normal to ``z``, ``s = g/|z|``; ``E - I = -D``), rank one.  So ``U`` has the unit columns of the stick
    components and ``t`` for each slip cell, ``W`` the matching rows, and ``J^-1 b = b - U (I + W U)^-1 W b``:
    one LU of two unknowns per stick cell and one per slip cell.
    """
    n = F.shape[0]
    b = -F.reshape(-1)
    stick, slip = np.flatnonzero(~sliding), np.flatnonzero(sliding)
    t0, t1 = -z[slip, 1] / norm[slip], z[slip, 0] / norm[slip]
    s = scale[slip]
    rows = (2 * stick[:, None] + np.arange(2)).reshape(-1)
    k = rows.size
    m = k + slip.size
    W = np.empty((m, 2 * n))
    np.multiply(c, matrix[rows], out=W[:k])
    W[np.arange(k), rows] -= 1.0
    pair = matrix.reshape(n, 2, 2 * n)[slip]
    np.multiply((c * s * t0)[:, None], pair[:, 0], out=W[k:])
    W[k:] += (c * s * t1)[:, None] * pair[:, 1]
    W[np.arange(k, m), 2 * slip] -= s * t0
    W[np.arange(k, m), 2 * slip + 1] -= s * t1
    capacitance = np.empty((m, m))
    capacitance[:, :k] = W[:, rows]
    np.multiply(W[:, 2 * slip], t0, out=capacitance[:, k:])
    capacitance[:, k:] += W[:, 2 * slip + 1] * t1
    capacitance[np.arange(m), np.arange(m)] += 1.0
    y = np.linalg.solve(capacitance, W @ b)
    b[rows] -= y[:k]
    b[2 * slip] -= t0 * y[k:]
    b[2 * slip + 1] -= t1 * y[k:]
    return b.reshape(-1, 2)


def woodbury_step(inverse: np.ndarray, F: np.ndarray, E: np.ndarray, sliding: np.ndarray) -> np.ndarray:
    """The Newton step ``J dp = -F`` from ``A^-1 = (c C)^-1`` (the Jacobian of an all-stick contact) by the
    Sherman-Morrison-Woodbury identity (Golub & Van Loan 2013, Sec 2.1.4).

    ``J = E + c D C`` differs from ``A`` only in the rows of the ``m`` slip cells ``S``, where ``D - I = -E``:
    ``J = A + U W`` with ``U`` the unit columns of ``S`` and ``W = E_S (I_S - A_S)``, so ``W A^-1 = E_S
    (A^-1_S - I_S)`` and ``J^-1 b = x0 - A^-1 U (I + E_S (A^-1_SS - I))^-1 E_S (x0_S - b_S)``, ``x0 = A^-1 b``:
    one LU of ``2m`` unknowns instead of ``2n``.
    """
    b = -F.reshape(-1)
    x0 = inverse @ b
    slip = np.flatnonzero(sliding)
    if slip.size == 0:
        return x0.reshape(-1, 2)
    rows = (2 * slip[:, None] + np.arange(2)).reshape(-1)
    k = rows.size
    E = E[slip]
    X = inverse[np.ix_(rows, rows)]
    X[np.arange(k), np.arange(k)] -= 1.0
    X = X.reshape(slip.size, 2, k)
    capacitance = E[:, :, 0, None] * X[:, None, 0, :]
    capacitance += E[:, :, 1, None] * X[:, None, 1, :]
    capacitance = capacitance.reshape(k, k)
    capacitance[np.arange(k), np.arange(k)] += 1.0
    d = (x0[rows] - b[rows]).reshape(-1, 2)
    y = np.linalg.solve(capacitance, np.einsum("kab,kb->ka", E, d).reshape(-1))
    return (x0 - inverse[:, rows] @ y).reshape(-1, 2)


def _step_solver(problem: TangentialProblem, z: np.ndarray, norm: np.ndarray, sliding: np.ndarray,
                 scale: np.ndarray, D: np.ndarray | None = None):
    """``solve(F, forcing, start=None) -> (dp, krylov steps)``: the solution of ``J dp = -F`` with the generalised
    Jacobian ``J = (I - D) + c D C`` at the state ``z`` (module docstring; ``D`` its projection's derivative where the
    caller has it); ``forcing`` the relative tolerance of GMRES where the system is iterative, ``start`` (n, 2) its
    first guess (the prepared dense and direct systems are solved exactly, without one)."""
    D = _derivative(z, norm, sliding, scale) if D is None else D
    E = -D
    E[:, 0, 0] += 1.0
    E[:, 1, 1] += 1.0
    c = problem.c
    cD = c * D
    inverse = problem.stick_inverse()
    if inverse is not None:  # prepared dense problems: a low-rank form of J (low_rank_step)
        return lambda F, _forcing, _start=None: (low_rank_step(problem.matrix, c, inverse, F, E, z, norm, sliding,
                                                              scale), 0)
    if problem.matrix is not None:  # J = E + c D C as one dense matrix: one product per GMRES step
        n = problem.n
        rows = problem.matrix.reshape(n, 2, 2 * n)
        jacobian = cD[:, :, 0, None] * rows[:, None, 0, :]
        jacobian += cD[:, :, 1, None] * rows[:, None, 1, :]
        jacobian.reshape(n, 2, n, 2)[np.arange(n), :, np.arange(n), :] += E
        jacobian = jacobian.reshape(2 * n, 2 * n)
        if n <= DIRECT_CELLS:
            return lambda F, _forcing, _start=None: (np.linalg.solve(jacobian, -F.reshape(-1)).reshape(-1, 2), 0)
        matvec = jacobian.__matmul__
    else:
        def matvec(v):
            v = v.reshape(-1, 2)
            Cv = problem.apply(v)
            out = E[:, :, 0] * v[:, 0, None]
            out += E[:, :, 1] * v[:, 1, None]
            out += cD[:, :, 0] * Cv[:, 0, None]
            out += cD[:, :, 1] * Cv[:, 1, None]
            return out.reshape(-1)
    precondition = problem.preconditioner(D, sliding)

    def solve(F, forcing, start=None):
        step, used = _gmres(matvec, precondition, -F.reshape(-1), forcing, 200, start)
        return step.reshape(-1, 2), used

    return solve


def semismooth_newton(problem: TangentialProblem, tolerance: float, max_iterations: int, start: np.ndarray | None):
    p = problem.marching_start() if start is None else start.copy()
    F, z, norm, sliding, scale = problem.residual(p)
    residual = float(np.max(np.abs(F))) / problem.gmax
    krylov = 0
    for iteration in range(1, max_iterations + 1):
        if residual <= tolerance:
            return p, iteration - 1, krylov, residual
        step, used = _step_solver(problem, z, norm, sliding, scale)(F, min(_FORCING, residual))
        krylov += used
        norm_F = float(np.sum(F * F))
        t = 1.0
        for _ in range(8):  # backtracking on |F|^2: the first step that decreases it
            trial = p + t * step
            result = problem.residual(trial)
            if float(np.sum(result[0] ** 2)) <= (1.0 - 1e-4 * t) * norm_F:
                break
            t *= 0.5
        p = trial
        F, z, norm, sliding, scale = result
        residual = float(np.max(np.abs(F))) / problem.gmax
    if residual <= tolerance:
        return p, max_iterations, krylov, residual
    raise ConvergenceError("rolling contact (semismooth Newton) did not converge: max|p - Proj(p - c s)| / max(g)",
                           residual=residual, iterations=max_iterations, tolerance=tolerance, reason="iteration limit")


def sensitivity(problem: TangentialProblem, p: np.ndarray, directions: np.ndarray,
                tolerance: float = SENSITIVITY_TOLERANCE, start: np.ndarray | None = None) -> np.ndarray:
    """``dp/dw`` along ``directions``: (n, 2, k) changes of the rigid slip ``w`` on the contact cells -> (n, 2, k)
    changes of the traction at the solution ``p`` (the implicit function theorem on ``F(p, w) = 0``:
    ``J dp = -c D dw``, ``D = Proj_g'(z)`` and ``J`` the generalised Jacobian of the last Newton step; docs/
    rolling_contact.md, 'Sensitivity').  A cell on the stick/slip boundary takes the derivative of the side its
    ``z`` lies on (the semismooth Newton's choice).  Iterative systems are solved to the relative ``tolerance``,
    from ``start`` (n, 2, k) where given (a nearby solution's sensitivity: fewer Krylov steps, the same tolerance)."""
    directions = np.asarray(directions, dtype=float)
    if directions.ndim != 3 or directions.shape[:2] != (problem.n, 2):
        raise ValueError(f"directions must have shape ({problem.n}, 2, k), got {directions.shape}")
    if start is not None and np.shape(start) != directions.shape:
        raise ValueError(f"start must have the shape of directions, {directions.shape}, got {np.shape(start)}")
    _, z, norm, sliding, scale = problem.residual(p)
    D = _derivative(z, norm, sliding, scale)
    solve = _step_solver(problem, z, norm, sliding, scale, D)
    out = np.empty_like(directions)
    with_c = problem.c * np.einsum("nab,nbk->nak", D, directions)  # c D dw: J dp = -F with F = c D dw
    for j in range(directions.shape[2]):
        out[:, :, j] = solve(with_c[:, :, j], tolerance, None if start is None else start[:, :, j])[0]
    return out


def check_solution(problem: TangentialProblem, p: np.ndarray, tolerance: float):
    """The defining conditions, re-evaluated from ``p`` alone; ConvergenceError naming the first that fails."""
    s = problem.slip(p)
    g, gmax, c = problem.g, problem.gmax, problem.c
    magnitude = np.hypot(p[:, 0], p[:, 1])
    slip_norm = np.hypot(s[:, 0], s[:, 1])
    z = p - c * s
    sliding = np.hypot(z[:, 0], z[:, 1]) > g
    limit = max(tolerance, CHECK_TOLERANCE)
    checks_ = []
    checks_.append(("Coulomb bound max(|p| - mu p_n) / max(mu p_n)", float(np.max(magnitude - g)) / gmax))
    stick_slip = c * slip_norm[~sliding]
    checks_.append(("stick condition max(c |s|) / max(mu p_n) in stick cells",
                    float(stick_slip.max()) / gmax if stick_slip.size else 0.0))
    moving = sliding & (c * slip_norm > limit * gmax)
    if np.any(moving):
        direction = p[moving] + g[moving, None] * s[moving] / slip_norm[moving, None]
        checks_.append(("slip direction max|p + mu p_n s/|s|| / max(mu p_n) in slip cells",
                        float(np.max(np.hypot(direction[:, 0], direction[:, 1]))) / gmax))
    work = -(p[:, 0] * s[:, 0] + p[:, 1] * s[:, 1]) * c
    checks_.append(("dissipation -min(c p . s) / max(mu p_n)^2 (no cell does negative work)",
                    max(0.0, -float(work.min())) / gmax ** 2))
    _raise_failed(checks_, limit)
    return s, ~sliding


_CHECK_NAMES = ("Coulomb bound max(|p| - mu p_n) / max(mu p_n)",
                "stick condition max(c |s|) / max(mu p_n) in stick cells",
                "slip direction max|p + mu p_n s/|s|| / max(mu p_n) in slip cells",
                "dissipation -min(c p . s) / max(mu p_n)^2 (no cell does negative work)")


def _raise_failed(checks_, limit: float) -> None:
    for name, value in checks_:
        if not (value <= limit):
            raise ConvergenceError(f"rolling contact: check failed, {name} = {value:.3e}", residual=value,
                                   iterations=0, tolerance=limit, reason=f"fails the check of {name}")


def compiled_solve(problem: TangentialProblem, tolerance: float, max_iterations: int, start: np.ndarray | None):
    """:func:`semismooth_newton` and :func:`check_solution` of a prepared dense problem (``(c C)^-1`` built,
    :meth:`TangentialProblem.prepare`) by the compiled kernels of :mod:`lowmodel.contact.rolling_kernels`: the
    same steps as loops, the same answer to round-off.  Returns ``(p, s, stick, iterations, 0, residual)``, or
    None where the kernels are off or missing or the problem is not prepared dense (then the numpy path runs;
    it also runs again where the kernel's Newton does not converge, and names the failure)."""
    inverse = problem.stick_inverse()
    if inverse is None or problem.matrix is None:
        return None
    module = kernels.load(KERNELS)
    if module is None:
        return None
    w = np.ascontiguousarray(problem.w, dtype=float)
    g = problem.g
    if start is not None:
        p = np.array(start, dtype=float)
    else:
        flexibility = problem.flexibility()
        if not (math.isfinite(flexibility) and flexibility > 0.0):
            p = np.zeros((problem.n, 2))
        else:
            p = module.marching_start(w, flexibility, problem._line_bound(), problem.line_of, problem.position)
    p, iterations, residual, status = module.newton(problem.matrix, inverse, problem.c, g, w, problem.gmax,
                                                    float(tolerance), int(max_iterations), p)
    if status != module.CONVERGED:
        return None
    limit = max(tolerance, CHECK_TOLERANCE)
    s, stick, values = module.check_values(problem.matrix, problem.c, g, w, problem.gmax, p, limit)
    named = list(zip(_CHECK_NAMES, values.tolist()))
    if not all(value <= limit for _, value in named):
        _raise_failed(named, limit)
    return p, s, stick, iterations, 0, residual

