"""Steady rolling contact with stick and slip on a grid (Kalker's exact theory, discretised).

Problem (Kalker 1990, Ch 2 and 5; CONTACT user guide, 'The contact conditions'): two bodies roll over each
other with speed ``V`` along ``+x`` of the contact plane (the contact moves along ``+x`` over both surfaces,
material passes through it along ``-x``: leading edge at ``x = +a``).  Given the normal pressure ``p_n``
(Hertz, or any field from the BEM or the FE) and the rigid slip ``w(x, y)`` of body 1 relative to body 2
per unit rolling distance (for creepages ``xi, eta`` and spin ``phi`` [rad/m]:
``w = (xi - phi y, eta + phi x)``), find the tangential traction ``p`` on body 1 such that with the slip
(per unit rolling distance)::

    s = w + (u(x) - u(x + dx)) / dx,   u = A * p          (steady state, rolling step = cell size dx)

Coulomb's law holds in every contact cell with the traction bound ``g = mu p_n``::

    |p| <= g;   stick: |p| < g  and  s = 0;   slip: |p| = g  and  p = -g s / |s|.

``A`` are the influence coefficients of :mod:`lowmodel.contact.influence` (half-space, closed form over
rectangles) or a condensed FE compliance (``W = B K^-1 B^T``, :class:`MatrixOperator`).  A shift
(Cattaneo-Mindlin: the bodies start unloaded and are shifted by ``W``) is the same problem with
``s = W + u`` (:func:`shift`).

Solution: semismooth Newton on ``F(p) = p - Proj_g(p - c s(p)) = 0`` (``Proj_g`` projects each cell's
traction onto the disc ``|p| <= g``; ``c = 1/max diag C``, so ``c s`` is a traction); its generalised
Jacobian ``J = (I - D) + c D C`` with ``D = Proj_g'`` (identity in stick cells, ``(g/|z|)(I - z z^T/|z|^2)``
in slip cells).  Each Newton system is solved by dense LU up to :data:`DIRECT_CELLS` contact cells, above
by GMRES (right preconditioned) with the exact inverse of ``J`` restricted to each grid line along the
rolling direction (the steady-state operator's coupling is mostly along ``x``: the lateral neighbours carry
8-17 % of the diagonal); the products with ``C`` are dense below :data:`DENSE_CELLS` contact cells and
zero-padded FFT convolutions (DC-FFT, exact) above.  Newton starts from the local (FASTSIM-like) solution
marched from the leading edge (:meth:`_Problem.marching_start`).
Costs (docs/rolling_contact.md): one product ``O(n log n)`` (FFT) or ``O(n^2)`` (dense), the line inverses
``O(n_y n_x^3)`` per Newton step, 4 to 12 Newton steps with 2 to 8 GMRES steps each.

Before returning, the solver re-evaluates the slip from the final traction and checks the conditions
that define the answer (Coulomb bound, zero slip in stick cells, traction opposite to the slip in slip
cells, non-negative dissipation in every cell); a failed check raises ConvergenceError naming it.

Conventions (Kalker's; docs/rolling_contact.md has the drawing): ``x`` rolling, ``y`` lateral, ``z``
normal pointing into body 1; forces and moment on body 1; ``xi = (v1 - v2)_x / V`` at the contact
centre, ``eta`` likewise, ``phi = (omega_1 - omega_2)_z / V`` [rad/m].  With these, the linear theory reads
``F_x = -G c^2 C11 xi``, ``F_y = -G c^2 (C22 eta + c C23 phi)`` (``c = sqrt(a b)``, Kalker 1990 Table E.3).
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.influence import combined_material, grid_kernels
from ballbench.lowmodel.errors import ConvergenceError

__all__ = [
    "RollingContact",
    "ConvolutionOperator",
    "MatrixOperator",
    "half_space_operator",
    "rigid_slip",
    "rigid_slip_field",
    "hertz_grid",
    "LineGrid",
    "steady_rolling_line",
    "hertz_pressure",
    "solve",
    "shift",
    "steady_rolling",
    "spin_parameter",
    "DENSE_CELLS",
    "DIRECT_CELLS",
]

DENSE_CELLS = 400  # contact cells up to which the operator's products are dense (measured, benchmarks)
DIRECT_CELLS = 150  # contact cells up to which each Newton system is solved by dense LU, not GMRES (benchmarks)
CHECK_TOLERANCE = 1e-7  # the defining conditions hold to this fraction of max(g) (traction units)
_FORCING = 0.1  # GMRES relative tolerance per Newton step (inexact Newton; min(0.1, residual))
_RESTART = 30


# --------------------------------------------------------------------------
# result
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class RollingContact:
    """Tangential solution on a grid (Kalker's frame: ``x`` rolling, ``y`` lateral, tractions on body 1).

    grid : the :class:`~lowmodel.contact.halfspace.SurfaceGrid` (arrays ``(nx, ny)``, ``[i, j]`` at
        ``(grid.x[i], grid.y[j])``; ``x`` along rolling)
    pressure : (nx, ny) normal pressure [Pa]
    traction : (nx, ny, 2) tangential traction on body 1 [Pa]
    slip : (nx, ny, 2) slip of body 1 relative to body 2, per unit rolling distance [-] (a shift: [m]); zero
        outside the contact
    rigid_slip : (nx, ny, 2) the rigid (kinematic) part ``w`` as given (same units)
    stick : (nx, ny) bool, contact cells in stick (``|p| < g``); slip cells are ``contact & ~stick``
    contact : (nx, ny) bool, cells with ``p_n > 0``
    friction_coefficient : mu; rolling_speed : V [m/s] (the power's scale)
    force_rolling, force_lateral : [N] on body 1, ``sum p dA``
    spin_moment : [N m] on body 1 about ``+z`` through the grid origin, ``sum (x p_y - y p_x) dA``
    frictional_power : [W] ``-V sum p . s dA`` (>= 0; a shift: the frictional work [J])
    rigid_power : [W] ``-V sum p . w dA``, the power of the tractions on the rigid slip: what the bodies'
        equilibrium sees (``-(F . v + M_z omega_z + ...)``, so a power balance of a ball closes on it exactly);
        it exceeds ``frictional_power`` by the discretisation's elastic term, O(dx): 0.2 % at 16 x 16 cells,
        0.06 % at 64 x 64 (docs/rolling_contact.md)
    stick_fraction : stick cells / contact cells
    normal_force : [N] ``sum p_n dA``
    iterations, krylov_iterations, residual : Newton steps, GMRES steps, final ``max|F| / max g``
    """

    grid: SurfaceGrid
    pressure: np.ndarray
    traction: np.ndarray
    slip: np.ndarray
    rigid_slip: np.ndarray
    stick: np.ndarray
    contact: np.ndarray
    friction_coefficient: float
    rolling_speed: float
    force_rolling: float
    force_lateral: float
    spin_moment: float
    frictional_power: float
    rigid_power: float
    stick_fraction: float
    normal_force: float
    iterations: int
    krylov_iterations: int
    residual: float

    def __post_init__(self):
        checks.freeze_arrays(self, "pressure", "traction", "slip", "rigid_slip", "stick", "contact")

    @property
    def slip_area(self) -> np.ndarray:
        """(nx, ny) bool, contact cells in slip."""
        return self.contact & ~self.stick

    @property
    def slip_velocity(self) -> np.ndarray:
        """(nx, ny, 2) slip velocity [m/s], ``V s``."""
        return self.rolling_speed * self.slip

    @property
    def traction_bound(self) -> np.ndarray:
        """(nx, ny) ``mu p_n`` [Pa]."""
        return self.friction_coefficient * self.pressure


# --------------------------------------------------------------------------
# operators: s = w + C p on the contact cells
# --------------------------------------------------------------------------
@functools.lru_cache(maxsize=1)
def _blas_controller():
    from threadpoolctl import ThreadpoolController

    return ThreadpoolController()


def _one_blas_thread():
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
        fft = self._fft
        padded = np.zeros((2, 2 * nx, 2 * ny))
        padded[0, :nx, :ny] = field[..., 0]
        padded[1, :nx, :ny] = field[..., 1]
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
            result = fft.c2r(out, axes=(1, 2), lastsize=2 * ny, forward=False, inorm=2)
        else:  # pragma: no cover
            result = np.fft.irfft2(out, s=self.shape)
        return np.stack([result[0, :nx, :ny], result[1, :nx, :ny]], axis=-1)


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
        if self._convolution is None:
            self._convolution = _Convolution(self.kernels, self.grid.nx, self.grid.ny)
        return self._convolution(field)

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


# --------------------------------------------------------------------------
# kinematics and Hertz input
# --------------------------------------------------------------------------
def rigid_slip(grid: SurfaceGrid, creepage_rolling, creepage_lateral, spin, *,
               centre: tuple[float, float] = (0.0, 0.0)) -> np.ndarray:
    """``w = (xi - phi (y - y0), eta + phi (x - x0))`` at the cell centres, (nx, ny, 2) [-].

    ``creepage_rolling`` xi, ``creepage_lateral`` eta [-], ``spin`` phi [rad/m] (Kalker's; module docstring);
    ``centre`` ``(x0, y0)`` [m] the spin centre.
    """
    xi = checks.finite("creepage_rolling", creepage_rolling)
    eta = checks.finite("creepage_lateral", creepage_lateral)
    phi = checks.finite("spin", spin, "rad/m")
    out = np.empty((grid.nx, grid.ny, 2))
    out[..., 0] = xi - phi * (grid.y[None, :] - centre[1])
    out[..., 1] = eta + phi * (grid.x[:, None] - centre[0])
    return out


def rigid_slip_field(grid: SurfaceGrid, sliding_velocity, angular_velocity, rolling_speed: float, *,
                     lateral_curvature: float = 0.0) -> np.ndarray:
    """Rigid slip per unit rolling distance (nx, ny, 2) of a rigid relative motion, Heathcote slip included.

    ``sliding_velocity`` (2,) [m/s]: velocity of body 1 relative to body 2 at the grid origin, in the
    contact plane (``x`` rolling, ``y`` lateral); ``angular_velocity`` (3,) [rad/s]: ``omega_1 - omega_2``
    in ``(x, y, z)`` (``z`` into body 1); ``rolling_speed`` V > 0 [m/s].  ``lateral_curvature`` [1/m]:
    the contact surface is ``z = k y^2 / 2`` (conformal contact: curved across the rolling direction,
    ``k > 0`` bending towards body 1, e.g. a ball in a groove).  Each surface point ``r = (x, y, k y^2/2)``
    slips at ``v + omega x r``::

        w_x = (v_x + omega_y k y^2/2 - omega_z y) / V        (the omega_y term is Heathcote's slip)
        w_y = (v_y + omega_z x - omega_x k y^2/2) / V
    """
    v = checks.finite("sliding_velocity", sliding_velocity, "m/s")
    omega = checks.finite("angular_velocity", angular_velocity, "rad/s")
    if np.shape(v) != (2,) or np.shape(omega) != (3,):
        raise ValueError("sliding_velocity must have shape (2,) and angular_velocity shape (3,)")
    speed = checks.positive("rolling_speed", rolling_speed, "m/s")
    curvature = checks.finite("lateral_curvature", lateral_curvature, "1/m")
    X, Y = grid.coordinates()
    height = 0.5 * curvature * Y * Y
    return np.stack([(v[0] + omega[1] * height - omega[2] * Y) / speed,
                     (v[1] + omega[2] * X - omega[0] * height) / speed], axis=-1)


def hertz_grid(semi_axis_rolling: float, semi_axis_lateral: float, cells) -> SurfaceGrid:
    """The grid of :func:`steady_rolling`: ``cells = (n_x, n_y)`` across the ellipse's ``2a x 2b`` box, plus
    one empty cell on each side (the contact must lie inside the grid)."""
    a = checks.positive("semi_axis_rolling", semi_axis_rolling, "m")
    b = checks.positive("semi_axis_lateral", semi_axis_lateral, "m")
    nx, ny = _cells(cells)
    return SurfaceGrid(nx + 2, ny + 2, 2.0 * a / nx, 2.0 * b / ny)


@dataclass(frozen=True)
class LineGrid:
    """A line contact's grid: ``nx`` cells of width ``dx`` [m] along ``x``, one of unit length 1 m along ``y``
    (forces are per metre of line).  The same attributes as :class:`~lowmodel.contact.halfspace.SurfaceGrid`."""

    nx: int
    dx: float
    ny: int = 1
    dy: float = 1.0
    x_centre: float = 0.0
    y_centre: float = 0.0

    def __post_init__(self):
        checks.count("nx", self.nx, 4, 1 << 20)
        checks.positive("dx", self.dx, "m")

    @property
    def x(self) -> np.ndarray:
        return self.x_centre + (np.arange(self.nx) - 0.5 * (self.nx - 1)) * self.dx

    @property
    def y(self) -> np.ndarray:
        return np.array([self.y_centre])

    @property
    def cell_area(self) -> float:
        return self.dx * self.dy

    def coordinates(self) -> tuple[np.ndarray, np.ndarray]:
        return np.meshgrid(self.x, self.y, indexing="ij")


def _cells(cells) -> tuple[int, int]:
    if isinstance(cells, (int, np.integer)) and not isinstance(cells, bool):
        cells = (cells, cells)
    try:
        nx, ny = cells
    except (TypeError, ValueError):
        raise ValueError(f"cells must be (n_rolling, n_lateral), got {cells!r}") from None
    return checks.count("cells[0] (n_rolling)", nx, 2, 4096), checks.count("cells[1] (n_lateral)", ny, 1, 4096)


@functools.lru_cache(maxsize=32)
def _gauss(order: int):
    nodes, weights = np.polynomial.legendre.leggauss(order)
    return checks.read_only(nodes), checks.read_only(0.5 * weights)


@functools.lru_cache(maxsize=32)
def _unit_pattern(x: tuple, y: tuple, order: int) -> np.ndarray:
    # cell averages of sqrt(1 - u^2 - v^2) over cells centred at x (width x[1] - x[0]) and y, unit semi-axes
    nodes, weights = _gauss(order)
    xs, ys = np.asarray(x), np.asarray(y)
    u = (xs[:, None] + 0.5 * (xs[1] - xs[0]) * nodes[None, :]).ravel()
    if len(ys) == 1:
        value = np.sqrt(np.maximum(1.0 - u * u, 0.0)).reshape(len(xs), order) @ weights
        return checks.read_only(value[:, None])
    v = (ys[:, None] + 0.5 * (ys[1] - ys[0]) * nodes[None, :]).ravel()
    value = np.sqrt(np.maximum(1.0 - u[:, None] ** 2 - v[None, :] ** 2, 0.0)).reshape(len(xs), order, len(ys), order)
    return checks.read_only(np.einsum("iajb,a,b->ij", value, weights, weights))


def hertz_pressure(grid, semi_axis_rolling: float, semi_axis_lateral: float, normal_force: float,
                   *, order: int = 8) -> np.ndarray:
    """Cell averages of the Hertz pressure ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``, ``p0 = 3 F / (2 pi a b)``, on
    ``grid`` [Pa] (``order``-point Gauss-Legendre per cell and direction; the cells' total is ``F`` to
    the rule's accuracy).  On a :class:`LineGrid` the strip ``p0 sqrt(1 - x^2/a^2)``, ``p0 = 2 F / (pi a)``
    with ``F`` per unit length [N/m].  The grid need not be :func:`hertz_grid`'s."""
    a = checks.positive("semi_axis_rolling", semi_axis_rolling, "m")
    b = checks.positive("semi_axis_lateral", semi_axis_lateral, "m")
    force = checks.positive("normal_force", normal_force, "N")
    order = checks.count("order", order, 1, 64)
    x = tuple(float(v) for v in np.round(grid.x / a, 14))
    if isinstance(grid, LineGrid):
        return (2.0 * force / (math.pi * a * grid.dy)) * _unit_pattern(x, (0.0,), order)
    y = tuple(float(v) for v in np.round(grid.y / b, 14))
    return (1.5 * force / (math.pi * a * b)) * _unit_pattern(x, y, order)


def spin_parameter(spin, semi_axis_lateral, friction_coefficient, central_pressure, shear_modulus) -> np.ndarray:
    """The spin parameter ``Lambda = |phi| b G / (mu p0)``, ``b`` the semi-axis across the rolling direction
    [m]: the spin's elastic slip over the contact against the friction bound; full slip holds for
    ``Lambda >> 1`` (docs/rolling_contact.md, 'When each rung suffices')."""
    phi = checks.finite("spin", spin, "rad/m")
    b = checks.positive("semi_axis_lateral", semi_axis_lateral, "m")
    mu = checks.positive("friction_coefficient", friction_coefficient)
    p0 = checks.positive("central_pressure", central_pressure, "Pa")
    g = checks.positive("shear_modulus", shear_modulus, "Pa")
    return np.abs(phi) * b * g / (mu * p0)


# --------------------------------------------------------------------------
# the solver
# --------------------------------------------------------------------------
def _gmres(matvec, precondition, rhs: np.ndarray, tolerance: float, max_iterations: int):
    """Right-preconditioned restarted GMRES (Saad 2003, Alg 9.5); returns ``(x, iterations)``."""
    n = rhs.size
    x = np.zeros(n)
    norm_b = math.sqrt(float(rhs @ rhs))
    if norm_b == 0.0:
        return x, 0
    residual = rhs
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


class _Problem:
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
        self.flat = self.line_of * grid.nx + self.position
        self._inverse = None
        self._pattern = None
        self._pairs = None

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

    def marching_start(self) -> np.ndarray:
        """A start for Newton: the local (FASTSIM-like) solution ``s = w + L (p_i - p_upstream) / dx = 0`` marched
        from the leading edge with the traction bound, ``L`` the flexibility that makes a unit traction ramp
        along each line give the operator's mean slip (one product with ``C``)."""
        nx, n_lines = self.shape[0], self.lines.size
        ramp = np.zeros((n_lines, nx))
        ramp[self.line_of, self.position] = 1.0
        ramp = np.cumsum(ramp[:, ::-1], axis=1)[:, ::-1] * (ramp > 0)  # contact cells upstream, incl. itself
        test = np.repeat(ramp[self.line_of, self.position][:, None], 2, axis=1)
        response = self.apply(test)
        flexibility = float(np.median(response[test[:, 0] > 1.5]) if np.any(test[:, 0] > 1.5) else
                            np.median(response))  # L / dx
        if not (math.isfinite(flexibility) and flexibility > 0.0):
            return np.zeros((self.n, 2))
        w = np.zeros((n_lines, nx, 2))
        w[self.line_of, self.position] = self.w / flexibility
        g = np.zeros((n_lines, nx))
        g[self.line_of, self.position] = self.g
        p = np.zeros((n_lines, nx, 2))
        upstream = np.zeros((n_lines, 2))
        for i in range(nx - 1, -1, -1):
            trial = upstream - w[:, i]
            norm = np.hypot(trial[:, 0], trial[:, 1])
            limit = g[:, i]
            trial *= np.where(norm > limit, limit / np.where(norm > 0.0, norm, 1.0), 1.0)[:, None]
            p[:, i] = upstream = trial
        return p[self.line_of, self.position]

    def preconditioner(self, D: np.ndarray, sliding: np.ndarray):
        """The inverse of ``J`` restricted to each grid line along ``x`` (line blocks; others identity).

        A line's inverse is rebuilt only when the stick/slip pattern of its cells changed since it was
        built (a stale slip direction only costs GMRES steps); single precision (a preconditioner).
        """
        nx = self.shape[0]
        n_lines = self.lines.size
        pattern = np.zeros((n_lines, nx), dtype=bool)
        pattern.reshape(-1)[self.flat] = sliding
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


def _pair_index_of(problem: "_Problem"):
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


def _newton(problem: _Problem, tolerance: float, max_iterations: int, start: np.ndarray | None):
    p = problem.marching_start() if start is None else start.copy()
    F, z, norm, sliding, scale = problem.residual(p)
    residual = float(np.max(np.abs(F))) / problem.gmax
    krylov = 0
    c = problem.c
    for iteration in range(1, max_iterations + 1):
        if residual <= tolerance:
            return p, iteration - 1, krylov, residual
        D = _derivative(z, norm, sliding, scale)
        E = -D
        E[:, 0, 0] += 1.0
        E[:, 1, 1] += 1.0
        cD = c * D

        if problem.matrix is not None:  # J = E + c D C as one dense matrix: one product per GMRES step
            n = problem.n
            rows = problem.matrix.reshape(n, 2, 2 * n)
            jacobian = cD[:, :, 0, None] * rows[:, None, 0, :]
            jacobian += cD[:, :, 1, None] * rows[:, None, 1, :]
            jacobian.reshape(n, 2, n, 2)[np.arange(n), :, np.arange(n), :] += E
            matvec = jacobian.reshape(2 * n, 2 * n).__matmul__
        else:
            def matvec(v, cD=cD, E=E):
                v = v.reshape(-1, 2)
                Cv = problem.apply(v)
                out = E[:, :, 0] * v[:, 0, None]
                out += E[:, :, 1] * v[:, 1, None]
                out += cD[:, :, 0] * Cv[:, 0, None]
                out += cD[:, :, 1] * Cv[:, 1, None]
                return out.reshape(-1)

        if problem.matrix is not None and problem.n <= DIRECT_CELLS:
            step = np.linalg.solve(jacobian.reshape(2 * n, 2 * n), -F.reshape(-1)).reshape(-1, 2)
        else:
            precondition = problem.preconditioner(D, sliding)
            step, used = _gmres(matvec, precondition, -F.reshape(-1), min(_FORCING, residual), 200)
            krylov += used
            step = step.reshape(-1, 2)
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
                           residual=residual, iterations=max_iterations, tolerance=tolerance)


def _check_solution(problem: _Problem, p: np.ndarray, tolerance: float):
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
    for name, value in checks_:
        if not (value <= limit):
            raise ConvergenceError(f"rolling contact: check failed, {name} = {value:.3e}", residual=value,
                                   iterations=0, tolerance=limit)
    return s, ~sliding


def _check_pressure(pressure, grid: SurfaceGrid, edge: bool = True) -> np.ndarray:
    pressure = np.asarray(checks.real("pressure", pressure), dtype=float)
    if pressure.shape != (grid.nx, grid.ny):
        raise ValueError(f"pressure must have the grid's shape {(grid.nx, grid.ny)}, got {pressure.shape}")
    if not np.all(np.isfinite(pressure)):
        raise ValueError("pressure must be finite (got NaN or inf) [Pa]")
    if np.any(pressure < 0.0):
        raise ValueError(f"pressure must be >= 0 Pa everywhere (compressive), got min {float(pressure.min())!r} Pa")
    if not np.any(pressure > 0.0):
        raise ValueError("pressure must be > 0 Pa somewhere: no contact on the grid")
    if edge and grid.ny > 1:
        ring = np.concatenate([pressure[0], pressure[-1], pressure[:, 0], pressure[:, -1]])
        if np.any(ring > 0.0):
            raise ValueError("the grid does not cover the contact: the pressure is > 0 in the outermost cells; "
                             "enlarge the grid so that the contact lies inside it")
    elif edge and (pressure[0, 0] > 0.0 or pressure[-1, 0] > 0.0):
        raise ValueError("the grid does not cover the contact: the pressure is > 0 in the first or last cell")
    return pressure


def _check_rigid(rigid, grid: SurfaceGrid, name: str) -> np.ndarray:
    rigid = np.asarray(checks.real(name, rigid), dtype=float)
    if rigid.shape != (grid.nx, grid.ny, 2):
        raise ValueError(f"{name} must have shape {(grid.nx, grid.ny, 2)}, got {rigid.shape}")
    if not np.all(np.isfinite(rigid)):
        raise ValueError(f"{name} must be finite (got NaN or inf)")
    return rigid


def solve(pressure, operator, friction_coefficient: float, rigid, *, rolling_speed: float = 1.0,
          tolerance: float = 1e-10, max_iterations: int = 60, dense: bool | None = None,
          initial_traction: np.ndarray | None = None) -> RollingContact:
    """Tangential tractions of a contact with stick and slip (module docstring).

    Parameters
    ----------
    pressure : (nx, ny) normal pressure [Pa] on ``operator.grid`` (>= 0; zero in the outermost cells)
    operator : :class:`ConvolutionOperator` (:func:`half_space_operator`) or :class:`MatrixOperator`;
        steady rolling (slip per unit rolling distance) or a shift, as built
    friction_coefficient : mu > 0
    rigid : (nx, ny, 2) the rigid slip ``w`` (:func:`rigid_slip`, :func:`rigid_slip_field`) [-] (a shift: [m])
    rolling_speed : V [m/s], scales the frictional power only
    tolerance : on ``max|F| / max(mu p_n)`` (traction units)
    dense : force dense (True) or FFT (False) products; default by :data:`DENSE_CELLS`
    initial_traction : (nx, ny, 2) start [Pa] (e.g. a nearby case)

    Raises ValueError for bad input, ConvergenceError when Newton does not converge or a defining
    condition fails its check.
    """
    grid = operator.grid
    pressure = _check_pressure(pressure, grid)
    mu = checks.positive("friction_coefficient", friction_coefficient)
    rigid = _check_rigid(rigid, grid, "rigid (the rigid slip)")
    speed = checks.positive("rolling_speed", rolling_speed, "m/s")
    checks.positive("tolerance", tolerance)
    max_iterations = checks.count("max_iterations", max_iterations, 1)
    coupled = operator.normal_slip(pressure)  # the pressure's slip through the normal-tangential coupling
    bound = mu * pressure
    problem = _Problem(operator, bound, rigid if coupled is None else rigid + coupled, dense)
    start = None
    if initial_traction is not None:
        start = _check_rigid(initial_traction, grid, "initial_traction").reshape(-1, 2)[problem.cells]
    with _one_blas_thread():
        p, iterations, krylov, residual = _newton(problem, tolerance, max_iterations, start)
        s, stick = _check_solution(problem, p, tolerance)
    return _result(problem, grid, pressure, p, s, stick, rigid, mu, speed, iterations, krylov, residual)


def _result(problem, grid, pressure, p, s, stick, rigid, mu, speed, iterations, krylov, residual) -> RollingContact:
    traction = np.zeros((grid.nx, grid.ny, 2))
    slip = np.zeros((grid.nx, grid.ny, 2))
    traction.reshape(-1, 2)[problem.cells] = p
    slip.reshape(-1, 2)[problem.cells] = s
    stick_grid = np.zeros((grid.nx, grid.ny), dtype=bool)
    stick_grid.reshape(-1)[problem.cells] = stick
    area = grid.cell_area
    force = traction.reshape(-1, 2).sum(axis=0) * area
    moment = float(np.sum(grid.x[:, None] * traction[..., 1] - grid.y[None, :] * traction[..., 0])) * area
    power = -speed * float(np.sum(p * s)) * area
    rigid_power = -speed * float(np.sum(p * rigid.reshape(-1, 2)[problem.cells])) * area
    return RollingContact(grid, pressure, traction, slip, rigid, stick_grid, problem.contact.copy(), mu, speed,
                          float(force[0]), float(force[1]), moment, power, rigid_power, float(stick.sum()) / problem.n,
                          float(pressure.sum()) * area, iterations, krylov, residual)


def shift(pressure, grid: SurfaceGrid, shear_modulus: float, poisson_ratio: float, friction_coefficient: float,
          rigid_shift, *, tolerance: float = 1e-10, max_iterations: int = 60) -> RollingContact:
    """A shift from the unloaded state (Cattaneo-Mindlin; CONTACT's 'shift', T = 1): ``s = W + u``.

    ``rigid_shift`` (2,) [m]: the rigid shift ``W`` of body 1 relative to body 2 (uniform), or an
    (nx, ny, 2) field.  Returns a :class:`RollingContact` whose ``slip`` is the shift [m] and whose
    ``frictional_power`` is the frictional work [J] (``rolling_speed`` 1).
    """
    operator = half_space_operator(grid, shear_modulus, poisson_ratio, steady=False)
    value = np.asarray(checks.real("rigid_shift", rigid_shift), dtype=float)
    if value.shape == (2,):
        value = np.broadcast_to(value, (grid.nx, grid.ny, 2))
    return solve(pressure, operator, friction_coefficient, value, tolerance=tolerance,
                 max_iterations=max_iterations)


def steady_rolling(semi_axis_rolling: float, semi_axis_lateral: float, normal_force: float, shear_modulus: float,
                   poisson_ratio: float, friction_coefficient: float, creepage_rolling: float,
                   creepage_lateral: float, spin: float, cells=(35, 35), *, rolling_speed: float = 1.0,
                   tolerance: float = 1e-10, max_iterations: int = 60) -> RollingContact:
    """Steady rolling of a Hertz contact with stick and slip on two elastic half-spaces (Kalker's exact theory).

    Parameters (SI)
    ---------------
    semi_axis_rolling, semi_axis_lateral : Hertz semi-axes ``a`` (along rolling) and ``b`` [m]
    normal_force : F [N] (Hertz pressure ``p0 sqrt(1 - x^2/a^2 - y^2/b^2)``, ``p0 = 3 F / (2 pi a b)``,
        cell-averaged)
    shear_modulus, poisson_ratio : combined G [Pa] and nu of the two bodies
        (:func:`lowmodel.contact.influence.combined_material`; quasi-identical bodies)
    friction_coefficient : mu > 0
    creepage_rolling, creepage_lateral : xi, eta [-]; spin : phi [rad/m] (Kalker's signs, module docstring)
    cells : (n_rolling, n_lateral) cells across the ellipse's ``2a x 2b`` box (the grid has one more empty
        cell on each side, :func:`hertz_grid`); an int for both
    rolling_speed : V [m/s] for the frictional power [W]

    Returns
    -------
    :class:`RollingContact`: ``force_rolling``, ``force_lateral`` [N], ``spin_moment`` [N m] (about the
    contact centre), ``stick_fraction``, ``frictional_power`` [W], the traction, slip and stick fields.
    """
    grid = hertz_grid(semi_axis_rolling, semi_axis_lateral, cells)
    pressure = hertz_pressure(grid, semi_axis_rolling, semi_axis_lateral, normal_force)
    shear, nu, _ = combined_material(shear_modulus, poisson_ratio)
    operator = half_space_operator(grid, shear, nu)
    w = rigid_slip(grid, creepage_rolling, creepage_lateral, spin)
    return solve(pressure, operator, friction_coefficient, w, rolling_speed=rolling_speed, tolerance=tolerance,
                 max_iterations=max_iterations)


def steady_rolling_line(semi_width: float, normal_load: float, shear_modulus: float, poisson_ratio: float,
                        friction_coefficient: float, creepage_rolling: float, cells: int = 200, *,
                        tolerance: float = 1e-10, max_iterations: int = 60) -> RollingContact:
    """Steady rolling of two cylinders (plane strain, Carter's problem) with stick and slip.

    ``semi_width`` a [m] of the Hertz strip ``p0 sqrt(1 - x^2/a^2)``, ``normal_load`` per unit length [N/m]
    (``p0 = 2 F / (pi a)``), combined ``shear_modulus`` [Pa] and ``poisson_ratio``, ``friction_coefficient``,
    ``creepage_rolling`` xi; ``cells`` across ``2a`` (plus one empty cell each side).  Forces per metre.
    """
    a = checks.positive("semi_width", semi_width, "m")
    n = checks.count("cells", cells, 4, 1 << 20)
    grid = LineGrid(n + 2, 2.0 * a / n)
    pressure = hertz_pressure(grid, a, 1.0, normal_load)
    shear, nu, _ = combined_material(shear_modulus, poisson_ratio)
    operator = half_space_operator(grid, shear, nu, plane_strain=True)
    w = rigid_slip(grid, creepage_rolling, 0.0, 0.0)
    return solve(pressure, operator, friction_coefficient, w, tolerance=tolerance, max_iterations=max_iterations)
