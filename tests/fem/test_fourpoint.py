"""FE four-point module (fem.fourpoint): exact gap, statics, loaded contact angles, FE-informed B2B."""
import math

import numpy as np
import pytest

from ballbench.fem import fourpoint as fp
from ballbench.lowmodel.linear_bearing import fourpoint as rigid
from ballbench.lowmodel.contact import hertz

THETA = math.radians(2.0)
DEVIATIONS = (-THETA, THETA, 0.0, 0.0)
GEOMETRY = fp.ModuleGeometry(5e-3, 0.56, tuple(math.pi / 4 + np.array(DEVIATIONS)))


def test_exact_gap_is_hertz_to_leading_order():
    # sphere R_B against the flank cylinder r_g: A = (1/R_B - 1/r_g)/2 along e1, B = 1/(2 R_B) along z
    curvature = hertz.ball_in_groove(5e-3, 0.56, youngs_modulus=2.1e11, poisson_ratio=0.28)
    for i in range(4):
        local = np.array([[0.0, 0.0], [2e-5, 0.0], [0.0, 2e-5], [-1.5e-5, 1e-5]])
        gap, surface = fp.exact_gap(GEOMETRY, i, local)
        quadratic = curvature.A * local[:, 0] ** 2 + curvature.B * local[:, 1] ** 2
        assert abs(gap[0]) < 1e-18
        np.testing.assert_allclose(gap[1:], quadratic[1:], rtol=2e-3)
        np.testing.assert_allclose(np.linalg.norm(surface, axis=1), 5e-3, rtol=1e-12)
    # the quartic terms of the real surfaces: 0.3 % above Hertz at 0.4 mm along e1 (conformity 0.56)
    gap, _ = fp.exact_gap(GEOMETRY, 0, np.array([[4e-4, 0.0]]))
    assert 1.0 < gap[0] / (curvature.A * 4e-4**2) < 1.01


def test_exact_gap_follows_a_tangential_shift():
    # a ball shifted by t along e1 touches the flank where the two surfaces' slopes agree,
    # x / R_B = (x + t) / r_g: the minimum of the gap moves to x = t R_B / (r_g - R_B) on the ball
    x = np.linspace(-2e-4, 2e-4, 4001)
    local = np.column_stack([x, np.zeros_like(x)])
    shift = 1e-6
    gap, _ = fp.exact_gap(GEOMETRY, 1, local, shift)
    r_g = GEOMETRY.groove_radius
    expected = shift * 5e-3 / (r_g - 5e-3)
    assert abs(x[np.argmin(gap)] - expected) < 2e-7
    assert gap.min() < 0.0  # second order: -t^2 / (2 (r_g - R_B)); the normal rigid motion is not in g0


def test_bad_input():
    with pytest.raises(ValueError, match="gap_limit"):
        fp.build_module_model("missing.msh", GEOMETRY, gap_limit=-1.0)


@pytest.fixture(scope="module")
def coarse_module():
    from ballbench.meshes.assemblies.fourpoint_module import fourpoint_module

    path = fourpoint_module(5e-3, 0.56, math.pi / 4, DEVIATIONS, 1, h_contact=4e-5, growth=1.4,
                            fine_radius=1.5e-4)  # the quick level of fe-b2b-linear-a
    return fp.build_module_model(path, GEOMETRY, gap_limit=6e-6)


@pytest.mark.slow
def test_module_statics_angles_and_b2b(coarse_module):
    from ballbench.lowmodel.linear_bearing import b2b_traction

    model = coarse_module
    results = [fp.solve(model, side, 100.0) for side in (-60.0, 60.0)]
    for side, result in zip((-60.0, 60.0), results):
        forces = np.array([c.normal_force for c in result.contacts])
        # small deformation, fixed normals: ball and top rail statics give lin2017 eq 36 exactly
        np.testing.assert_allclose(forces, rigid.normal_forces(side, 100.0, np.array(GEOMETRY.contact_angles)),
                                   rtol=1e-9)
        # approaches near Hertz's delta (bulk compliance of the truncated bodies included)
        ref = hertz.solve_load(hertz.ball_in_groove(5e-3, 0.56, youngs_modulus=2.1e11, poisson_ratio=0.28),
                               forces)
        approach = np.array([c.approach for c in result.contacts])
        np.testing.assert_allclose(approach, ref.delta, rtol=0.1)
        # the loaded contacts move along the conforming flanks by |t| r_g/(r_g - R_B) (tenths of a degree)
        shift = np.degrees([c.contact_angle for c in result.contacts]) - np.degrees(GEOMETRY.contact_angles)
        assert np.all(np.abs(shift) < 1.0) and np.max(np.abs(shift)) > 0.05
    patches = [fp.traction_patches(model, r) for r in results]
    state = b2b_traction.solve(patches, ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.01)
    assert state.power_balance < 1e-6
    assert 3.5 < state.b2b_force[0] < 4.5  # lin2019 Table 3 case (a): 3.96 N (ANSYS), 4.01 N (low-order)


@pytest.fixture(scope="module")
def heavy_module():
    """The module of ``ballbench init linear-guide`` (1/8-inch ball, f 0.52, BL/BR at 43/47 deg) whose candidate
    zones are the whole 30 deg caps: BR's cap ends at 77 deg, past its flank's end at the land (75.6 deg)."""
    from ballbench.meshes.assemblies.fourpoint_module import fourpoint_module

    radius, theta = 1.5875e-3, math.radians(2.0)
    deviations = (-theta, theta, 0.0, 0.0)
    path = fourpoint_module(radius, 0.52, math.pi / 4, deviations, 1, h_contact=radius / 5, growth=1.6,
                            fine_radius=radius / 2)
    geometry = fp.ModuleGeometry(radius, 0.52, tuple(math.pi / 4 + np.array(deviations)))
    return fp.build_module_model(path, geometry, gap_limit=1e-3)


def test_candidate_zone_ends_on_the_flank(heavy_module):
    # before: "contact BR: a ball quadrature point projects outside its flank" (a ValueError of a heavy contact)
    from ballbench.lowmodel import truncation

    geometry = heavy_module.geometry
    for i, patch in enumerate(heavy_module.patches):
        shoulder = truncation.shoulder_angle(geometry.ball_radius, geometry.conformity, geometry.contact_angles[i])
        seen = np.arctan2(np.abs(patch.surface[:, 0]), np.abs(patch.surface[:, 1]))  # from the load axis
        assert seen.max() < shoulder
        # only BR's cap (47 + 30 deg) reaches past its flank: only its zone has an edge at the shoulder
        assert patch.shoulder.any() == (patch.name == "BR")


def test_contact_reaching_the_shoulder_is_named(heavy_module):
    # 3 kN on ball 2 (N_x = +0.6 N_y): BR's Hertz ellipse (a / R_B about 0.85) would end far past the flank's end
    with pytest.raises(fp.ShoulderContact, match="BR.*shoulder") as error:
        fp.solve(heavy_module, 0.6 * 3000.0, 3000.0)
    assert error.value.contact == "BR"
    # a light load stays inside the zones
    result = fp.solve(heavy_module, 0.6 * 50.0, 50.0)
    assert all(c.normal_force > 0 for c in result.contacts)
