"""Contact-pair meshes: physical groups, frame, exact surfaces, refinement, cache, bad input."""
from __future__ import annotations

import numpy as np
import pytest

from ballbench.fem.elasticity import load_pair
from ballbench.meshes import gmsh_tools, refinement
from ballbench.meshes.assemblies import contact_pairs

R = 5e-3
COARSE = dict(h_contact=2.5e-4, growth=1.5)


@pytest.fixture(scope="module")
def groove_mesh():
    return load_pair(contact_pairs.ball_in_groove_pair(R, 0.56, **COARSE, fine_radius=5e-4))


def _groups_ok(pair, symmetry):
    for name in ("ball_contact", "counter_contact", "ball_load", "counter_support"):
        assert name in pair.surfaces, name
    assert ("symmetry_x" in pair.surfaces) == (symmetry == "quarter")
    assert ("symmetry_y" in pair.surfaces) == (symmetry in ("quarter", "half"))
    assert set(np.unique(pair.body)) == {0, 1}
    ball_nodes = np.unique(pair.tets[pair.body == 0])
    counter_nodes = np.unique(pair.tets[pair.body == 1])
    assert np.intersect1d(ball_nodes, counter_nodes).size == 0  # the bodies share no nodes


def test_groove_groups_and_exact_surfaces(groove_mesh):
    pair = groove_mesh
    _groups_ok(pair, "quarter")
    p = pair.points
    ball = p[pair.nodes("ball_contact")]
    assert np.allclose(np.linalg.norm(ball - [0, 0, R], axis=1), R, rtol=0, atol=1e-9)
    r_g = 0.56 * 2 * R
    groove = p[pair.nodes("counter_contact")]
    assert np.allclose(np.hypot(groove[:, 0], groove[:, 2] - r_g), r_g, rtol=0, atol=1e-9)
    # frame: contact point at the origin, ball above, counter below
    assert np.min(ball[:, 2]) == pytest.approx(0.0, abs=1e-12)
    assert np.all(p[np.unique(pair.tets[pair.body == 1]), 2] <= r_g)
    assert np.allclose(p[pair.nodes("symmetry_x"), 0], 0.0, atol=1e-12)
    assert np.allclose(p[pair.nodes("symmetry_y"), 1], 0.0, atol=1e-12)
    assert np.allclose(p[pair.nodes("ball_load"), 2], R, atol=1e-12)
    assert np.allclose(p[pair.nodes("counter_support"), 2], -0.6 * R, atol=1e-12)


def test_flat_and_ball_ball_groups():
    flat = load_pair(contact_pairs.ball_on_flat_pair(R, **COARSE, symmetry="half"))
    _groups_ok(flat, "half")
    assert np.allclose(flat.points[flat.nodes("counter_contact"), 2], 0.0, atol=1e-12)
    balls = load_pair(contact_pairs.ball_on_ball_pair(R, **COARSE, other_radius=4e-3))
    _groups_ok(balls, "quarter")
    lower = balls.points[balls.nodes("counter_contact")]
    assert np.allclose(np.linalg.norm(lower - [0, 0, -4e-3], axis=1), 4e-3, atol=1e-9)


def test_refinement_size_at_contact():
    h = 1e-4
    pair = load_pair(contact_pairs.ball_on_flat_pair(R, h, 1.3, fine_radius=3e-4))
    tris = pair.surfaces["counter_contact"]
    p = pair.points
    centre = p[tris].mean(axis=1)
    near = tris[np.linalg.norm(centre, axis=1) < 2.5e-4]
    edges = np.linalg.norm(p[near[:, 0]] - p[near[:, 1]], axis=1)
    assert 0.7 * h < np.mean(edges) < 1.3 * h
    far = tris[np.linalg.norm(centre, axis=1) > 3e-3]
    assert np.mean(np.linalg.norm(p[far[:, 0]] - p[far[:, 1]], axis=1)) > 3 * h


def test_refinement_follows_the_growth_law_about_the_segment():
    """meshes.refinement: edge lengths of the counter face follow h(d) = min(h_max, h_contact +
    (growth - 1) max(0, d - fine_radius)), d the distance from the segment |x| <= fine_half_length
    (mean ratio per distance band within 30 %; a point fine zone would double the size at x = L)."""
    h, growth, fine_radius, half_length = 1e-4, 1.3, 2e-4, 6e-4
    pair = load_pair(contact_pairs.ball_on_flat_pair(R, h, growth, fine_radius=fine_radius,
                                                     fine_half_length=half_length))
    tris, p = pair.surfaces["counter_contact"], pair.points
    centre = p[tris].mean(axis=1)
    d = np.hypot(np.maximum(np.abs(centre[:, 0]) - half_length, 0.0), centre[:, 1])
    edges = np.mean([np.linalg.norm(p[tris[:, i]] - p[tris[:, (i + 1) % 3]], axis=1) for i in range(3)], axis=0)
    law = np.minimum(R / 3, h + (growth - 1) * np.maximum(0.0, d - fine_radius))
    for lo, hi in [(0, 2e-4), (2e-4, 5e-4), (5e-4, 1e-3), (1e-3, 2e-3), (2e-3, 5e-3)]:
        band = (d >= lo) & (d < hi)
        assert band.sum() >= 10
        assert 0.7 < np.mean(edges[band] / law[band]) < 1.3, (lo, hi)
    end = np.abs(np.abs(centre[:, 0]) - half_length) + np.abs(centre[:, 1]) < 1.5e-4  # near (+-L, 0)
    assert np.mean(edges[end]) < 1.3 * h


def test_cache_hit_and_vtu(tmp_path):
    first = contact_pairs.ball_on_flat_pair(R, **COARSE)
    stamp = first.stat().st_mtime_ns
    second = contact_pairs.ball_on_flat_pair(R, **COARSE)
    assert second == first and second.stat().st_mtime_ns == stamp
    other = contact_pairs.ball_on_flat_pair(R, 2.4e-4, 1.5)
    assert other != first
    vtu = gmsh_tools.msh_to_vtu(first, tmp_path / "pair.vtu")
    import meshio

    assert meshio.read(vtu).cells[0].type == "tetra"


@pytest.mark.parametrize("kwargs, word", [
    (dict(conformity=0.5), "conformity"),
    (dict(conformity=float("nan")), "conformity"),
    (dict(h_contact=-1e-4), "h_contact"),
    (dict(h_contact=2e-3), "h_contact"),
    (dict(growth=0.9), "growth"),
    (dict(symmetry="eighth"), "symmetry"),
    (dict(ball_radius=-1.0), "ball_radius"),
    (dict(block_half_width=6e-3), "block_half_width"),
    (dict(h_max=1e-5), "h_max"),
    (dict(element_order=3), "element_order"),
    (dict(element_order=True), "element_order"),
    (dict(fine_radius=6e-3), "fine_radius"),
    (dict(fine_half_length=-1e-4), "fine_half_length"),
])
def test_bad_input(kwargs, word):
    args = dict(ball_radius=R, conformity=0.56, h_contact=2.5e-4, growth=1.5)
    args.update(kwargs)
    with pytest.raises(ValueError, match=word):
        contact_pairs.ball_in_groove_pair(**args, cache=False)


def test_refinement_helper_bad_input():
    with gmsh_tools.session("t") as gmsh:
        with pytest.raises(ValueError, match="growth"):
            refinement.contact_refinement(gmsh, 1e-4, 5.0, 1e-3)
        with pytest.raises(ValueError, match="h_max"):
            refinement.contact_refinement(gmsh, 1e-4, 1.2, 1e-5)
