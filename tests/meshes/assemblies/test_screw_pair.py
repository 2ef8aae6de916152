"""meshes.assemblies.screw_pair: the ball in a screw or nut groove, and the exact helical groove geometry it
meshes (lowmodel.geometry.groove; lin2019 Table 4; coarse meshes)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.meshes.assemblies import screw_pair
from tests.meshes.mesh_support import (BETA, CONF, COARSE, LEAD, R_B, R_P, group_cells, group_nodes,
                                       pair_hertz_geometry, quadratic_fit, surface_area_and_longest_edge, tet_volume)
from tests.meshes.mesh_support import private_cache  # noqa: F401 - the autouse fixture: a private mesh cache

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


# --------------------------------------------------------------------------
# exact helical geometry
# --------------------------------------------------------------------------
@pytest.mark.parametrize("body", ["screw", "nut"])
def test_pair_hertz_geometry_axial_equals_lowmodel_hertz(body):
    mine = pair_hertz_geometry(R_B, CONF, R_P, LEAD, BETA, body, profile_plane="axial")
    lead_angle = math.atan(LEAD / (2 * math.pi * R_P))
    reference = hertz.ball_in_screw_groove(R_B, CONF, R_P, BETA, lead_angle, body, profile_plane="axial")
    assert mine.A == pytest.approx(reference.A, rel=1e-12)
    assert mine.B == pytest.approx(reference.B, rel=1e-12)
    # the lin2019 normal-section profile is a different groove: at 100 N, a differs by
    # 1.0 % (screw) and 5.0 % (nut), so the FE scene must compare with its own geometry
    normal = pair_hertz_geometry(R_B, CONF, R_P, LEAD, BETA, body)
    a_axial, a_normal = hertz.solve_load(mine, 100.0).a, hertz.solve_load(normal, 100.0).a
    assert 5e-3 < abs(a_normal / a_axial - 1) < 0.1


@pytest.mark.parametrize("plane", ["normal", "axial"])
@pytest.mark.parametrize("body", ["screw", "nut"])
def test_zero_lead_is_the_bearing_raceway(plane, body):
    """lead = 0: the torus of a bearing raceway (Harris): (-1/r_g, +-cos b/(R_P -+ R_B cos b))."""
    groove = groove_core.helical_groove(R_B, CONF, R_P, 0.0, BETA, body, "left", plane)
    frame = groove_core.contact_frame(groove)
    sign = 1.0 if body == "screw" else -1.0
    assert frame.curvature_major == pytest.approx(-1.0 / (2 * CONF * R_B), rel=1e-12)
    assert frame.curvature_minor == pytest.approx(sign * math.cos(BETA) / (R_P - sign * R_B * math.cos(BETA)),
                                                  rel=1e-12)
    assert frame.profile_angle == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("body", ["screw", "nut"])
def test_normal_profile_contact_normal_passes_through_ball_centre_on_helix(body):
    """lin2019 eq 37: a ball centred on the helix touches the groove at beta from -+x3
    in the plane normal to the helix, and the groove normal there passes through its centre."""
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, body, "left", "normal")
    frame = groove_core.contact_frame(groove)
    assert np.linalg.norm(frame.ball_centre - groove.helix(0.0)) < 1e-12 * R_B
    radial = np.array([1.0, 0.0, 0.0])
    toward_ball = radial if body == "screw" else -radial  # the normal points from the groove into the ball
    assert math.acos(frame.normal @ toward_ball) == pytest.approx(BETA, abs=1e-12)
    tangent = groove.helix(1e-6) - groove.helix(-1e-6)
    assert abs(frame.normal @ tangent) < 1e-9 * np.linalg.norm(tangent)  # in the normal plane


def test_axial_profile_puts_the_ball_centre_off_the_helix():
    """With the profile in the axial plane the contact normal tilts out of that plane
    by atan(p sin b / rho) (8.8 deg for lin2019 Table 4), so the ball centre leaves the helix."""
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "screw", "left", "axial")
    frame = groove_core.contact_frame(groove)
    rho = R_P - R_B * math.cos(BETA)
    tilt = math.atan(groove.lead_per_radian * math.sin(BETA) / rho)
    assert math.asin(abs(frame.normal[1])) == pytest.approx(tilt, rel=1e-12)
    assert np.linalg.norm(frame.ball_centre - groove.helix(0.0)) > 0.1 * R_B


@pytest.mark.parametrize("plane", ["normal", "axial"])
@pytest.mark.parametrize("body", ["screw", "nut"])
def test_contact_frame_maps_the_surface_to_its_hertz_quadratic(plane, body):
    """In the contact frame the exact surface is z = -(k_major x^2 + k_minor y^2)/2 + O(r^3):
    tangent plane z = 0 and principal axes x, y (no xy term)."""
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, body, "left", plane)
    frame = groove_core.contact_frame(groove)
    eps = 1e-5
    theta = groove.contact_theta + eps * np.cos(np.linspace(0, 2 * np.pi, 13))
    phi = 0.2 * eps * np.sin(np.linspace(0, 2 * np.pi, 13))
    local = (groove.surface(theta, phi) - frame.point) @ frame.rotation.T
    x, y, z = local.T
    quadratic = -(frame.curvature_major * x**2 + frame.curvature_minor * y**2) / 2
    assert np.abs(z - quadratic).max() < 1e-4 * np.abs(quadratic).max()


@pytest.mark.parametrize("plane", ["normal", "axial"])
def test_profile_coordinates_invert_the_screw_motion(plane):
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "nut", "right", plane)
    theta = groove.contact_theta + np.linspace(-0.5, 0.5, 7)
    phi = np.linspace(-0.4, 0.4, 5)
    points = groove.surface(theta[:, None], phi[None, :]).reshape(-1, 3)
    phi_found, uw = groove_core.profile_coordinates(groove, points)
    assert np.allclose(phi_found, np.broadcast_to(phi[None, :], (7, 5)).ravel(), atol=1e-13)
    assert np.allclose(uw, groove.profile(np.repeat(theta, 5)), atol=1e-15)
    assert np.abs(groove_core.surface_residual(groove, points)).max() < 1e-15
    assert groove_core.surface_residual(groove, groove.helix(0.0)[None, :])[0] == pytest.approx(-R_B, rel=1e-12)


@pytest.mark.parametrize("plane", ["normal", "axial"])
@pytest.mark.parametrize("body", ["screw", "nut"])
def test_left_and_right_flanks_are_congruent(body, plane):
    """The half-turn about the radial line through a helix point maps the helix onto itself,
    so both flanks have the same principal curvatures (groove_curvatures_helical evaluates the
    right flank only; the builders mesh either)."""
    frames = [groove_core.contact_frame(groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, body, flank, plane))
              for flank in ("left", "right")]
    assert frames[0].curvature_major == pytest.approx(frames[1].curvature_major, rel=1e-12)
    assert frames[0].curvature_minor == pytest.approx(frames[1].curvature_minor, rel=1e-12)
    assert frames[0].profile_angle == pytest.approx(frames[1].profile_angle, abs=1e-12)


# --------------------------------------------------------------------------
# the contact-pair mesh
# --------------------------------------------------------------------------
@pytest.fixture(scope="module")
def screw_pair_mesh(tmp_path_factory):
    import os
    old = os.environ.get("BALLBENCH_CACHE")
    os.environ["BALLBENCH_CACHE"] = str(tmp_path_factory.mktemp("cache"))
    try:
        path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", h_contact=2.5e-5,
                                                    growth=1.5, h_max=R_B / 6)
    finally:
        if old is None:
            del os.environ["BALLBENCH_CACHE"]
        else:
            os.environ["BALLBENCH_CACHE"] = old
    return path, meshio.read(path)


def test_pair_physical_groups_exist_and_are_not_empty(screw_pair_mesh):
    _, mesh = screw_pair_mesh
    for name in ("ball", "counter"):
        assert len(group_cells(mesh, name, "tetra")) > 100
    for name in ("ball_contact", "ball_load", "counter_contact", "counter_support"):
        assert len(group_cells(mesh, name, "triangle")) > 10
    ball = set(group_nodes(mesh, "ball"))
    counter = set(group_nodes(mesh, "counter"))
    assert not ball & counter  # the two bodies share no nodes


def test_pair_contact_point_lies_on_both_surfaces_with_normal_plus_z(screw_pair_mesh):
    _, mesh = screw_pair_mesh
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "screw")
    frame = groove_core.contact_frame(groove)
    assert abs(groove_core.surface_residual(groove, frame.point[None, :])[0]) < 1e-15  # origin on the groove
    points = mesh.points
    ball_nodes = points[group_nodes(mesh, "ball_contact")]
    # the ball surface passes through the origin with the centre at (0, 0, R_B)
    assert np.abs(np.linalg.norm(ball_nodes - [0.0, 0.0, R_B], axis=1) - R_B).max() < 1e-12
    assert ball_nodes[:, 2].min() < 1e-4 * R_B
    # groove surface nodes: local fit z = c0 + c1 x + c2 y + ... : through the origin, normal +z
    coef = quadratic_fit(points[group_nodes(mesh, "counter_contact")], 0.1 * R_B, degree=4)
    assert abs(coef[0]) < 1e-11  # [m], against a Hertz approach of some um
    assert abs(coef[1]) < 1e-7 and abs(coef[2]) < 1e-7  # slope [rad]
    # and no node of the counter body lies inside the undeformed ball (one point of contact)
    counter = points[group_nodes(mesh, "counter")]
    assert np.linalg.norm(counter - [0.0, 0.0, R_B], axis=1).min() > R_B * (1 - 1e-12)


def test_pair_groove_nodes_lie_on_the_helical_arc(screw_pair_mesh):
    """Every counter_contact node lies at r_g = 2 conf R_B from the flank's arc centre
    in the profile plane of its azimuth (the helix equation of the swept profile)."""
    _, mesh = screw_pair_mesh
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "screw")
    frame = groove_core.contact_frame(groove)
    local = mesh.points[group_nodes(mesh, "counter_contact")]
    world = frame.point + local @ frame.rotation
    assert np.abs(groove_core.surface_residual(groove, world)).max() < 1e-12 * R_B
    # and the ball-centre path is the helix of lin2019 eq 42: z = p phi at rho = R_P
    phi, uw = groove_core.profile_coordinates(groove, world)
    assert np.ptp(phi) > 0.1  # the block spans a real stretch of helix


def test_pair_principal_directions_and_curvatures_from_the_mesh(screw_pair_mesh):
    """Independent route: a cubic fit of the meshed groove surface around the origin
    gives z = -(kappa_major x^2 + kappa_minor y^2)/2 with no xy term."""
    _, mesh = screw_pair_mesh
    frame = groove_core.contact_frame(groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "screw"))
    coef = quadratic_fit(mesh.points[group_nodes(mesh, "counter_contact")], 0.1 * R_B, degree=4)
    assert coef[3] == pytest.approx(-frame.curvature_major / 2, rel=1e-3)
    assert coef[5] == pytest.approx(-frame.curvature_minor / 2, rel=1e-3)
    assert abs(coef[4]) < 1e-3 * abs(coef[3])


def test_pair_mesh_size_at_the_contact(screw_pair_mesh):
    _, mesh = screw_pair_mesh
    h_contact = 2.5e-5
    for name in ("ball_contact", "counter_contact"):
        tri = group_cells(mesh, name, "triangle")
        points = mesh.points
        centre = points[tri].mean(axis=1)
        near = np.linalg.norm(centre, axis=1) < 2 * h_contact
        edges = np.linalg.norm(points[tri[near, 0]] - points[tri[near, 1]], axis=1)
        assert len(edges) >= 3
        assert 0.5 * h_contact < np.median(edges) < 2.0 * h_contact


def test_pair_fine_patch_refines_the_ellipse_not_a_ball():
    """fine_patch = (l_x, l_y): h_contact over the rectangle (a Hertz ellipse's box), growing
    beyond it; at (0.9 l_x, 0) the size is h_contact, at (0, 0.9 l_x) it is several times it."""
    h, l_x, l_y = 2e-5, 3e-4, 6e-5
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", h_contact=h, growth=1.3,
                                             fine_patch=(l_x, l_y))
    mesh = meshio.read(path)
    tri = group_cells(mesh, "counter_contact", "triangle")
    centre = mesh.points[tri].mean(axis=1)
    edges = np.linalg.norm(mesh.points[tri[:, 0]] - mesh.points[tri[:, 1]], axis=1)

    def size_near(x, y):
        near = np.hypot(centre[:, 0] - x, centre[:, 1] - y) < 2 * h
        return np.median(edges[near]) if near.any() else np.inf

    assert 0.5 * h < size_near(0.9 * l_x, 0.0) < 2 * h
    assert size_near(0.0, 0.9 * l_x) > 2.5 * h  # h + 0.3 (0.9 l_x - l_y) = 4.2 h
    # the capsule of contact_pairs: fine_radius about the segment |x| <= fine_half_length
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", h_contact=h, growth=1.3,
                                             fine_radius=l_y, fine_half_length=l_x)
    mesh = meshio.read(path)
    tri = group_cells(mesh, "counter_contact", "triangle")
    centre = mesh.points[tri].mean(axis=1)
    edges = np.linalg.norm(mesh.points[tri[:, 0]] - mesh.points[tri[:, 1]], axis=1)
    assert 0.5 * h < size_near(0.9 * l_x, 0.0) < 2 * h
    assert size_near(0.0, 0.9 * l_x) > 2.5 * h


@pytest.mark.parametrize("body, plane", [("screw", "normal"), ("nut", "axial")])
def test_pair_initial_gap_is_the_exact_separation(body, plane):
    """counter_height reproduces the meshed groove nodes (which lie on the exact surface);
    the exact initial gap is >= 0, zero at the contact and tends to Hertz's A x^2 + B y^2."""
    args = (R_B, CONF, R_P, LEAD, BETA, body)
    path = screw_pair.ball_in_screw_groove_pair(*args, profile_plane=plane, **COARSE)
    mesh = meshio.read(path)
    groove = groove_core.helical_groove(*args, "left", plane)
    nodes = mesh.points[group_nodes(mesh, "counter_contact")]
    near = np.hypot(nodes[:, 0], nodes[:, 1]) < 0.4 * R_B
    height = groove_core.counter_height(groove, nodes[near, 0], nodes[near, 1])
    assert np.abs(height - nodes[near, 2]).max() < 1e-15
    gap = groove_core.pair_initial_gap(*args, profile_plane=plane)
    geometry = pair_hertz_geometry(*args, profile_plane=plane)
    assert gap(0.0, 0.0) == pytest.approx(0.0, abs=1e-18)
    r = 1e-5
    assert gap(r, 0.0) == pytest.approx(geometry.A * r * r, rel=1e-3)
    assert gap(0.0, r) == pytest.approx(geometry.B * r * r, rel=1e-3)
    ball = mesh.points[group_nodes(mesh, "ball_contact")]
    ball = ball[np.hypot(ball[:, 0], ball[:, 1]) < 0.3 * R_B]
    assert gap(ball[:, 0], ball[:, 1]).min() > -1e-15  # the exact bodies do not overlap


def test_pair_volumes_against_closed_forms():
    """Ball cap: pi c^2 (3 R - c) / 3.  Helical block: Pappus for a screw motion,
    V = 2 dphi A [(R_P + u_c) cos(lambda) + p sin(lambda)] (flux of the screw velocity
    through the section in the normal plane; u_c the section centroid).  P1 facets cut
    the curved faces: a triangle of longest edge e inscribed in a surface of radius r
    departs from it by at most e^2 / (6 r), which bounds the volume error."""
    cap = 0.8 * R_B
    half_width = half_length = depth = 0.5 * R_B
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "nut", h_contact=1e-4, growth=1.5,
                                             h_max=R_B / 10, cap_height=cap, block_half_width=half_width,
                                             block_half_length=half_length, block_depth=depth)
    mesh = meshio.read(path)
    ball = tet_volume(mesh.points, group_cells(mesh, "ball", "tetra"))
    exact = math.pi * cap**2 * (3 * R_B - cap) / 3
    area, edge = surface_area_and_longest_edge(mesh, "ball_contact")
    assert exact - area * edge**2 / (6 * R_B) < ball < exact  # inscribed polyhedron
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "nut")
    frame = groove_core.contact_frame(groove)
    speed = np.linalg.norm(np.cross([0, 0, 1.0], frame.point) + [0, 0, groove.lead_per_radian])
    dphi = half_length / speed
    r1, r2 = groove.groove_radius, groove.groove_radius + depth
    gamma = half_width / r1
    section = gamma * (r2**2 - r1**2)
    centroid_radius = 2.0 / 3.0 * (r2**3 - r1**3) / (r2**2 - r1**2) * math.sin(gamma) / gamma
    u_c = groove.arc_centre[0] + centroid_radius * math.cos(groove.contact_theta)
    lam = groove.lead_angle
    exact = 2 * dphi * section * ((R_P + u_c) * math.cos(lam) + groove.lead_per_radian * math.sin(lam))
    counter = tet_volume(mesh.points, group_cells(mesh, "counter", "tetra"))
    bound = 0.0
    for name in ("counter_contact", "counter_support"):
        area, edge = surface_area_and_longest_edge(mesh, name)
        bound += area * edge**2 / (6 * r1)
    assert abs(counter - exact) < bound
    assert bound < 0.02 * exact  # the check is not vacuous (measured error 3e-5)


@pytest.mark.parametrize("body, plane, flank", [("nut", "normal", "right"), ("screw", "axial", "left"),
                                                ("nut", "axial", "left")])
def test_pair_other_grooves_touch_the_ball_at_the_origin_only(body, plane, flank):
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, body, flank=flank, profile_plane=plane,
                                             **COARSE)
    mesh = meshio.read(path)
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, body, flank, plane)
    frame = groove_core.contact_frame(groove)
    local = mesh.points[group_nodes(mesh, "counter_contact")]
    assert np.abs(groove_core.surface_residual(groove, frame.point + local @ frame.rotation)).max() < 1e-12 * R_B
    counter = mesh.points[group_nodes(mesh, "counter")]
    assert np.linalg.norm(counter - [0.0, 0.0, R_B], axis=1).min() > R_B * (1 - 1e-12)
    coef = quadratic_fit(local, 0.3 * R_B, degree=4)
    assert abs(coef[1]) < 1e-5 and abs(coef[2]) < 1e-5  # coarse mesh: tangent plane z = 0
    assert coef[3] == pytest.approx(-frame.curvature_major / 2, rel=0.01)


def test_pair_quadratic_elements_stay_on_the_helical_surface():
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "nut", element_order=2, **COARSE)
    mesh = meshio.read(path)
    assert len(group_cells(mesh, "counter", "tetra10")) > 100
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "nut")
    frame = groove_core.contact_frame(groove)
    tri = np.concatenate([block.data[ids] for block, ids in zip(mesh.cells, mesh.cell_sets["counter_contact"])
                          if len(ids)])
    assert tri.shape[1] == 6  # mid-side nodes included
    world = frame.point + mesh.points[np.unique(tri)] @ frame.rotation
    assert np.abs(groove_core.surface_residual(groove, world)).max() < 1e-12 * R_B


def test_pair_cache_hit_does_not_rebuild(monkeypatch):
    first = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", **COARSE)
    stamp = first.stat().st_mtime_ns

    def refuse(*args, **kwargs):
        raise AssertionError("gmsh was started for a cached mesh")

    monkeypatch.setattr(gmsh, "initialize", refuse)
    second = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", **COARSE)
    assert second == first and second.stat().st_mtime_ns == stamp
    other = dict(COARSE, growth=1.6)
    with pytest.raises(AssertionError, match="gmsh was started"):
        screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", **other)


@pytest.mark.parametrize("kwargs, name", [
    (dict(conformity=0.5), "conformity"),
    (dict(conformity=0.45), "conformity"),
    (dict(conformity=float("nan")), "conformity"),
    (dict(ball_radius=-1e-3), "ball_radius"),
    (dict(ball_radius=float("nan")), "ball_radius"),
    (dict(pitch_radius=0.0), "pitch_radius"),
    (dict(pitch_radius=2e-3), "pitch_radius"),
    (dict(lead=-1e-3), "lead"),
    (dict(lead=float("inf")), "lead"),
    (dict(contact_angle=0.0), "contact_angle"),
    (dict(contact_angle=math.pi / 2), "contact_angle"),
    (dict(contact_angle=-0.1), "contact_angle"),
    (dict(contact_angle=float("nan")), "contact_angle"),
    (dict(body="bolt"), "body"),
    (dict(h_contact=0.0), "h_contact"),
    (dict(h_contact=float("nan")), "h_contact"),
    (dict(h_contact=2e-3), "h_contact"),
    (dict(growth=0.9), "growth"),
    (dict(h_max=1e-6), "h_max"),
    (dict(block_half_width=3e-3), "block_half_width"),
    (dict(cap_height=-1.0), "cap_height"),
    (dict(cap_height=2 * R_B), "cap_height"),
    (dict(flank="up"), "flank"),
    (dict(profile_plane="oblique"), "profile_plane"),
    (dict(fine_patch=(1e-4, -1e-4)), "fine_patch"),
    (dict(fine_patch=(1e-4,)), "fine_patch"),
    (dict(fine_patch=(1e-4, 1e-4, 1e-4, 1e-4)), "fine_patch"),
    (dict(fine_patch=1e-4), "fine_patch"),
    (dict(fine_half_length=-1e-4), "fine_half_length"),
    (dict(element_order=True), "element_order"),
    (dict(fine_half_length=1e-4, fine_patch=(1e-4, 1e-4)), "fine_patch and fine_half_length"),
])
def test_pair_bad_input_names_the_parameter(kwargs, name):
    args = dict(ball_radius=R_B, conformity=CONF, pitch_radius=R_P, lead=LEAD, contact_angle=BETA, body="screw",
                **COARSE)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        screw_pair.ball_in_screw_groove_pair(**args)
