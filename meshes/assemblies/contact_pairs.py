"""Hertz contact pairs for the FE benchmark: ball on flat, ball on ball, ball in a
straight gothic-arch groove (one flank: a circular groove of radius ``r_g``).

Frame (docs/developing.md, contact-pair meshes): the undeformed contact point at
the origin, ``+z`` the contact normal from the counter body into the ball (ball
centre at ``(0, 0, R_B)``), the major semi-axis ``a`` of the Hertz ellipse along
``x`` (across the groove), the minor ``b`` along ``y`` (along the groove axis).

Bodies (only what a Hertz check needs):

* ball: the cap ``0 <= z <= R_B`` of the sphere (a hemisphere), loaded on its
  flat face ``z = R_B`` (``ball_load``);
* flat: the block ``|x|, |y| <= block_half_width``, ``-block_depth <= z <= 0``;
* second ball (radius ``R_2``): the hemisphere ``-R_2 <= z <= 0`` of the sphere
  centred at ``(0, 0, -R_2)``, held on its flat face;
* groove: the block ``|x| <= block_half_width``, ``|y| <= block_half_length``,
  ``z >= -block_depth``, below the circular cylinder of radius
  ``r_g = conformity * 2 R_B`` with axis ``(0, y, r_g)`` (the groove cross-section
  is the arc through the contact point; lin2019 eq 37 with a straight axis).

Symmetry cuts (``symmetry``): ``"quarter"`` keeps ``x >= 0, y >= 0`` (groups
``symmetry_x`` on x = 0 and ``symmetry_y`` on y = 0), ``"half"`` keeps ``y >= 0``,
``"full"`` keeps everything.  Counter supports (``counter_support``): the face
opposite the contact.

Mesh size (:func:`meshes.refinement.refine_contact`): ``h_contact`` within
``fine_radius`` of the segment ``|x| <= fine_half_length`` on the x axis (cover the
contact ellipse: ``fine_half_length ~ a``, ``fine_radius ~ 1.3 b``), growing by
the factor ``growth`` per element up to ``h_max``.  Or, with ``fine_ellipse = (l_1, l_2, l_3)``,
``h_contact`` within the elliptic slab ``x^2/l_1^2 + y^2/l_2^2 <= 1, |z| <= l_3`` (the contact
ellipse, thin across the contact: :func:`meshes.refinement.ellipse_distance`), growing from it.

All lengths in metres.  Builders return the path of a cached gmsh 4.1 ``.msh``.
"""
from __future__ import annotations

import math
from pathlib import Path

from ballbench.lowmodel import checks
from ballbench.lowmodel.geometry.groove import groove_radius
from ballbench.meshes import gmsh_tools
from ballbench.meshes.refinement import check_fine_ellipse, check_fine_zone, check_refinement, refine_contact

__all__ = ["ball_on_flat_pair", "ball_on_ball_pair", "ball_in_groove_pair", "groove_block_limit", "SYMMETRIES"]

MESH_FORMAT_VERSION = "contact-pairs-1"
SYMMETRIES = ("quarter", "half", "full")


def _check_common(ball_radius, h_contact, growth, h_max, fine_radius, fine_half_length, symmetry, element_order):
    radius = checks.positive("ball_radius", ball_radius, "m")
    h_contact, growth, h_max, fine_radius = check_refinement(radius, h_contact, growth, h_max, fine_radius,
                                                             fine_radius_max=radius)
    fine_half_length, _ = check_fine_zone(fine_half_length, upper=radius)
    checks.choice("symmetry", symmetry, SYMMETRIES)
    element_order = checks.count("element_order", element_order, 1, 2)
    return radius, h_contact, growth, h_max, fine_radius, fine_half_length, element_order


def _bounds(symmetry: str, half_x: float, half_y: float) -> tuple[float, float, float, float]:
    """(x0, x1, y0, y1) of the kept region."""
    x0 = 0.0 if symmetry == "quarter" else -half_x
    y0 = 0.0 if symmetry in ("quarter", "half") else -half_y
    return x0, half_x, y0, half_y


def _classify_faces(gmsh, volume: tuple[int, int], tol: float) -> dict[str, list[int]]:
    """Boundary faces of ``volume`` by kind: 'x0', 'y0' (planes x = 0, y = 0), 'other_plane', 'curved'."""
    faces: dict[str, list[int]] = {"x0": [], "y0": [], "other_plane": [], "curved": []}
    for _, tag in gmsh.model.getBoundary([volume], oriented=False):
        kind = gmsh.model.getType(2, tag)
        if kind == "Plane":
            lo = gmsh.model.getBoundingBox(2, tag)
            if abs(lo[0]) < tol and abs(lo[3]) < tol:
                faces["x0"].append(tag)
            elif abs(lo[1]) < tol and abs(lo[4]) < tol:
                faces["y0"].append(tag)
            else:
                faces["other_plane"].append(tag)
        else:
            faces["curved"].append(tag)
    return faces


def _plane_at_z(gmsh, tags: list[int], z: float, tol: float) -> list[int]:
    out = []
    for tag in tags:
        box = gmsh.model.getBoundingBox(2, tag)
        if abs(box[2] - z) < tol and abs(box[5] - z) < tol:
            out.append(tag)
    return out


def _build_pair(kind: str, params: dict, counter_factory, *, radius: float, symmetry: str,
                h_contact: float, growth: float, h_max: float, fine_radius: float, fine_half_length: float,
                element_order: int, cache: bool, fine_ellipse=None) -> Path:
    fine_ellipse = check_fine_ellipse(fine_ellipse)
    if fine_ellipse is not None:  # only then: the cache names of the other zones stay as they were
        params = dict(params, fine_ellipse=list(fine_ellipse))
    path, build = gmsh_tools.cached_msh(kind, params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path
    tol = 1e-4 * radius  # OCC bounding boxes are padded by ~1e-7 m
    with gmsh_tools.session(kind) as gmsh:
        occ = gmsh.model.occ
        x0, x1, y0, y1 = _bounds(symmetry, 2 * radius, 2 * radius)
        sphere = occ.addSphere(0.0, 0.0, radius, radius)
        box = occ.addBox(x0, y0, 0.0, x1 - x0, y1 - y0, radius)
        ball, _ = occ.intersect([(3, sphere)], [(3, box)])
        counter, contact_kind, support_z = counter_factory(occ)
        occ.synchronize()
        (ball_vol,) = ball
        (counter_vol,) = counter
        bf = _classify_faces(gmsh, ball_vol, tol)
        cf = _classify_faces(gmsh, counter_vol, tol)
        gmsh_tools.physical(gmsh, 3, [ball_vol[1]], "ball")
        gmsh_tools.physical(gmsh, 3, [counter_vol[1]], "counter")
        gmsh_tools.physical(gmsh, 2, bf["curved"], "ball_contact")
        gmsh_tools.physical(gmsh, 2, _plane_at_z(gmsh, bf["other_plane"], radius, tol), "ball_load")
        if contact_kind == "plane":
            contact = _plane_at_z(gmsh, cf["other_plane"], 0.0, tol)
        else:
            contact = cf["curved"]
        gmsh_tools.physical(gmsh, 2, contact, "counter_contact")
        gmsh_tools.physical(gmsh, 2, _plane_at_z(gmsh, cf["other_plane"], support_z, tol), "counter_support")
        if symmetry == "quarter":
            gmsh_tools.physical(gmsh, 2, bf["x0"] + cf["x0"], "symmetry_x")
        if symmetry in ("quarter", "half"):
            gmsh_tools.physical(gmsh, 2, bf["y0"] + cf["y0"], "symmetry_y")
        refine_contact(gmsh, h_contact, growth, h_max, fine_radius=fine_radius, fine_half_length=fine_half_length,
                       fine_ellipse=fine_ellipse)
        gmsh.model.mesh.generate(3)
        if element_order == 2:
            gmsh.model.mesh.setOrder(2)
        gmsh_tools.write_msh(gmsh, path)
    return path


def _common_params(**kwargs) -> dict:
    return {k: (float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else v) for k, v in kwargs.items()}


def ball_on_flat_pair(ball_radius: float, h_contact: float, growth: float = 1.3, *, h_max: float | None = None,
                      fine_radius: float = 0.0, fine_half_length: float = 0.0, symmetry: str = "quarter",
                      block_half_width: float | None = None, block_depth: float | None = None,
                      element_order: int = 1, cache: bool = True, fine_ellipse=None) -> Path:
    """Ball (hemisphere, radius ``ball_radius`` [m]) on a flat block; cached ``.msh`` path.

    Block defaults: half-width and depth ``R_B``.  Mesh size: module docstring.
    """
    radius, h_contact, growth, h_max, fine_radius, fine_half_length, element_order = _check_common(
        ball_radius, h_contact, growth, h_max, fine_radius, fine_half_length, symmetry, element_order)
    half = radius if block_half_width is None else checks.positive("block_half_width", block_half_width, "m")
    depth = radius if block_depth is None else checks.positive("block_depth", block_depth, "m")

    def counter(occ):
        x0, x1, y0, y1 = _bounds(symmetry, half, half)
        return [(3, occ.addBox(x0, y0, -depth, x1 - x0, y1 - y0, depth))], "plane", -depth

    params = _common_params(radius=radius, h=h_contact, g=growth, hmax=h_max, fr=fine_radius, fl=fine_half_length,
                            sym=symmetry, half=half, depth=depth, order=element_order)
    return _build_pair("ball-flat", params, counter, radius=radius, symmetry=symmetry, h_contact=h_contact,
                       growth=growth, h_max=h_max, fine_radius=fine_radius, fine_half_length=fine_half_length,
                       element_order=element_order, cache=cache, fine_ellipse=fine_ellipse)


def ball_on_ball_pair(ball_radius: float, h_contact: float, growth: float = 1.3, *, other_radius: float | None = None,
                      h_max: float | None = None, fine_radius: float = 0.0, fine_half_length: float = 0.0,
                      symmetry: str = "quarter", element_order: int = 1, cache: bool = True,
                      fine_ellipse=None) -> Path:
    """Ball on ball (the B2B pair): the counter is the hemisphere ``-R_2 <= z <= 0`` of a
    second ball of radius ``other_radius`` (default ``ball_radius``) [m], held on its flat face."""
    radius, h_contact, growth, h_max, fine_radius, fine_half_length, element_order = _check_common(
        ball_radius, h_contact, growth, h_max, fine_radius, fine_half_length, symmetry, element_order)
    other = radius if other_radius is None else checks.positive("other_radius", other_radius, "m")

    def counter(occ):
        x0, x1, y0, y1 = _bounds(symmetry, 2 * other, 2 * other)
        sphere = occ.addSphere(0.0, 0.0, -other, other)
        box = occ.addBox(x0, y0, -other, x1 - x0, y1 - y0, other)
        vol, _ = occ.intersect([(3, sphere)], [(3, box)])
        return vol, "curved", -other

    params = _common_params(radius=radius, other=other, h=h_contact, g=growth, hmax=h_max, fr=fine_radius,
                            fl=fine_half_length, sym=symmetry, order=element_order)
    return _build_pair("ball-ball", params, counter, radius=radius, symmetry=symmetry, h_contact=h_contact,
                       growth=growth, h_max=h_max, fine_radius=fine_radius, fine_half_length=fine_half_length,
                       element_order=element_order, cache=cache, fine_ellipse=fine_ellipse)


def groove_block_limit(ball_radius: float, conformity: float) -> float:
    """The largest half-width [m] across a straight groove of a counter block of :func:`ball_in_groove_pair`: 90 % of
    the groove radius ``r_g = 2 f R_B``, so the block stays on the groove's face."""
    return 0.9 * groove_radius(ball_radius, conformity)


def ball_in_groove_pair(ball_radius: float, conformity: float, h_contact: float, growth: float = 1.3, *,
                        h_max: float | None = None, fine_radius: float = 0.0, fine_half_length: float = 0.0,
                        symmetry: str = "quarter", block_half_width: float | None = None,
                        block_half_length: float | None = None, block_depth: float | None = None,
                        element_order: int = 1, cache: bool = True, fine_ellipse=None) -> Path:
    """Ball in a straight circular groove of radius ``r_g = conformity * 2 R_B`` [m].

    ``conformity`` in (0.5, 1).  Block defaults: half-width (across the groove)
    ``0.6 R_B`` (at most ``0.9 r_g``), half-length (along it) ``0.6 R_B``, depth
    below the contact ``0.6 R_B``.
    """
    radius, h_contact, growth, h_max, fine_radius, fine_half_length, element_order = _check_common(
        ball_radius, h_contact, growth, h_max, fine_radius, fine_half_length, symmetry, element_order)
    conformity = checks.conformity("conformity", conformity)
    r_g = groove_radius(radius, conformity)
    half_w = 0.6 * radius if block_half_width is None else checks.positive("block_half_width", block_half_width, "m")
    if half_w > groove_block_limit(radius, conformity):
        raise ValueError(f"block_half_width must lie in (0, 0.9 r_g] = (0, {groove_block_limit(radius, conformity)!r}] "
                         f"m, got {half_w!r}")
    half_l = 0.6 * radius if block_half_length is None else checks.positive("block_half_length", block_half_length, "m")
    depth = 0.6 * radius if block_depth is None else checks.positive("block_depth", block_depth, "m")

    def counter(occ):
        x0, x1, y0, y1 = _bounds(symmetry, half_w, half_l)
        z_edge = r_g - math.sqrt(r_g * r_g - half_w * half_w)  # groove height at |x| = half_w
        top = z_edge + 0.2 * depth
        block = occ.addBox(x0, y0, -depth, x1 - x0, y1 - y0, top + depth)
        cylinder = occ.addCylinder(0.0, y0 - radius, r_g, 0.0, (y1 - y0) + 2 * radius, 0.0, r_g)
        vol, _ = occ.cut([(3, block)], [(3, cylinder)])
        return vol, "curved", -depth

    params = _common_params(radius=radius, conformity=conformity, h=h_contact, g=growth, hmax=h_max, fr=fine_radius,
                            fl=fine_half_length, sym=symmetry, half_w=half_w, half_l=half_l, depth=depth,
                            order=element_order)
    return _build_pair("ball-groove", params, counter, radius=radius, symmetry=symmetry, h_contact=h_contact,
                       growth=growth, h_max=h_max, fine_radius=fine_radius, fine_half_length=fine_half_length,
                       element_order=element_order, cache=cache, fine_ellipse=fine_ellipse)
