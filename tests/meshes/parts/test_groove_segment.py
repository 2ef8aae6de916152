"""meshes.parts.groove_segment: the full screw / nut groove segment (lin2019 Table 4; coarse meshes)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.meshes.parts import groove_segment
from tests.meshes.mesh_support import BETA, CONF, LEAD, R_B, R_P, group_cells, group_nodes, radii
from tests.meshes.mesh_support import private_cache  # noqa: F401 - the autouse fixture: a private mesh cache

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


# --------------------------------------------------------------------------
# full screw / nut groove segment
# --------------------------------------------------------------------------
@pytest.mark.parametrize("body, deviations", [("screw", (0.0, 0.0)), ("nut", (0.0, 0.0)),
                                               ("screw", (0.0, math.radians(3.0)))])
def test_groove_segment_flanks_land_and_four_point_contact(body, deviations):
    """Both flanks are the exact helical arcs; the land is the cylinder of its radius; a
    ball centred anywhere on the helix touches both flanks (distance R_B) and nowhere
    lies inside them (lin2019 Fig 13: four-point contact with screw and nut), also with
    a contact angle deviation of 3 deg on one flank (lin2019 Fig 17, case b)."""
    h = 1e-4
    path = groove_segment.screw_groove_segment(R_B, CONF, R_P, LEAD, BETA, body, deviations=deviations, h_contact=h,
                                        growth=1.5)
    mesh = meshio.read(path)
    assert len(group_cells(mesh, body, "tetra")) > 100
    land = R_P - 0.25 * R_B if body == "screw" else R_P + 0.25 * R_B
    back = R_P - 5.25 * R_B if body == "screw" else R_P + 5.25 * R_B  # the deep default bodies (docs/fe_b2b.md)
    np.testing.assert_allclose(radii(mesh, "back"), back, rtol=1e-12)
    nodes = mesh.points[group_nodes(mesh, "land")]
    # (its edges with the flanks carry flank nodes moved onto the exact helical surface:
    # OCC's loft/boolean intersection lies within 1e-7 m of it)
    assert np.abs(np.hypot(nodes[:, 0], nodes[:, 1]) - land).max() < 1e-7
    for flank, deviation in zip(("left", "right"), deviations):
        groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA + deviation, body, flank)
        nodes = mesh.points[group_nodes(mesh, f"flank_{flank}")]
        assert np.abs(groove_core.surface_residual(groove, nodes)).max() < 1e-12 * R_B
        for phi in (-0.1, 0.0, 0.1):
            distance = np.linalg.norm(nodes - groove.helix(phi), axis=1)
            assert distance.min() > R_B * (1 - 1e-12)
            if phi == 0.0:  # refined there: chord sagitta h^2 / (8 R_B) bounds the miss
                assert distance.min() < R_B + h**2 / (8 * R_B)
    # the flanks meet at the groove bottom: a helix, fixed in the profile plane
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, body)
    shared = np.intersect1d(group_nodes(mesh, "flank_left"), group_nodes(mesh, "flank_right"))
    assert len(shared) > 5
    phi, uw = groove_core.profile_coordinates(groove, mesh.points[shared])
    assert np.ptp(uw[:, 1]) < 1e-12 and np.ptp(uw[:, 0]) < 1e-12
    assert (abs(uw[0, 1]) < 1e-12) == (deviations[0] == deviations[1])  # symmetric only without deviation


@pytest.mark.parametrize("kwargs, match", [
    (dict(deviations=(0.0,)), "deviations"),
    (dict(deviations=(0.0, math.radians(20))), "deviations"),
    (dict(deviations=(float("nan"), 0.0)), "deviations"),
    (dict(contact_angle=math.radians(88), deviations=(0.0, math.radians(3))), "contact_angle"),
    (dict(land_radius=R_P - R_B), "land_radius"),
    (dict(back_radius=R_P - 0.5 * R_B), "back_radius"),
    (dict(axial_half_width=15e-3), "axial_half_width"),
    (dict(half_angle=2.0), "half_angle"),
])
def test_groove_segment_bad_input_names_the_parameter(kwargs, match):
    args = dict(ball_radius=R_B, conformity=CONF, pitch_radius=R_P, lead=LEAD, contact_angle=BETA)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        groove_segment.screw_groove_segment(**args, cache=False)
