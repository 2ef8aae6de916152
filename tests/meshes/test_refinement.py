"""meshes.refinement: the fine zone shaped as the contact ellipse (``fine_ellipse``, docs/fem.md).

The distance field is checked against the exact distance from the elliptic slab (dense sampling of
the ellipse), and a meshed groove pair is checked for the size it produces: fine over the ellipse,
coarse beyond the minor axis and below the slab's thickness."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.meshes import refinement

gmsh = pytest.importorskip("gmsh")
meshio = pytest.importorskip("meshio")


@pytest.fixture(autouse=True)
def _private_cache(tmp_path, monkeypatch):
    monkeypatch.setenv("BALLBENCH_CACHE", str(tmp_path))


class _Recorder:
    """Stands in for ``gmsh``: records the MathEval expression of a distance field."""

    def __init__(self):
        self.expression = None
        outer = self

        class Field:
            @staticmethod
            def add(kind):
                return 1

            @staticmethod
            def setString(tag, key, value):
                outer.expression = value

        class Mesh:
            field = Field

        class Model:
            mesh = Mesh

        self.model = Model


def _distance_function(semi_axes, **kwargs):
    recorder = _Recorder()
    refinement.ellipse_distance(recorder, semi_axes, **kwargs)
    text = recorder.expression.replace("^", "**").replace("Sqrt", "math.sqrt").replace("Abs", "abs")
    assert "e-" not in text and "e+" not in text  # gmsh's MathEval reads no exponents
    return eval("lambda x, y, z: " + text, {"math": math})  # noqa: S307 - our own expression


def test_ellipse_distance_is_zero_inside_and_bounded_by_the_true_distance():
    """0 in the slab; outside between 0.3 and 1.0 of the exact distance (never more: the fine zone is never
    thinner than asked), exact along the minor axis and across the slab.  Catches a distance from the centre
    point or from the bounding box (> the true distance near the ellipse's tips) and a slab of the wrong
    thickness."""
    l1, l2, l3 = 4.2e-4, 1.0e-4, 5e-5
    d = _distance_function((l1, l2, l3))
    t = np.linspace(0.0, 2 * np.pi, 20001)
    ex, ey = l1 * np.cos(t), l2 * np.sin(t)
    rng = np.random.default_rng(0)
    ratios = []
    for x, y, z in zip(rng.uniform(-3 * l1, 3 * l1, 1500), rng.uniform(-6 * l2, 6 * l2, 1500),
                       rng.uniform(-4 * l3, 4 * l3, 1500)):
        inside = (x / l1) ** 2 + (y / l2) ** 2 <= 1.0
        true = math.hypot(0.0 if inside else float(np.min(np.hypot(ex - x, ey - y))), max(0.0, abs(z) - l3))
        if true == 0.0:
            assert d(x, y, z) < 1e-12 * l1
        else:
            ratios.append(d(x, y, z) / true)
    assert 0.3 < min(ratios) and max(ratios) < 1.0 + 1e-9
    assert d(0.0, l2 + 3e-5, 0.0) == pytest.approx(3e-5, rel=1e-9)
    assert d(0.3 * l1, 0.2 * l2, l3 + 2e-5) == pytest.approx(2e-5, rel=1e-9)


def test_ellipse_distance_in_a_rotated_frame():
    """With a contact frame (rows e1, e2, e3) and centre the same slab is found about that contact."""
    l1, l2, l3 = 3e-4, 1e-4, 2e-5
    c, s = math.cos(0.7), math.sin(0.7)
    frame = np.array([[c, s, 0.0], [0.0, 0.0, 1.0], [s, -c, 0.0]])
    centre = np.array([1e-3, -2e-3, 5e-4])
    d = _distance_function((l1, l2, l3), centre=centre, frame=frame)
    for u, v, w, expected in ((0.9 * l1, 0.0, 0.0, 0.0), (0.0, l2 + 1e-5, 0.0, 1e-5), (0.0, 0.0, l3 + 4e-5, 4e-5)):
        point = centre + u * frame[0] + v * frame[1] + w * frame[2]
        assert d(*point) == pytest.approx(expected, abs=1e-12)


@pytest.mark.parametrize("value", [(1e-4,), (1e-4, -1e-4), (1e-4, 1e-4, -1e-5), "abc", (1e-4, 1e-4, 1e-4, 1e-4)])
def test_bad_fine_ellipse_names_the_parameter(value):
    with pytest.raises(ValueError, match="fine_ellipse"):
        refinement.check_fine_ellipse(value)


def test_groove_pair_with_the_elliptic_fine_zone():
    """Fine (h_contact) over the ellipse to its tip; beyond the minor axis and below the slab the size grows.
    The capsule of the same length (fine_radius = l_2 about |x| <= l_1) keeps h_contact to depth l_2, which
    this test tells apart (depth l_3 + 6 h = 0.93 l_2).  Without fine_ellipse the cache name is the old one."""
    from ballbench.meshes.assemblies import contact_pairs

    radius, h, l1, l2, l3 = 5e-3, 4e-5, 8e-4, 3e-4, 4e-5
    args = (radius, 0.56, h, 1.3)
    path = contact_pairs.ball_in_groove_pair(*args, fine_ellipse=(l1, l2, l3), block_half_width=1.5e-3,
                                             block_half_length=1.5e-3, block_depth=1.5e-3)
    assert path != contact_pairs.ball_in_groove_pair(*args, block_half_width=1.5e-3, block_half_length=1.5e-3,
                                                     block_depth=1.5e-3, cache=False, fine_radius=l2,
                                                     fine_half_length=l1)
    mesh = meshio.read(path)
    tets = np.vstack([block.data for block in mesh.cells if block.type == "tetra"])
    corners = mesh.points[tets]
    centre = corners.mean(axis=1)
    edge = np.linalg.norm(corners[:, 0] - corners[:, 1], axis=1)

    def size_near(x, y, z):
        near = np.linalg.norm(centre - np.array([x, y, z]), axis=1) < 1.5 * h
        assert near.any()
        return float(np.median(edge[near]))

    assert size_near(0.85 * l1, 0.0, 0.0) < 1.6 * h  # the tip of the ellipse is fine
    assert size_near(0.0, l2 + 4 * h, 0.0) > 1.5 * h  # h + 0.3 * 4 h = 2.2 h beyond the minor axis
    assert size_near(0.0, 0.0, -(l3 + 6 * h)) > 1.5 * h  # h + 0.3 * 6 h below the slab (the capsule: h)


def test_fourpoint_module_with_elliptic_fine_zones():
    """fine_ellipses in the four-point module: gmsh parses the rotated slabs (constants with their signs) and
    the mesh is fine along each contact's e1 to 0.8 l_1 and coarser below the slab along the normal.  Catches
    slabs in the wrong frame (e1 and e2 swapped: coarse at 0.8 l_1 along e1)."""
    from ballbench.lowmodel.geometry.fourpoint import contact_points
    from ballbench.meshes.assemblies.fourpoint_module import fourpoint_module

    radius, h, l1, l2, l3 = 2.5e-3, 6e-5, 6e-4, 1.5e-4, 5e-5
    beta, deviations = math.radians(45.0), (-0.035, 0.035, 0.0, 0.0)
    path = fourpoint_module(radius, 0.56, beta, deviations, 1, h_contact=h, growth=1.4, fine_radius=1e-4,
                            fine_ellipses=(l1, l2, l3))
    mesh = meshio.read(path)
    tets = np.vstack([block.data for block in mesh.cells if block.type == "tetra"])
    corners = mesh.points[tets]
    centre = corners.mean(axis=1)
    edge = np.linalg.norm(corners[:, 0] - corners[:, 1], axis=1)

    def size_near(point):
        near = np.linalg.norm(centre - point, axis=1) < 1.5 * h
        assert near.any()
        return float(np.median(edge[near]))

    angles = [beta + deviations[0], beta + deviations[1], beta + deviations[2], beta + deviations[3]]
    for point2 in contact_points(radius, angles):
        n = np.append(point2 / radius, 0.0)
        e1 = np.array([-n[1], n[0], 0.0])
        contact = radius * n
        assert size_near(contact + 0.8 * l1 * e1 - 0.3 * h * n) < 1.6 * h  # along the major axis: fine
        assert size_near(contact - (l3 + 6 * h) * n) > 1.5 * h  # into the ball, below the slab: coarser
