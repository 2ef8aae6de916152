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
"""
from __future__ import annotations

import ctypes

import numpy as np
import scipy.sparse as sp

__all__ = ["compliance", "inverse_block", "factorize", "METHODS"]

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
    from scipy.sparse.linalg import splu

    lu = splu(K.tocsc())

    def solve(b):
        return lu.solve(np.asarray(b, dtype=float))

    solve.free = lambda: None
    return solve


def _schur_pardiso(K: sp.csr_matrix, c: np.ndarray, mtype: int = 2) -> np.ndarray:
    """Dense Schur complement of the symmetric ``K`` onto ``c`` by MKL pardiso (iparm[35] = 1);
    ``mtype`` 2 (SPD) or -2 (symmetric indefinite)."""
    import pypardiso

    host = pypardiso.PyPardisoSolver(mtype=mtype)
    lib = host._mkl_pardiso
    upper = sp.triu(K, format="csr")
    upper.sort_indices()
    n = upper.shape[0]
    nschur = int(c.size)
    pt = np.zeros(64, dtype=np.int64)
    iparm = np.zeros(64, dtype=np.int32)
    iparm[0] = 1  # no solver defaults
    iparm[1] = 2  # nested dissection (METIS)
    iparm[9] = 8  # pivot perturbation 1e-8
    iparm[34] = 1  # zero-based indexing
    iparm[35] = 1  # Schur complement
    perm = np.zeros(n, dtype=np.int32)
    perm[c] = 1
    ia = upper.indptr.astype(np.int32)
    ja = upper.indices.astype(np.int32)
    data = np.ascontiguousarray(upper.data, dtype=float)
    schur = np.zeros((nschur, nschur), dtype=float, order="F")
    b = np.zeros(n)
    error = ctypes.c_int32(0)
    i32 = ctypes.POINTER(ctypes.c_int32)
    f64 = ctypes.POINTER(ctypes.c_double)

    def call(phase: int, x) -> None:
        lib(pt.ctypes.data_as(ctypes.POINTER(ctypes.c_int64)), ctypes.byref(ctypes.c_int32(1)),
            ctypes.byref(ctypes.c_int32(1)), ctypes.byref(ctypes.c_int32(mtype)), ctypes.byref(ctypes.c_int32(phase)),
            ctypes.byref(ctypes.c_int32(n)), data.ctypes.data_as(f64), ia.ctypes.data_as(i32),
            ja.ctypes.data_as(i32), perm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(1)),
            iparm.ctypes.data_as(i32), ctypes.byref(ctypes.c_int32(0)), b.ctypes.data_as(f64),
            x.ctypes.data_as(f64), ctypes.byref(error))

    try:
        call(12, schur)
        if error.value != 0:
            raise RuntimeError(f"MKL pardiso Schur complement failed with error {error.value}")
    finally:
        call(-1, np.zeros(1))
    # pardiso returns the Schur block in the order of increasing global index of c
    return np.ascontiguousarray(schur)


def compliance(K: sp.spmatrix, B: sp.spmatrix, method: str = "augmented") -> np.ndarray:
    """Dense ``W = B K^-1 B^T`` (m x m) for SPD sparse ``K`` (n x n) and sparse ``B`` (m x n).

    ``"augmented"``: pardiso's Schur complement of the symmetric indefinite
    ``[[K, B^T], [B, 0]]`` onto its last m rows is ``-W`` (the dense part is only
    m x m, not the size of B's column support).  Other methods: ``B_c (K^-1)_cc B_c^T``
    with :func:`inverse_block` on the columns ``c`` that B touches.
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
        schur = _schur_pardiso(upper, np.arange(n, n + m), mtype=-2)
        W = -schur
        return 0.5 * (W + W.T)
    columns = np.flatnonzero(B.getnnz(axis=0))
    block = inverse_block(K, columns, "schur" if method == "augmented" else method)
    Bc = B[:, columns].toarray()
    W = Bc @ block @ Bc.T
    return 0.5 * (W + W.T)


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
        from scipy.sparse.linalg import splu

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
