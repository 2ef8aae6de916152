"""Mesh-size control of every builder in ``meshes/``: one growth law, its fine zones, the
uniform fallback and the checks of their arguments.

Growth law (the only size control when refining; docs/meshes.md):

    h(d) = min(h_max, h_contact + (growth - 1) max(0, d - fine_radius))

with ``d`` the distance [m] from a fine zone: a point (:func:`point_distance`), the
segment ``|x| <= L`` of the x axis (:func:`segment_distance`, an elongated Hertz
ellipse of a contact pair), the box ``|x| <= l_x, |y| <= l_y, |z| <= l_z``
(:func:`box_distance`) or the elliptic slab ``u^2/l_1^2 + v^2/l_2^2 <= 1, |w| <= l_3``
in a contact's own frame (:func:`ellipse_distance`: the fine zone shaped as the contact
ellipse, thin across the contact, so the fine tetrahedra follow the patch instead of
filling a capsule as deep as it is wide).  Along a ray away from the fine zone the sizes of
neighbouring elements differ by about the factor ``growth`` (``h(d + h) = h +
(growth - 1) h``).  gmsh's own size sources (MeshSizeFromPoints,
MeshSizeFromCurvature, MeshSizeExtendFromBoundary) are switched off, otherwise gmsh
ignores the field near small curves.

* :func:`check_refinement` - validated ``(h_contact, growth, h_max, fine_radius)`` of
  a builder (``h_contact <= R_B / 4``, ``growth`` in [1, 3], ``h_max`` default ``R_B / 3``);
  :func:`check_fine_zone` - validated segment half-length or box half-lengths;
  :func:`check_fine_ellipse` - validated elliptic slab ``(l_1, l_2, l_3)``.
* :func:`size_threshold` - the law on any gmsh distance field, set as background mesh.
* :func:`contact_refinement` - the law about one point; :func:`refine_at_points` -
  the smallest of the laws about several points (the contacts of a module), or about
  an elliptic slab at each of them (``ellipses``);
  :func:`refine_contact` - the law about the fine zone of a contact pair.
* :func:`refine_at_surfaces` - the law about surfaces (a body's loaded faces: the FE rungs' carriage and nut);
* :func:`uniform_size` - the fallback without refinement: sizes in ``[h_max / 2, h_max]``;
  :func:`size_at_points` - the contacts' refinement or that fallback.

gmsh is passed in (the module of an open :func:`meshes.gmsh_tools.session`); all
lengths in metres.
"""
from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from ballbench.lowmodel import checks

__all__ = ["check_refinement", "check_fine_zone", "check_fine_ellipse", "four_slabs", "four_factors", "size_threshold",
           "point_distance",
           "segment_distance", "box_distance", "ellipse_distance", "contact_refinement", "refine_at_points",
           "refine_contact", "uniform_size", "size_at_points", "refine_at_surfaces"]

GROWTH_RANGE = (1.0, 3.0)  # size ratio of neighbouring elements away from the fine zone


# --------------------------------------------------------------------------
# argument checks
# --------------------------------------------------------------------------
def _check_law(h_contact, growth, h_max, fine_radius) -> tuple[float, float, float, float]:
    """The growth law's own conditions: lengths finite and positive, growth in [1, 3],
    ``h_max >= h_contact``, ``fine_radius >= 0``."""
    h_contact = checks.positive("h_contact", h_contact, "m")
    growth = checks.finite("growth", growth)
    if not GROWTH_RANGE[0] <= growth <= GROWTH_RANGE[1]:
        raise ValueError(f"growth (size ratio of neighbouring elements) must lie in [1, 3], got {growth!r}")
    h_max = checks.positive("h_max", h_max, "m")
    if h_max < h_contact:
        raise ValueError(f"h_max must be >= h_contact = {h_contact!r} m, got {h_max!r}")
    fine_radius = checks.non_negative("fine_radius", fine_radius, "m")
    return h_contact, growth, h_max, fine_radius


def check_refinement(ball_radius: float, h_contact, growth, h_max=None, fine_radius=None, *,
                     fine_radius_max: float = math.inf) -> tuple[float, float, float, float]:
    """Validated ``(h_contact, growth, h_max, fine_radius)`` [m, -, m, m] of a builder
    meshing a ball of radius ``ball_radius`` [m] (already validated).

    ``h_contact`` in (0, R_B/4]; ``growth`` in [1, 3]; ``h_max`` (default ``R_B / 3``)
    ``>= h_contact``; ``fine_radius`` (default 0) in ``[0, fine_radius_max]``.
    ValueError names the parameter and its range.
    """
    h_contact = checks.positive("h_contact", h_contact, "m")
    if h_contact > ball_radius / 4.0:
        raise ValueError(f"h_contact must lie in (0, ball_radius/4] = (0, {ball_radius / 4!r}] m, got {h_contact!r}")
    h_max = ball_radius / 3.0 if h_max is None else h_max
    h_contact, growth, h_max, fine_radius = _check_law(h_contact, growth, h_max,
                                                       0.0 if fine_radius is None else fine_radius)
    if fine_radius > fine_radius_max:
        raise ValueError(f"fine_radius must lie in [0, {fine_radius_max!r}] m, got {fine_radius!r}")
    return h_contact, growth, h_max, fine_radius


def four_slabs(value, labels: str) -> list[tuple[float, float, float]]:
    """Validated fine slabs of a module's four contacts (``labels``, e.g. "(BL, BR, TR, TL)"): one ``(l_1, l_2,
    l_3)`` [m] for all four or four of them, each by :func:`check_fine_ellipse`."""
    try:
        items = list(value)
        nested = len(items) == 4 and all(hasattr(item, "__len__") for item in items)
    except TypeError:
        raise ValueError(f"fine_ellipses must be (l_1, l_2, l_3) or four of them {labels} [m], got "
                         f"{value!r}") from None
    return [check_fine_ellipse(item) for item in (items if nested else [items] * 4)]


def four_factors(value, labels: str) -> list[float]:
    """Validated size factors of a module's four contacts (``labels``): four numbers in (0, 1]."""
    try:
        factors = [float(v) for v in value]
    except (TypeError, ValueError, OverflowError):
        raise ValueError(f"size_factors must be four factors {labels} in (0, 1], got {value!r}") from None
    if len(factors) != 4 or not all(0.0 < f <= 1.0 for f in factors):
        raise ValueError(f"size_factors must be four factors {labels} in (0, 1], got {value!r}")
    return factors


def check_fine_zone(fine_half_length=0.0, fine_patch=None, *,
                    upper: float = math.inf) -> tuple[float, tuple[float, ...] | None]:
    """Validated fine zone of a contact pair: ``fine_half_length`` [m] in ``[0, upper]``
    (the segment ``|x| <= fine_half_length``; 0: the point) or ``fine_patch``, the box
    half-lengths ``(l_x, l_y[, l_z])`` [m], each > 0; not both."""
    fine_half_length = checks.non_negative("fine_half_length", fine_half_length, "m")
    if fine_half_length > upper:
        raise ValueError(f"fine_half_length must lie in [0, {upper!r}] m, got {fine_half_length!r}")
    if fine_patch is None:
        return fine_half_length, None
    if fine_half_length > 0.0:
        raise ValueError("fine_patch and fine_half_length exclude each other: give one fine zone")
    try:
        fine_patch = tuple(checks.positive("fine_patch", v, "m") for v in fine_patch)
    except TypeError:
        raise ValueError(f"fine_patch must be half-lengths (l_x, l_y[, l_z]) [m], got {fine_patch!r}") from None
    if len(fine_patch) not in (2, 3):
        raise ValueError(f"fine_patch must be half-lengths (l_x, l_y[, l_z]) [m], got {fine_patch!r}")
    return fine_half_length, fine_patch


def check_fine_ellipse(fine_ellipse) -> tuple[float, float, float] | None:
    """Validated elliptic slab ``(l_1, l_2[, l_3])`` [m] (semi-axes along e1, e2 and the half-thickness
    along the contact normal; ``l_3`` default 0), each finite and > 0 (``l_3 >= 0``), or None."""
    if fine_ellipse is None:
        return None
    try:
        values = [float(v) for v in fine_ellipse]
    except (TypeError, ValueError):
        raise ValueError(f"fine_ellipse must be (l_1, l_2[, l_3]) [m], got {fine_ellipse!r}") from None
    if len(values) not in (2, 3):
        raise ValueError(f"fine_ellipse must be (l_1, l_2[, l_3]) [m], got {fine_ellipse!r}")
    semi = tuple(checks.positive("fine_ellipse", v, "m") for v in values[:2])
    depth = checks.non_negative("fine_ellipse", values[2], "m") if len(values) == 3 else 0.0
    return semi + (depth,)


# --------------------------------------------------------------------------
# distance fields (gmsh MathEval) and the growth law
# --------------------------------------------------------------------------
def _num(value: float) -> str:
    """``value`` in plain decimal notation (gmsh's MathEval parser reads no exponent)."""
    return np.format_float_positional(float(value), trim="-")


def _beyond(axis: str, half_length: float) -> str:
    """``max(0, |axis| - half_length)`` as a MathEval expression (exact: (a + |a|) / 2)."""
    return f"((Abs({axis}) - ({half_length!r}) + Abs(Abs({axis}) - ({half_length!r}))) / 2)"


def point_distance(gmsh, point: Sequence[float] = (0.0, 0.0, 0.0)) -> int:
    """Field tag of the distance [m] from ``point`` [m]."""
    x0, y0, z0 = (float(c) for c in point)
    field = gmsh.model.mesh.field
    distance = field.add("MathEval")
    field.setString(distance, "F", f"Sqrt((x-({x0!r}))^2 + (y-({y0!r}))^2 + (z-({z0!r}))^2)")
    return distance


def box_distance(gmsh, half_lengths: Sequence[float]) -> int:
    """Field tag of the distance [m] from the box ``|x| <= l_x, |y| <= l_y, |z| <= l_z``
    about the origin (``half_lengths = (l_x, l_y[, l_z])`` [m], missing ones 0)."""
    lengths = [float(v) for v in half_lengths] + [0.0] * (3 - len(half_lengths))
    beyond = [_beyond(axis, length) for axis, length in zip("xyz", lengths)]
    field = gmsh.model.mesh.field
    distance = field.add("MathEval")
    field.setString(distance, "F", f"Sqrt({beyond[0]}^2 + {beyond[1]}^2 + {beyond[2]}^2)")
    return distance


def segment_distance(gmsh, half_length: float) -> int:
    """Field tag of the distance [m] from the segment ``|x| <= half_length`` [m] of the x axis."""
    field = gmsh.model.mesh.field
    distance = field.add("MathEval")
    field.setString(distance, "F", f"Sqrt({_beyond('x', float(half_length))}^2 + y^2 + z^2)")
    return distance


def ellipse_distance(gmsh, fine_ellipse: Sequence[float], *, centre: Sequence[float] = (0.0, 0.0, 0.0),
                     frame=None) -> int:
    """Field tag of an approximate distance [m] from the elliptic slab ``u^2/l_1^2 + v^2/l_2^2 <= 1,
    |w| <= l_3`` (``fine_ellipse = (l_1, l_2[, l_3])`` [m]) with ``(u, v, w) = frame (p - centre)``
    (``frame`` rows ``e1, e2, e3``; default the identity: ``e3 = z`` the contact normal).

    ``d = sqrt(d_e^2 + max(0, |w| - l_3)^2)`` with ``d_e`` the in-plane distance from the ellipse,
    taken as the larger of two estimates that are both exact on the ellipse and both grow
    from it: Sampson's first-order distance ``(r^2 - 1) / |grad r^2|``, ``r^2 = u^2/l_1^2 + v^2/l_2^2``
    (exact to first order next to the ellipse; half the true distance far away), and
    ``(r - 1) l_min`` (a lower bound, exact along the minor axis).  Inside, ``d_e = 0``.
    """
    l1, l2, l3 = check_fine_ellipse(fine_ellipse)
    c = [float(v) for v in centre]
    e = np.eye(3) if frame is None else np.asarray(frame, dtype=float)
    if e.shape != (3, 3):
        raise ValueError(f"frame must be three rows e1, e2, e3, got shape {e.shape}")
    # scaled coordinates U = u / l_1, V = v / l_2 (all constants in plain decimal notation for MathEval)
    scaled = e / np.array([l1, l2, 1.0])[:, None]
    shift = scaled @ np.array(c)
    U, V, w = (f"(({_num(scaled[k, 0])})*x + ({_num(scaled[k, 1])})*y + ({_num(scaled[k, 2])})*z - ({_num(shift[k])}))"
               for k in range(3))  # every constant in brackets: MathEval refuses "+ -1"
    r2 = f"({U}^2 + {V}^2)"
    # Sampson: (r^2 - 1) / |grad r^2| = (r^2 - 1) / (2 sqrt(U^2/l1^2 + V^2/l2^2)); the small constant
    # keeps the centre finite
    sampson = (f"(({r2} - 1) / (2*Sqrt({U}^2*{_num(1 / l1**2)} + {V}^2*{_num(1 / l2**2)}) + "
               f"{_num(1e-6 / max(l1, l2))}))")
    radial = f"((Sqrt({r2}) - 1)*{_num(min(l1, l2))})"
    larger = f"(({sampson} + {radial} + Abs({sampson} - {radial}))/2)"
    in_plane = f"(({larger} + Abs({larger}))/2)"
    field = gmsh.model.mesh.field
    distance = field.add("MathEval")
    field.setString(distance, "F", f"Sqrt({in_plane}^2 + {_beyond(w, l3).replace(repr(l3), _num(l3))}^2)")
    return distance


def size_threshold(gmsh, distance_field: int, h_contact: float, growth: float, h_max: float, *,
                   fine_radius: float = 0.0) -> int:
    """Background size ``h = min(h_max, h_contact + (growth - 1) max(0, d - fine_radius))``
    with ``d`` the value [m] of the gmsh field ``distance_field``; returns the field tag.

    Turns off MeshSizeFromPoints/FromCurvature/ExtendFromBoundary so that the
    field alone governs the size (docs/meshes.md).
    """
    h_contact, growth, h_max, fine_radius = _check_law(h_contact, growth, h_max, fine_radius)
    field = gmsh.model.mesh.field
    threshold = field.add("Threshold")
    field.setNumber(threshold, "InField", distance_field)
    field.setNumber(threshold, "SizeMin", h_contact)
    field.setNumber(threshold, "SizeMax", h_max)
    field.setNumber(threshold, "DistMin", fine_radius)
    slope = max(growth - 1.0, 1e-9)
    field.setNumber(threshold, "DistMax", fine_radius + (h_max - h_contact) / slope)
    field.setAsBackgroundMesh(threshold)
    for option in ("Mesh.MeshSizeFromPoints", "Mesh.MeshSizeFromCurvature", "Mesh.MeshSizeExtendFromBoundary"):
        gmsh.option.setNumber(option, 0)
    gmsh.option.setNumber("Mesh.MeshSizeMax", h_max)
    gmsh.option.setNumber("Mesh.MeshSizeMin", 0.0)
    return threshold


# --------------------------------------------------------------------------
# fine zones of the builders
# --------------------------------------------------------------------------
def contact_refinement(gmsh, h_contact: float, growth: float, h_max: float, *,
                       point: Sequence[float] = (0.0, 0.0, 0.0), fine_radius: float = 0.0) -> int:
    """The growth law about ``point`` [m] (a contact point) as background mesh; returns the field tag."""
    _check_law(h_contact, growth, h_max, fine_radius)
    return size_threshold(gmsh, point_distance(gmsh, point), h_contact, growth, h_max, fine_radius=fine_radius)


def refine_at_points(gmsh, points, h_contact, growth: float, h_max: float, fine_radius: float, *,
                     ellipses=None) -> int:
    """Background size ``min_k h_k`` with ``h_k`` the growth law about the point ``X_k``
    (``points`` shape (n, 3) [m]: the contacts of a module); returns the field tag.

    ``h_contact`` [m]: one size for every point, or one per point (each contact's fine zone at its own size).
    ``ellipses``: per point ``None`` or ``(fine_ellipse, frame)``: the law about the elliptic slab
    ``fine_ellipse = (l_1, l_2, l_3)`` [m] in the contact frame ``frame`` (rows e1, e2, e3; e3 the
    normal) centred on ``X_k`` (:func:`ellipse_distance`; ``fine_radius`` unused there)."""
    points = np.atleast_2d(np.asarray(points, dtype=float)).tolist()
    ellipses = [None] * len(points) if ellipses is None else list(ellipses)
    if len(ellipses) != len(points):
        raise ValueError(f"ellipses must give one entry per point ({len(points)}), got {len(ellipses)}")
    sizes = np.atleast_1d(np.asarray(h_contact, dtype=float))
    if sizes.shape not in ((1,), (len(points),)):
        raise ValueError(f"h_contact must be one size or one per point ({len(points)}), got {len(sizes)}")
    sizes = np.broadcast_to(sizes, (len(points),))
    fields = []
    for point, ellipse, size in zip(points, ellipses, sizes):
        if ellipse is None:
            fields.append(contact_refinement(gmsh, float(size), growth, h_max, point=point, fine_radius=fine_radius))
        else:
            semi, frame = ellipse
            fields.append(size_threshold(gmsh, ellipse_distance(gmsh, semi, centre=point, frame=frame), float(size),
                                         growth, h_max))
    minimum = gmsh.model.mesh.field.add("Min")
    gmsh.model.mesh.field.setNumbers(minimum, "FieldsList", fields)
    gmsh.model.mesh.field.setAsBackgroundMesh(minimum)
    return minimum


def refine_contact(gmsh, h_contact: float, growth: float, h_max: float, *, fine_radius: float = 0.0,
                   fine_half_length: float = 0.0, fine_patch: Sequence[float] | None = None,
                   fine_ellipse: Sequence[float] | None = None) -> int:
    """The growth law about the fine zone of a contact pair at the origin (checked by
    :func:`check_fine_zone`, :func:`check_fine_ellipse`): the elliptic slab ``fine_ellipse``
    (``|z| <= l_3`` about the ellipse ``x^2/l_1^2 + y^2/l_2^2 <= 1``) or the box ``fine_patch`` if
    given (``fine_radius`` unused), else the segment ``|x| <= fine_half_length`` of the x axis, else
    the origin."""
    if fine_ellipse is not None:
        return size_threshold(gmsh, ellipse_distance(gmsh, fine_ellipse), h_contact, growth, h_max)
    if fine_patch is not None:
        return size_threshold(gmsh, box_distance(gmsh, fine_patch), h_contact, growth, h_max)
    if fine_half_length > 0.0:
        distance = segment_distance(gmsh, fine_half_length)
    else:
        distance = point_distance(gmsh)
    return size_threshold(gmsh, distance, h_contact, growth, h_max, fine_radius=fine_radius)


def uniform_size(gmsh, h_max: float) -> None:
    """No refinement: element sizes between ``h_max / 2`` and ``h_max`` [m]."""
    gmsh.option.setNumber("Mesh.MeshSizeMax", h_max)
    gmsh.option.setNumber("Mesh.MeshSizeMin", h_max / 2)


def size_at_points(gmsh, points, h_contact: float, growth: float, h_max: float, fine_radius: float, *,
                   ellipses=None) -> None:
    """The size of a module or part: :func:`refine_at_points` about ``points`` (n, 3) [m] (and their
    ``ellipses``), or :func:`uniform_size` ``h_max`` where ``points`` is None (the builder was given no
    ``h_contact``)."""
    if points is None:
        uniform_size(gmsh, h_max)
    else:
        refine_at_points(gmsh, points, h_contact, growth, h_max, fine_radius, ellipses=ellipses)


def refine_at_surfaces(gmsh, surfaces, h_fine: float, growth: float, h_max: float) -> int:
    """The growth law about the ``surfaces`` (gmsh tags): ``min(h_fine, h_max)`` on them (a Distance field,
    :func:`size_threshold`); returns the field's tag."""
    distance = gmsh.model.mesh.field.add("Distance")
    gmsh.model.mesh.field.setNumbers(distance, "SurfacesList", [int(t) for t in surfaces])
    return size_threshold(gmsh, distance, min(h_fine, h_max), growth, h_max)
