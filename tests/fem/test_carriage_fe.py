"""The FE rung of the whole carriage (fem.carriage_fe; docs/carriage.md, "Elastic carriage"): the grooves' patches
read a rigid motion exactly, the compliance is symmetric and non-negative, a very stiff body gives the rigid carriage,
and an elastic body is softer than the rigid one."""
from __future__ import annotations

import math

import numpy as np
import pytest

from ballbench.fem import carriage_fe
from ballbench.fem.elasticity import load_pair, vector_basis
from ballbench.lowmodel.bearing import LinearGuide, Material
from ballbench.lowmodel.linear_bearing import carriage
from ballbench.meshes.parts.carriage_body import carriage_body

GUIDE = LinearGuide(ball_radius=1.5875e-3, conformity=0.52, nominal_angle=math.pi / 4, material=Material(210e9, 0.3),
                    friction_coefficient=0.1, groove_velocity=0.1)
BODY = carriage.Carriage(GUIDE, carriage.gothic_rows(half_width=5.5e-3, height=3e-3, contact_angles=[math.pi / 4] * 4),
                         balls_per_row=4, pitch=3.3e-3, oversize=2e-6)
LOAD = carriage.Load(vertical=150.0, roll=0.5)
H_MAX, H_WALL = 3e-3, 0.6e-3


def test_the_patches_read_a_rigid_motion_at_the_grooves_curvature_centres():
    """The operator's rows applied to the displacement field of a rigid motion ``u + phi x r`` give the motion of
    each groove's curvature centre written out from the rigid kinematics (1e-12 of the largest)."""
    shape = carriage_fe.body_shape(BODY)
    path = carriage_body(half_width=shape.half_width, slot_half_width=shape.slot_half_width, bottom=shape.bottom,
                         slot_top=shape.slot_top, top=shape.top, length=shape.length, h_max=H_MAX, h_wall=H_WALL)
    pair = load_pair(path, {"carriage": 0})
    basis = vector_basis(pair, 2)
    points, centres, _ = carriage.groove_points(BODY)
    operator, counts = carriage_fe.patch_operator(pair, basis, points, centres, shape,
                                                  carriage_fe.default_patch_radius(BODY))
    assert counts.min() >= carriage_fe.MIN_PATCH_NODES
    u, phi = np.array([2e-6, -1e-6, 0.5e-6]), np.array([3e-5, -2e-5, 4e-5])
    field = np.zeros(basis.N)
    motion = u + np.cross(phi, pair.points)  # (n, 3) at the vertices
    for c in range(3):
        field[basis.nodal_dofs[c]] = motion[:, c]
    expected = (u + np.cross(phi, centres))[:, :2].reshape(-1)
    assert operator @ field == pytest.approx(expected, abs=1e-12 * np.abs(expected).max())


def test_a_very_stiff_body_gives_the_rigid_carriage_and_an_elastic_one_is_softer():
    """The body's modulus a million times steel's: the ball loads and the stiffness of the rigid carriage (1e-5); at
    steel's the compliance is symmetric and not negative, the loads balance, the carriage is softer (every diagonal
    stiffness lower) and the preload relaxes."""
    stiff = carriage_fe.compare(BODY, LOAD, h_max=H_MAX, h_wall=H_WALL, youngs_modulus=210e15)
    assert np.max(np.abs(stiff.error)) < 1e-5
    assert np.diag(stiff.elastic.stiffness) == pytest.approx(np.diag(stiff.rigid.stiffness), rel=1e-5)
    steel = carriage_fe.compare(BODY, LOAD, h_max=H_MAX, h_wall=H_WALL)
    matrix = steel.compliance.matrix
    assert matrix == pytest.approx(matrix.T, abs=1e-15 * np.abs(matrix).max())
    assert np.linalg.eigvalsh(matrix).min() >= -1e-12 * np.abs(matrix).max()
    assert steel.compliance.local <= steel.compliance.boussinesq
    assert steel.elastic.balance < carriage.BALANCE_TOLERANCE
    assert np.all(steel.stiffness_change > 0.0)
    unloaded = carriage_fe.compare(BODY, carriage.Load(), h_max=H_MAX, h_wall=H_WALL)
    assert unloaded.elastic_load.max() < unloaded.rigid_load.max()  # the flanges open: the preload relaxes
    # the body's field under the elastic state's groove forces: zero on the mounting face (held by the table)
    field = steel.compliance.displacement(steel.groove_forces)
    mount = np.abs(steel.compliance.points[:, 1] - carriage_fe.body_shape(BODY).top) < 1e-12
    assert mount.sum() > 10 and np.max(np.abs(field[mount])) == 0.0 and np.max(np.abs(field)) > 1e-8


def test_the_elastic_carriage_writes_its_field_for_paraview(tmp_path):
    import meshio

    comparison = carriage_fe.compare(BODY, LOAD, h_max=H_MAX, h_wall=H_WALL)
    path = carriage_fe.write_vtu(tmp_path / "carriage.vtu", comparison)
    mesh = meshio.read(path)
    assert mesh.points.shape == comparison.compliance.points.shape and "displacement_m" in mesh.point_data
    assert np.max(mesh.point_data["displacement_magnitude_m"]) > 0.0
