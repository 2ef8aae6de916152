"""A ball split into contact caps: the ball of the four-point and ball-screw modules.

The sphere is cut by planes into a core and one spherical cap of half-angle
``cap_angle`` around each contact direction, so every contact has its own
surface group; the sphere's parametrisation poles are turned away from the caps.
All lengths in metres, angles in radians.
"""
from __future__ import annotations

import math

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["cap_limit", "check_cap_angle", "add_split_ball", "DEFAULT_CAP_ANGLE"]

DEFAULT_CAP_ANGLE = math.radians(30.0)  # a ball cap's default half-angle [rad] (check_cap_angle)


def _pole_axis(directions: list[np.ndarray]) -> np.ndarray:
    """Unit axis whose two poles lie farthest (in angle) from every direction (n, 3)."""
    golden = math.pi * (3.0 - math.sqrt(5.0))
    k = np.arange(200)
    z = 1.0 - (k + 0.5) / 200  # a Fibonacci half-sphere of candidates
    r = np.sqrt(1.0 - z * z)
    candidates = np.stack([r * np.cos(golden * k), r * np.sin(golden * k), z], 1)
    worst = np.max(np.abs(candidates @ np.asarray(directions).T), axis=1)  # cos of the nearest cap, both poles
    return candidates[int(np.argmin(worst))]


def cap_limit(directions: list[np.ndarray]) -> float:
    """The largest cap half-angle [rad] of a ball: ``0.45 x`` with ``x`` the smallest angle between two of its
    contact directions (unit, (n, 3)), so the caps do not overlap."""
    unit = np.asarray(directions, dtype=float)
    cosines = np.clip(unit @ unit.T, -1.0, 1.0)
    np.fill_diagonal(cosines, -1.0)
    return 0.45 * math.acos(float(cosines.max()))


def check_cap_angle(cap_angle, directions: list[np.ndarray], min_cap_angle: float | None = None) -> float:
    """Validated cap half-angle [rad]: default ``min(30 deg, 0.45 x)`` with ``x`` the
    smallest angle between two contact directions (unit, (n, 3)) of a ball (caps must not overlap,
    :func:`cap_limit`).  ``min_cap_angle`` [rad] (with the default): at least this, up to the limit (a heavy
    contact's ellipse needs a larger cap than 30 deg; docs/truncation.md)."""
    limit = cap_limit(directions)
    if cap_angle is None:
        default = min(DEFAULT_CAP_ANGLE, limit)
        if min_cap_angle is None:
            return default
        return max(default, min(checks.positive("min_cap_angle", min_cap_angle, "rad"), limit))
    cap_angle = checks.finite("cap_angle", cap_angle, "rad")
    if not 0.0 < cap_angle <= limit:
        raise ValueError(f"cap_angle must lie in (0, {limit!r}] rad (0.45 x the smallest angle between two contacts "
                         f"of a ball, so the caps do not overlap), got {cap_angle!r}")
    return cap_angle


def add_split_ball(gmsh, centre: np.ndarray, radius: float, directions: dict[str, np.ndarray],
                   cap_angle: float) -> tuple[list[int], dict[str, list[int]]]:
    """Add a ball (``centre`` (3,) [m], ``radius`` [m]) cut by planes into a core and one cap
    of half-angle ``cap_angle`` [rad] around each named unit direction; synchronises the model.
    Returns (volume tags, surfaces by name; 'free' is the rest of the sphere)."""
    occ = gmsh.model.occ
    ball = occ.addSphere(*centre, radius)
    # turn the sphere's poles (degenerate points of its parametrisation) away from the caps
    axis = _pole_axis(list(directions.values()))
    turn = np.cross([0.0, 0.0, 1.0], axis)
    if np.linalg.norm(turn) > 1e-12:
        occ.rotate([(3, ball)], *centre, *turn, math.acos(float(np.clip(axis[2], -1.0, 1.0))))
    disks = []
    for direction in directions.values():
        middle = centre + radius * math.cos(cap_angle) * direction
        helper = np.array([0.0, 0.0, 1.0]) if abs(direction[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
        x_axis = np.cross(direction, helper)
        size = 1.5 * radius * math.sin(cap_angle)
        disks.append((2, occ.addDisk(*middle, size, size, zAxis=direction.tolist(), xAxis=x_axis.tolist())))
    pieces, _ = occ.fragment([(3, ball)], disks)
    occ.synchronize()
    volumes = [tag for dim, tag in pieces if dim == 3]
    leftovers = [(dim, tag) for dim, tag in pieces if dim == 2 and len(gmsh.model.getAdjacencies(2, tag)[0]) == 0]
    occ.remove(leftovers, recursive=True)
    occ.synchronize()
    surfaces: dict[str, list[int]] = {name: [] for name in directions}
    surfaces["free"] = []
    cap_area = 2 * math.pi * radius**2 * (1 - math.cos(cap_angle))
    areas = {name: 0.0 for name in directions}
    for _, tag in gmsh.model.getBoundary([(3, v) for v in volumes], combined=True, oriented=False):
        if gmsh.model.getType(2, tag) != "Sphere":
            continue
        offset = np.asarray(occ.getCenterOfMass(2, tag)) - centre
        area = occ.getMass(2, tag)
        name = "free"
        if area < cap_area * (1 + 1e-3) and np.linalg.norm(offset) > 0:
            # a cap, or a piece of one cut by the sphere's seam meridian (its centre of
            # mass lies inside the cap's cone, up to round-off for a sliver at the rim)
            unit = offset / np.linalg.norm(offset)
            best = max(directions, key=lambda key: unit @ directions[key])
            if unit @ directions[best] > math.cos(1.02 * cap_angle):
                name = best
                areas[name] += area
        surfaces[name].append(tag)
    for name, area in areas.items():
        if abs(area - cap_area) > 1e-3 * cap_area:
            raise RuntimeError(f"ball cap {name} not identified (area {area!r} of {cap_area!r} m^2)")
    return volumes, surfaces
