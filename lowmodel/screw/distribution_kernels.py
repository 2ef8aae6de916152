"""Compiled steps of the axial load distribution over a nut's balls (:mod:`lowmodel.screw.load_distribution`).

:func:`lowmodel.screw.load_distribution.distribute` finds, at every step of its fixed-point iteration, the shift
``u_0`` that makes the balls carry the axial load, ``sum_j U^-1(clip(u_0 - s o_j, low, high)) = F_a``, by Brent's
method (Brent 1973, ch. 4).  On the numpy path scipy's ``brentq`` calls a Python function for every trial
``u_0`` (about 50 per step of the whole screw).  Here the same function is a C callback compiled by numba
(:func:`mismatch`), handed to the same routine of scipy through its public Cython interface
(``scipy.optimize.cython_optimize.brentq``: the C code behind ``scipy.optimize.brentq``), so that no trial
leaves C.  The callback repeats the numpy code's arithmetic operation for operation:

* ``v_j = min(max(u_0 - s o_j, low), high)`` (``np.maximum``, then ``np.minimum``);
* the pchip ``U^-1(v_j)`` of :class:`lowmodel.cubic_pieces.CubicPieces` (the piece by ``searchsorted(side="right")``
  over the inner breakpoints, ``c_3 + c_2 s + c_1 s^2 + c_0 s^3`` in that order);
* the sum over the balls in numpy's order for ``np.sum`` of a contiguous array (pairwise: below 8 values one
  running sum; up to 128 values eight running sums over strides of 8, joined as ``((r0 + r1) + (r2 + r3)) +
  ((r4 + r5) + (r6 + r7))``, the remainder added in turn; :data:`MAX_BALLS` is that limit, beyond which
  numpy splits the array and :func:`lowmodel.screw.load_distribution.distribute` keeps its numpy path);
* minus ``F_a``;

so the trials, and the root, are the same to the last bit.  :func:`offsets` computes the rest of a fixed-point
step (the balls' elastic offsets by running sums over the balls in axial order, as ``np.cumsum``; the bracket of
``u_0``; the mismatch at its ends) and :func:`loads_at` the loads at the root, so a step makes three calls out of
Python instead of about 60 (tests/lowmodel/screw/test_load_distribution_kernels.py compares both paths on random
tables and offsets at 0 difference).  Loaded by :func:`lowmodel.kernels.load`; never imported by
``import ballbench.lowmodel``.
"""
from __future__ import annotations

import ctypes
import math

import numba
import numpy as np
from numba import types
from numba.extending import get_cython_function_address

from ballbench.lowmodel.cubic_pieces import CubicPieces

__all__ = ["mismatch", "offsets", "loads_at", "nut_shift", "pack", "shifted", "warm_up", "CONVERGED", "NOT_CONVERGED",
           "NOT_BRACKETED", "MAX_BALLS"]

MAX_BALLS = 128   # numpy sums up to 128 values as one block of eight running sums

CONVERGED = 0
NOT_BRACKETED = -1   # scipy's SIGNERR: f(a) and f(b) of the same sign
NOT_CONVERGED = -2   # scipy's CONVERR: the iteration limit

_HEADER = 5   # n, m, low, high, total


class _FullOutput(ctypes.Structure):
    """scipy.optimize.cython_optimize's ``zeros_full_output``."""

    _fields_ = [("funcalls", ctypes.c_int), ("iterations", ctypes.c_int), ("error_num", ctypes.c_int),
                ("root", ctypes.c_double)]


_BRENTQ = ctypes.CFUNCTYPE(ctypes.c_double, ctypes.c_void_p, ctypes.c_double, ctypes.c_double, ctypes.c_void_p,
                           ctypes.c_double, ctypes.c_double, ctypes.c_int, ctypes.POINTER(_FullOutput))(
    get_cython_function_address("scipy.optimize.cython_optimize._zeros", "brentq"))

_jit = numba.njit(cache=True, nogil=True, error_model="numpy")


@_jit
def _pairwise_sum(values, start, count):
    """``np.sum`` of ``values[start:start + count]``, ``count <= MAX_BALLS``, in numpy's pairwise order (module
    docstring)."""
    if count < 8:
        total = -0.0
        for i in range(start, start + count):
            total += values[i]
        return total
    r0, r1, r2, r3 = values[start], values[start + 1], values[start + 2], values[start + 3]
    r4, r5, r6, r7 = values[start + 4], values[start + 5], values[start + 6], values[start + 7]
    i = 8
    while i < count - count % 8:
        r0 += values[start + i]
        r1 += values[start + i + 1]
        r2 += values[start + i + 2]
        r3 += values[start + i + 3]
        r4 += values[start + i + 4]
        r5 += values[start + i + 5]
        r6 += values[start + i + 6]
        r7 += values[start + i + 7]
        i += 8
    total = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    while i < count:
        total += values[start + i]
        i += 1
    return total


@_jit
def loads_at(u0, data, loads):
    """The balls' loads ``U^-1(clip(u_0 - s o_j))`` of the packed ``data`` (:func:`pack`) into ``loads`` (n,); returns
    their sum (``np.sum``'s order)."""
    n, m = int(data[0]), int(data[1])
    low, high = data[2], data[3]
    shifted = _HEADER
    breaks = shifted + n
    inner = breaks + m + 1
    c0 = inner + m - 1
    c1, c2, c3 = c0 + m, c0 + 2 * m, c0 + 3 * m
    for j in range(n):
        v = u0 - data[shifted + j]
        v = v if v >= low else low    # np.maximum (no NaN: the offsets and u_0 are finite)
        v = v if v <= high else high  # np.minimum
        piece, top = 0, m - 1         # searchsorted(inner, v, side="right"): the inner breakpoints <= v
        while piece < top:
            middle = (piece + top) // 2
            if data[inner + middle] <= v:
                piece = middle + 1
            else:
                top = middle
        s = v - data[breaks + piece]
        square = s * s
        loads[j] = data[c3 + piece] + data[c2 + piece] * s + data[c1 + piece] * square + data[c0 + piece] * (square * s)
    return _pairwise_sum(loads, 0, n)


@numba.cfunc(types.float64(types.float64, types.voidptr), cache=True, nopython=True, error_model="numpy")
def mismatch(u0, address):
    """``sum_j U^-1(clip(u_0 - s o_j)) - F_a`` [N] of the packed data at ``address`` (scipy's callback type)."""
    header = numba.carray(address, (_HEADER,), dtype=np.float64)
    n, m = int(header[0]), int(header[1])
    data = numba.carray(address, (_HEADER + 2 * n + 6 * m,), dtype=np.float64)
    return loads_at(u0, data, data[_HEADER + n + 6 * m:]) - data[4]


@_jit
def offsets(loads, order, segment, geometric, total, compliance_s, compliance_n, flange, sign, data):
    """The elastic and geometric offsets of one fixed-point step of
    :func:`lowmodel.screw.load_distribution.distribute`, signed, into ``data``'s slots (:func:`pack`); returns the
    bracket ``(start, end)`` of ``u_0`` and the mismatch at both ends.  The numpy code's operations in its order:
    ``S`` by a running sum over the balls in ``order`` (``np.cumsum``), ``int_0^z (eps_s + eps_n)`` likewise
    (``flange`` 1 or 0: the nut's flange at the loaded end or the far end)."""
    n = loads.size
    cumulative = 0.0
    integral = 0.0
    low, high = data[2], data[3]
    offset_max = -math.inf
    shifted_min = math.inf
    shifted_max = -math.inf
    for i in range(n):
        j = order[i]
        cumulative = loads[j] if i == 0 else cumulative + loads[j]
        before = 0.0 if i == 0 else cumulative - loads[j]
        strain = (total - before) * compliance_s + (flange * total - before) * compliance_n
        term = strain * segment[i]
        integral = term if i == 0 else integral + term
        offset = integral + geometric[j]
        shifted = sign * offset
        data[_HEADER + j] = shifted
        if offset > offset_max or offset != offset:   # np.max: NaN wins
            offset_max = offset if offset_max == offset_max else offset_max
        if shifted < shifted_min or shifted != shifted:
            shifted_min = shifted if shifted_min == shifted_min else shifted_min
        if shifted > shifted_max or shifted != shifted:
            shifted_max = shifted if shifted_max == shifted_max else shifted_max
    start, other = low - offset_max, low + shifted_min   # Python's min(start, other) and max(end, other)
    start = other if other < start else start
    end, other = high + offset_max, high + shifted_max
    end = other if other > end else end
    scratch = data[_HEADER + n + 6 * int(data[1]):]
    return start, end, loads_at(start, data, scratch) - total, loads_at(end, data, scratch) - total


def pack(n: int, low: float, high: float, total: float, pieces) -> np.ndarray:
    """The data of :func:`offsets`, :func:`mismatch` and :func:`loads_at`: ``n, m, low, high, F_a``, room for the
    signed offsets ``s o_j`` (n,) that :func:`offsets` fills, the pchip's breakpoints (m + 1,), inner breakpoints
    (m - 1,) and coefficients ``c_0 .. c_3`` (m,) each (:class:`lowmodel.cubic_pieces.CubicPieces`), and room for
    the n loads of a trial; ``1 <= n <= MAX_BALLS``."""
    if not 1 <= n <= MAX_BALLS:
        raise ValueError(f"n must be 1 to {MAX_BALLS} balls, got {n}")
    m = pieces.c0.size
    return np.concatenate(([n, m, low, high, total], np.zeros(n), pieces.breaks, pieces.inner, pieces.c0,
                           pieces.c1, pieces.c2, pieces.c3, np.zeros(n))).astype(float, copy=False)


def shifted(data: np.ndarray) -> np.ndarray:
    """The signed offsets ``s o_j`` [m] held in ``data`` (a view)."""
    return data[_HEADER:_HEADER + int(data[0])]


def nut_shift(data: np.ndarray, start: float, end: float, xtol: float, rtol: float, maxiter: int):
    """scipy's Brent routine on :func:`mismatch` of ``data`` (:func:`pack`) over ``[start, end]``:
    ``(u_0, status, iterations)``, status :data:`CONVERGED`, :data:`NOT_BRACKETED` or :data:`NOT_CONVERGED`."""
    output = _FullOutput()
    root = _BRENTQ(mismatch.address, start, end, data.ctypes.data, xtol, rtol, maxiter, ctypes.byref(output))
    return float(root), int(output.error_num), int(output.iterations)


def warm_up() -> None:
    """Compile (or load from numba's disk cache) the kernels with the argument types the model passes; one step
    on a two-piece linear table (``U^-1(v) = v``) whose root is known."""
    pieces = CubicPieces(np.array([0.0, 1.0, 2.0]), np.array([1.0]), np.zeros(2), np.zeros(2), np.ones(2),
                         np.array([0.0, 1.0]))
    data = pack(3, 0.0, 2.0, 3.0, pieces)
    start, end, _, _ = offsets(np.ones(3), np.arange(3), np.zeros(3), np.zeros(3), 3.0, 1.0, 1.0, 1.0, 1.0, data)
    root, status, _ = nut_shift(data, start, end, 1e-12, 4 * np.finfo(float).eps, 100)
    loads = np.empty(3)
    if status != CONVERGED or abs(root - 1.0) > 1e-9 or abs(loads_at(root, data, loads) - 3.0) > 1e-9:
        raise RuntimeError(f"the compiled root search failed its warm-up: root {root!r}, status {status}")
