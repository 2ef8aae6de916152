"""Input of the steady rolling problem: grids, Hertz pressure, rigid slip, the spin parameter.

Kalker's conventions (docs/rolling_contact.md, :mod:`lowmodel.contact.rolling`): ``x`` rolling (the contact
moves along ``+x`` over both surfaces, material enters at the leading edge ``x = +a``), ``y`` lateral, ``z``
into body 1; the rigid slip ``w`` of body 1 relative to body 2 per unit rolling distance.

* :func:`hertz_grid` and :class:`LineGrid`: the grids of :func:`lowmodel.contact.rolling.steady_rolling` and
  ``steady_rolling_line`` (the contact inside, one empty cell on each side);
* :func:`hertz_pressure`: cell averages of Hertz's pressure (Gauss-Legendre per cell);
* :func:`rigid_slip` (creepages and spin) and :func:`rigid_slip_field` (any rigid relative motion on a contact
  surface curved across the rolling direction, Heathcote's slip included);
* :func:`spin_parameter`: ``Lambda = |phi| b G / (mu p0)``, which tells how far a contact is from full slip.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact.halfspace import SurfaceGrid

__all__ = ["rigid_slip", "rigid_slip_field", "hertz_grid", "LineGrid", "hertz_pressure", "spin_parameter"]


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
    """The grid of :func:`steady_rolling`: ``cells = (n_x, n_y)`` across the ellipse's ``2a x 2b`` box, each in
    [2, 4096], plus one empty cell on each side (the contact must lie inside the grid; a
    :class:`~lowmodel.contact.halfspace.SurfaceGrid` has at least 4 cells each way)."""
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
    return checks.count("cells[0] (n_rolling)", nx, 2, 4096), checks.count("cells[1] (n_lateral)", ny, 2, 4096)


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
