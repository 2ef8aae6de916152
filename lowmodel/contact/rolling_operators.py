"""Operators of the steady rolling problem: ``s = w + C p`` on the cells of a grid (docs/rolling_contact.md).

One concept: the linear map ``C`` from the tangential traction to the slip (steady rolling, per unit rolling
distance) or to the shift (Cattaneo-Mindlin), in the two forms the solver of :mod:`lowmodel.contact.rolling`
takes:

* :class:`ConvolutionOperator`, two half-spaces on a regular grid: the kernels of
  :func:`lowmodel.contact.influence.grid_kernels` (Cerruti's solution over rectangles, Johnson 1985 eq 2.19),
  products by zero-padded FFT (DC-FFT, exact; ducc0) or dense blocks; built and cached by
  :func:`half_space_operator`;
* :class:`MatrixOperator`, any dense compliance over all cells of a grid (e.g. condensed from the FE,
  :mod:`fem.rolling_compliance`).

Both give the solver the same four things: the self-influence (``diagonal``), dense blocks among chosen cells
(``dense``), the blocks of each grid line along ``x`` (``line_blocks``, the preconditioner), products
(``apply``), and the slip of the normal pressure through the normal-tangential coupling (``normal_slip``).
"""
from __future__ import annotations

import functools

import numpy as np
from threadpoolctl import ThreadpoolController

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.influence import grid_kernels

__all__ = ["ConvolutionOperator", "MatrixOperator", "half_space_operator", "one_blas_thread"]

@functools.lru_cache(maxsize=1)
def _blas_controller():
    return ThreadpoolController()


def one_blas_thread():
    """One BLAS thread for the solve: its many small products stall (10x slower) in a threaded BLAS when the
    machine's cores are shared (the same reason as lowmodel.contact.ehl)."""
    return _blas_controller().limit(limits=1, user_api="blas")


@functools.lru_cache(maxsize=1)
def _ducc_fft():
    try:
        import ducc0.fft
    except ImportError:  # pragma: no cover - ducc0 is a dependency; scipy.fft otherwise
        return None
    return ducc0.fft


class _Convolution:
    """Zero-padded (DC-FFT, exact) products of the 2x2 block kernel with a field on an nx x ny grid."""

    def __init__(self, kernels, nx: int, ny: int):
        self.nx, self.ny = nx, ny
        self.shape = (2 * nx, 2 * ny)
        rows = np.arange(-(nx - 1), nx) % (2 * nx)
        cols = np.arange(-(ny - 1), ny) % (2 * ny)
        spectra = []
        for kernel in kernels:
            padded = np.zeros(self.shape)
            padded[np.ix_(rows, cols)] = kernel
            spectra.append(np.fft.rfft2(padded))
        self.xx, self.xy, self.yy = spectra
        self._fft = _ducc_fft()

    def __call__(self, field: np.ndarray) -> np.ndarray:
        """``C * field`` for ``field`` (nx, ny, 2); returns (nx, ny, 2)."""
        nx, ny = self.nx, self.ny
        padded = np.zeros((2, 2 * nx, 2 * ny))
        padded[0, :nx, :ny] = field[..., 0]
        padded[1, :nx, :ny] = field[..., 1]
        result = self._convolve(padded)
        return np.stack([result[0, :nx, :ny], result[1, :nx, :ny]], axis=-1)

    def padded_index(self, i: np.ndarray, j: np.ndarray) -> np.ndarray:
        """The flat index of the cells ``(i, j)`` in the zero-padded field of :meth:`on_cells`."""
        return np.asarray(i) * (2 * self.ny) + np.asarray(j)

    def on_cells(self, index: np.ndarray, values: np.ndarray) -> np.ndarray:
        """``C * field`` at the cells of :meth:`padded_index` ``index`` for a field that is ``values`` (n, 2) there
        and zero elsewhere: (n, 2), without the whole-grid fields of :meth:`__call__`."""
        padded = np.zeros((2, 4 * self.nx * self.ny))
        padded[:, index] = values.T
        return self._convolve(padded.reshape(2, 2 * self.nx, 2 * self.ny)).reshape(2, -1)[:, index].T

    def _convolve(self, padded: np.ndarray) -> np.ndarray:
        # the cyclic convolution of the zero-padded (2, 2 nx, 2 ny) field with the kernels (exact on the grid)
        ny = self.ny
        fft = self._fft
        if fft is not None:
            spectrum = fft.r2c(padded, axes=(1, 2))
        else:  # pragma: no cover
            spectrum = np.fft.rfft2(padded)
        out = np.empty_like(spectrum)
        np.multiply(self.xx, spectrum[0], out=out[0])
        out[0] += self.xy * spectrum[1]
        np.multiply(self.xy, spectrum[0], out=out[1])
        out[1] += self.yy * spectrum[1]
        if fft is not None:
            return fft.c2r(out, axes=(1, 2), lastsize=2 * ny, forward=False, inorm=2)
        return np.fft.irfft2(out, s=self.shape)  # pragma: no cover


class ConvolutionOperator:
    """The steady-state (or shift) operator of two half-spaces on a regular grid: ``C`` as convolution kernels.

    ``kernels`` = ``(xx, xy, yy)`` of :func:`lowmodel.contact.influence.grid_kernels` (index ``[k + nx - 1,
    l + ny - 1]`` for the cell offset ``(k, l)``); ``normal`` = ``(xn, yn)`` or None (normal-tangential
    coupling: the pressure's contribution to the slip).  Units [1/Pa] (rolling) or [m/Pa] (shift).
    """

    def __init__(self, grid: SurfaceGrid, kernels, normal=None):
        self.grid = grid
        self.kernels = tuple(kernels)
        self.normal = None if normal is None else tuple(normal)
        nx, ny = grid.nx, grid.ny
        for kernel in self.kernels + (self.normal or ()):
            if kernel.shape != (2 * nx - 1, 2 * ny - 1):
                raise ValueError(f"kernels must have shape {(2 * nx - 1, 2 * ny - 1)} for the grid, got {kernel.shape}")
        self._convolution = None

    @property
    def diagonal(self) -> np.ndarray:
        """(2,) the self-influence ``C_xx(0, 0), C_yy(0, 0)``."""
        nx, ny = self.grid.nx, self.grid.ny
        return np.array([self.kernels[0][nx - 1, ny - 1], self.kernels[2][nx - 1, ny - 1]])

    def dense(self, cells: np.ndarray) -> np.ndarray:
        """(2n, 2n) ``C`` among the flat cell indices ``cells`` (interleaved x, y per cell); the last few are kept."""
        key = cells.tobytes()
        cache = self.__dict__.setdefault("_dense_cache", {})
        if key not in cache:
            if len(cache) >= 4:
                cache.pop(next(iter(cache)))
            matrix = self._dense_matrix(cells)
            matrix.setflags(write=False)
            cache[key] = matrix
        return cache[key]

    def _dense_matrix(self, cells: np.ndarray) -> np.ndarray:
        nx, ny = self.grid.nx, self.grid.ny
        i, j = np.divmod(cells, ny)
        di = i[:, None] - i[None, :] + nx - 1
        dj = j[:, None] - j[None, :] + ny - 1
        n = cells.size
        matrix = np.empty((n, 2, n, 2))
        xx, xy, yy = self.kernels
        matrix[:, 0, :, 0] = xx[di, dj]
        matrix[:, 0, :, 1] = matrix[:, 1, :, 0] = xy[di, dj]
        matrix[:, 1, :, 1] = yy[di, dj]
        return matrix.reshape(2 * n, 2 * n)

    def line_blocks(self, lines: np.ndarray) -> np.ndarray:
        """(len(lines), 2 nx, 2 nx): ``C`` within each grid line ``j`` along ``x`` (all ``nx`` cells)."""
        nx, ny = self.grid.nx, self.grid.ny
        k = np.arange(nx)
        di = k[:, None] - k[None, :] + nx - 1
        block = np.empty((nx, 2, nx, 2))
        xx, xy, yy = (kernel[:, ny - 1] for kernel in self.kernels)
        block[:, 0, :, 0] = xx[di]
        block[:, 0, :, 1] = block[:, 1, :, 0] = xy[di]
        block[:, 1, :, 1] = yy[di]
        return np.broadcast_to(block.reshape(2 * nx, 2 * nx), (len(lines), 2 * nx, 2 * nx))

    def apply(self, field: np.ndarray) -> np.ndarray:
        """``C * field`` on the whole grid, ``field`` (nx, ny, 2) -> (nx, ny, 2)."""
        return self.convolution()(field)

    def convolution(self) -> _Convolution:
        """The FFT convolution with the kernels (built on first use, then kept): ``op.convolution()(field)``, or
        ``.on_cells(index, values)`` for a field given on some cells only (``index`` of ``.padded_index(i, j)``)."""
        if self._convolution is None:
            self._convolution = _Convolution(self.kernels, self.grid.nx, self.grid.ny)
        return self._convolution

    def normal_slip(self, pressure: np.ndarray) -> np.ndarray | None:
        """(nx, ny, 2) the slip (or shift) of the normal pressure through the coupling, None without coupling."""
        if self.normal is None:
            return None
        nx, ny = self.grid.nx, self.grid.ny
        rows = np.arange(-(nx - 1), nx) % (2 * nx)
        cols = np.arange(-(ny - 1), ny) % (2 * ny)
        spectrum = np.fft.rfft2(pressure, s=(2 * nx, 2 * ny))
        out = np.empty((nx, ny, 2))
        for component, kernel in enumerate(self.normal):
            padded = np.zeros((2 * nx, 2 * ny))
            padded[np.ix_(rows, cols)] = kernel
            out[..., component] = np.fft.irfft2(np.fft.rfft2(padded) * spectrum, s=(2 * nx, 2 * ny))[:nx, :ny]
        return out


class MatrixOperator:
    """``C`` as a dense matrix over all cells of a grid (e.g. condensed from the FE), shape ``(2N, 2N)``.

    Rows and columns ordered by flat cell index ``i ny + j`` with the ``x, y`` components interleaved.
    ``normal`` (2N, N) optional: the slip per unit normal pressure (coupling).
    """

    def __init__(self, grid: SurfaceGrid, matrix: np.ndarray, normal: np.ndarray | None = None):
        n = grid.nx * grid.ny
        matrix = np.asarray(matrix, dtype=float)
        if matrix.shape != (2 * n, 2 * n):
            raise ValueError(f"matrix must have shape {(2 * n, 2 * n)} for the grid, got {matrix.shape}")
        if not np.all(np.isfinite(matrix)):
            raise ValueError("matrix must be finite")
        self.grid = grid
        self.matrix = matrix
        self.normal = None if normal is None else np.asarray(normal, dtype=float)
        if self.normal is not None and self.normal.shape != (2 * n, n):
            raise ValueError(f"normal must have shape {(2 * n, n)}, got {self.normal.shape}")

    @property
    def diagonal(self) -> np.ndarray:
        d = np.diag(self.matrix).reshape(-1, 2)
        return np.array([d[:, 0].max(), d[:, 1].max()])

    def dense(self, cells: np.ndarray) -> np.ndarray:
        index = np.stack([2 * cells, 2 * cells + 1], axis=1).ravel()
        return self.matrix[np.ix_(index, index)]

    def line_blocks(self, lines: np.ndarray) -> np.ndarray:
        nx, ny = self.grid.nx, self.grid.ny
        blocks = np.empty((len(lines), 2 * nx, 2 * nx))
        for b, j in enumerate(lines):
            cells = np.arange(nx) * ny + j
            blocks[b] = self.dense(cells)
        return blocks

    def apply(self, field: np.ndarray) -> np.ndarray:
        return (self.matrix @ field.reshape(-1)).reshape(field.shape)

    def normal_slip(self, pressure: np.ndarray) -> np.ndarray | None:
        if self.normal is None:
            return None
        return (self.normal @ pressure.reshape(-1)).reshape(pressure.shape + (2,))


def half_space_operator(grid: SurfaceGrid, shear_modulus: float, poisson_ratio: float, *, coupling: float = 0.0,
                        steady: bool = True, plane_strain: bool = False) -> ConvolutionOperator:
    """The half-space operator on ``grid`` (:func:`lowmodel.contact.influence.grid_kernels`).

    ``shear_modulus`` [Pa], ``poisson_ratio``, ``coupling`` K: Kalker's combined constants
    (:func:`lowmodel.contact.influence.combined_material`).  ``steady``: rolling (else a shift);
    ``plane_strain``: the 2D line contact (``grid.ny == 1``).  One operator per grid and material is
    kept (its FFT spectra, dense blocks and line blocks are reused by every solve on it: a creep curve).
    """
    shear = float(checks.positive("shear_modulus", shear_modulus, "Pa"))
    nu = float(checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True))
    return _operator(grid, shear, nu, float(checks.finite("coupling", coupling)), bool(steady), bool(plane_strain))


@functools.lru_cache(maxsize=16)
def _operator(grid, shear: float, nu: float, coupling: float, steady: bool, plane_strain: bool):
    kernels = grid_kernels(grid.nx, grid.ny, grid.dx, grid.dy, shear, nu, coupling=coupling, steady=steady,
                           plane_strain=plane_strain)
    return ConvolutionOperator(grid, kernels[:3], kernels[3:] if len(kernels) > 3 else None)

