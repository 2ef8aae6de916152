"""meshes.assemblies.fourpoint_module: the four-point module of the linear guide (lin2019 Table 1, Fig 7;
coarse meshes)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.meshes.assemblies import fourpoint_module
from tests.meshes.mesh_support import (BETA, CONF, DEV, R_RAIL, circle_fit, group_cells, group_nodes,
                                       surface_area_and_longest_edge, tet_volume)
from tests.meshes.mesh_support import private_cache  # noqa: F401 - the autouse fixture: a private mesh cache

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


# --------------------------------------------------------------------------
# four-point module
# --------------------------------------------------------------------------
@pytest.fixture(scope="module")
def module_mesh():
    deviations = (-DEV, DEV, 0.5 * DEV, 0.0)  # lin2019 Fig 7 on the bottom rail, and one on TR
    path = fourpoint_module.fourpoint_module(R_RAIL, CONF, BETA, deviations, n_balls=2, h_contact=4e-4,
                                             growth=1.5, cache=False)
    return deviations, meshio.read(path)


def test_module_groups_per_contact_and_body(module_mesh):
    _, mesh = module_mesh
    bodies = ("bottom_rail", "top_rail", "ball1", "ball2")
    for name in bodies:
        assert len(group_cells(mesh, name, "tetra")) > 100
    for name in ("BL", "BR", "TR", "TL", "bottom_support", "top_load", "bottom_land", "top_land"):
        assert len(group_cells(mesh, name, "triangle")) > 0
    nodes = [set(group_nodes(mesh, name)) for name in bodies]
    for i in range(4):
        for j in range(i + 1, 4):
            assert not nodes[i] & nodes[j], f"{bodies[i]} and {bodies[j]} share nodes"


def test_module_every_ball_touches_every_flank_at_its_contact_angle(module_mesh):
    """For each named rail flank, a circle fit of its nodes gives r_g; each ball centre lies
    r_g - R_B from the arc centre (internal tangency: four-point contact), on the line of
    the contact angle b_0 + db measured from -+y (lin2017 eq 1); the ball cap named after
    the contact is centred on that contact point."""
    deviations, mesh = module_mesh
    r_g = 2 * CONF * R_RAIL
    signs = {"BL": (-1, -1), "BR": (1, -1), "TR": (1, 1), "TL": (-1, 1)}
    for name, deviation in zip(fourpoint_module.CONTACTS, deviations):
        xy = mesh.points[group_nodes(mesh, name), :2]
        centre, radius = circle_fit(xy)
        assert radius == pytest.approx(r_g, rel=1e-10)
        assert np.linalg.norm(centre) == pytest.approx(r_g - R_RAIL, rel=1e-9)
        direction = -centre / np.linalg.norm(centre)  # ball centre -> contact point
        sx, sy = signs[name]
        assert math.atan2(sx * direction[0], sy * direction[1]) == pytest.approx(BETA + deviation, abs=1e-9)
        for k, z_centre in ((1, -R_RAIL), (2, R_RAIL)):
            cap = mesh.points[group_nodes(mesh, f"ball{k}_{name}")]
            assert np.abs(np.linalg.norm(cap - [0, 0, z_centre], axis=1) - R_RAIL).max() < 1e-12
            mean = cap.mean(axis=0) - [0, 0, z_centre]
            axis = mean / np.linalg.norm(mean)
            assert math.degrees(math.acos(np.clip(axis @ np.append(direction, 0.0), -1, 1))) < 2.0


def test_module_b2b_caps_face_each_other(module_mesh):
    _, mesh = module_mesh
    for k, sign in ((1, 1.0), (2, -1.0)):
        cap = mesh.points[group_nodes(mesh, f"ball{k}_B2B")]
        centre = np.array([0.0, 0.0, -sign * R_RAIL])
        mean = cap.mean(axis=0) - centre
        assert mean[2] * sign > 0.9 * np.linalg.norm(mean)
        assert np.linalg.norm(cap, axis=1).min() < 4e-4  # refined at the B2B contact point (the origin)


def test_module_ball_volumes(module_mesh):
    _, mesh = module_mesh
    exact = 4.0 / 3.0 * math.pi * R_RAIL**3
    for k in (1, 2):
        volume = tet_volume(mesh.points, group_cells(mesh, f"ball{k}", "tetra"))
        area = edge = 0.0
        for part in ("BL", "BR", "TR", "TL", "B2B", "free"):
            a, e = surface_area_and_longest_edge(mesh, f"ball{k}_{part}")
            area, edge = area + a, max(edge, e)
        assert exact - area * edge**2 / (6 * R_RAIL) < volume < exact


@pytest.mark.parametrize("kwargs, match", [
    (dict(deviations=(0.0, 0.0, 0.0)), "deviations"),
    (dict(deviations=(0.0, 0.0, float("nan"), 0.0)), "deviation_left"),
    (dict(n_balls=3), "n_balls"),
    (dict(n_balls=True), "n_balls"),
    (dict(n_balls=2, spacing=9e-3), "spacing"),
    (dict(land_height=-0.8 * R_RAIL), "four-point contact"),
    (dict(conformity=0.49), "conformity"),
    (dict(cap_angle=1.0), "cap_angle"),
    (dict(contact_angle=math.radians(60), cap_angle=math.radians(30)), "cap_angle"),
])
def test_module_bad_input_names_the_parameter(kwargs, match):
    args = dict(ball_radius=R_RAIL, conformity=CONF, contact_angle=BETA)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        fourpoint_module.fourpoint_module(**args, cache=False)
