"""Normal contact of two elastic half-spaces on an arbitrary gap (boundary-element method).

sun2021 eqs 3-12 (minimum complementary energy, "minimum excess principle"):
the gap ``c = d0 + c_g + c_r + V`` (eq 3) with the elastic deformation
``V = K * p`` (eq 4), ``c >= 0, p >= 0, c p = 0`` (eqs 5-8); the pressure
minimises ``W(P) = c_bar^T P + P^T K P / 2`` (eq 10) under those conditions.

Discretisation and solver (the standard tools, written here from the papers):

* Pressure uniform on each rectangular cell of a regular grid; deflection at
  the cell centres from Love's closed form for a uniformly loaded rectangle
  (Love 1929; Johnson 1985 eq 3.25), composite modulus ``E*``::

      V(x, y) = 1/(pi E*) sum_kl p_kl [G(X, Y)]_{x-x_k-dx/2}^{x-x_k+dx/2} [.]_{y-y_l-dy/2}^{y-y_l+dy/2}
      G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|)       (d^2 G / dX dY = 1/r; G = 0 on X = 0 or Y = 0)

  (the ``X ln|X| + Y ln|Y|`` part of the textbook antiderivative cancels in the
  double difference, so this form has no logarithm of a cancelling sum).
* The discrete convolution (eq 4) by FFT with zero padding and the kernel laid
  out in wrap-around order (DC-FFT; Liu, Wang & Liu, Wear 243 (2000) 101): the
  result equals the direct sum exactly, with no periodic images.  The kernel
  spectra (rfft2, ``2 nx x 2 ny``) are cached per grid.
* The constrained conjugate gradient of Polonsky & Keer (Wear 231 (1999) 206)
  with load control (the mean gap on the contact set is the approach) or
  approach control; convergence measure sun2021 eq 12,
  ``eps = dA sum |p - p_old| / F``.

Sign convention: ``gap`` is the separation of the undeformed surfaces [m]
(>= 0 away from contact, e.g. ``A x^2 + B y^2``); ``approach`` is the rigid
approach of distant points; in the contact set ``gap + V = approach``.

One concept in one file (about 780 lines): the grid, Love's influence coefficients, their FFT convolution, the
constrained conjugate gradient that applies them and the check of its answer (:func:`verify`) are one
boundary-element solver of sun2021 eqs 3-12; the kernel layouts (full grid, coarse start, sparse cells,
single-precision increments) are internal to that solve.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import scipy.fft

from ballbench.lowmodel import checks
from ballbench.lowmodel.errors import ConvergenceError

__all__ = [
    "SurfaceGrid",
    "HalfSpaceContact",
    "surface_grid",
    "hertz_surface_grid",
    "influence_coefficients",
    "deformation",
    "quadratic_gap",
    "solve",
    "verify",
    "pressure_ellipse",
]


LARGEST_LENGTH = 1e30  # m: gaps and deflections stay far inside float32 (the CG's increments, 3.4e38)


def _finite_positive(name: str, value: float, unit: str) -> float:
    return float(checks.positive(name, value, unit))


def _cell_count(name: str, value: int) -> int:
    return checks.count(name, value, 4, 8192)  # an integer, not a bool or float


# --------------------------------------------------------------------------
# grid
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class SurfaceGrid:
    """Regular grid of ``nx x ny`` rectangular cells ``dx x dy`` [m] centred on ``(x_centre, y_centre)`` [m].

    Arrays on the grid have shape ``(nx, ny)`` and index ``[i, j]`` = cell at
    ``(x[i], y[j])`` (cell centres).
    """

    nx: int
    ny: int
    dx: float
    dy: float
    x_centre: float = 0.0
    y_centre: float = 0.0

    def __post_init__(self):
        _cell_count("nx", self.nx)
        _cell_count("ny", self.ny)
        _finite_positive("dx", self.dx, "m")
        _finite_positive("dy", self.dy, "m")
        checks.finite("x_centre", self.x_centre, "m")
        checks.finite("y_centre", self.y_centre, "m")

    @property
    def x(self) -> np.ndarray:
        """Cell-centre x coordinates [m], shape ``(nx,)``."""
        return self.x_centre + (np.arange(self.nx) - 0.5 * (self.nx - 1)) * self.dx

    @property
    def y(self) -> np.ndarray:
        """Cell-centre y coordinates [m], shape ``(ny,)``."""
        return self.y_centre + (np.arange(self.ny) - 0.5 * (self.ny - 1)) * self.dy

    @property
    def cell_area(self) -> float:
        """``dx dy`` [m^2]."""
        return self.dx * self.dy

    def coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        """Cell-centre coordinates ``(X, Y)`` [m], each ``(nx, ny)`` (``indexing='ij'``)."""
        return np.meshgrid(self.x, self.y, indexing="ij")


def surface_grid(half_width_x: float, half_width_y: float | None = None, nx: int = 256, ny: int | None = None,
                 centre: tuple[float, float] = (0.0, 0.0)) -> SurfaceGrid:
    """Grid covering ``|x - x_c| <= half_width_x``, ``|y - y_c| <= half_width_y`` [m] with ``nx x ny`` cells."""
    half_width_x = _finite_positive("half_width_x", half_width_x, "m")
    half_width_y = half_width_x if half_width_y is None else _finite_positive("half_width_y", half_width_y, "m")
    nx = _cell_count("nx", nx)
    ny = nx if ny is None else _cell_count("ny", ny)
    cx, cy = (float(c) for c in centre)
    if not (math.isfinite(cx) and math.isfinite(cy)):
        raise ValueError(f"centre must be finite, got {centre!r}")
    dx = _finite_positive("cell size 2 half_width_x / nx", 2.0 * half_width_x / nx, "m")  # may underflow to 0
    dy = _finite_positive("cell size 2 half_width_y / ny", 2.0 * half_width_y / ny, "m")
    return SurfaceGrid(nx, ny, dx, dy, cx, cy)


def hertz_surface_grid(a: float, b: float | None = None, n: int = 256, margin: float = 1.25,
                       square_cells: bool = False) -> SurfaceGrid:
    """Grid for a contact of (estimated) semi-axes ``a`` along x and ``b`` along y [m].

    Half-widths ``margin * a`` and ``margin * b``; with ``square_cells`` both
    directions use the cell size of the larger axis (``n`` cells across ``2 margin a``)
    and the cell count across y is rounded up to an even number.
    """
    a = _finite_positive("a", a, "m")
    b = a if b is None else _finite_positive("b", b, "m")
    margin = float(margin)
    if not (math.isfinite(margin) and margin > 1.0):
        raise ValueError(f"margin must be > 1 (the grid must hold the contact), got {margin!r}")
    n = _cell_count("n", n)
    _finite_positive("margin * a", margin * a, "m")  # the half-widths, finite
    _finite_positive("margin * b", margin * b, "m")
    if not square_cells:
        return surface_grid(margin * a, margin * b, n, n)
    size = _finite_positive("cell size 2 margin max(a, b) / n", 2.0 * margin * max(a, b) / n, "m")
    nx = n if a >= b else 2 * math.ceil(margin * a / size)
    ny = n if b >= a else 2 * math.ceil(margin * b / size)
    return SurfaceGrid(max(nx, 4), max(ny, 4), size, size)


# --------------------------------------------------------------------------
# influence coefficients and DC-FFT
# --------------------------------------------------------------------------
def _love_primitive(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    # G(X, Y) = X asinh(Y/|X|) + Y asinh(X/|Y|); d^2G/dXdY = 1/sqrt(X^2 + Y^2)
    ax, ay = np.abs(X), np.abs(Y)
    with np.errstate(divide="ignore", invalid="ignore"):
        first = np.where(ax > 0.0, X * np.arcsinh(Y / np.where(ax > 0.0, ax, 1.0)), 0.0)
        second = np.where(ay > 0.0, Y * np.arcsinh(X / np.where(ay > 0.0, ay, 1.0)), 0.0)
    return first + second


def influence_coefficients(nx: int, ny: int, dx: float, dy: float) -> np.ndarray:
    """Love's influence coefficients for unit ``E*`` [m / Pa * Pa = m per unit p/E*].

    Returns ``K`` of shape ``(2 nx - 1, 2 ny - 1)``: the deflection at a cell
    centre offset ``((i - nx + 1) dx, (j - ny + 1) dy)`` from a cell carrying
    unit pressure, for ``E* = 1``; divide by ``E*`` [Pa] for the real deflection.
    """
    nx, ny = _cell_count("nx", nx), _cell_count("ny", ny)
    dx, dy = _finite_positive("dx", dx, "m"), _finite_positive("dy", dy, "m")
    if not (math.isfinite(dy / dx) and math.isfinite(dx / dy)):
        raise ValueError(f"dx = {dx!r} m and dy = {dy!r} m: the cell's aspect ratio is beyond the floating-point range")
    # offsets are exact multiples of the cell size: compute in cell units and scale by dx
    xs = np.arange(-(nx - 1), nx, dtype=float)[:, None]
    ys = (np.arange(-(ny - 1), ny, dtype=float) * (dy / dx))[None, :]
    hx, hy = 0.5, 0.5 * dy / dx
    kernel = (_love_primitive(xs + hx, ys + hy) - _love_primitive(xs + hx, ys - hy)
              - _love_primitive(xs - hx, ys + hy) + _love_primitive(xs - hx, ys - hy))
    return kernel * (dx / math.pi)


@functools.lru_cache(maxsize=16)
def _kernel(nx: int, ny: int, dx: float, dy: float) -> np.ndarray:
    kernel = influence_coefficients(nx, ny, dx, dy)
    kernel.setflags(write=False)
    return kernel


def _kernel_spectrum(nx: int, ny: int, dx: float, dy: float) -> np.ndarray:
    return _box_spectrum(nx, ny, dx, dy, nx, ny)


def _box_kernel(nx: int, ny: int, dx: float, dy: float, mx: int, my: int) -> np.ndarray:
    # the coefficients of an mx x my box of the nx x ny grid: the offsets up to mx - 1 (my - 1), a view
    kernel = _kernel(nx, ny, dx, dy)
    return kernel[nx - mx:nx + mx - 1, ny - my:ny + my - 1]


@functools.lru_cache(maxsize=16)
def _box_spectrum(nx: int, ny: int, dx: float, dy: float, mx: int, my: int) -> np.ndarray:
    # wrap-around order in a 2mx x 2my array, index mx (resp. my) left zero (DC-FFT); the kernel sliced from
    # the nx x ny grid's (computed once per grid)
    kernel = _box_kernel(nx, ny, dx, dy, mx, my)
    nx, ny = mx, my
    padded = np.zeros((2 * nx, 2 * ny))
    padded[:nx, :ny] = kernel[nx - 1:, ny - 1:]
    padded[nx + 1:, :ny] = kernel[:nx - 1, ny - 1:]
    padded[:nx, ny + 1:] = kernel[nx - 1:, :ny - 1]
    padded[nx + 1:, ny + 1:] = kernel[:nx - 1, :ny - 1]
    spectrum = scipy.fft.rfft2(padded)  # (2 nx, ny + 1)
    # Love's coefficients are even in both offsets, so the padded kernel is an even sequence and its
    # spectrum is real (the imaginary part is round-off, ~1e-15 of the largest value); the 1/(4 nx ny) of
    # the inverse transform is folded in
    spectrum = np.ascontiguousarray(spectrum.real) / (4 * nx * ny)
    spectrum.setflags(write=False)
    return spectrum


@functools.lru_cache(maxsize=1)
def _ducc_fft():
    # ducc0 (the successor of the pocketfft inside scipy.fft) is ~25 % faster here; scipy.fft otherwise
    try:
        import ducc0.fft
    except ImportError:  # pragma: no cover - ducc0 is a dependency, the fallback keeps the module usable
        return None
    return ducc0.fft


def _convolve(spectrum: np.ndarray, field: np.ndarray, single_spectrum: np.ndarray | None = None) -> np.ndarray:
    # The zero-padded 2nx x 2ny convolution (rfft2/irfft2 with s=(2nx, 2ny)), arranged for speed: the
    # transforms skip the rows known to be zero on input or not wanted on output, the column transforms
    # run in place, and the real spectrum (already scaled by 1/(4 nx ny)) multiplies the complex array.
    # ``single_spectrum`` (``spectrum`` as float32): the transforms in single precision (relative error ~1e-7
    # of the result; a float32 array is returned), for the increments of the conjugate gradient, whose
    # error is relative to the step, not to the deflection.
    nx, ny = field.shape
    fft = _ducc_fft()
    single = single_spectrum is not None and fft is not None
    real, cplx = (np.float32, np.complex64) if single else (float, complex)
    padded = np.zeros((nx, 2 * ny), dtype=real)
    padded[:, :ny] = field
    columns = np.empty((2 * nx, ny + 1), dtype=cplx)
    columns[nx:] = 0.0
    if fft is not None:
        fft.r2c(padded, axes=(1,), out=columns[:nx])
        fft.c2c(columns, axes=(0,), forward=True, out=columns)
        columns *= single_spectrum if single else spectrum
        fft.c2c(columns, axes=(0,), forward=False, out=columns)
        fft.c2r(columns[:nx], axes=(1,), lastsize=2 * ny, forward=False, out=padded)
        return padded[:, :ny]
    columns[:nx] = scipy.fft.rfft(padded, axis=1)
    columns = scipy.fft.fft(columns, axis=0, overwrite_x=True)
    columns *= spectrum
    columns = scipy.fft.ifft(columns, axis=0, overwrite_x=True, norm="forward")
    return scipy.fft.irfft(columns[:nx], n=2 * ny, axis=1, norm="forward")[:, :ny]


def _dot(a: np.ndarray, b: np.ndarray) -> float:
    # inner product without BLAS: a threaded BLAS dot stalls (5x slower) when the cores are shared
    return float(np.einsum("i,i->", a, b))


_SINGLE_MAX = 1e38  # below the largest float32 (3.4e38)
_SPARSE_CELLS = 20  # a direct sum costs ~1 grid pass per cell, a single-precision convolution ~20-40


def _apply_sparse(spectrum: np.ndarray, kernel: np.ndarray, cells: np.ndarray, values: np.ndarray,
                  shape: tuple[int, int], single_spectrum: np.ndarray | None, kernel_scale: float) -> np.ndarray:
    # K * field for the field that is ``values`` at the flat indices ``cells`` and zero elsewhere; ``spectrum``
    # (and ``single_spectrum``) already carry the scale that ``kernel`` gets from ``kernel_scale`` (1/E*)
    nx, ny = shape
    if cells.size > _SPARSE_CELLS:
        field = np.zeros(shape)
        field.flat[cells] = values
        return _convolve(spectrum, field, single_spectrum)
    result = np.zeros(shape)
    for cell, value in zip(cells, values):
        k, m = divmod(int(cell), ny)
        result += (value * kernel_scale) * kernel[nx - 1 - k:2 * nx - 1 - k, ny - 1 - m:2 * ny - 1 - m]
    return result


def deformation(pressure: np.ndarray, grid: SurfaceGrid, contact_modulus: float) -> np.ndarray:
    """Combined normal deflection ``V`` [m] of both surfaces under ``pressure`` [Pa] (sun2021 eq 4).

    ``pressure`` has shape ``(grid.nx, grid.ny)``; ``contact_modulus`` is E* [Pa].
    Non-periodic (DC-FFT): equal to the direct double sum over all cells.
    """
    pressure = np.asarray(pressure, dtype=float)
    if pressure.shape != (grid.nx, grid.ny):
        raise ValueError(f"pressure must have shape {(grid.nx, grid.ny)}, got {pressure.shape}")
    e_star = _finite_positive("contact_modulus", contact_modulus, "Pa")
    with np.errstate(over="ignore"):
        deflection = _convolve(_kernel_spectrum(grid.nx, grid.ny, grid.dx, grid.dy), pressure) / e_star
    if not np.all(np.isfinite(deflection)):
        raise ValueError(f"pressure / contact_modulus ({contact_modulus!r} Pa) gives a deflection beyond the "
                         "floating-point range")
    return deflection


# --------------------------------------------------------------------------
# gaps
# --------------------------------------------------------------------------
def quadratic_gap(grid: SurfaceGrid, A: float, B: float, angle: float = 0.0,
                  centre: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """Hertz gap ``A x'^2 + B y'^2`` [m] on the grid, ``(x', y')`` the frame rotated by ``angle`` [rad].

    ``A``, ``B`` [1/m] are half the principal relative curvatures (as in
    :class:`ballbench.lowmodel.contact.hertz.HertzGeometry`); the ``A`` axis
    makes ``angle`` with x.  Shape ``(nx, ny)``.
    """
    A = _finite_positive("A", A, "1/m")
    B = _finite_positive("B", B, "1/m")
    X, Y = grid.coordinates()
    X = X - centre[0]
    Y = Y - centre[1]
    angle = checks.finite("angle", angle, "rad")
    c, s = math.cos(angle), math.sin(angle)
    xr, yr = c * X + s * Y, -s * X + c * Y
    with np.errstate(over="ignore"):
        gap = A * xr * xr + B * yr * yr
    if not np.all(np.isfinite(gap)):
        raise ValueError(f"A = {A!r} 1/m and B = {B!r} 1/m give a gap beyond the floating-point range on the grid")
    return gap


# --------------------------------------------------------------------------
# solution
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class HalfSpaceContact:
    """Solution of the half-space contact on a grid.

    Attributes
    ----------
    grid : the :class:`SurfaceGrid`
    pressure : (nx, ny) cell pressures [Pa], ``>= 0``
    deformation : (nx, ny) combined elastic deflection ``V`` [m]
    separation : (nx, ny) loaded gap ``gap + V - approach`` [m], ``>= 0``, zero in contact
    force : total load ``sum p dA`` [N]
    approach : rigid approach of distant points [m]
    contact_area : area of the cells with ``p > 0`` [m^2]
    central_pressure : pressure at ``centre`` (bilinear in the cell centres) [Pa]
    max_pressure : largest cell pressure [Pa]
    semi_axis_a, semi_axis_b : semi-axes of the fitted ellipse [m], ``a >= b``
    ellipse_angle : angle of the ``a`` axis from x [rad] in ``(-pi/2, pi/2]``
    centroid : pressure centroid ``(x, y)`` [m]
    iterations : conjugate-gradient iterations
    residual : final eq-12 change ``dA sum |p - p_old| / F``
    """

    grid: SurfaceGrid
    pressure: np.ndarray
    deformation: np.ndarray
    separation: np.ndarray
    force: float
    approach: float
    contact_area: float
    central_pressure: float
    max_pressure: float
    semi_axis_a: float
    semi_axis_b: float
    ellipse_angle: float
    centroid: tuple[float, float]
    iterations: int
    residual: float


def pressure_ellipse(pressure: np.ndarray, grid: SurfaceGrid) -> tuple[float, float, float, tuple[float, float]]:
    """Ellipse fitted to a pressure field: ``(a, b, angle, centroid)``.

    The ellipse whose Hertz pressure ``p0 sqrt(1 - x'^2/a^2 - y'^2/b^2)`` has
    the same centroid and second moments as ``pressure``: for the Hertz field
    ``<x'^2> = a^2/5``, ``<y'^2> = b^2/5`` (pressure-weighted means), so
    ``a, b = sqrt(5 lambda)`` of the eigenvalues of the moment tensor and the
    angle is that of its major eigenvector (rad, from x, in ``(-pi/2, pi/2]``).
    Exact for a Hertz field in the limit of a fine grid; smooth in the grid
    size (no staircase of the contact edge).
    """
    X, Y = grid.coordinates()
    total = float(pressure.sum())
    if not total > 0.0:
        raise ValueError("pressure must have a positive sum to fit an ellipse")
    xc = float((pressure * X).sum() / total)
    yc = float((pressure * Y).sum() / total)
    dxs, dys = X - xc, Y - yc
    # cell-average of x^2 over a cell of width dx adds dx^2/12 to the moment of point values
    mxx = float((pressure * dxs * dxs).sum() / total) + grid.dx**2 / 12.0
    myy = float((pressure * dys * dys).sum() / total) + grid.dy**2 / 12.0
    mxy = float((pressure * dxs * dys).sum() / total)
    eigenvalues, eigenvectors = np.linalg.eigh(np.array([[mxx, mxy], [mxy, myy]]))
    major = eigenvectors[:, 1]
    angle = math.atan2(major[1], major[0])
    if angle <= -math.pi / 2:
        angle += math.pi
    elif angle > math.pi / 2:
        angle -= math.pi
    return (math.sqrt(5.0 * eigenvalues[1]), math.sqrt(5.0 * max(eigenvalues[0], 0.0)), angle, (xc, yc))


def _bilinear(field: np.ndarray, grid: SurfaceGrid, point: tuple[float, float]) -> float:
    fi = (point[0] - grid.x[0]) / grid.dx
    fj = (point[1] - grid.y[0]) / grid.dy
    if not (0.0 <= fi <= grid.nx - 1 and 0.0 <= fj <= grid.ny - 1):
        raise ValueError(f"centre {point!r} lies outside the grid's cell centres")
    i = min(int(fi), grid.nx - 2)
    j = min(int(fj), grid.ny - 2)
    s, t = fi - i, fj - j
    return float((1 - s) * (1 - t) * field[i, j] + s * (1 - t) * field[i + 1, j]
                 + (1 - s) * t * field[i, j + 1] + s * t * field[i + 1, j + 1])


_FULL = (slice(None), slice(None))
_BOX_MIN_CELLS = 128  # grids with fewer cells across than this run on the full grid
_COARSENING = 4


def _coarse_start(gap: np.ndarray, grid: SurfaceGrid, e_star: float, force: float | None, approach: float | None,
                  tolerance: float, start: np.ndarray | None) -> tuple[tuple[slice, slice], np.ndarray | None]:
    # The same problem on every 4th cell (a grid of 4x the cell size, 1/16 of the work): the bounding box of its
    # contact, widened by 2.5 coarse cells, joined with the support of ``start`` and rounded up to sizes whose
    # padded transforms (2 m) are fast; and its pressure interpolated (bilinear) onto the grid, the start of the
    # fine CG unless ``start`` is given.  The full grid and no start when the box would not be much smaller than
    # the grid or the coarse solve fails (e.g. its contact reaches the grid edge).
    nx, ny = gap.shape
    if min(nx, ny) < _BOX_MIN_CELLS:
        return _FULL, None
    k = _COARSENING
    first = (k - 1) // 2
    coarse_gap = np.ascontiguousarray(gap[first::k, first::k])
    xs, ys = grid.x[first::k], grid.y[first::k]
    coarse = SurfaceGrid(coarse_gap.shape[0], coarse_gap.shape[1], k * grid.dx, k * grid.dy,
                         0.5 * (xs[0] + xs[-1]), 0.5 * (ys[0] + ys[-1]))
    try:
        solution = solve(coarse_gap, coarse, e_star, force=force, approach=approach, centre=(xs[0], ys[0]),
                         tolerance=max(tolerance, 1e-6))
    except (ValueError, ConvergenceError):
        return _FULL, None
    support = np.zeros(gap.shape, dtype=bool)
    support[first::k, first::k] = solution.pressure > 0.0
    if start is not None:
        support |= start > 0.0
    box = []
    for axis, n in enumerate((nx, ny)):
        used = np.flatnonzero(support.any(axis=1 - axis))
        pad = 2 * k + k // 2
        low, high = max(int(used[0]) - pad, 0), min(int(used[-1]) + 1 + pad, n)
        size = min(_fft_size(high - low), n)
        if size > 0.9 * n:
            return _FULL, None
        low = min(max(low - (size - (high - low)) // 2, 0), n - size)
        box.append(slice(low, low + size))
    if start is not None:
        return (box[0], box[1]), start
    # bilinear interpolation of the coarse cell values (at the fine cells first::k) onto every fine cell
    i = np.clip((np.arange(nx) - first) / k, 0.0, coarse.nx - 1.0)
    j = np.clip((np.arange(ny) - first) / k, 0.0, coarse.ny - 1.0)
    i0 = np.minimum(i.astype(int), coarse.nx - 2)
    j0 = np.minimum(j.astype(int), coarse.ny - 2)
    s, t = (i - i0)[:, None], (j - j0)[None, :]
    p = solution.pressure
    fine = ((1 - s) * (1 - t) * p[np.ix_(i0, j0)] + s * (1 - t) * p[np.ix_(i0 + 1, j0)]
            + (1 - s) * t * p[np.ix_(i0, j0 + 1)] + s * t * p[np.ix_(i0 + 1, j0 + 1)])
    return (box[0], box[1]), fine


def _fft_size(m: int) -> int:
    # the smallest m' >= m whose padded length 2 m' has only the factors 2, 3, 5 and 7 (fast transforms)
    while scipy.fft.next_fast_len(2 * m, real=True) != 2 * m:
        m += 1
    return m


def _constrained_cg(gap: np.ndarray, grid: SurfaceGrid, e_star: float, force: float | None,  # noqa: C901 - one Polonsky-Keer CG with its Jacobi re-entry and load/approach control
                    approach: float | None, p: np.ndarray | None, tolerance: float,
                    max_iterations: int) -> tuple[np.ndarray, int, float]:
    # Polonsky & Keer's constrained CG on ``gap``, a box of ``grid`` (or all of it), from the pressure ``p`` (None
    # or zero: the default start); returns the pressure, the iterations and the eq-12 residual
    load_control = force is not None
    nx, ny = gap.shape
    spectrum = _box_spectrum(grid.nx, grid.ny, grid.dx, grid.dy, nx, ny) / e_star  # the deflection for this E*
    spectrum_single = spectrum.astype(np.float32)
    kernel = _box_kernel(grid.nx, grid.ny, grid.dx, grid.dy, nx, ny)
    area = grid.cell_area
    self_step = e_star / float(kernel[nx - 1, ny - 1])  # 1 / K_00: the pressure that moves its own cell by 1 m
    if max_iterations < 1:
        raise ConvergenceError("half-space contact (Polonsky-Keer CG) did not converge", residual=math.inf,
                               iterations=0, tolerance=tolerance, reason="iteration limit")

    def apply(field, single=False):
        return _convolve(spectrum, field, spectrum_single if single else None)

    if p is None or not p.sum() > 0.0:
        if load_control:
            # start: uniform pressure where the gap is within the lowest 1 % of its range
            p = (gap <= gap.min() + 0.01 * max(float(np.ptp(gap)), 1e-300)).astype(float)
        else:
            # start: interference times the stiffness of a flat punch of the overlap's size, 2 E* / (pi a)
            overlap = np.maximum(approach - gap, 0.0)
            radius = math.sqrt(np.count_nonzero(overlap) * area / math.pi)
            p = overlap * (2.0 * e_star / (math.pi * radius))
    if load_control:
        p *= force / (area * p.sum())
    t = np.zeros_like(p)
    g = np.empty_like(p)
    g_old = 1.0
    delta = 0.0
    residual = math.inf
    u = apply(p)
    for iteration in range(1, max_iterations + 1):
        if iteration % 32 == 0:
            u = apply(p)  # remove the drift of the incremental update below
        np.add(u, gap, out=g)
        in_contact = p > 0.0
        # the CG works on the contact set only: gather it once, scatter the direction back
        g_c = g[in_contact]
        shift = float(g_c.mean()) if load_control else approach
        g_c -= shift  # the full-grid g keeps the shift: it is only compared with it (overlap) below
        g_norm = _dot(g_c, g_c)
        t_c = g_c + (delta * g_norm / g_old) * t[in_contact] if delta else g_c
        g_old = g_norm
        t = np.zeros_like(p)
        t[in_contact] = t_c
        r_raw = apply(t, single=True)  # float32 (single-precision increment)
        r_c = r_raw[in_contact].astype(float)
        if load_control:
            r_c -= r_c.mean()
        denominator = _dot(r_c, t_c)
        if g_norm > 0.0 and not denominator > 0.0:
            # K t underflowed in single precision (deflections near the bottom of its range): in double precision
            r_raw = apply(t)
            r_c = r_raw[in_contact]
            if load_control:
                r_c = r_c - r_c.mean()
            denominator = _dot(r_c, t_c)
        if g_norm > 0.0 and denominator > 0.0:
            tau = _dot(g_c, t_c) / denominator
        else:
            # zero search direction: the gap is uniform on the contact set (a single cell, or cells placed
            # symmetrically, e.g. the start on a grid whose centre lies on a cell or a cell corner), so ``p`` solves
            # the problem restricted to that set; the cells that interpenetrate re-enter below with the step of
            # their own stiffness, 1 / K_00 (a Jacobi step), instead of the CG step, which is 0 here
            tau = self_step
        p_old = p
        trial = p - tau * t
        p = np.maximum(trial, 0.0)
        changed = trial < 0.0  # clipped cells
        # cells outside the contact set that overlap (g - shift < 0) re-enter with p = -tau (g - shift)
        overlap = g < shift
        overlap &= p == 0.0
        if np.any(overlap):
            delta = 0.0
            p[overlap] -= tau * (g[overlap] - shift)
            changed |= overlap
        else:
            delta = 1.0
        # K p = K p_old - tau K t + K (p - trial): p - trial is zero except on the clipped and re-entering cells
        cells = np.flatnonzero(changed)
        correction = p.flat[cells] - trial.flat[cells]
        total = float(p.sum()) * area
        if load_control:
            factor = force / total
        elif total > 0.0:
            factor = 1.0
        else:
            raise ConvergenceError("approach control lost all contact", residual=math.inf, iterations=iteration,
                                   tolerance=tolerance, reason="no contact left")
        if g_norm > 0.0:  # (t = 0 otherwise)
            # the step in double precision where it lies beyond the single-precision range of r_raw
            u -= tau * (r_raw if abs(tau) < _SINGLE_MAX else r_raw.astype(float))
        if cells.size:
            u += _apply_sparse(spectrum, kernel, cells, correction, p.shape, spectrum_single, 1.0 / e_star)
        u *= factor
        p *= factor
        reference = force if load_control else total
        np.subtract(p, p_old, out=trial)  # trial is no longer needed: its buffer takes the change
        residual = area * float(np.abs(trial, out=trial).sum()) / reference
        if residual < tolerance:
            break
    else:
        raise ConvergenceError("half-space contact (Polonsky-Keer CG) did not converge", residual=residual,
                               iterations=max_iterations, tolerance=tolerance, reason="iteration limit")
    return p, iteration, residual


PHYSICAL_MODULUS = (1e6, 1e14)  # Pa: E* from rubber to diamond
PHYSICAL_CELL = (1e-9, 1.0)  # m
GAP_CHECK_FLOOR = 1e-6  # of the interference: above the single-precision increments' floor (~1.3e-7 measured)


def verify(gap: np.ndarray, pressure: np.ndarray, deformation: np.ndarray, approach: float, grid: SurfaceGrid,
           force: float | None, tolerance: float, *, iterations: int = 0) -> None:
    """Check a half-space solution against the conditions that define it (sun2021 eqs 5-8) on the full grid.

    ``deformation`` must be computed from ``pressure`` independently of the iteration that produced it
    (:func:`deformation`).  With the loaded gap ``c = gap + V - approach`` and the interference
    ``d = approach - min(gap)`` (the rigid approach from first touch, the scale of every gap and deflection in
    the contact), the checks and their tolerances are:

    * no tension: ``p >= 0`` everywhere (exactly);
    * closure in the contact: ``max |c|`` over the cells with ``p > 0`` at most ``(10 tolerance + 1e-6) d``
      (plus the round-off of ``c``, 8 eps of the largest of ``|approach|`` and ``|gap|`` in the contact);
    * no overlap outside it: ``-min c`` over the cells with ``p = 0`` at most the same;
    * load balance (load control, ``force`` given): ``|dA sum p - force|`` at most
      ``max(tolerance, cells * 2.2e-16) force``.

    ``tolerance`` is the eq-12 tolerance of the solve: the measured closure of converged solutions is below
    ``1.3 tolerance d`` plus the ``1.3e-7 d`` of the single-precision increments (docs/halfspace.md).
    Raises ConvergenceError naming the check, its value and its tolerance.
    """
    loaded = gap + deformation - approach
    in_contact = pressure > 0.0
    failed = None
    if not np.all(np.isfinite(pressure)) or not np.all(np.isfinite(loaded)):
        failed = ("finite pressure and deflection", math.inf, 0.0, "")
    elif float(pressure.min()) < 0.0:
        failed = ("no tension (p >= 0)", -float(pressure.min()), 0.0, "Pa")
    elif not in_contact.any():
        failed = ("some contact (p > 0 somewhere)", 0.0, 0.0, "")
    else:
        # the interference may round to 0 against the gap values (a load whose deflection lies below their
        # resolution): the round-off of gap + V - approach is the floor
        interference = max(approach - float(gap.min()), 0.0)
        roundoff = 8.0 * np.finfo(float).eps * max(abs(approach), float(np.max(np.abs(gap[in_contact]))))
        gap_tolerance = (10.0 * tolerance + GAP_CHECK_FLOOR) * interference + roundoff
        closure = float(np.max(np.abs(loaded[in_contact])))
        overlap = -float(loaded[~in_contact].min()) if not in_contact.all() else 0.0
        if closure > gap_tolerance:
            failed = ("closure in the contact max |gap + V - approach|", closure, gap_tolerance, "m")
        elif overlap > gap_tolerance:
            failed = ("no overlap outside the contact -min(gap + V - approach)", overlap, gap_tolerance, "m")
        elif force is not None:
            imbalance = abs(float(pressure.sum()) * grid.cell_area - force)
            load_tolerance = max(tolerance, pressure.size * 2.2e-16) * force
            if imbalance > load_tolerance:
                failed = ("load balance |dA sum p - force|", imbalance, load_tolerance, "N")
    if failed is not None:
        check, value, limit, unit = failed
        unit = f" {unit}" if unit else ""
        raise ConvergenceError(f"half-space contact: the solution fails its check of {check}: {value:.3e}{unit} "
                               f"> {limit:.3e}{unit}", residual=value, iterations=iterations, tolerance=limit,
                               reason=f"fails the check of {check}")


def solve(gap: np.ndarray, grid: SurfaceGrid, contact_modulus: float, *, force: float | None = None,  # noqa: C901 - load or approach control, checks, coarse start: one Polonsky-Keer solve
          approach: float | None = None, centre: tuple[float, float] = (0.0, 0.0), tolerance: float = 1e-8,
          max_iterations: int = 2000, initial_pressure: np.ndarray | None = None) -> HalfSpaceContact:
    """Half-space contact on ``gap`` [m] by the Polonsky-Keer conjugate gradient (sun2021 eqs 3-12).

    Parameters
    ----------
    gap : (nx, ny) separation of the undeformed surfaces at the cell centres [m]
        (roughness included, sun2021 eq 9 ``c_g + c_r``).
    grid : :class:`SurfaceGrid`
    contact_modulus : E* [Pa]
    force : load [N] (load control), or
    approach : rigid approach [m] (approach control); exactly one of the two.
    centre : point [m] where ``central_pressure`` is read (the initial contact point).
    tolerance : on sun2021 eq 12, ``dA sum |p - p_old| / F``.
    max_iterations : conjugate-gradient iterations before ConvergenceError.
    initial_pressure : optional (nx, ny) start [Pa] (e.g. the solution of a nearby case).

    Raises
    ------
    ValueError
        bad input, or the contact reaches the grid edge (the grid is too small).
    ConvergenceError
        no convergence in ``max_iterations``, or a result that fails its own check on the full grid
        (:func:`verify`: no tension, closure in the contact, no overlap outside it, load balance).
    """
    gap = np.asarray(gap, dtype=float)
    if gap.shape != (grid.nx, grid.ny):
        raise ValueError(f"gap must have shape {(grid.nx, grid.ny)}, got {gap.shape}")
    if not np.all(np.isfinite(gap)):
        raise ValueError("gap must be finite (got NaN or inf)")
    if float(np.max(np.abs(gap))) > LARGEST_LENGTH:
        raise ValueError(f"gap must lie within +-{LARGEST_LENGTH:g} m (the single-precision increments of the "
                         f"conjugate gradient), got {float(np.max(np.abs(gap)))!r} m")
    e_star = _finite_positive("contact_modulus", contact_modulus, "Pa")
    if (force is None) == (approach is None):
        raise ValueError("give exactly one of force [N] (load control) or approach [m] (approach control)")
    load_control = force is not None
    if load_control:
        force = _finite_positive("force", force, "N")
        if force > LARGEST_LENGTH * e_star * min(grid.dx, grid.dy):  # the deflection of the load on one cell
            raise ValueError(f"force / (contact_modulus * cell size) must be <= {LARGEST_LENGTH:g} m (the "
                             f"single-precision increments of the conjugate gradient), got {force!r} N")
    else:
        approach = float(approach)
        if not math.isfinite(approach):
            raise ValueError(f"approach must be finite [m], got {approach!r}")
        if abs(approach) > LARGEST_LENGTH:
            raise ValueError(f"approach must lie within +-{LARGEST_LENGTH:g} m, got {approach!r}")
        if approach <= float(gap.min()):
            raise ValueError(f"approach {approach!r} m does not exceed the smallest gap {float(gap.min())!r} m: "
                             "the surfaces do not touch")
    tolerance = _finite_positive("tolerance", tolerance, "")
    if int(max_iterations) < 1:
        raise ValueError(f"max_iterations must be >= 1, got {max_iterations!r}")
    max_iterations = int(max_iterations)
    area = grid.cell_area
    # Outside the physical range of moduli and cells the solve runs in pressures divided by ``scale``, a power of two
    # near E* / (cell size), with the modulus E* / scale: the influence coefficients of the conjugate gradient's
    # single-precision increments are then of order one (E* of 1e35 Pa underflowed them to zero and the solver
    # returned its start).  The scaling is exact in binary floating point; inside the physical range the solve runs
    # unscaled, as before (the scaled one differs there by round-off in the single-precision increments).
    scale = 1.0
    if not (PHYSICAL_MODULUS[0] <= e_star <= PHYSICAL_MODULUS[1]
            and PHYSICAL_CELL[0] <= min(grid.dx, grid.dy) <= PHYSICAL_CELL[1]):
        exponent = math.frexp(e_star)[1] - math.frexp(min(grid.dx, grid.dy))[1]
        scale = math.ldexp(1.0, min(max(exponent, -1000), 1000))
    user_force, e_star = force, e_star / scale
    if load_control:
        force = force / scale
    if initial_pressure is not None:
        p = np.array(initial_pressure, dtype=float)
        if p.shape != gap.shape or not np.all(np.isfinite(p)) or np.any(p < 0):
            raise ValueError("initial_pressure must be a finite, non-negative array of the grid's shape")
        p /= scale
    else:
        p = None
    # the conjugate gradient runs on a box that holds the contact (from a solve on a 4x coarser grid): the
    # convolutions of a field that is zero outside the box are DC-FFTs of the box's size, exactly; the
    # complementarity outside the box is checked on the full grid at the end, and the full grid takes over
    # (from the box's solution) if any cell there interpenetrates
    box, p = _coarse_start(gap, grid, e_star, force, approach, tolerance, p)
    iterations = 0
    while True:
        rows, cols = box
        p_box = None if p is None else np.array(p[rows, cols])
        p_box, used, residual = _constrained_cg(np.ascontiguousarray(gap[rows, cols]), grid, e_star, force,
                                                approach, p_box, tolerance, max_iterations - iterations)
        iterations += used
        p = np.zeros_like(gap)
        p[rows, cols] = p_box
        u = np.ascontiguousarray(deformation(p, grid, e_star))
        in_contact = p > 0.0
        if load_control:
            approach = float((u + gap)[in_contact].mean())
        if box == _FULL:
            break
        outside = np.ones(gap.shape, dtype=bool)
        outside[rows, cols] = False
        if not np.any((gap + u < approach) & outside):
            break
        box = _FULL  # a cell outside the box interpenetrates: the full grid, started from the box's solution
    if in_contact[0, :].any() or in_contact[-1, :].any() or in_contact[:, 0].any() or in_contact[:, -1].any():
        raise ValueError("the contact reaches the edge of the grid: enlarge the grid (half_width) so that it "
                         "holds the whole contact")
    with np.errstate(over="ignore", under="ignore"):
        p = p * scale
    peak = float(p.max())
    if not (math.isfinite(peak) and peak * np.finfo(float).eps >= np.finfo(float).tiny):
        raise ValueError(f"contact_modulus {contact_modulus!r} Pa with this {'force' if load_control else 'approach'} "
                         f"gives pressures beyond the double-precision range (largest {peak!r} Pa)")
    total = float(p.sum()) * area
    verify(gap, p, u, float(approach), grid, user_force, tolerance, iterations=iterations)
    separation = np.maximum(gap + u - approach, 0.0)
    separation[in_contact] = 0.0
    a, b, angle, centroid = pressure_ellipse(p, grid)
    return HalfSpaceContact(grid=grid, pressure=p, deformation=u, separation=separation, force=total,
                            approach=float(approach), contact_area=float(in_contact.sum()) * area,
                            central_pressure=_bilinear(p, grid, centre), max_pressure=float(p.max()),
                            semi_axis_a=a, semi_axis_b=b, ellipse_angle=angle, centroid=centroid,
                            iterations=iterations, residual=residual)
