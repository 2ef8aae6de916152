"""Sparse symmetric positive-definite solves for the contact solver.

:func:`inverse_block` returns ``(K^-1)[c, c]``, the block of the inverse of a
sparse SPD matrix on a (small) set ``c`` of DOFs: this is the contact
compliance of those DOFs.  Methods (measured in docs/fem.md):

``"schur"``  MKL pardiso's Schur-complement mode (``iparm[35] = 1``): the
    factorisation with the ``c`` DOFs ordered last returns the dense Schur
    complement ``S = K_cc - K_ci K_ii^-1 K_ic``; ``(K^-1)_cc = S^-1``.
``"rhs"``    pardiso factorisation, then ``K X = E_c`` for the unit columns of
    ``c`` in blocks of 256 right-hand sides.
``"splu"``   SciPy SuperLU with the same block right-hand sides (no MKL needed).

:func:`factorize` returns a callable ``solve(b)`` (pardiso, else SuperLU).
:func:`compliance` with ``keep_factor=True`` also returns the factor it used
(:class:`CondensedFactor`), so the full displacement field of a solved contact needs no
second factorisation of ``K`` (docs/fem.md).
"""
from __future__ import annotations

import ctypes
import weakref

import numpy as np
import scipy.sparse as sp
from scipy.sparse.linalg import splu

__all__ = ["compliance", "inverse_block", "factorize", "CondensedFactor", "METHODS"]

METHODS = ("schur", "rhs", "splu")


def _pardiso_available() -> bool:
    try:
        import pypardiso  # noqa: F401
    except Exception:  # pragma: no cover - MKL missing
        return False
    return True


def factorize(K: sp.spmatrix):
    """``solve(b)`` for the SPD matrix ``K`` (b of shape (n,) or (n, k))."""
    K = sp.csr_matrix(K)
    if _pardiso_available():
        import pypardiso

        solver = pypardiso.PyPardisoSolver(mtype=2)  # real SPD: the upper triangle is used
        upper = sp.triu(K, format="csr")
        upper.sort_indices()
        solver.factorize(upper)

        def solve(b):
            return solver.solve(upper, np.asarray(b, dtype=float))

        solve.free = lambda: solver.free_memory(everything=True)
        return solve
    lu = splu(K.tocsc())

    def solve(b):
        return lu.solve(np.asarray(b, dtype=float))

    solve.free = lambda: None
    return solve


class _Pardiso:
    """One MKL pardiso handle (symmetric ``mtype`` 2 or -2) on the upper triangle of a matrix, called
    through pypardiso's MKL handle; ``schur`` DOFs (optional) are ordered last (``iparm[35] = 2``:
    their dense Schur complement is returned by the factorisation and the whole factor is kept for
    partial solves)."""

    def __init__(self, upper: sp.csr_matrix, mtype: int, schur: np.ndarray | None = None):
        import pypardiso

        host = pypardiso.PyPardisoSolver(mtype=mtype)
        self._lib = host._mkl_pardiso
        self.n = upper.shape[0]
        self.mtype = mtype
        self.pt = np.zeros(64, dtype=np.int64)
        self.iparm = np.zeros(64, dtype=np.int32)
        self.iparm[0] = 1  # no solver defaults
        self.iparm[1] = 2  # nested dissection (METIS)
        self.iparm[9] = 8  # pivot perturbation 1e-8
        self.iparm[34] = 1  # zero-based indexing
        self.perm = np.zeros(self.n, dtype=np.int32)
        self.nschur = 0 if schur is None else int(schur.size)
        if schur is not None:
            self.iparm[35] = 2  # Schur complement, whole factor kept (partial solves 331-333)
            self.perm[schur] = 1
        self.ia = upper.indptr.astype(np.int32)
        self.ja = upper.indices.astype(np.int32)
        self.data = np.ascontiguousarray(upper.data, dtype=float)
        self.alive = False

    def call(self, phase: int, b: np.ndarray, x: np.ndarray, nrhs: int = 1) -> None:
        error = ctypes.c_int32(0)
        i32 = ctypes.POINTER(ctypes.c_int32)
        f64 = ctypes.POINTER(ctypes.c_double)
        self._lib(self.pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)), ctypes.byref(ctypes.c_int32(1)),
                  ctypes.byref(ctypes.c_int32(1)), ctypes.byref(ctypes.c_int32(self.mtype)),
                  ctypes.byref(ctypes.c_int32(phase)), ctypes.byref(ctypes.c_int32(self.n)),
                  self.data.ctypes.data_as(f64), self.ia.ctypes.data_as(i32), self.ja.ctypes.data_as(i32),
                  self.perm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(nrhs)),
                  self.iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)), b.ctypes.data_as(f64),
                  x.ctypes.data_as(f64), ctypes.byref(error))
        if error.value != 0:
            raise RuntimeError(f"MKL pardiso phase {phase} failed with error {error.value}")

    def factorize(self) -> np.ndarray | None:
        """Analysis and factorisation; the dense Schur complement (``nschur`` x ``nschur``) if any."""
        schur = np.zeros((max(self.nschur, 1), max(self.nschur, 1)), dtype=float, order="F")
        try:
            self.call(12, np.zeros(self.n), schur)
        except RuntimeError:
            self.free()
            raise
        self.alive = True
        # pardiso returns the Schur block in the order of increasing global index
        return np.ascontiguousarray(schur) if self.nschur else None

    def free(self) -> None:
        if self.alive or self.pt.any():
            self.call(-1, np.zeros(1), np.zeros(1))
        self.alive = False


def _schur_pardiso(K: sp.csr_matrix, c: np.ndarray, mtype: int = 2) -> np.ndarray:
    """Dense Schur complement of the symmetric ``K`` onto ``c`` by MKL pardiso (iparm[35] = 1);
    ``mtype`` 2 (SPD) or -2 (symmetric indefinite)."""
    upper = sp.triu(K, format="csr")
    upper.sort_indices()
    handle = _Pardiso(upper, mtype, np.asarray(c))
    try:
        return handle.factorize()
    finally:
        handle.free()


class CondensedFactor:
    """The factor of the augmented ``[[K, B^T], [B, 0]]`` that :func:`compliance` computed ``W`` with,
    kept so that solves with the same ``K`` need no second factorisation.

    ``solve(f, mu=None)`` returns ``u = K^-1 (f - B^T mu)`` (n,) [``mu`` (m,), default 0: ``K^-1 f``]
    by pardiso's partial solves (forward 331, diagonal 332, then the Schur unknowns set to ``mu``,
    backward 333: the block LDL^T of the augmented matrix with the multipliers last).  ``free()``
    releases the factor (also when the object is collected)."""

    def __init__(self, handle: _Pardiso, n: int):
        self._handle = handle
        self.n = n
        self._finalizer = weakref.finalize(self, handle.free)

    @property
    def alive(self) -> bool:
        return self._handle.alive

    def solve(self, f, mu=None) -> np.ndarray:
        if not self._handle.alive:
            raise RuntimeError("the factor was freed")
        f = np.asarray(f, dtype=float)
        if f.shape != (self.n,):
            raise ValueError(f"f must have shape ({self.n},), got {f.shape}")
        total = self._handle.n
        rhs = np.zeros(total)
        rhs[:self.n] = f
        forward, diagonal, out = np.zeros(total), np.zeros(total), np.zeros(total)
        self._handle.call(331, rhs, forward)
        self._handle.call(332, forward, diagonal)
        diagonal[self.n:] = 0.0 if mu is None else np.asarray(mu, dtype=float)
        self._handle.call(333, diagonal, out)
        return out[:self.n]

    __call__ = solve

    def free(self) -> None:
        self._finalizer()


def compliance(K: sp.spmatrix, B: sp.spmatrix, method: str = "augmented", *, keep_factor: bool = False):
    """Dense ``W = B K^-1 B^T`` (m x m) for SPD sparse ``K`` (n x n) and sparse ``B`` (m x n).

    ``"augmented"``: pardiso's Schur complement of the symmetric indefinite
    ``[[K, B^T], [B, 0]]`` onto its last m rows is ``-W`` (the dense part is only
    m x m, not the size of B's column support).  Other methods: ``B_c (K^-1)_cc B_c^T``
    with :func:`inverse_block` on the columns ``c`` that B touches.

    ``keep_factor``: return ``(W, factor)``, ``factor`` the :class:`CondensedFactor` that solves with the
    same ``K`` without factorising again (``"augmented"`` with pardiso; None for the other methods,
    which factorise ``K`` itself only where they must).
    """
    B = sp.csr_matrix(B)
    if method == "augmented" and _pardiso_available():
        m = B.shape[0]
        zero = sp.diags(np.zeros(m), format="csr")  # explicit zero diagonal (pardiso needs the entries)
        augmented = sp.bmat([[sp.csr_matrix(K), B.T], [B, zero]], format="csr")
        augmented.sum_duplicates()
        upper = sp.triu(augmented, format="csr")
        # make sure the zero diagonal entries are stored
        upper = upper + sp.diags(np.r_[np.zeros(K.shape[0]), np.full(m, 1e-300)], format="csr")
        n = K.shape[0]
        upper = sp.csr_matrix(upper)
        upper.sort_indices()
        handle = _Pardiso(upper, -2, np.arange(n, n + m))
        W = -handle.factorize()
        W = 0.5 * (W + W.T)
        if keep_factor:
            return W, CondensedFactor(handle, n)
        handle.free()
        return W
    columns = np.flatnonzero(B.getnnz(axis=0))
    block = inverse_block(K, columns, "schur" if method == "augmented" else method)
    Bc = B[:, columns].toarray()
    W = Bc @ block @ Bc.T
    W = 0.5 * (W + W.T)
    return (W, None) if keep_factor else W


def inverse_block(K: sp.spmatrix, c: np.ndarray, method: str = "schur") -> np.ndarray:
    """Dense ``(K^-1)[c][:, c]`` (|c| x |c|) of the SPD sparse matrix ``K``; ``c`` distinct DOF indices."""
    if method not in METHODS:
        raise ValueError(f"method must be one of {METHODS}, got {method!r}")
    c = np.asarray(c, dtype=np.int64)
    K = sp.csr_matrix(K)
    if method != "splu" and not _pardiso_available():
        method = "splu"
    if method == "schur":
        order = np.argsort(c)
        schur = _schur_pardiso(K, c[order])
        inv_sorted = np.linalg.inv(schur)
        inv_sorted = 0.5 * (inv_sorted + inv_sorted.T)
        out = np.empty_like(inv_sorted)
        out[np.ix_(order, order)] = inv_sorted
        return out
    solve = factorize(K) if method == "rhs" else None
    if method == "splu":
        lu = splu(K.tocsc())
        solve = lu.solve
    n = K.shape[0]
    out = np.empty((c.size, c.size))
    for start in range(0, c.size, 256):
        cols = c[start:start + 256]
        rhs = np.zeros((n, cols.size), order="F")
        rhs[cols, np.arange(cols.size)] = 1.0
        x = solve(rhs)
        out[:, start:start + cols.size] = x[c]
    if method == "rhs":
        solve.free()
    return 0.5 * (out + out.T)
