"""The steel body of a ball-screw nut: a tube, for the FE rung of the whole nut (fem.nut_fe; docs/nut.md, "Elastic
nut").

Frame of lowmodel.screw (``z`` the screw's axis): the tube ``inner_radius <= r <= outer_radius``,
``z0 <= z <= z1``.  As the nut bar of lowmodel.screw.load_distribution its bore is at ``R_P + R_B``; the groove is
not cut: each ball's load enters the bore over a patch around its contact point (fem.nut_fe), the groove's own
flattening being Hertz's.  The end seals and the balls' return carry no load and are left out.  All lengths in
metres.

Physical groups: volume ``nut``; surfaces ``flange`` (the end face held by the table: ``z = z0``, the loaded end, or
``z = z1``), ``bore`` (the tube's inner face), ``free`` (the rest).
"""
from __future__ import annotations

import math
from pathlib import Path

from ballbench.lowmodel import checks
from ballbench.meshes.gmsh_tools import cached_msh, face_point, name_solid, session, write_msh
from ballbench.meshes.refinement import refine_at_surfaces

__all__ = ["nut_body", "MESH_FORMAT_VERSION"]

MESH_FORMAT_VERSION = "1"


def nut_body(*, inner_radius: float, outer_radius: float, start: float, end: float, h_max: float,
             h_bore: float | None = None, growth: float = 1.3, held: str = "start", cache: bool = True) -> Path:
    """The nut body (module docstring: ``z0 = start``, ``z1 = end`` [m]; ``held`` the flange's end, ``"start"`` or
    ``"end"``) meshed with linear tetrahedra of size
    ``h_max`` [m] (the solver adds P2's mid-side nodes) as a cached gmsh 4.1 ``.msh``; ``h_bore`` [m] on the bore
    (the balls' patches; default ``h_max``), growing by ``growth`` away from it (meshes.refinement.size_threshold)."""
    for name, value in (("inner_radius", inner_radius), ("outer_radius", outer_radius), ("h_max", h_max)):
        checks.positive(name, value, "m")
    if not inner_radius < outer_radius:
        raise ValueError(f"outer_radius {outer_radius!r} m must exceed inner_radius {inner_radius!r} m")
    if not start < end:
        raise ValueError(f"need start < end [m], got {start!r}, {end!r}")
    h_bore = h_max if h_bore is None else checks.positive("h_bore", h_bore, "m")
    checks.choice("held", held, ("start", "end"))
    params = dict(builder="nut_body", inner=inner_radius, outer=outer_radius, start=start, end=end, h_max=h_max,
                  h_bore=h_bore, growth=growth)
    if held == "end":
        params["held"] = held   # (the cached meshes held at the start keep their names)
    path, build = cached_msh("nut", params, MESH_FORMAT_VERSION, cache=cache)
    if not build:
        return path
    with session("nut") as gmsh:
        occ = gmsh.model.occ
        outer = occ.addCylinder(0.0, 0.0, start, 0.0, 0.0, end - start, outer_radius)
        bore = occ.addCylinder(0.0, 0.0, start - 1.0, 0.0, 0.0, end - start + 2.0, inner_radius)
        (volume,), _ = occ.cut([(3, outer)], [(3, bore)])
        occ.synchronize()
        roles = {"flange": [], "bore": [], "free": []}
        tolerance = 1e-9 * max(outer_radius, end - start)
        for _, face in gmsh.model.getBoundary([volume], oriented=False):
            x, y, z = face_point(gmsh, face)
            if abs(z - (start if held == "start" else end)) < tolerance:
                roles["flange"].append(face)
            elif abs(math.hypot(x, y) - inner_radius) < 1e-6 * inner_radius:
                roles["bore"].append(face)
            else:
                roles["free"].append(face)
        name_solid(gmsh, volume[1], "nut", roles)
        refine_at_surfaces(gmsh, roles["bore"], h_bore, growth, h_max)
        gmsh.model.mesh.generate(3)
        write_msh(gmsh, path)
    return path
