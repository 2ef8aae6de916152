"""fem.surface.locate_along_z (the z-projection on the counter surface) and the mortar model of a concave nut
contact, whose z window holds ball nodes beside the counter block (point B of sun2021; docs/fem.md)."""
import math

import numpy as np
import pytest

from ballbench.fem.surface import locate_along_z


def trough(n=9, half=1.0):
    """A concave trough z = x^2 on the square |x|, |y| <= half, n x n nodes, two triangles per cell."""
    x = np.linspace(-half, half, n)
    X, Y = np.meshgrid(x, x, indexing="ij")
    points = np.column_stack([X.ravel(), Y.ravel(), X.ravel() ** 2])
    index = np.arange(n * n).reshape(n, n)
    a, b, c, d = index[:-1, :-1].ravel(), index[1:, :-1].ravel(), index[1:, 1:].ravel(), index[:-1, 1:].ravel()
    triangles = np.vstack([np.column_stack([a, b, c]), np.column_stack([a, c, d])])
    return points, triangles


def test_points_beside_a_concave_surface_are_outside():
    points, triangles = trough()
    rng = np.random.default_rng(3)
    xy_in = rng.uniform(-0.99, 0.99, (50, 2))
    xy_out = np.array([[1.05, 0.0], [-1.2, 0.3], [0.2, 1.01], [1.5, 1.5]])
    nodes, weights, inside = locate_along_z(points, triangles, np.vstack([xy_in, xy_out]))
    assert inside.tolist() == [True] * 50 + [False] * 4
    # inside: the weights reproduce the point and interpolate the facetted surface (z = x^2 at the nodes)
    xyz = np.einsum("ij,ijk->ik", weights[:50], points[nodes[:50]])
    assert np.allclose(xyz[:, :2], xy_in, atol=1e-12)
    assert np.all(xyz[:, 2] >= xy_in[:, 0] ** 2 - 1e-12)  # the chords of a convex-down z lie above it
    assert np.all(xyz[:, 2] <= xy_in[:, 0] ** 2 + (2 / 8) ** 2 / 4 + 1e-12)  # chord error <= h^2 / 4 (z'' = 2)


def test_a_large_triangle_beside_small_ones_is_found():
    # a large triangle next to a strip of 60 small ones along its edge x = 0: a point just inside the large one
    # has 60 small triangles' centroids nearer than its own (the 32-nearest-centroid search alone misses it)
    big = [[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [0.0, 10.0, 0.0]]
    strip = []
    for k in range(61):
        strip += [[-0.05, 0.1 * k, 0.0], [0.0, 0.1 * k, 0.0]]
    points = np.array(big + strip)
    triangles = [[0, 1, 2]]
    for k in range(60):
        p, q, r, s = 3 + 2 * k, 4 + 2 * k, 5 + 2 * k, 6 + 2 * k
        triangles += [[p, q, s], [p, s, r]]
    triangles = np.array(triangles)
    nodes, weights, inside = locate_along_z(points, triangles, np.array([[0.01, 3.0], [-0.02, 3.03]]))
    assert inside.all()
    assert nodes[0].tolist() == [0, 1, 2]
    assert weights[0] @ points[nodes[0], :2] == pytest.approx([0.01, 3.0], abs=1e-12)
    assert weights[1] @ points[nodes[1], :2] == pytest.approx([-0.02, 3.03], abs=1e-12)


def test_mortar_on_the_concave_nut_contact():
    """The sun2021 nut contact (B, 21.71 deg) on a coarse P2 mesh: before the candidate filter dropped the ball
    nodes beside the nut block it raised "projects outside counter_contact"; now it builds, carries the load
    and gives the full-tensor Hertz patch within 3 % (2 % measured: the mesh is coarse, b / h = 3)."""
    from ballbench.fem import contact, hertz_case
    from ballbench.fem.elasticity import load_pair
    from ballbench.fem.mortar import build_mortar_model
    from ballbench.lowmodel.contact import hertz
    from ballbench.lowmodel.geometry import groove, helix
    from ballbench.meshes.assemblies import screw_pair
    from ballbench.validation.cases.sun2021 import SCREW as t1
    from ballbench.validation.studies import sun2021

    lead = float(helix.lead_from_angle(math.radians(21.71), t1.pitch_radius))
    args = (t1.ball_radius, t1.conformity, t1.pitch_radius, lead, t1.nominal_angle, "nut")
    frame = groove.contact_frame(groove.helical_groove(*args, "right"))
    curvature = 1.0 / t1.ball_radius
    geometry = hertz.from_curvatures((curvature, curvature), (frame.curvature_major, frame.curvature_minor),
                                     **t1.material.keywords)
    ref = hertz.solve_load(geometry, sun2021.contact_load())  # full-tensor Hertz of the exact nut surface
    a, b, delta = float(ref.a), float(ref.b), float(ref.delta)
    path = screw_pair.ball_in_screw_groove_pair(*args, h_contact=b / 3, growth=2.0, flank="right",
                                                fine_radius=1.2 * b, fine_half_length=a)
    # the case that failed: ball nodes in the z window of the concave block lie outside its footprint
    pair = load_pair(path)
    counter = pair.surfaces["counter_contact"]
    z_top = pair.points[np.unique(counter), 2].max() + 1.05 * delta
    ball = pair.nodes("ball_contact")
    window = ball[pair.points[ball, 2] <= z_top]
    assert not locate_along_z(pair.points, counter, pair.points[window, :2])[2].all()

    model = build_mortar_model(path, t1.material.pair, 1.05 * delta, order=2)
    state = contact.solve_force(model, sun2021.contact_load(), tol=1e-10)
    assert state.force == pytest.approx(sun2021.contact_load(), rel=1e-9)
    fit = hertz_case.fit_contact_patch(model, state)
    assert (fit.p0, fit.a, fit.b) == pytest.approx((float(ref.p0), a, b), rel=0.03)
