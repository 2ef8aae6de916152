"""The steel body of a linear-guide carriage: a block with the rail's slot, for the FE rung of the whole carriage
(fem.carriage_fe; docs/carriage.md, "Elastic carriage").

Frame of lowmodel.linear_bearing.carriage (``z`` along the rail, ``y`` up from the rail, ``x`` lateral): the box
``|x| <= W``, ``y0 <= y <= y1``, ``|z| <= L / 2`` less the slot ``|x| < s``, ``y < ys`` in which the rail and the
balls run.  The carriage's grooves are not cut: each contact's load enters the slot's wall over a patch around the
contact point (fem.carriage_fe), the groove's own flattening being Hertz's.  The end caps (plastic, the balls'
return) carry no load and are left out.  All lengths in metres.

Physical groups: volume ``carriage``; surfaces ``mount`` (the top face ``y = y1``, bolted to the rigid table),
``slot`` (the slot's side walls ``|x| = s``), ``free`` (the rest).
"""
from __future__ import annotations

from pathlib import Path

from ballbench.lowmodel import checks
from ballbench.meshes.gmsh_tools import cached_msh, face_point, name_solid, session, write_msh
from ballbench.meshes.refinement import refine_at_surfaces

__all__ = ["carriage_body", "MESH_FORMAT_VERSION"]

MESH_FORMAT_VERSION = "1"


def carriage_body(*, half_width: float, slot_half_width: float, bottom: float, slot_top: float, top: float,
                  length: float, h_max: float, h_wall: float | None = None, growth: float = 1.3,
                  cache: bool = True) -> Path:
    """The carriage body (module docstring: ``W = half_width``, ``s = slot_half_width``, ``y0 = bottom``,
    ``ys = slot_top``, ``y1 = top``, ``L = length`` [m]) meshed with linear tetrahedra of size ``h_max`` [m] (the
    solver adds P2's mid-side nodes itself) as a cached gmsh 4.1 ``.msh``; ``h_wall`` [m] on the slot's walls (the
    grooves' patches; default ``h_max``), growing by ``growth`` away from them (meshes.refinement.size_threshold)."""
    for name, value in (("half_width", half_width), ("slot_half_width", slot_half_width), ("length", length),
                        ("h_max", h_max)):
        checks.positive(name, value, "m")
    if not slot_half_width < half_width:
        raise ValueError(f"slot_half_width {slot_half_width!r} m must be below half_width {half_width!r} m")
    if not bottom < slot_top < top:
        raise ValueError(f"need bottom < slot_top < top [m], got {bottom!r}, {slot_top!r}, {top!r}")
    h_wall = h_max if h_wall is None else checks.positive("h_wall", h_wall, "m")
    params = dict(builder="carriage_body", half_width=half_width, slot=slot_half_width, bottom=bottom,
                  slot_top=slot_top, top=top, length=length, h_max=h_max, h_wall=h_wall, growth=growth)
    path, build = cached_msh("carriage", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path
    with session("carriage") as gmsh:
        occ = gmsh.model.occ
        box = occ.addBox(-half_width, bottom, -0.5 * length, 2 * half_width, top - bottom, length)
        slot = occ.addBox(-slot_half_width, bottom - length, -length, 2 * slot_half_width, slot_top - bottom + length,
                          2 * length)
        (volume,), _ = occ.cut([(3, box)], [(3, slot)])
        occ.synchronize()
        roles = {"mount": [], "slot": [], "free": []}
        tolerance = 1e-9 * max(half_width, top - bottom, length)
        for _, face in gmsh.model.getBoundary([volume], oriented=False):
            x, y, _ = face_point(gmsh, face)
            if abs(y - top) < tolerance:
                roles["mount"].append(face)
            elif abs(abs(x) - slot_half_width) < tolerance and y < slot_top - tolerance:
                roles["slot"].append(face)
            else:
                roles["free"].append(face)
        name_solid(gmsh, volume[1], "carriage", roles)
        refine_at_surfaces(gmsh, roles["slot"], h_wall, growth, h_max)
        gmsh.model.mesh.generate(3)
        write_msh(gmsh, path)
    return path
