"""FE-informed B2B model (lowmodel.linear_bearing.b2b_traction) against the low-order model and physics checks."""
import math

import numpy as np
import pytest

from ballbench.lowmodel.errors import ConvergenceError
from ballbench.lowmodel.linear_bearing import b2b, b2b_traction as bt
from ballbench.lowmodel.linear_bearing import ball as bearing_ball
from hypothesis import given, strategies as st
from tests.property_support import SLOW, call, one_bad, real

THETA = math.radians(2.0)


def _contacts(case="a", rho=-0.6):
    top = (0.0, 0.0) if case == "a" else (-THETA, THETA)
    return b2b.module_contacts(THETA, rho, top_deviations=top)


def _solve(contacts, patches, **kw):
    return bt.solve(patches, ball_radius=contacts.ball_radius, friction_coefficient=contacts.friction_coefficient,
                    groove_velocity=contacts.groove_velocity, **kw)


def test_hertz_samples_reproduce_low_order_b2b_force():
    # planar Hertz samples are the low-order model's contact: F_B2B must agree to the quadrature error
    contacts = _contacts("a")
    low = b2b.solve(contacts, gaps=[0.0])
    errors = []
    for n_radial, n_angular in ((8, 32), (24, 96)):
        patches = [bt.hertz_patches(contacts, j, n_radial=n_radial, n_angular=n_angular) for j in range(2)]
        state = _solve(contacts, patches)
        errors.append(abs(state.b2b_force[0] / low.b2b_force[0] - 1.0))
        # the ball-to-groove friction forces too (same equilibrium), in units of mu F
        scale = contacts.friction_coefficient * contacts.normal_forces.max()
        assert np.max(np.abs(state.friction_force - low.friction_force)) < 5e-3 * scale
    assert errors[-1] < 3e-3
    assert errors[-1] < errors[0]


def test_free_balls_reproduce_low_order_velocity_deviation():
    contacts = _contacts("a")
    free = bearing_ball.solve(contacts)
    state = _solve(contacts, [bt.hertz_patches(contacts, j) for j in range(2)], gaps=[1e-4])
    assert np.all(state.b2b_force == 0.0)
    np.testing.assert_allclose(state.velocity_deviation, free.velocity_deviation, rtol=1e-2)
    np.testing.assert_allclose(state.omega, free.omega, rtol=1e-3, atol=1e-3 * np.abs(free.omega).max())


def test_case_b_has_no_b2b_force():
    contacts = _contacts("b")
    state = _solve(contacts, [bt.hertz_patches(contacts, j, n_radial=8, n_angular=32) for j in range(2)])
    assert state.b2b_force[0] == 0.0
    np.testing.assert_allclose(state.velocity_deviation, 0.0, atol=1e-12)


def test_power_balance_and_equilibrium_from_the_state():
    contacts = _contacts("a")
    patches = [bt.hertz_patches(contacts, j, n_radial=8, n_angular=32, planar=False) for j in range(2)]
    state = _solve(contacts, patches)
    assert state.b2b_force[0] > 0.0
    # recomputed from the reported forces: v sum_top f_z = groove losses + mu F_B2B |dv| (lin2019 eq 7)
    top = contacts.groove_velocity * state.friction_force[:, 2:].sum()
    losses = state.friction_loss.sum() + contacts.friction_coefficient * state.b2b_force.sum() * state.b2b_slip.sum()
    assert abs(top - losses) <= 1e-6 * abs(top)
    assert state.power_balance <= bt.POWER_BALANCE_TOLERANCE
    # z equilibrium of each ball with the B2B force (ball 0 pushed back, ball 1 forward; eq 8)
    fz = state.friction_force.sum(axis=1)
    np.testing.assert_allclose(fz, [state.b2b_force[0], -state.b2b_force[0]], atol=1e-9)


def test_mirror_symmetry():
    # x -> -x swaps left and right contacts: same v_B, omega_y changes sign
    contacts = _contacts("a", rho=-0.3)
    patches = bt.hertz_patches(contacts, 0, n_radial=8, n_angular=32, planar=False)
    mirror = np.diag([-1.0, 1.0, 1.0])
    mirrored = [bt.TractionPatch(p.points @ mirror, p.normals @ mirror, p.forces, p.top, p.name) for p in patches]
    one = _solve(contacts, [patches])
    two = _solve(contacts, [mirrored])
    np.testing.assert_allclose(two.ball_velocity, one.ball_velocity, rtol=1e-9)
    np.testing.assert_allclose(two.omega[:, 0], one.omega[:, 0], rtol=1e-9)
    np.testing.assert_allclose(two.omega[:, 1], -one.omega[:, 1], rtol=1e-8, atol=1e-12)


def test_loaded_contact_angle_of_a_patch():
    contacts = _contacts("a")
    patches = bt.hertz_patches(contacts, 0, n_radial=4, n_angular=16)
    np.testing.assert_allclose([p.contact_angle() for p in patches], contacts.contact_angles[0], atol=1e-12)


def test_bad_input_and_non_convergence():
    contacts = _contacts("a")
    patches = [bt.hertz_patches(contacts, j, n_radial=4, n_angular=16) for j in range(2)]
    with pytest.raises(ValueError, match="friction_coefficient"):
        bt.solve(patches, ball_radius=5e-3, friction_coefficient=0.0, groove_velocity=0.01)
    with pytest.raises(ValueError, match="groove_velocity"):
        bt.solve(patches, ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.0)
    bad = list(patches[0])
    bad[0] = bt.TractionPatch(bad[0].points, bad[0].normals, -bad[0].forces, False, "BL")
    with pytest.raises(ValueError, match="BL: forces"):
        bt.solve([bad, patches[1]], ball_radius=5e-3, friction_coefficient=0.1, groove_velocity=0.01)
    with pytest.raises(ValueError, match="gaps"):
        _solve(contacts, patches, gaps=[-1.0])
    with pytest.raises(ConvergenceError):
        _solve(contacts, patches, max_iterations=1)


# --- edge inputs: each case failed before its fix (a NaN or inf, a warning, an error naming no parameter,
# nonsense accepted); every warning is an error -----------------------------------------------------------------------


@pytest.mark.filterwarnings("error")
def test_bool_ball_index_is_refused():
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=2)
    with pytest.raises(ValueError, match="ball"):  # was "setting an array element with a sequence"
        bt.hertz_patches(contacts, True)
    with pytest.raises(ValueError, match="ball"):
        bt.hertz_patches(contacts, 2)


@pytest.mark.filterwarnings("error")
def test_traction_solve_of_a_subnormal_ball_radius():
    contacts = b2b.module_contacts(math.radians(2.0), -0.6, n_balls=2)
    patches = [bt.hertz_patches(contacts, j, n_radial=2, n_angular=8) for j in range(2)]
    with pytest.raises(ValueError, match="ball_radius"):  # r / 5e-324 overflowed (RuntimeWarning)
        bt.solve(patches, ball_radius=5e-324, friction_coefficient=0.1, groove_velocity=0.01)


# --- properties (hypothesis, tests/property_support.py): finite results or an error naming a parameter,
# over the documented ranges and a little beyond ----------------------------------------------------------------------


@SLOW
@given(kw=one_bad(
    dict(rho=real(-0.9, 0.9), ball=st.integers(0, 1), n_radial=st.integers(1, 6), n_angular=st.integers(4, 16),
         planar=st.booleans(), mu=real(0.01, 0.5), velocity=st.sampled_from([-0.5, 0.01, 2.0]),
         gap=st.one_of(real(0.0, 1e-4), st.none())),
    dict(ball=st.sampled_from([-1, 2, True]), n_radial=st.sampled_from([0, -1, True]), mu=st.sampled_from([0.0, -0.1]),
         velocity=st.sampled_from([0.0, 1e300]), gap=st.sampled_from([-1e-4, 1e300]),
         radius=st.sampled_from([0.0, -5e-3, 5e-324]))))
def test_b2b_traction(kw):
    contacts = b2b.module_contacts(math.radians(2.0), kw["rho"], n_balls=2, friction_coefficient=0.1)
    patches = [call(bt.hertz_patches, contacts, j, n_radial=kw["n_radial"], n_angular=kw["n_angular"],
                    planar=kw["planar"]) for j in (kw["ball"], 1 - kw["ball"] if kw["ball"] in (0, 1) else 0)]
    if patches[0] is None or patches[1] is None:
        return
    state = call(bt.solve, patches, ball_radius=kw.get("radius", contacts.ball_radius), friction_coefficient=kw["mu"],
                 groove_velocity=kw["velocity"], gaps=None if kw["gap"] is None else [kw["gap"]], max_iterations=60)
    if state is not None:
        assert abs(state.power_balance) <= bt.POWER_BALANCE_TOLERANCE
