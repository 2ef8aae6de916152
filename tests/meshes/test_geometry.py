"""Geometry checks of the gmsh builders of meshes/ (parts: rail, groove segment; assemblies:
screw pair, four-point module, ball-screw module) and of the exact helical groove geometry
they mesh (coarse meshes; default-run budget 90 s)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.lowmodel.contact import hertz
from ballbench.lowmodel.geometry import groove as groove_core
from ballbench.lowmodel.geometry import helix
from ballbench.meshes.assemblies import ball_screw_module, fourpoint_module, screw_pair
from ballbench.meshes.parts import groove_segment, rail

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")

# lin2019 Table 4
R_B, CONF, R_P, LEAD, BETA = 2.778e-3, 0.56, 16.5e-3, 20e-3, math.radians(45.0)
COARSE = dict(h_contact=1.0e-4, growth=1.5)


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))


def _group_nodes(mesh, name: str) -> np.ndarray:
    blocks = [block.data[ids] for block, ids in zip(mesh.cells, mesh.cell_sets[name]) if len(ids)]
    assert blocks, f"physical group {name} is empty"
    return np.unique(np.concatenate([b.ravel() for b in blocks]))


def _group_cells(mesh, name: str, kind: str) -> np.ndarray:
    blocks = [block.data[ids] for block, ids in zip(mesh.cells, mesh.cell_sets[name])
              if len(ids) and block.type == kind]
    return np.concatenate(blocks) if blocks else np.empty((0, 4 if kind == "tetra" else 3), int)


def _radii(mesh, group: str) -> np.ndarray:
    nodes = mesh.points[_group_nodes(mesh, group)]
    return np.hypot(nodes[:, 0], nodes[:, 1])


def _tet_volume(points: np.ndarray, tets: np.ndarray) -> float:
    a, b, c, d = (points[tets[:, i]] for i in range(4))
    return float(np.sum(np.abs(np.einsum("ij,ij->i", np.cross(b - a, c - a), d - a))) / 6.0)


def _quadratic_fit(points: np.ndarray, radius: float, degree: int = 3) -> np.ndarray:
    """Least-squares z = polynomial of ``degree`` in (x, y) on nodes with |(x, y)| < radius
    (coordinates scaled by ``radius``).  Returns the coefficients of (1, x, y, x^2, xy, y^2) [SI]."""
    near = points[np.hypot(points[:, 0], points[:, 1]) < radius]
    x, y, z = near.T / radius
    basis = np.stack([x**i * y ** (n - i) for n in range(degree + 1) for i in range(n, -1, -1)], 1)
    assert len(near) > 2 * basis.shape[1]
    coef, *_ = np.linalg.lstsq(basis, z, rcond=None)
    return coef[:6] * radius / radius ** np.array([0, 1, 1, 2, 2, 2])


def pair_hertz_geometry(ball_radius, conformity, pitch_radius, lead, contact_angle, body="screw", *, flank="left",
                        profile_plane="normal", youngs_modulus=2.1e11, poisson_ratio=0.28):
    """Hertz geometry of the contact meshed by ``ball_in_screw_groove_pair`` with the same
    arguments: the ball's curvature ``1/R_B`` and the groove's exact principal curvatures at
    the contact (``A`` belongs to the contact-frame x axis)."""
    frame = groove_core.contact_frame(groove_core.helical_groove(ball_radius, conformity, pitch_radius, lead,
                                                                 contact_angle, body, flank, profile_plane))
    curvature = 1.0 / float(ball_radius)
    return hertz.from_curvatures((curvature, curvature), (frame.curvature_major, frame.curvature_minor),
                                 youngs_modulus=youngs_modulus, poisson_ratio=poisson_ratio)


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
        assert len(_group_cells(mesh, name, "tetra")) > 100
    for name in ("ball_contact", "ball_load", "counter_contact", "counter_support"):
        assert len(_group_cells(mesh, name, "triangle")) > 10
    ball = set(_group_nodes(mesh, "ball"))
    counter = set(_group_nodes(mesh, "counter"))
    assert not ball & counter  # the two bodies share no nodes


def test_pair_contact_point_lies_on_both_surfaces_with_normal_plus_z(screw_pair_mesh):
    _, mesh = screw_pair_mesh
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "screw")
    frame = groove_core.contact_frame(groove)
    assert abs(groove_core.surface_residual(groove, frame.point[None, :])[0]) < 1e-15  # origin on the groove
    points = mesh.points
    ball_nodes = points[_group_nodes(mesh, "ball_contact")]
    # the ball surface passes through the origin with the centre at (0, 0, R_B)
    assert np.abs(np.linalg.norm(ball_nodes - [0.0, 0.0, R_B], axis=1) - R_B).max() < 1e-12
    assert ball_nodes[:, 2].min() < 1e-4 * R_B
    # groove surface nodes: local fit z = c0 + c1 x + c2 y + ... : through the origin, normal +z
    coef = _quadratic_fit(points[_group_nodes(mesh, "counter_contact")], 0.1 * R_B, degree=4)
    assert abs(coef[0]) < 1e-11  # [m], against a Hertz approach of some um
    assert abs(coef[1]) < 1e-7 and abs(coef[2]) < 1e-7  # slope [rad]
    # and no node of the counter body lies inside the undeformed ball (one point of contact)
    counter = points[_group_nodes(mesh, "counter")]
    assert np.linalg.norm(counter - [0.0, 0.0, R_B], axis=1).min() > R_B * (1 - 1e-12)


def test_pair_groove_nodes_lie_on_the_helical_arc(screw_pair_mesh):
    """Every counter_contact node lies at r_g = 2 conf R_B from the flank's arc centre
    in the profile plane of its azimuth (the helix equation of the swept profile)."""
    _, mesh = screw_pair_mesh
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, "screw")
    frame = groove_core.contact_frame(groove)
    local = mesh.points[_group_nodes(mesh, "counter_contact")]
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
    coef = _quadratic_fit(mesh.points[_group_nodes(mesh, "counter_contact")], 0.1 * R_B, degree=4)
    assert coef[3] == pytest.approx(-frame.curvature_major / 2, rel=1e-3)
    assert coef[5] == pytest.approx(-frame.curvature_minor / 2, rel=1e-3)
    assert abs(coef[4]) < 1e-3 * abs(coef[3])


def test_pair_mesh_size_at_the_contact(screw_pair_mesh):
    _, mesh = screw_pair_mesh
    h_contact = 2.5e-5
    for name in ("ball_contact", "counter_contact"):
        tri = _group_cells(mesh, name, "triangle")
        points = mesh.points
        centre = points[tri].mean(axis=1)
        near = np.linalg.norm(centre, axis=1) < 2 * h_contact
        edges = np.linalg.norm(points[tri[near, 0]] - points[tri[near, 1]], axis=1)
        assert len(edges) >= 3
        assert 0.5 * h_contact < np.median(edges) < 2.0 * h_contact


def _surface_area_and_longest_edge(mesh, name: str) -> tuple[float, float]:
    tri = _group_cells(mesh, name, "triangle")
    a, b, c = (mesh.points[tri[:, i]] for i in range(3))
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()
    edges = np.concatenate([np.linalg.norm(b - a, axis=1), np.linalg.norm(c - b, axis=1),
                            np.linalg.norm(a - c, axis=1)])
    return float(area), float(edges.max())


def test_pair_fine_patch_refines_the_ellipse_not_a_ball():
    """fine_patch = (l_x, l_y): h_contact over the rectangle (a Hertz ellipse's box), growing
    beyond it; at (0.9 l_x, 0) the size is h_contact, at (0, 0.9 l_x) it is several times it."""
    h, l_x, l_y = 2e-5, 3e-4, 6e-5
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "screw", h_contact=h, growth=1.3,
                                             fine_patch=(l_x, l_y))
    mesh = meshio.read(path)
    tri = _group_cells(mesh, "counter_contact", "triangle")
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
    tri = _group_cells(mesh, "counter_contact", "triangle")
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
    nodes = mesh.points[_group_nodes(mesh, "counter_contact")]
    near = np.hypot(nodes[:, 0], nodes[:, 1]) < 0.4 * R_B
    height = groove_core.counter_height(groove, nodes[near, 0], nodes[near, 1])
    assert np.abs(height - nodes[near, 2]).max() < 1e-15
    gap = groove_core.pair_initial_gap(*args, profile_plane=plane)
    geometry = pair_hertz_geometry(*args, profile_plane=plane)
    assert gap(0.0, 0.0) == pytest.approx(0.0, abs=1e-18)
    r = 1e-5
    assert gap(r, 0.0) == pytest.approx(geometry.A * r * r, rel=1e-3)
    assert gap(0.0, r) == pytest.approx(geometry.B * r * r, rel=1e-3)
    ball = mesh.points[_group_nodes(mesh, "ball_contact")]
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
    ball = _tet_volume(mesh.points, _group_cells(mesh, "ball", "tetra"))
    exact = math.pi * cap**2 * (3 * R_B - cap) / 3
    area, edge = _surface_area_and_longest_edge(mesh, "ball_contact")
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
    counter = _tet_volume(mesh.points, _group_cells(mesh, "counter", "tetra"))
    bound = 0.0
    for name in ("counter_contact", "counter_support"):
        area, edge = _surface_area_and_longest_edge(mesh, name)
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
    local = mesh.points[_group_nodes(mesh, "counter_contact")]
    assert np.abs(groove_core.surface_residual(groove, frame.point + local @ frame.rotation)).max() < 1e-12 * R_B
    counter = mesh.points[_group_nodes(mesh, "counter")]
    assert np.linalg.norm(counter - [0.0, 0.0, R_B], axis=1).min() > R_B * (1 - 1e-12)
    coef = _quadratic_fit(local, 0.3 * R_B, degree=4)
    assert abs(coef[1]) < 1e-5 and abs(coef[2]) < 1e-5  # coarse mesh: tangent plane z = 0
    assert coef[3] == pytest.approx(-frame.curvature_major / 2, rel=0.01)


def test_pair_quadratic_elements_stay_on_the_helical_surface():
    path = screw_pair.ball_in_screw_groove_pair(R_B, CONF, R_P, LEAD, BETA, "nut", element_order=2, **COARSE)
    mesh = meshio.read(path)
    assert len(_group_cells(mesh, "counter", "tetra10")) > 100
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
    assert len(_group_cells(mesh, body, "tetra")) > 100
    land = R_P - 0.25 * R_B if body == "screw" else R_P + 0.25 * R_B
    back = R_P - 5.25 * R_B if body == "screw" else R_P + 5.25 * R_B  # the deep default bodies (docs/fe_b2b.md)
    np.testing.assert_allclose(_radii(mesh, "back"), back, rtol=1e-12)
    nodes = mesh.points[_group_nodes(mesh, "land")]
    # (its edges with the flanks carry flank nodes moved onto the exact helical surface:
    # OCC's loft/boolean intersection lies within 1e-7 m of it)
    assert np.abs(np.hypot(nodes[:, 0], nodes[:, 1]) - land).max() < 1e-7
    for flank, deviation in zip(("left", "right"), deviations):
        groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA + deviation, body, flank)
        nodes = mesh.points[_group_nodes(mesh, f"flank_{flank}")]
        assert np.abs(groove_core.surface_residual(groove, nodes)).max() < 1e-12 * R_B
        for phi in (-0.1, 0.0, 0.1):
            distance = np.linalg.norm(nodes - groove.helix(phi), axis=1)
            assert distance.min() > R_B * (1 - 1e-12)
            if phi == 0.0:  # refined there: chord sagitta h^2 / (8 R_B) bounds the miss
                assert distance.min() < R_B + h**2 / (8 * R_B)
    # the flanks meet at the groove bottom: a helix, fixed in the profile plane
    groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA, body)
    shared = np.intersect1d(_group_nodes(mesh, "flank_left"), _group_nodes(mesh, "flank_right"))
    assert len(shared) > 5
    phi, uw = groove_core.profile_coordinates(groove, mesh.points[shared])
    assert np.ptp(uw[:, 1]) < 1e-12 and np.ptp(uw[:, 0]) < 1e-12
    assert (abs(uw[0, 1]) < 1e-12) == (deviations[0] == deviations[1])  # symmetric only without deviation


# --------------------------------------------------------------------------
# straight gothic-arch rail
# --------------------------------------------------------------------------
R_RAIL = 5e-3  # lin2019 Table 1
DEV = math.radians(2.0)


def _circle_fit(xy: np.ndarray) -> tuple[np.ndarray, float]:
    """Algebraic (Kasa) least-squares circle through points (n, 2): centre, radius."""
    basis = np.column_stack([2 * xy, np.ones(len(xy))])
    (cx, cy, c), *_ = np.linalg.lstsq(basis, (xy**2).sum(1), rcond=None)
    return np.array([cx, cy]), math.sqrt(c + cx * cx + cy * cy)


@pytest.fixture(scope="module")
def rail_mesh(tmp_path_factory):
    path = rail.rail_segment(R_RAIL, CONF, BETA, -DEV, DEV, h_contact=2e-4, growth=1.5, cache=False)
    return meshio.read(path)


def test_rail_groups_exist_and_flanks_are_the_stated_arcs(rail_mesh):
    """Circle fits of the meshed flanks: radius 2 conf R_B, centre on the line through the
    ball centre at the contact angle b_0 + db (lin2017 eq 1), r_g - R_B from it."""
    for name in ("groove_left", "groove_right", "land", "support", "rail_free"):
        assert len(_group_cells(rail_mesh, name, "triangle")) > 0
    assert len(_group_cells(rail_mesh, "rail", "tetra")) > 100
    for name, sign, beta in (("groove_left", -1.0, BETA - DEV), ("groove_right", 1.0, BETA + DEV)):
        xy = rail_mesh.points[_group_nodes(rail_mesh, name), :2]
        centre, radius = _circle_fit(xy)
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
    mesh_volume = _tet_volume(rail_mesh.points, _group_cells(rail_mesh, "rail", "tetra"))
    area = edge = 0.0
    for name in ("groove_left", "groove_right"):
        a, e = _surface_area_and_longest_edge(rail_mesh, name)
        area, edge = area + a, max(edge, e)
    # concave flanks: the chords lie inside the groove void, the mesh is larger
    assert exact < mesh_volume < exact + area * edge**2 / (6 * r_g)


def test_rail_refined_at_both_contacts(rail_mesh):
    arch = rail.gothic_arch(R_RAIL, CONF, BETA, -DEV, DEV)
    for name, side in (("groove_left", "left"), ("groove_right", "right")):
        tri = _group_cells(rail_mesh, name, "triangle")
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
        assert len(_group_cells(mesh, name, "tetra")) > 100
    for name in ("BL", "BR", "TR", "TL", "bottom_support", "top_load", "bottom_land", "top_land"):
        assert len(_group_cells(mesh, name, "triangle")) > 0
    nodes = [set(_group_nodes(mesh, name)) for name in bodies]
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
        xy = mesh.points[_group_nodes(mesh, name), :2]
        centre, radius = _circle_fit(xy)
        assert radius == pytest.approx(r_g, rel=1e-10)
        assert np.linalg.norm(centre) == pytest.approx(r_g - R_RAIL, rel=1e-9)
        direction = -centre / np.linalg.norm(centre)  # ball centre -> contact point
        sx, sy = signs[name]
        assert math.atan2(sx * direction[0], sy * direction[1]) == pytest.approx(BETA + deviation, abs=1e-9)
        for k, z_centre in ((1, -R_RAIL), (2, R_RAIL)):
            cap = mesh.points[_group_nodes(mesh, f"ball{k}_{name}")]
            assert np.abs(np.linalg.norm(cap - [0, 0, z_centre], axis=1) - R_RAIL).max() < 1e-12
            mean = cap.mean(axis=0) - [0, 0, z_centre]
            axis = mean / np.linalg.norm(mean)
            assert math.degrees(math.acos(np.clip(axis @ np.append(direction, 0.0), -1, 1))) < 2.0


def test_module_b2b_caps_face_each_other(module_mesh):
    _, mesh = module_mesh
    for k, sign in ((1, 1.0), (2, -1.0)):
        cap = mesh.points[_group_nodes(mesh, f"ball{k}_B2B")]
        centre = np.array([0.0, 0.0, -sign * R_RAIL])
        mean = cap.mean(axis=0) - centre
        assert mean[2] * sign > 0.9 * np.linalg.norm(mean)
        assert np.linalg.norm(cap, axis=1).min() < 4e-4  # refined at the B2B contact point (the origin)


def test_module_ball_volumes(module_mesh):
    _, mesh = module_mesh
    exact = 4.0 / 3.0 * math.pi * R_RAIL**3
    for k in (1, 2):
        volume = _tet_volume(mesh.points, _group_cells(mesh, f"ball{k}", "tetra"))
        area = edge = 0.0
        for part in ("BL", "BR", "TR", "TL", "B2B", "free"):
            a, e = _surface_area_and_longest_edge(mesh, f"ball{k}_{part}")
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
    nodes = [set(_group_nodes(mesh, name)) for name in bodies]
    for i in range(4):
        for j in range(i + 1, 4):
            assert not nodes[i] & nodes[j]
    for name in ("screw_land", "nut_land", "screw_support", "nut_load"):
        assert len(_group_cells(mesh, name, "triangle")) > 0
    dphi = helix.ball_centre_azimuths(R_P, LEAD, 2 * R_B)
    flanks = {"SL": ("screw", "left", 0), "SR": ("screw", "right", 1), "NR": ("nut", "right", 2),
              "NL": ("nut", "left", 3)}
    h = 1e-4
    for name, (body, flank, index) in flanks.items():
        groove = groove_core.helical_groove(R_B, CONF, R_P, LEAD, BETA + SCREW_DEVIATIONS[index], body, flank)
        flank_nodes = mesh.points[_group_nodes(mesh, name)]
        assert np.abs(groove_core.surface_residual(groove, flank_nodes)).max() < 1e-12 * R_B
        for k, phi in ((1, -dphi / 2), (2, dphi / 2)):
            centre = groove.helix(phi)
            distance = np.linalg.norm(flank_nodes - centre, axis=1)
            assert R_B * (1 - 1e-12) < distance.min() < R_B + h**2 / (8 * R_B)
            contact = groove.surface(groove.contact_theta, phi)
            cap = mesh.points[_group_nodes(mesh, f"ball{k}_{name}")]
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
        cap = mesh.points[_group_nodes(mesh, f"ball{k}_B2B")]
        assert np.linalg.norm(cap - contact, axis=1).min() < 2e-4  # refined at the B2B point
    exact = 4.0 / 3.0 * math.pi * R_B**3
    volume = _tet_volume(mesh.points, _group_cells(mesh, "ball1", "tetra"))
    area = edge = 0.0
    for part in ("SL", "SR", "NR", "NL", "B2B", "free"):
        a, e = _surface_area_and_longest_edge(mesh, f"ball1_{part}")
        area, edge = area + a, max(edge, e)
    assert exact - area * edge**2 / (6 * R_B) < volume < exact


def test_screw_module_default_bodies_are_the_deep_validated_ones(screw_module_mesh):
    """By default the screw core and the nut's outside lie at R_P -+ 5.25 R_B, the depth of the validated FE module
    (issue 12, docs/fe_b2b.md "Depth of the FE bodies": at the former 2 R_B the FE forces were up to 5.5 % above the
    frictionless Hertz statics).  The default h_max R_B/3 (0.93 mm) lies within 0.1 % of the 1 mm the scenes take."""
    for group, radius in (("screw_support", R_P - 5.25 * R_B), ("nut_load", R_P + 5.25 * R_B)):
        np.testing.assert_allclose(_radii(screw_module_mesh, group), radius, rtol=1e-12)


def test_thin_screw_keeps_a_core():
    """R_P = 4 R_B: the deep default R_P - 5.25 R_B would cross the axis; the screw keeps a core of 0.1 R_P
    (without it the core radius is negative and gmsh fails on a default the user did not give)."""
    r_p = 4.0 * R_B
    mesh = meshio.read(ball_screw_module.ball_screw_module(R_B, CONF, r_p, LEAD, BETA, cache=False))
    np.testing.assert_allclose(_radii(mesh, "screw_support"), 0.1 * r_p, rtol=1e-12)
    np.testing.assert_allclose(_radii(mesh, "nut_load"), r_p + 5.25 * R_B, rtol=1e-12)


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


def test_builders_over_the_parameter_range():
    """Every builder meshes across conformity 0.51-0.7, contact angle 30-60 deg, lead 0-40 mm,
    screw/nut, both profile planes, one and two balls (coarse; 14.7 s CPU with the deep default bodies, 11.7 s
    with the former 2 R_B, 2026-11-23)."""
    import itertools
    for conformity, beta, lead, body, plane in itertools.product((0.51, 0.6, 0.7), (30, 45, 60), (0.0, 5e-3, 40e-3),
                                                                  ("screw", "nut"), ("normal", "axial")):
        screw_pair.ball_in_screw_groove_pair(R_B, conformity, R_P, lead, math.radians(beta), body, h_contact=2e-4,
                                          growth=1.6, profile_plane=plane, cache=False)
    for conformity, beta in itertools.product((0.51, 0.7), (30, 60)):
        groove_segment.screw_groove_segment(R_B, conformity, R_P, LEAD, math.radians(beta), "nut", cache=False)
        for n_balls in (1, 2):
            ball_screw_module.ball_screw_module(R_B, conformity, R_P, LEAD, math.radians(beta), n_balls=n_balls,
                                             cache=False)
            fourpoint_module.fourpoint_module(R_RAIL, conformity, math.radians(beta), (0.03, -0.03, 0.02, 0.0),
                                              n_balls=n_balls, cache=False)


@pytest.mark.parametrize("build", [
    lambda: rail.rail_segment(R_RAIL, CONF, BETA, h_contact=5e-4),
    lambda: groove_segment.screw_groove_segment(R_B, CONF, R_P, LEAD, BETA, "nut"),
    lambda: fourpoint_module.fourpoint_module(R_RAIL, CONF, BETA),
    lambda: ball_screw_module.ball_screw_module(R_B, CONF, R_P, LEAD, BETA),
], ids=["rail", "segment", "fourpoint", "ballscrew"])
def test_every_builder_hits_its_cache(build, monkeypatch):
    first = build()
    stamp = first.stat().st_mtime_ns

    def refuse(*args, **kwargs):
        raise AssertionError("gmsh was started for a cached mesh")

    monkeypatch.setattr(gmsh, "initialize", refuse)
    second = build()
    assert second == first and second.stat().st_mtime_ns == stamp
