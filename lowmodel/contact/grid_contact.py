"""A ball-to-groove contact on a rolling grid, fixed to the ball: the contact data of the stick/slip law
(:mod:`lowmodel.contact.rolling_friction`).

A contact (:class:`GridContact`) is a regular grid in its tangent plane, centred on the contact centre ``c``
(relative to the ball centre) with the outward normal ``n`` (ball into groove), the grid's ``x`` along the groove
``axis`` and ``y`` along ``lateral = axis x n``; the normal pressure on the cells (Hertz's, :func:`hertz_contact`,
or an FE pressure binned onto the grid, :func:`sampled_pressure`, :func:`sampled_contact`); the surface point of
cell ``(X, Y)`` is ``c + X axis + Y lateral - (k Y^2 / 2) n`` (the contact surface curved across the groove with the
curvature ``k`` of the deformed surface, as :func:`lowmodel.contact.rolling.rigid_slip_field`: Heathcote's slip).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from ballbench.lowmodel import checks
from ballbench.lowmodel.contact import rolling
from ballbench.lowmodel.contact.halfspace import SurfaceGrid
from ballbench.lowmodel.contact.traction import TractionPatch

__all__ = ["GridContact", "contact_frame", "grid_contact", "hertz_contact", "sampled_pressure", "sampled_contact"]


def contact_frame(normal, axis) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(n, axis, lateral)``: the unit outward normal, the groove axis made normal to it, ``lateral = axis x n``
    (ValueError if ``axis`` is parallel to ``normal``)."""
    n = np.asarray(checks.finite("normal", normal), dtype=float).reshape(3)
    n = n / np.linalg.norm(n)
    t = np.asarray(checks.finite("axis", axis), dtype=float).reshape(3)
    t = t - (t @ n) * n
    norm = float(np.linalg.norm(t))
    if not norm > 1e-9:
        raise ValueError("axis must not be parallel to the contact normal")
    t = t / norm
    return n, t, np.cross(t, n)


@dataclass(frozen=True)
class GridContact:
    """One ball-to-groove contact on a rolling grid, fixed to the ball (module docstring).

    name : e.g. "BL", "SL";  top : on the driven groove (top rail, nut)
    grid : :class:`~lowmodel.contact.halfspace.SurfaceGrid` centred on (0, 0): ``x`` along ``axis``, ``y`` along
        ``lateral`` [m] (the grid of :func:`lowmodel.contact.rolling.hertz_grid`)
    pressure : (nx, ny) normal pressure [Pa], zero in the outermost cells
    centre : (3,) contact centre relative to the ball centre [m] (the ball's frame)
    normal : (3,) outward unit normal (ball into groove);  axis : (3,) unit tangent along the groove
    lateral_curvature : k [1/m] of the contact surface across the groove (0: planar)
    operator : the rolling operator on ``grid`` (:func:`~lowmodel.contact.rolling.half_space_operator` or an FE
        :class:`~lowmodel.contact.rolling.MatrixOperator`), in Kalker's frame with ``x_K = axis``; it must be
        symmetric under the turn by pi about the normal (half-space; a symmetric FE pair)
    shear_modulus : combined G [Pa] (the spin parameter)
    """

    name: str
    top: bool
    grid: SurfaceGrid
    pressure: np.ndarray
    centre: np.ndarray
    normal: np.ndarray
    axis: np.ndarray
    lateral_curvature: float
    operator: object
    shear_modulus: float

    def __post_init__(self):
        checks.freeze_arrays(self, "pressure", "centre", "normal", "axis")

    @property
    def lateral(self) -> np.ndarray:
        """(3,) ``axis x normal``: the grid's ``y`` (Kalker's ``y_K`` where ``x_K = axis``, ``z_K = -normal``)."""
        return np.cross(self.axis, self.normal)

    @property
    def cells(self) -> np.ndarray:
        """Flat indices of the contact cells (``pressure > 0``)."""
        return np.flatnonzero(self.pressure.reshape(-1) > 0.0)

    def points(self) -> np.ndarray:
        """(nx, ny, 3) the surface points of the cells relative to the ball centre [m] (module docstring)."""
        X, Y = self.grid.coordinates()
        return (self.centre + X[..., None] * self.axis + Y[..., None] * self.lateral
                - (0.5 * self.lateral_curvature * Y * Y)[..., None] * self.normal)

    @property
    def normal_force(self) -> float:
        """``sum p dA`` [N]."""
        return float(self.pressure.sum() * self.grid.cell_area)

    def semi_axes(self) -> tuple[float, float]:
        """Semi-axes ``(a, b)`` [m] along the groove and across it of the ellipse with the pressure's second moments
        (``<x^2> = a^2 / 5`` for Hertz's pressure): the Hertz semi-axes for a Hertz pressure."""
        X, Y = self.grid.coordinates()
        weight = self.pressure / self.pressure.sum()
        mx, my = float((weight * X).sum()), float((weight * Y).sum())
        return (math.sqrt(5.0 * float((weight * (X - mx) ** 2).sum())),
                math.sqrt(5.0 * float((weight * (Y - my) ** 2).sum())))

    def central_pressure(self) -> float:
        """``p0 = 3 F / (2 pi a b)`` of :meth:`semi_axes` [Pa] (Hertz's maximum for a Hertz pressure)."""
        a, b = self.semi_axes()
        return 1.5 * self.normal_force / (math.pi * a * b)

    def patch(self) -> TractionPatch:
        """The contact cells as sampled points with the cell forces ``p dA`` and the contact normal: the same
        contact for the pointwise full-slip law (:class:`~lowmodel.contact.traction.SampledCoulomb`)."""
        cells = self.cells
        points = self.points().reshape(-1, 3)[cells]
        forces = self.pressure.reshape(-1)[cells] * self.grid.cell_area
        return TractionPatch(points, np.repeat(self.normal[None, :], len(cells), axis=0), forces, top=self.top,
                             name=self.name)


def grid_contact(name: str, top: bool, grid: SurfaceGrid, pressure, centre, normal, axis, *,
                 lateral_curvature: float, shear_modulus: float, poisson_ratio: float,
                 operator=None) -> GridContact:
    """A :class:`GridContact` with its inputs checked; ``operator`` default the half-space of the combined
    ``shear_modulus`` [Pa] and ``poisson_ratio`` (:func:`lowmodel.contact.rolling.half_space_operator`)."""
    if abs(grid.x_centre) > 0.0 or abs(grid.y_centre) > 0.0:
        raise ValueError("grid must be centred on (0, 0) (the contact centre): the turn by pi maps it onto itself")
    pressure = np.asarray(checks.non_negative("pressure", pressure, "Pa"), dtype=float)
    if pressure.shape != (grid.nx, grid.ny):
        raise ValueError(f"pressure must have the grid's shape {(grid.nx, grid.ny)}, got {pressure.shape}")
    if not np.any(pressure > 0.0):
        raise ValueError(f"contact {name}: pressure must be > 0 somewhere on the grid")
    ring = np.concatenate([pressure[0], pressure[-1], pressure[:, 0], pressure[:, -1]])
    if np.any(ring > 0.0):
        raise ValueError(f"contact {name}: the grid does not cover the contact (pressure > 0 in the outermost cells)")
    n, t, _ = contact_frame(normal, axis)
    centre = np.asarray(checks.finite("centre", centre, "m"), dtype=float).reshape(3)
    shear = checks.positive("shear_modulus", shear_modulus, "Pa")
    nu = checks.bounded("poisson_ratio", poisson_ratio, -1.0, 0.5, upper_closed=True)
    curvature = checks.finite("lateral_curvature", lateral_curvature, "1/m")
    if operator is None:
        operator = rolling.half_space_operator(grid, shear, nu)
    elif operator.grid != grid:
        raise ValueError(f"contact {name}: the operator's grid differs from the contact's grid")
    return GridContact(str(name), bool(top), grid, pressure, centre, n, t, float(curvature), operator, float(shear))


def hertz_contact(name: str, top: bool, centre, normal, axis, semi_axis_along: float, semi_axis_across: float,
                  normal_force: float, cells, *, lateral_curvature: float, shear_modulus: float, poisson_ratio: float,
                  operator_for=None) -> GridContact:
    """A Hertz contact (semi-axes [m] along and across the groove, force [N]) on the grid of
    :func:`lowmodel.contact.rolling.hertz_grid` with ``cells = (n_along, n_across)``, or on ``cells`` itself if it is
    a :class:`SurfaceGrid` (a fixed grid, e.g. an FE compliance's); ``operator_for(grid)`` gives the operator
    (default the half-space)."""
    grid = cells if isinstance(cells, SurfaceGrid) else rolling.hertz_grid(semi_axis_along, semi_axis_across, cells)
    pressure = rolling.hertz_pressure(grid, semi_axis_along, semi_axis_across, normal_force)
    return grid_contact(name, top, grid, pressure, centre, normal, axis, lateral_curvature=lateral_curvature,
                        shear_modulus=shear_modulus, poisson_ratio=poisson_ratio,
                        operator=None if operator_for is None else operator_for(grid))


def sampled_pressure(grid: SurfaceGrid, x, y, pressure, weights, normal_force: float | None = None, *,
                     order: int = 4, outside: float = 0.0) -> np.ndarray:
    """A sampled pressure (e.g. an FE pressure at its quadrature points) as cell values on ``grid`` [Pa].

    ``x``, ``y`` (q,) [m]: the samples' coordinates in the grid's frame; ``pressure`` (q,) [Pa] >= 0; ``weights``
    (q,) [m^2] their quadrature areas.  At ``order x order`` Gauss-Legendre points of each cell the field takes
    the value of the nearest sample (scipy ``cKDTree``; zero farther than twice the samples' median spacing
    from any sample), and the mean over a cell's points is the cell's value: a cell average of the sampled field
    whatever the samples' distribution (the mean of the samples inside a cell is biased where their areas vary
    across it); then all cells are scaled so that ``sum p dA`` is the samples' force ``sum pressure weights`` (or
    ``normal_force`` [N]).  Samples with ``pressure > 0`` outside the grid's inner cells raise ValueError (the
    grid must cover the contact with one empty cell on each side) unless they carry at most the share
    ``outside`` of the force (a fixed grid, e.g. an FE compliance's, and an FE pressure whose piecewise-linear
    tail reaches one element beyond the contact): those are dropped and their force restored by the scaling.
    """
    x = np.asarray(checks.finite("x", x, "m"), dtype=float).reshape(-1)
    y = np.asarray(checks.finite("y", y, "m"), dtype=float).reshape(-1)
    p = np.asarray(checks.non_negative("pressure", pressure, "Pa"), dtype=float).reshape(-1)
    w = np.asarray(checks.non_negative("weights", weights, "m^2"), dtype=float).reshape(-1)
    if not (x.shape == y.shape == p.shape == w.shape):
        raise ValueError(f"x, y, pressure and weights must have one shape, got {x.shape}, {y.shape}, {p.shape}, "
                         f"{w.shape}")
    order = checks.count("order", order, 1, 16)
    i = np.floor((x - grid.x[0]) / grid.dx + 0.5).astype(int)
    j = np.floor((y - grid.y[0]) / grid.dy + 0.5).astype(int)
    inner = (i >= 1) & (i <= grid.nx - 2) & (j >= 1) & (j <= grid.ny - 2)
    share = float((p * w)[~inner].sum() / max((p * w).sum(), 1e-300))
    if share > checks.non_negative("outside", outside):
        raise ValueError(f"the grid does not cover the sampled contact: pressure > 0 outside its inner cells "
                         f"(a share {share:.3g} of the force, allowed {outside:g})")
    p = np.where(inner, p, 0.0)
    nodes, gauss_weights = np.polynomial.legendre.leggauss(order)
    gx = (grid.x[1:-1, None] + 0.5 * grid.dx * nodes[None, :]).reshape(-1)
    gy = (grid.y[1:-1, None] + 0.5 * grid.dy * nodes[None, :]).reshape(-1)
    GX, GY = np.meshgrid(gx, gy, indexing="ij")
    tree = cKDTree(np.column_stack([x, y]))
    spacing = float(np.median(tree.query(np.column_stack([x, y]), k=2)[0][:, 1])) if x.size > 1 else math.inf
    distance, nearest = tree.query(np.column_stack([GX.reshape(-1), GY.reshape(-1)]))
    field = np.where(distance <= 2.0 * spacing, p[nearest], 0.0).reshape(grid.nx - 2, order, grid.ny - 2, order)
    cells = np.zeros((grid.nx, grid.ny))
    cells[1:-1, 1:-1] = 0.25 * np.einsum("iajb,a,b->ij", field, gauss_weights, gauss_weights)
    target = float((p * w).sum()) if normal_force is None else checks.positive("normal_force", normal_force, "N")
    total = float(cells.sum() * grid.cell_area)
    if not total > 0.0:
        raise ValueError("the samples carry no force on the grid")
    return cells * (target / total)


def sampled_contact(name: str, top: bool, points, pressure, areas, axis, *, cells=None, grid: SurfaceGrid | None = None,
                    lateral_curvature: float, shear_modulus: float, poisson_ratio: float, operator=None,
                    outside: float = 0.0) -> GridContact:
    """A contact from a sampled pressure on the ball's surface (e.g. an FE pressure at its quadrature points).

    ``points`` (q, 3) [m] relative to the ball centre, ``pressure`` (q,) [Pa], ``areas`` (q,) [m^2]; ``axis`` (3,)
    the groove's direction.  The contact centre is the force-weighted centre of the points moved radially onto
    their mean radius (a point of the ball's surface), the normal its radial direction; the samples' coordinates
    in the tangent plane give the cell pressure (:func:`sampled_pressure`).  ``cells = (n_along, n_across)``: a
    grid of that many cells over the pressure's support (one empty cell on each side); or a given ``grid``
    centred on the contact centre (e.g. the grid of an FE compliance, ``operator``; ``outside``: the share of the
    force that may lie beyond its inner cells, :func:`sampled_pressure`).
    """
    points = np.asarray(checks.finite("points", points, "m"), dtype=float).reshape(-1, 3)
    p = np.asarray(checks.non_negative("pressure", pressure, "Pa"), dtype=float).reshape(-1)
    w = np.asarray(checks.non_negative("areas", areas, "m^2"), dtype=float).reshape(-1)
    if not (len(points) == len(p) == len(w)):
        raise ValueError(f"points, pressure and areas must have one length, got {len(points)}, {len(p)}, {len(w)}")
    force = p * w
    if not force.sum() > 0.0:
        raise ValueError(f"contact {name}: the samples carry no force")
    centroid = force @ points / force.sum()
    radius = float(np.average(np.linalg.norm(points, axis=1), weights=force))
    centre = centroid * (radius / float(np.linalg.norm(centroid)))
    n, t, lateral = contact_frame(centre, axis)
    X, Y = (points - centre) @ t, (points - centre) @ lateral
    if grid is None:
        if cells is None:
            raise ValueError("give cells or grid")
        loaded = p > 0.0
        margin = 1.0 + 1e-6
        grid = rolling.hertz_grid(margin * float(np.abs(X[loaded]).max()), margin * float(np.abs(Y[loaded]).max()),
                                  cells)
    cell_pressure = sampled_pressure(grid, X, Y, p, w, outside=outside)
    return grid_contact(name, top, grid, cell_pressure, centre, n, t, lateral_curvature=lateral_curvature,
                        shear_modulus=shear_modulus, poisson_ratio=poisson_ratio, operator=operator)
