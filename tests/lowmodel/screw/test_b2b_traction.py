"""FE-informed screw B2B model (lowmodel.screw.b2b_traction): Hertz limit, power, lead 0, theta 0, errors."""
import math
from functools import lru_cache

import numpy as np
import pytest

from ballbench.lowmodel.contact.traction import SampledCoulomb, TractionPatch
from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b, b2b_traction as bt
from ballbench.lowmodel.screw import b2b as screw_b2b
from ballbench.lowmodel.screw import contacts as screw_contacts
from ballbench.lowmodel.screw import b2b_traction as sbt

OVERSIZE = 1.6848e-6  # m, the preload fitted on Table 5 case a (docs/ball_screw.md)
THETA = {"a": math.radians(2.0), "b": math.radians(3.0)}  # lin2019 Table 5: ball 2's deviation (ball 1: 0)
AXIAL_LOAD = 50.0  # N on the screw, lin2019 Sec 3.3


def _module(**kw):
    return screw_contacts.screw_module(oversize=OVERSIZE, **kw)  # lin2019 Table 4 defaults


@lru_cache(maxsize=4)
def _low_order(case: str):
    """(contacts, free balls, touching balls) of the low-order model (screw_b2b), Table 5 case."""
    contacts = screw_contacts.ball_contacts(_module(), np.array([0.0, THETA[case]]), reading="tilted")
    return contacts, screw_b2b.solve(contacts, AXIAL_LOAD, with_b2b=False), screw_b2b.solve(contacts, AXIAL_LOAD)


def _patches(state, contacts, **kw):
    return [sbt.hertz_patches(state, contacts, j, **kw) for j in range(contacts.n_balls)]


@pytest.mark.parametrize("case", ["a", "b"])
def test_hertz_patches_reproduce_screw_b2b(case):
    # planar Hertz samples at the low-order state are the low-order model's contacts: F_B2B, orbit speed and
    # friction must agree to the quadrature error, and converge with the sample density
    contacts, free, low = _low_order(case)
    errors = []
    for n_radial, n_angular in ((8, 32), (16, 64), (24, 96)):
        state = sbt.solve(_patches(low, contacts, n_radial=n_radial, n_angular=n_angular), contacts.module)
        errors.append(abs(state.b2b_force[0] / low.b2b_force[0] - 1.0))
    assert errors[0] < 5e-3  # 8 x 32: measured 1.2e-3 (b)
    assert errors[-1] < 2e-5  # 24 x 96: measured 1.1e-6 (a), 5.7e-6 (b)
    assert errors[2] < errors[1] < errors[0]
    scale = contacts.module.friction_coefficient * low.normal_force.max()
    assert np.max(np.abs(state.friction_force - low.friction_force)) < 1e-4 * scale
    np.testing.assert_allclose(state.orbit_speed, low.orbit_speed, rtol=1e-6)
    np.testing.assert_allclose(state.omega, low.omega, rtol=0, atol=1e-4 * np.abs(low.omega).max())
    # the friction increase of lin2019 Sec 3.3 (free balls from the low-order free state's contacts)
    result = sbt.module_b2b(_patches(low, contacts), contacts.module, free_balls=_patches(free, contacts))
    increase = 100.0 * (low.total_loss / free.total_loss - 1.0)
    assert abs(result.friction_increase - increase) < 1e-2  # percentage points; measured 1e-3
    assert result.power_balance < 1e-9
    np.testing.assert_allclose(result.free.orbit_speed, free.orbit_speed, rtol=1e-6)


def test_power_balance_and_equilibrium_recomputed_from_the_state():
    # curved patches: the input power recomputed from each nut patch's friction force and moment
    # (omega_N z_hat . (c_0 x F + M) + omega_N p z_hat . F, c_0 = R_P x3) equals the groove and B2B losses
    contacts, free, low = _low_order("a")
    module = contacts.module
    z_hat = np.array([0.0, math.sin(module.lead_angle), math.cos(module.lead_angle)])
    c0 = np.array([module.pitch_radius, 0.0, 0.0])
    for with_b2b in (True, False):
        state = sbt.solve(_patches(low, contacts, n_radial=8, n_angular=32, planar=False), module,
                          with_b2b=with_b2b)
        nut = np.array([[name in ("NR", "NL") for name in names] for names in state.names])
        force, moment = state.friction_force[nut], state.friction_moment[nut]
        power = module.nut_speed * float(np.sum(np.cross(c0, force) @ z_hat + moment @ z_hat
                                                + module.lead_per_radian * force @ z_hat))
        assert abs(power - state.total_loss) <= 1e-6 * state.total_loss
        assert state.power_balance < 1e-9
        assert (state.b2b_force[0] > 0.0) == with_b2b
    # balls apart: each ball's friction has no force along y3 and no moment about its centre
    scale = module.friction_coefficient * state.normal_force.max()
    assert np.max(np.abs(state.friction_force[:, :, 1].sum(axis=1))) < 1e-9 * scale
    assert np.max(np.abs(state.friction_moment.sum(axis=1))) < 1e-9 * scale * module.ball_radius
    # the screw's patches carry the axial load (normal + friction, along the screw axis)
    assert abs(state.axial_force.sum() - AXIAL_LOAD) < 1e-2 * AXIAL_LOAD


def test_lead_zero_is_the_linear_bearing_model():
    # lead 0 and R_P -> infinity: the helix is a straight raceway and the screw model must be
    # lowmodel.linear_bearing.b2b_traction with the same patches (frames: linear (x, y, z) = CS3 (z3, x3, y3)),
    # the difference falling like R_B / R_P
    contacts = b2b.module_contacts(math.radians(2.0), -0.6)
    linear_patches = [bt.hertz_patches(contacts, j, n_radial=8, n_angular=32) for j in range(2)]
    linear = bt.solve(linear_patches, ball_radius=contacts.ball_radius,
                      friction_coefficient=contacts.friction_coefficient, groove_velocity=contacts.groove_velocity)
    names = {"BL": "SL", "BR": "SR", "TR": "NR", "TL": "NL"}
    screw_patches = [[TractionPatch(p.points[:, [1, 2, 0]], p.normals[:, [1, 2, 0]], p.forces, p.top, names[p.name])
                      for p in ball] for ball in linear_patches]
    differences = []
    for ratio in (1e3, 1e5):
        pitch_radius = ratio * contacts.ball_radius
        module = screw_contacts.screw_module(ball_radius=contacts.ball_radius, conformity=0.56,
                                             pitch_radius=pitch_radius, lead=0.0,
                                             nut_speed=contacts.groove_velocity / pitch_radius,
                                             friction_coefficient=contacts.friction_coefficient)
        state = sbt.solve(screw_patches, module)
        spin = state.omega + state.orbit_speed[:, None] * np.array([0.0, 0.0, 1.0])  # absolute, CS3
        difference = max(abs(state.b2b_force[0] / linear.b2b_force[0] - 1.0),
                         float(np.max(np.abs(state.orbit_speed * pitch_radius / linear.ball_velocity - 1.0))),
                         float(np.max(np.abs(spin[:, [2, 0]] - linear.omega)) / np.abs(linear.omega).max()),
                         abs(state.total_loss / linear.total_loss - 1.0))
        assert difference < 1.0 / ratio  # measured 0.71 R_B / R_P
        assert np.max(np.abs(spin[:, 1])) < 1e-5 / ratio * np.abs(linear.omega).max()  # linear omega_z = 0
        differences.append(difference)
    assert 50.0 < differences[0] / differences[1] < 200.0  # ~ R_B / R_P


def test_no_b2b_force_at_theta_zero_or_with_the_faster_ball_ahead():
    module = _module()
    same = screw_contacts.ball_contacts(module, np.array([0.0, 0.0]), reading="tilted")
    free = screw_b2b.solve(same, AXIAL_LOAD, with_b2b=False)
    state = sbt.solve(_patches(free, same, n_radial=8, n_angular=32), module)
    assert state.b2b_force[0] == 0.0
    np.testing.assert_allclose(state.orbit_speed[1], state.orbit_speed[0], rtol=1e-12)
    # case a with the balls swapped: the deviated (slower) ball behind separates from the faster one ahead
    contacts, free_a, _ = _low_order("a")
    swapped = _patches(free_a, contacts, n_radial=8, n_angular=32)[::-1]
    state = sbt.solve(swapped, module)
    apart = sbt.solve(swapped, module, with_b2b=False)
    assert state.b2b_force[0] == 0.0
    assert state.orbit_speed[1] > state.orbit_speed[0]
    np.testing.assert_allclose(state.orbit_speed, apart.orbit_speed, rtol=1e-12)


def test_bad_patches_raise_value_error_naming_them():
    contacts, free, _ = _low_order("a")
    module = contacts.module
    good = _patches(free, contacts, n_radial=4, n_angular=8)

    def with_patch(index, **changes):
        patch = good[0][index]
        fields = dict(points=patch.points, normals=patch.normals, forces=patch.forces, top=patch.top,
                      name=patch.name)
        fields.update(changes)
        return [tuple(TractionPatch(**fields) if i == index else p for i, p in enumerate(good[0])), good[1]]

    p = good[0][0]
    cases = [(with_patch(0, forces=-p.forces), "SL: forces"),
             (with_patch(0, normals=2.0 * p.normals), "SL: normals must be unit"),
             (with_patch(0, points=p.points[:, :2]), "SL: points and normals must have shape"),
             (with_patch(0, points=1e3 * p.points), "SL: points must lie within 5 % of ball_radius"),
             (with_patch(0, normals=-p.normals), "SL: normals must point out of the ball"),
             (with_patch(0, forces=np.where(np.arange(len(p.forces)) == 0, np.nan, p.forces)), "SL: points, normals"),
             ([[q for q in good[0] if not q.top], good[1]], "nut patch"),
             ([], "balls must hold")]
    for balls, message in cases:
        with pytest.raises(ValueError, match=message):
            sbt.solve(balls, module)
    with pytest.raises(ValueError, match="module must be"):
        sbt.solve(good, object())
    with pytest.raises(ValueError, match="regularisation"):
        sbt.solve(good, module, regularisation=0.0)
    with pytest.raises(ValueError, match="gaps"):
        sbt.solve(good, module, gaps=[-1.0])
    with pytest.raises(ValueError, match="n_radial"):
        sbt.hertz_patches(free, contacts, 0, n_radial=0)
    with pytest.raises(ConvergenceError):
        sbt.solve(good, module, max_iterations=1)


def test_point_friction_is_tangent_full_slip_and_opposes_the_slip():
    # lowmodel.contact.traction.SampledCoulomb on curved patches: every point's friction lies in the tangent
    # plane of its normal, has the magnitude of its normal force (full slip) and opposes the tangential slip
    contacts, free, _ = _low_order("a")
    balls = _patches(free, contacts, n_radial=4, n_angular=16, planar=False)
    points = np.concatenate([p.points for p in balls[0]])
    normals = np.concatenate([p.normals for p in balls[0]])
    loads = np.concatenate([p.forces for p in balls[0]])
    rng = np.random.default_rng(3)
    slip_matrix = rng.normal(size=(len(points), 3, 4))
    groove = rng.normal(size=(len(points), 3))
    core = SampledCoulomb(np.zeros(len(points), dtype=int), slip_matrix, groove, normals, loads, 1, 1e-12)
    x = rng.normal(size=(1, 4))
    residual, jac, slip, force = core.evaluate(x)
    np.testing.assert_allclose(np.einsum("ki,ki->k", force, normals), 0.0, atol=1e-12 * loads.max())
    np.testing.assert_allclose(np.linalg.norm(force, axis=1), loads, rtol=1e-9)
    tangential = slip - normals * np.einsum("ki,ki->k", normals, slip)[:, None]
    np.testing.assert_allclose(np.einsum("ki,ki->k", force, tangential), -loads * np.linalg.norm(tangential, axis=1),
                               rtol=1e-9)
    np.testing.assert_allclose(residual[0], np.einsum("kij,ki->j", slip_matrix, force), rtol=1e-9)
    # the Jacobian against central differences, and symmetric (gradient of the dissipation)
    step = 1e-7
    numeric = np.stack([(core.evaluate(x + step * np.eye(4)[j])[0][0] - core.evaluate(x - step * np.eye(4)[j])[0][0])
                        / (2 * step) for j in range(4)], axis=1)
    np.testing.assert_allclose(jac[0], numeric, rtol=1e-5, atol=1e-6 * np.abs(numeric).max())
    np.testing.assert_allclose(jac[0], jac[0].T, atol=1e-12 * np.abs(jac[0]).max())


@pytest.mark.parametrize("degrees", [(2.0, 0.0, 1.0), (0.0, 2.0, 0.0, 3.0)])
def test_chains_reproduce_screw_b2b(degrees):
    # 3 and 4 balls (eqs 60-61 for every neighbouring pair): the touching and separating pairs and the B2B
    # forces of the low-order chain from its own Hertz patches (16 x 64 samples: quadrature error ~1e-4)
    contacts = screw_contacts.ball_contacts(_module(), np.radians(degrees), reading="tilted")
    low = screw_b2b.solve(contacts, 25.0 * len(degrees))
    state = sbt.solve(_patches(low, contacts, n_radial=16, n_angular=64), contacts.module)
    np.testing.assert_array_equal(state.b2b_force > 0.0, low.b2b_force > 0.0)
    np.testing.assert_allclose(state.b2b_force, low.b2b_force, rtol=0, atol=2e-4 * low.b2b_force.max())
    np.testing.assert_allclose(state.orbit_speed, low.orbit_speed, rtol=1e-5)
    assert state.power_balance < 1e-9
