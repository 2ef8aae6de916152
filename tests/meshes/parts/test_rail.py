"""meshes.parts.rail: the straight gothic-arch rail (lin2019 Table 1; coarse meshes)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.meshes.parts import rail
from tests.meshes.mesh_support import (BETA, CONF, DEV, R_RAIL, circle_fit, group_cells, group_nodes,
                                       surface_area_and_longest_edge, tet_volume)
from tests.meshes.mesh_support import private_cache  # noqa: F401 - the autouse fixture: a private mesh cache

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


# --------------------------------------------------------------------------
# straight gothic-arch rail
# --------------------------------------------------------------------------


@pytest.fixture(scope="module")
def rail_mesh(tmp_path_factory):
    path = rail.rail_segment(R_RAIL, CONF, BETA, -DEV, DEV, h_contact=2e-4, growth=1.5, cache=False)
    return meshio.read(path)


def test_rail_groups_exist_and_flanks_are_the_stated_arcs(rail_mesh):
    """Circle fits of the meshed flanks: radius 2 conf R_B, centre on the line through the
    ball centre at the contact angle b_0 + db (lin2017 eq 1), r_g - R_B from it."""
    for name in ("groove_left", "groove_right", "land", "support", "rail_free"):
        assert len(group_cells(rail_mesh, name, "triangle")) > 0
    assert len(group_cells(rail_mesh, "rail", "tetra")) > 100
    for name, sign, beta in (("groove_left", -1.0, BETA - DEV), ("groove_right", 1.0, BETA + DEV)):
        xy = rail_mesh.points[group_nodes(rail_mesh, name), :2]
        centre, radius = circle_fit(xy)
        assert radius == pytest.approx(2 * CONF * R_RAIL, rel=1e-10)
        assert np.abs(np.hypot(*(xy - centre).T) - radius).max() < 1e-12
        assert np.linalg.norm(centre) == pytest.approx(radius - R_RAIL, rel=1e-9)  # internally tangent
        # the contact normal (arc centre -> contact point) passes through the ball centre
        contact = -centre / np.linalg.norm(centre) * R_RAIL
        assert math.atan2(sign * contact[0], -contact[1]) == pytest.approx(beta, abs=1e-9)
        # and the contact point is a point of the flank: mesh nodes surround it
        assert np.min(np.hypot(*(xy - contact).T)) < 4e-4


def test_rail_volume_against_closed_form(rail_mesh):
    """Box minus the gothic-arch lens below the land (quadrature of the two circles)."""
    from scipy.integrate import quad
    arch = rail.gothic_arch(R_RAIL, CONF, BETA, -DEV, DEV)
    r_g = arch.groove_radius
    c_l, c_r = arch.arc_centre("left"), arch.arc_centre("right")

    def void_height(x):
        lows = [c[1] - math.sqrt(max(r_g**2 - (x - c[0]) ** 2, 0.0)) for c in (c_l, c_r)]
        return max(arch.land_height - max(lows), 0.0)

    x0, x1 = arch.edge("left")[0], arch.edge("right")[0]
    lens, _ = quad(void_height, x0, x1, points=[arch.bottom[0]], epsabs=1e-16, epsrel=1e-12)
    width, depth, length = 2.6 * R_RAIL, 1.6 * R_RAIL, 2.0 * R_RAIL
    exact = (width * depth - lens) * length
    mesh_volume = tet_volume(rail_mesh.points, group_cells(rail_mesh, "rail", "tetra"))
    area = edge = 0.0
    for name in ("groove_left", "groove_right"):
        a, e = surface_area_and_longest_edge(rail_mesh, name)
        area, edge = area + a, max(edge, e)
    # concave flanks: the chords lie inside the groove void, the mesh is larger
    assert exact < mesh_volume < exact + area * edge**2 / (6 * r_g)


def test_rail_refined_at_both_contacts(rail_mesh):
    arch = rail.gothic_arch(R_RAIL, CONF, BETA, -DEV, DEV)
    for name, side in (("groove_left", "left"), ("groove_right", "right")):
        tri = group_cells(rail_mesh, name, "triangle")
        points = rail_mesh.points
        centre = points[tri].mean(axis=1)
        contact = np.append(arch.contact_point(side), 0.0)
        near = np.linalg.norm(centre - contact, axis=1) < 4e-4
        edges = np.linalg.norm(points[tri[near, 0]] - points[tri[near, 1]], axis=1)
        assert len(edges) >= 3 and 0.5 * 2e-4 < np.median(edges) < 2.0 * 2e-4


@pytest.mark.parametrize("kwargs, match", [
    (dict(conformity=0.5), "conformity"),
    (dict(conformity=float("nan")), "conformity"),
    (dict(ball_radius=-5e-3), "ball_radius"),
    (dict(contact_angle=math.radians(90)), "contact_angle"),
    (dict(contact_angle=float("nan")), "contact_angle"),
    (dict(deviation_left=math.radians(20)), "deviation_left"),
    (dict(deviation_right=float("nan")), "deviation_right"),
    (dict(contact_angle=math.radians(5), deviation_left=math.radians(-10)), "contact_angle \\+ deviation_left"),
    (dict(land_height=0.1e-3), "land_height"),
    (dict(land_height=-0.8 * R_RAIL), "four-point contact"),
    (dict(contact_angle=math.radians(80)), "four-point contact"),
])
def test_rail_bad_input_names_the_parameter(kwargs, match):
    args = dict(ball_radius=R_RAIL, conformity=CONF, contact_angle=BETA)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        rail.rail_segment(**args, h_contact=5e-4, cache=False)
