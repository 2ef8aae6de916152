"""meshes.assemblies.ball_screw_module: the ball-screw module (lin2019 Fig 12b, Table 4; coarse meshes)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.lowmodel.geometry import helix
from ballbench.meshes.assemblies import ball_screw_module
from tests.meshes.mesh_support import (BETA, CONF, LEAD, R_B, R_P, group_cells, group_nodes, radii,
                                       surface_area_and_longest_edge, tet_volume)
from tests.meshes.mesh_support import private_cache  # noqa: F401 - the autouse fixture: a private mesh cache

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


# --------------------------------------------------------------------------
# ball-screw module (lin2019 Fig 12b)
# --------------------------------------------------------------------------
SCREW_DEVIATIONS = (0.0, math.radians(2.0), 0.0, 0.0)  # lin2019 Fig 17 case (a) on the screw, uniform


@pytest.fixture(scope="module")
def screw_module_mesh():
    path = ball_screw_module.ball_screw_module(R_B, CONF, R_P, LEAD, BETA, SCREW_DEVIATIONS, n_balls=2,
                                            h_contact=1e-4, growth=1.5, cache=False)
    return meshio.read(path)


def test_ball_centre_azimuths_against_lin2019_eq56():
    """lin2019 eq 56: touching balls are 2 beta_B2B apart, beta_B2B = asin(2 pi R_B / L),
    L = sqrt((2 pi R_P)^2 + p^2) (eq 45): the helix taken as a circle of radius L / 2 pi.
    The exact chord agrees to 1.7e-4 for Table 4, the difference vanishing as lead^2."""
    def relative_gap(lead):
        length = math.hypot(2 * math.pi * R_P, lead)
        beta_b2b = math.asin(2 * math.pi * R_B / length)
        exact = helix.ball_centre_azimuths(R_P, lead, 2 * R_B)
        return abs(exact - 2 * beta_b2b) / exact

    assert relative_gap(LEAD) < 2e-4
    assert 12.0 < relative_gap(LEAD) / relative_gap(LEAD / 4) < 18.0  # ~ lead^2
    assert relative_gap(0.0) < 1e-14


def test_screw_module_groups_and_four_point_contact_of_both_balls(screw_module_mesh):
    """Every ball centre lies R_B from each of the four flanks (touching, never inside);
    flank nodes on their exact helical surfaces; caps centred on their contacts."""
    mesh = screw_module_mesh
    bodies = ("screw", "nut", "ball1", "ball2")
    nodes = [set(group_nodes(mesh, name)) for name in bodies]
    for i in range(4):
        for j in range(i + 1, 4):
            assert not nodes[i] & nodes[j]
    for name in ("screw_land", "nut_land", "screw_support", "nut_load"):
        assert len(group_cells(mesh, name, "triangle")) > 0
    dphi = helix.ball_centre_azimuths(R_P, LEAD, 2 * R_B)
    flanks = {"SL": ("screw", "left", 0), "SR": ("screw", "right", 1), "NR": ("nut", "right", 2),
              "NL": ("nut", "left", 3)}
    h = 1e-4
    for name, (body, flank, index) in flanks.items():
        groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA + SCREW_DEVIATIONS[index], body, flank)
        flank_nodes = mesh.points[group_nodes(mesh, name)]
        assert np.abs(groove_core.surface_residual(groove, flank_nodes)).max() < 1e-12 * R_B
        for k, phi in ((1, -dphi / 2), (2, dphi / 2)):
            centre = groove.helix(phi)
            distance = np.linalg.norm(flank_nodes - centre, axis=1)
            assert R_B * (1 - 1e-12) < distance.min() < R_B + h**2 / (8 * R_B)
            contact = groove.surface(groove.contact_theta, phi)
            cap = mesh.points[group_nodes(mesh, f"ball{k}_{name}")]
            assert np.abs(np.linalg.norm(cap - centre, axis=1) - R_B).max() < 1e-12
            axis = cap.mean(axis=0) - centre
            cosine = axis @ (contact - centre) / (np.linalg.norm(axis) * R_B)
            assert math.degrees(math.acos(min(1.0, cosine))) < 2.0


def test_screw_module_balls_touch_each_other(screw_module_mesh):
    mesh = screw_module_mesh
    dphi = helix.ball_centre_azimuths(R_P, LEAD, 2 * R_B)
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA)
    contact = (groove.helix(-dphi / 2) + groove.helix(dphi / 2)) / 2
    for k in (1, 2):
        cap = mesh.points[group_nodes(mesh, f"ball{k}_B2B")]
        assert np.linalg.norm(cap - contact, axis=1).min() < 2e-4  # refined at the B2B point
    exact = 4.0 / 3.0 * math.pi * R_B**3
    volume = tet_volume(mesh.points, group_cells(mesh, "ball1", "tetra"))
    area = edge = 0.0
    for part in ("SL", "SR", "NR", "NL", "B2B", "free"):
        a, e = surface_area_and_longest_edge(mesh, f"ball1_{part}")
        area, edge = area + a, max(edge, e)
    assert exact - area * edge**2 / (6 * R_B) < volume < exact


def test_screw_module_default_bodies_are_the_deep_validated_ones(screw_module_mesh):
    """By default the screw core and the nut's outside lie at R_P -+ 5.25 R_B, the depth of the validated FE module
    (docs/fe_b2b.md "Depth of the FE bodies": at the former 2 R_B the FE forces were up to 5.5 % above the
    frictionless Hertz statics).  The default h_max R_B/3 (0.93 mm) lies within 0.1 % of the 1 mm the scenes take."""
    for group, radius in (("screw_support", R_P - 5.25 * R_B), ("nut_load", R_P + 5.25 * R_B)):
        np.testing.assert_allclose(radii(screw_module_mesh, group), radius, rtol=1e-12)


def test_thin_screw_keeps_a_core():
    """R_P = 4 R_B: the deep default R_P - 5.25 R_B would cross the axis; the screw keeps a core of 0.1 R_P
    (without it the core radius is negative and gmsh fails on a default the user did not give)."""
    r_p = 4.0 * R_B
    mesh = meshio.read(ball_screw_module.ball_screw_module(R_B, CONF, r_p, LEAD, BETA, cache=False))
    np.testing.assert_allclose(radii(mesh, "screw_support"), 0.1 * r_p, rtol=1e-12)
    np.testing.assert_allclose(radii(mesh, "nut_load"), r_p + 5.25 * R_B, rtol=1e-12)


@pytest.mark.parametrize("kwargs, match", [
    (dict(deviations=(0.0, 0.0)), "deviations"),
    (dict(n_balls=0), "n_balls"),
    (dict(n_balls=2.0), "n_balls"),
    (dict(n_balls=2, spacing=5e-3), "spacing"),
    (dict(half_angle=0.05), "half_angle"),
    (dict(nut_land_radius=R_P + 0.8 * R_B), "nut_land_radius"),
    (dict(screw_back_radius=R_P - 0.5 * R_B), "screw_back_radius"),
    (dict(conformity=0.5), "conformity"),
    (dict(lead=-1.0), "lead"),
])
def test_screw_module_bad_input_names_the_parameter(kwargs, match):
    args = dict(ball_radius=R_B, conformity=CONF, pitch_radius=R_P, lead=LEAD, contact_angle=BETA)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        ball_screw_module.ball_screw_module(**args, cache=False)


def test_ball_screw_module_with_elliptic_fine_zones_and_size_factors():
    """fine_ellipses and size_factors in the screw module: each contact's slab lies across the groove (e1, in the
    plane normal to the helix, normal to the contact normal), fine to 0.8 l_1 along it and coarser at 0.8 l_1 along
    the helix (catches the slab in the wrong frame: e1 and e2 swapped); a contact with the factor 0.5 is meshed
    about twice as fine as one with 1."""
    h, l1, l2, l3 = 6e-5, 6e-4, 1.5e-4, 5e-5
    factors = (1.0, 0.5, 1.0, 1.0)  # SR at half the size
    path = ball_screw_module.ball_screw_module(R_B, CONF, R_P, LEAD, BETA, h_contact=h, growth=1.4,
                                               fine_ellipses=(l1, l2, l3), size_factors=factors, cache=False)
    mesh = meshio.read(path)
    tets = np.vstack([block.data for block in mesh.cells if block.type == "tetra"])
    corners = mesh.points[tets]
    centre = corners.mean(axis=1)
    edge = np.linalg.norm(corners[:, 0] - corners[:, 1], axis=1)

    def size_near(point, reach=1.5 * h):
        near = np.linalg.norm(centre - point, axis=1) < reach
        assert near.any()
        return float(np.median(edge[near]))

    ball_centre = np.array([R_P, 0.0, 0.0])  # one ball at phi = 0
    tangent = np.array([0.0, R_P, LEAD / (2 * math.pi)])
    sizes = {}
    for name, factor in zip(ball_screw_module.CONTACTS, factors):
        cap = mesh.points[np.unique(group_nodes(mesh, f"ball1_{name}"))] - ball_centre
        n = cap.mean(axis=0)
        n /= np.linalg.norm(n)  # the cap is centred on the contact
        e2 = tangent - (tangent @ n) * n
        e2 /= np.linalg.norm(e2)
        e1 = np.cross(e2, n)
        contact = ball_centre + R_B * n
        assert size_near(contact + 0.8 * l1 * e1 - 0.3 * h * n) < 1.6 * factor * h  # across the groove: fine
        assert size_near(contact + 0.8 * l1 * e2 - 0.3 * h * n) > 1.5 * h  # along the helix past l_2: coarser
        sizes[name] = size_near(contact - 0.3 * factor * h * n, reach=2.0 * factor * h)
    assert sizes["SR"] < 0.7 * min(sizes[name] for name in ("SL", "NR", "NL"))
    with pytest.raises(ValueError, match="size_factors must be four factors"):
        ball_screw_module.ball_screw_module(R_B, CONF, R_P, LEAD, BETA, h_contact=h, size_factors=(1.0, 0.0, 1, 1),
                                            cache=False)
